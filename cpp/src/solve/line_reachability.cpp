#include "solve/line_reachability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pathpace::detail {

namespace {

// A row whose line in (x, y) is steeper than this: a rounding error r in θ_k moves its bound on θ_{k+1} by
// r |α / β|. Where the greedy profile sits at such a row's corner (a vertical edge of the polygon, e.g. a
// near-vertical edge of a projected contact polygon, or p'_j ~ 0 at a reversal on a fine grid), a few ulps
// of θ_k move θ_{k+1} by O(1): the polygons' slices read such an edge as vertical (the whole edge is the
// slice), the lines cannot, and their relaxed profile would no longer bound every feasible one from above.
// Beyond 1e5 the polygons decide; below, the few ulps of θ_k that its rounding leaves move θ_{k+1} by at
// most ~1e-10 relative, far inside any certified tolerance (and the test against the polygons sees 1e-12).
// At 1e5 an arm's row is steep only where the grid lands within ~1e-5 Δs of a joint's reversal.
constexpr double kSteep = 1e5;

// The slice [Lo, Hi] of interval k's set at x for the greedy pass and the repair (see the header): Hi =
// min(y_hi, the lines of the rows with β > 0), Lo = max(y_lo, those with β < 0), one division per row.
struct Slice {
  double hi, lo;
};

Slice slice(View<Line> rows, double x, double y_lo, double y_hi) {
  Slice e{y_hi, y_lo};
  for (const Line& r : rows) {
    if (r.b == 0.0) continue;  // a bound on x alone: in the box (interval_lines)
    const double v = (r.c - r.a * x) / r.b;
    if (r.b > 0.0) e.hi = std::min(e.hi, v);
    else e.lo = std::max(e.lo, v);
  }
  return e;
}

// Interval k's lines y = P + Q x in the backward pass, where each is evaluated a few times (two divisions
// once, then one multiply-add each time).
struct Ln {
  double P, Q;
};
struct IntervalLines {
  std::vector<Ln> up, lo;  // rows with β > 0, β < 0: [0, n_up), [0, n_lo) (sized once, never shrunk)
  std::size_t n_up = 0, n_lo = 0;
  bool c_nonnegative = true;
};

// Interval k's lines, and the rows with β = 0, which bound x alone: x_top comes down to theirs. False if one
// of those is infeasible on its own or bounds x from below above x_lo (then K_k's bottom is not x_lo), or if a
// row is steep (see kSteep).
bool interval_lines(View<Line> rows, double x_lo, double& x_top, IntervalLines& L) {
  if (L.up.size() < rows.n) L.up.resize(rows.n), L.lo.resize(rows.n);
  // Written through pointers, counted in locals: push_back would check the capacity and store the vector's
  // end at every row.
  Ln* up = L.up.data();
  Ln* lo = L.lo.data();
  std::size_t n_up = 0, n_lo = 0;
  bool c_nonnegative = true;
  for (const Line& r : rows) {
    c_nonnegative = c_nonnegative && r.c >= 0.0;
    if (r.b != 0.0) {
      if (std::abs(r.a) > kSteep * std::abs(r.b)) return false;
      (r.b > 0.0 ? up[n_up++] : lo[n_lo++]) = {r.c / r.b, -r.a / r.b};
    } else if (r.a > 0.0) {
      x_top = std::min(x_top, r.c / r.a);
    } else if (r.a < 0.0) {
      if (r.c / r.a > x_lo) return false;
    } else if (r.c < 0.0) {
      return false;
    }
  }
  L.n_up = n_up;
  L.n_lo = n_lo;
  L.c_nonnegative = c_nonnegative;
  return x_top >= x_lo;
}

// g = min(y_hi, up) - max(y_lo, lo) at x, each with the line active just left of x (on a tie the one with the
// larger slope for Hi, the smaller for Lo: g's left derivative); the box sides have slope 0.
struct Active {
  double hi, lo, hi_P, hi_Q, lo_P, lo_Q;
};
Active active(const IntervalLines& L, double x, double y_lo, double y_hi) {
  Active e{y_hi, y_lo, y_hi, 0.0, y_lo, 0.0};
  for (std::size_t i = 0; i < L.n_up; ++i) {
    const Ln& l = L.up[i];
    const double v = l.P + l.Q * x;
    if (v < e.hi || (v == e.hi && l.Q > e.hi_Q)) e.hi = v, e.hi_P = l.P, e.hi_Q = l.Q;
  }
  for (std::size_t i = 0; i < L.n_lo; ++i) {
    const Ln& l = L.lo[i];
    const double v = l.P + l.Q * x;
    if (v > e.lo || (v == e.lo && l.Q < e.lo_Q)) e.lo = v, e.lo_P = l.P, e.lo_Q = l.Q;
  }
  return e;
}

bool meets(double hi, double lo, double rel) { return hi - lo >= -rel * std::max({1.0, std::abs(hi), std::abs(lo)}); }

// K_k's top: the largest x in [x_lo, x_top] with g(x) >= 0, by Newton's method from x_top (see the header),
// or NaN if g(x_lo) < 0 (K_k's bottom is not x_lo, or K_k is empty) or Newton does not settle.
double k_top(const IntervalLines& L, double x_lo, double x_top, double y_lo, double y_hi) {
  // From rest (x_lo = y_lo = 0) with every c >= 0, (0, 0) meets every row: g(0) >= 0 needs no evaluation.
  if (!(x_lo == 0.0 && y_lo == 0.0 && y_hi >= 0.0 && L.c_nonnegative)) {
    const Active e = active(L, x_lo, y_lo, y_hi);
    if (!meets(e.hi, e.lo, 1e-15)) return std::numeric_limits<double>::quiet_NaN();
  }
  double x = x_top;
  for (int step = 0; step < 64; ++step) {
    const Active e = active(L, x, y_lo, y_hi);
    if (meets(e.hi, e.lo, 1e-15)) return x;
    const double g_slope = e.hi_Q - e.lo_Q;
    // g < 0 here and not increasing to the left: g < 0 on all of [x_lo, x] (concave), which g(x_lo) >= 0
    // denies, unless rounding: let the polygons decide.
    if (!(g_slope < 0.0)) break;
    // Where the two active lines cross (not x - g / g': from a far x, as the cap of a point that nothing
    // bounds, that difference would cancel to nothing).
    const double next = (e.lo_P - e.hi_P) / g_slope;
    if (!(next < x)) {
      // No step left: x is the root to rounding, which a steep line multiplies (its value at x is off by
      // about eps |slope x|).
      const double scale = std::max({1.0, std::abs(e.hi), std::abs(e.lo), (std::abs(e.hi_Q) + std::abs(e.lo_Q)) * x});
      if (e.lo - e.hi <= 1e-13 * scale) return x;
      break;
    }
    if (next <= x_lo) return x_lo;
    x = next;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

View<Line> block(const Chain& chain, bool relaxed, Eigen::Index k) {
  return relaxed ? chain.relaxed_rows(k) : chain.rows(k);
}

// The lower side of interval k's y-box: K_{k+1}'s bottom.
double y_low(const Chain& chain, const LineAnalysis& a, Eigen::Index k1) {
  return k1 == chain.intervals() ? a.theta_end : chain.x_lo[k1];
}

}  // namespace

bool line_analysis(const Chain& chain, bool relaxed, double theta_begin, double theta_end, LineAnalysis& a,
                   const LineAnalysis* base) {
  const Eigen::Index n = chain.intervals();
  a.relaxed = relaxed;
  a.theta_end = theta_end;
  if (!(theta_end >= chain.x_lo[n] && theta_end <= chain.x_hi[n])) return false;
  if (base && (base->theta_end != theta_end || base->k_hi.size() != n + 1)) base = nullptr;
  Eigen::VectorXd& k_hi = a.k_hi;
  k_hi.resize(n + 1);
  k_hi[n] = theta_end;
  // Interval k is base's own where it has no coupling rows and meets the same K_{k+1}.
  auto same = [&](Eigen::Index k) {
    return base && chain.coupled_rows(k).n == 0 && k_hi[k + 1] == base->k_hi[k + 1];
  };
  IntervalLines lines;
  for (Eigen::Index k = n - 1; k >= 0; --k) {
    if (same(k)) {
      k_hi[k] = base->k_hi[k];
      continue;
    }
    double x_top = chain.x_hi[k];
    if (!interval_lines(block(chain, relaxed, k), chain.x_lo[k], x_top, lines)) return false;
    const double top = k_top(lines, chain.x_lo[k], x_top, y_low(chain, a, k + 1), k_hi[k + 1]);
    if (!std::isfinite(top)) return false;
    // Unbounded beyond θ_0 (which is given): the polygons name the point.
    if (k > 0 && top >= chain.cap * (1 - 1e-9)) return false;
    k_hi[k] = top;
  }
  const double tol0 = 1e-12 * std::max(1.0, k_hi[0]);
  if (theta_begin < chain.x_lo[0] - tol0 || theta_begin > k_hi[0] + tol0) return false;
  Eigen::VectorXd& theta = a.theta;
  theta.resize(n + 1);
  double x = std::clamp(theta_begin, chain.x_lo[0], k_hi[0]);
  theta[0] = theta_begin;
  for (Eigen::Index k = 0; k < n; ++k) {
    // The same interval from the same θ_k: base's step, to the bit (θ_0 may be clamped differently).
    if (k > 0 && same(k) && x == base->theta[k]) {
      theta[k + 1] = x = base->theta[k + 1];
      continue;
    }
    const Slice e = slice(block(chain, relaxed, k), x, y_low(chain, a, k + 1), k_hi[k + 1]);
    // θ_k at K_k's top, a root found to rounding, may see Hi a few ulps below Lo: the top is the slice.
    if (!meets(e.hi, e.lo, 1e-13) || !std::isfinite(e.hi)) return false;
    theta[k + 1] = x = e.hi;
  }
  theta[n] = theta_end;
  return true;
}

Eigen::VectorXd line_forward_pass(const Chain& chain, const LineAnalysis& a, double theta_begin,
                                  const Eigen::VectorXd& caps) {
  const Eigen::Index n = chain.intervals();
  const Eigen::VectorXd& g = a.theta;
  Eigen::VectorXd theta(n + 1);
  theta[0] = theta_begin;
  for (Eigen::Index k = 0; k < n; ++k) {
    // g_0 is the start speed, which the greedy pass may have clamped into K_0: interval 0 is always sliced.
    if (k > 0 && theta[k] == g[k] && caps[k + 1] >= g[k + 1]) {
      theta[k + 1] = g[k + 1];
      continue;
    }
    const double x = std::clamp(theta[k], chain.x_lo[k], a.k_hi[k]);
    const Slice e = slice(block(chain, a.relaxed, k), x, y_low(chain, a, k + 1), a.k_hi[k + 1]);
    theta[k + 1] = std::clamp(caps[k + 1], std::min(e.lo, e.hi), e.hi);  // a vertex to rounding: its top
  }
  return theta;
}

}  // namespace pathpace::detail
