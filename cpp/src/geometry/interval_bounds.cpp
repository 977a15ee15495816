#include "geometry/interval_bounds.hpp"

#include <algorithm>
#include <cmath>

#include "base/validate.hpp"

namespace pathpace::detail {

namespace {

// Taylor coefficients of coordinate j of a piece (power coefficients c about its breakpoint) about x0:
// p_j(x0 + τ) = Σ_m t[m] τ^m, t[m] = Σ_{i>=m} c_i C(i, m) x0^(i-m).
void taylor(const Eigen::MatrixXd& c, Eigen::Index j, double x0, std::vector<double>& t) {
  const int D = static_cast<int>(c.rows()) - 1;
  t.assign(static_cast<size_t>(D) + 1, 0.0);
  for (int m = 0; m <= D; ++m) {
    double v = 0.0;
    for (int i = D; i >= m; --i) {
      double binom = 1.0;
      for (int r = 0; r < m; ++r) binom = binom * static_cast<double>(i - r) / static_cast<double>(r + 1);
      v = v * x0 + c(i, j) * binom;
    }
    t[static_cast<size_t>(m)] = v;
  }
}

}  // namespace

void bernstein(const double* c, int d, double h, double* b) {
  // a_j = c_j h^j are the coefficients in t = τ / h on [0, 1]; b_i = Σ_{j<=i} C(i, j) / C(d, j) a_j.
  // The callers check the degrees (interval_rows: d = D - 1 <= 15; the velocity bounds: d <= 15); checked
  // again here, which also tells the compiler that a[] is written before it is read.
  double a[16];
  if (d < 0 || d > 15) fail("bernstein: degree " + std::to_string(d) + " is beyond 15");
  double hp = 1.0;
  for (int j = 0; j <= d; ++j, hp *= h) a[j] = c[j] * hp;
  for (int i = 0; i <= d; ++i) {
    double sum = 0.0, ratio = 1.0;  // C(i, j) / C(d, j), updated by j
    for (int j = 0; j <= i; ++j) {
      sum += ratio * a[j];
      ratio *= static_cast<double>(i - j) / static_cast<double>(d - j);
    }
    b[i] = sum;
  }
}

IntervalRows interval_rows(const PiecewisePolynomialPath& path, const Eigen::VectorXd& grid) {
  const Eigen::Index N = grid.size() - 1, n = path.dof();
  const Eigen::VectorXd& bp = path.breakpoints();
  const int D = static_cast<int>(path.coefficients()[0].rows()) - 1;  // degree of p
  if (D > 16)
    fail("guarantee = 'continuous' handles paths of degree <= 16; this one has degree " + std::to_string(D));
  // A_j and B_j have degree max(D - 1, D - 2 + 1) = D - 1 (2σ p'' and p' both have degree D - 1).
  const int d = std::max(D - 1, 0);
  IntervalRows out;
  out.offset.assign(static_cast<size_t>(N) + 1, 0);
  out.dq_min.resize(N, n);
  out.dq_max.resize(N, n);
  std::vector<double> t, dp(static_cast<size_t>(d) + 1), ddp(static_cast<size_t>(d) + 1),
      A(static_cast<size_t>(d) + 1), B(static_cast<size_t>(d) + 1), bA(static_cast<size_t>(d) + 1),
      bB(static_cast<size_t>(d) + 1), bdp(static_cast<size_t>(d) + 1);
  for (Eigen::Index k = 0; k < N; ++k) {
    const double sk = grid[k], sk1 = grid[k + 1], h = sk1 - sk;
    out.dq_min.row(k).setConstant(std::numeric_limits<double>::infinity());
    out.dq_max.row(k).setConstant(-std::numeric_limits<double>::infinity());
    // Sub-pieces: the interval cut at the path's breakpoints inside it.
    double lo = sk;
    Eigen::Index piece = path.piece(sk);
    while (lo < sk1) {
      double hi = (piece + 1 < bp.size() - 1) ? std::min(sk1, bp[piece + 1]) : sk1;
      // A breakpoint within rounding of the interval's end is the end (a sliver piece would only repeat
      // the end's rows).
      if (sk1 - hi <= 1e-12 * h) hi = sk1;
      const double w = hi - lo;
      if (w <= 1e-12 * h) {
        ++piece;
        continue;
      }
      const Eigen::MatrixXd& c = path.coefficients()[static_cast<size_t>(piece)];
      const double x0 = lo - bp[piece], s0 = lo - sk;  // piece-local start; σ at the start
      const bool first_sub = lo == sk, last_sub = hi == sk1;
      for (Eigen::Index j = 0; j < n; ++j) {
        // Taylor coefficients of p_j at the sub-piece start: p_j(lo + τ) = Σ t[m] τ^m.
        taylor(c, j, x0, t);
        // p' and p'' in τ (degree d, zero-padded).
        std::fill(dp.begin(), dp.end(), 0.0);
        std::fill(ddp.begin(), ddp.end(), 0.0);
        for (int m = 1; m <= D; ++m) dp[static_cast<size_t>(m - 1)] = m * t[static_cast<size_t>(m)];
        for (int m = 2; m <= D; ++m) ddp[static_cast<size_t>(m - 2)] = m * (m - 1) * t[static_cast<size_t>(m)];
        // E = 2σ p'' + p' with σ = s0 + τ: (2 s0 + 2τ) p'' + p'.
        for (int m = 0; m <= d; ++m) {
          double e = dp[static_cast<size_t>(m)] + 2.0 * s0 * ddp[static_cast<size_t>(m)];
          if (m >= 1) e += 2.0 * ddp[static_cast<size_t>(m - 1)];
          B[static_cast<size_t>(m)] = e / (2.0 * h);
          A[static_cast<size_t>(m)] = ddp[static_cast<size_t>(m)] - B[static_cast<size_t>(m)];
        }
        bernstein(A.data(), d, w, bA.data());
        bernstein(B.data(), d, w, bB.data());
        bernstein(dp.data(), d, w, bdp.data());
        for (int i = 0; i <= d; ++i) {
          out.dq_min(k, j) = std::min(out.dq_min(k, j), bdp[static_cast<size_t>(i)]);
          out.dq_max(k, j) = std::max(out.dq_max(k, j), bdp[static_cast<size_t>(i)]);
          // The end forms of the whole interval are eq. (26)'s rows, already present.
          if ((first_sub && i == 0) || (last_sub && i == d)) continue;
          out.joint.push_back(static_cast<int>(j));
          out.A.push_back(bA[static_cast<size_t>(i)]);
          out.B.push_back(bB[static_cast<size_t>(i)]);
        }
      }
      lo = hi;
      ++piece;
    }
    out.offset[static_cast<size_t>(k) + 1] = out.joint.size();
  }
  return out;
}

namespace {

// The pieces of [a, b] cut at the path's breakpoints and at `extra` cuts (if inside): f(piece, lo, hi).
// Cuts within rounding of another cut are dropped (slivers would only repeat their end's values).
template <class F>
void for_each_sub(const PiecewisePolynomialPath& path, double a, double b, std::initializer_list<double> extra, F f) {
  const Eigen::VectorXd& bp = path.breakpoints();
  const double tiny = 1e-12 * (b - a);
  std::vector<double> cuts{a};
  for (Eigen::Index i = path.piece(a) + 1; i < bp.size() - 1 && bp[i] < b; ++i)
    if (bp[i] > a + tiny && bp[i] < b - tiny) cuts.push_back(bp[i]);
  for (double cut : extra)
    if (cut > a + tiny && cut < b - tiny) cuts.push_back(cut);
  std::sort(cuts.begin(), cuts.end());
  cuts.push_back(b);
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (cuts[i + 1] - cuts[i] <= tiny) continue;
    f(path.piece(0.5 * (cuts[i] + cuts[i + 1])), cuts[i], cuts[i + 1]);
  }
}

// The largest Bernstein coefficient, over a piece [s0, s0 + w] of an interval of width h, of
// P(τ) ((1 - σ/h) m0 + (σ/h) m1) with σ = s0 + τ and P of degree d in τ (d <= 14): an upper bound of the
// row's value there when ṡ² follows the line from m0 to m1 across the interval.
double line_product_bound(const double* P, int d, double s0, double w, double h, double m0, double m1) {
  double E[16] = {}, F[16] = {}, bE[16], bF[16];
  for (int x = 0; x <= d; ++x) {
    const double p = P[x];
    F[x] += p * s0 / h;
    F[x + 1] += p / h;
    E[x] += p - p * s0 / h;
    E[x + 1] -= p / h;
  }
  bernstein(E, d + 1, w, bE);
  bernstein(F, d + 1, w, bF);
  double worst = 0.0;
  for (int i = 0; i <= d + 1; ++i) worst = std::max(worst, m0 * bE[i] + m1 * bF[i]);
  return worst;
}

// The bound x <= (1 - λ) m0 + λ m1 over an interval whose largest product with the rate's square is
// `worst`: scaled down until that product is v2, replaced by the flat bound if that allows more at both
// ends, and written into the ends' bounds.
void settle_line(double worst, double v2, double flat, double m0, double m1, double& out0, double& out1) {
  if (worst > v2) {
    m0 *= v2 / worst;
    m1 *= v2 / worst;
  }
  if (m0 < flat && m1 < flat) m0 = m1 = flat;
  out0 = std::min(out0, m0);
  out1 = std::min(out1, m1);
}

}  // namespace

Eigen::VectorXd continuous_speed_bounds(const PiecewisePolynomialPath& path, const Eigen::VectorXd& grid,
                                        const IntervalRows& ir, const Eigen::MatrixXd& dqg, const Eigen::VectorXd& vmin,
                                        const Eigen::VectorXd& vmax) {
  const Eigen::Index N = grid.size() - 1, n = path.dof();
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd out = Eigen::VectorXd::Constant(N + 1, inf);
  const Eigen::VectorXd& bp = path.breakpoints();
  const int D = static_cast<int>(path.coefficients()[0].rows()) - 1;
  const int dd = std::max(D - 1, 0);   // degree of p'
  const int dq = 2 * dd + 1;           // degree of p'² × line
  if (dq > 15) fail("guarantee = 'continuous' handles paths of degree <= 8 for velocity limits; this one has degree " +
                    std::to_string(D));
  // The speed bound at the grid points themselves (eq. 16): no end of a line needs to exceed it.
  Eigen::VectorXd G = Eigen::VectorXd::Constant(N + 1, inf);
  for (Eigen::Index k = 0; k <= N; ++k)
    for (Eigen::Index j = 0; j < n; ++j) {
      const double d = dqg(k, j), lim = d > 0.0 ? vmax[j] : vmin[j];
      if (d != 0.0 && std::isfinite(lim)) G[k] = std::min(G[k], (lim / d) * (lim / d));
    }
  struct Sub {
    double s0, w;               // σ at its start, width
    std::vector<double> P;      // p'_j² in τ
  };
  std::vector<Sub> subs;
  std::vector<double> t, bP(static_cast<size_t>(2 * dd) + 1);
  for (Eigen::Index k = 0; k < N; ++k) {
    const double sk = grid[k], sk1 = grid[k + 1], h = sk1 - sk;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double hi = ir.dq_max(k, j), lo = ir.dq_min(k, j);
      // The limit that applies: by the sign of p'_j over the interval, the tighter one if it changes sign.
      double v = inf;
      if (hi > 0.0) v = std::min(v, std::abs(vmax[j]));
      if (lo < 0.0) v = std::min(v, std::abs(vmin[j]));
      if (!std::isfinite(v)) continue;
      const double v2 = v * v;
      // The line starts from the exact bounds at the ends, V = v²/p'_j² there, then is checked over the
      // whole interval and scaled down if needed (where V is convex between the ends, by O(Δs²)).
      subs.clear();
      double max_all = 0.0;
      for_each_sub(path, sk, sk1, {sk + 0.125 * h, sk + 0.5 * h, sk1 - 0.125 * h}, [&](Eigen::Index piece, double a, double b) {
        Sub sub{a - sk, b - a, std::vector<double>(static_cast<size_t>(2 * dd) + 1, 0.0)};
        taylor(path.coefficients()[static_cast<size_t>(piece)], j, a - bp[piece], t);
        for (int x = 0; x < dd + 1; ++x)
          for (int y = 0; y < dd + 1; ++y)
            sub.P[static_cast<size_t>(x + y)] += (x + 1) * t[static_cast<size_t>(x) + 1] * (y + 1) * t[static_cast<size_t>(y) + 1];
        bernstein(sub.P.data(), 2 * dd, sub.w, bP.data());
        const double m = *std::max_element(bP.begin(), bP.end());
        max_all = std::max(max_all, m);
        subs.push_back(std::move(sub));
      });
      // No end needs more than the grid point's own bound over all joints: aiming the line there keeps
      // it from cutting through v²/p'_j² where joint j does not bind at an end (p'_j ~ 0 there).
      auto at = [&](Eigen::Index i) { return dqg(i, j) != 0.0 ? v2 / (dqg(i, j) * dqg(i, j)) : inf; };
      double m0 = std::min(at(k), G[k]), m1 = std::min(at(k + 1), G[k + 1]);
      const double flat = v2 / max_all;
      if (!std::isfinite(m0) || !std::isfinite(m1)) m0 = m1 = flat;
      double worst = 0.0;  // max over the interval of p'² ((1 - λ) m0 + λ m1), by Bernstein per piece
      for (const Sub& sub : subs) worst = std::max(worst, line_product_bound(sub.P.data(), 2 * dd, sub.s0, sub.w, h, m0, m1));
      // The flat bound (max p'² over the whole interval at both ends) is valid too.
      settle_line(worst, v2, flat, m0, m1, out[k], out[k + 1]);
    }
  }
  return out;
}

namespace {

// The coefficients of Σ_j c[j] τ^j about τ = a (in place, degree d).
void shift(double* c, int d, double a) {
  for (int i = 0; i < d; ++i)
    for (int j = d - 1; j >= i; --j) c[j] += a * c[j + 1];
}

// Per interval k, an estimate of max |e⁽⁴⁾| (over e's components) on it: 6 times the third divided
// differences of e' over four neighbouring grid points, the largest of the windows that hold the interval
// (a sampled estimate, which the caller's audit checks; 0 where the grid has fewer than four points).
Eigen::VectorXd fourth_derivative_estimate(const Eigen::VectorXd& grid, const Eigen::MatrixXd& de) {
  const Eigen::Index N = grid.size() - 1;
  Eigen::VectorXd window = Eigen::VectorXd::Zero(std::max<Eigen::Index>(N - 2, 0)), out = Eigen::VectorXd::Zero(N);
  for (Eigen::Index i = 0; i + 3 <= N; ++i)
    for (Eigen::Index c = 0; c < de.cols(); ++c) {
      double d[4];
      for (int r = 0; r < 4; ++r) d[r] = de(i + r, c);
      for (int order = 1; order <= 3; ++order)
        for (int r = 3; r >= order; --r) d[r] = (d[r] - d[r - 1]) / (grid[i + r] - grid[i + r - order]);
      window[i] = std::max(window[i], 6.0 * std::abs(d[3]));
    }
  for (Eigen::Index k = 0; k < N; ++k)
    for (Eigen::Index i = std::max<Eigen::Index>(k - 2, 0); i <= k && i + 3 <= N; ++i) out[k] = std::max(out[k], window[i]);
  return out;
}

}  // namespace

Eigen::VectorXd hermite_speed_bounds(const Eigen::VectorXd& grid, const Eigen::MatrixXd& e, const Eigen::MatrixXd& de,
                                     double lo, double hi, const Eigen::VectorXd& start) {
  const Eigen::Index N = grid.size() - 1, m = e.cols();
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd out = Eigen::VectorXd::Constant(N + 1, inf);
  if (m < 1 || m > 3) fail("hermite_speed_bounds: " + std::to_string(m) + " components, expected 1 to 3");
  const double cuts[5] = {0.0, 0.125, 0.5, 0.875, 1.0};
  const Eigen::VectorXd d4 = fourth_derivative_estimate(grid, de);
  for (Eigen::Index k = 0; k < N; ++k) {
    const double h = grid[k + 1] - grid[k];
    // The model's error per component, |e - H| <= h⁴/384 max |e⁽⁴⁾|, with twice the estimate.
    const double delta = 2.0 * std::sqrt(static_cast<double>(m)) * std::pow(h, 4) / 384.0 * d4[k];
    // Each component's cubic in σ = s - s_k (Hermite: values and slopes at both ends).
    double H[3][4];
    for (Eigen::Index i = 0; i < m; ++i) {
      const double e0 = e(k, i), e1 = e(k + 1, i), d0 = de(k, i), d1 = de(k + 1, i), q = (e1 - e0) / h;
      H[i][0] = e0;
      H[i][1] = d0;
      H[i][2] = (3.0 * q - 2.0 * d0 - d1) / h;
      H[i][3] = (d0 + d1 - 2.0 * q) / (h * h);
    }
    double v = hi;
    if (m == 1) {
      double b[4];
      bernstein(H[0], 3, h, b);
      const double bmin = *std::min_element(b, b + 4), bmax = *std::max_element(b, b + 4);
      v = inf;
      if (bmax + delta > 0.0) v = std::min(v, std::abs(hi));
      if (bmin - delta < 0.0) v = std::min(v, std::abs(lo));
    }
    if (!std::isfinite(v)) continue;
    const double v2 = v * v;
    // Per piece [a, a + w] of the interval: P = ‖H‖² in τ = σ - a (degree 6), and its Bernstein maximum.
    double P[4][7], bP[7];
    double max_all = 0.0;
    for (int p = 0; p < 4; ++p) {
      const double a = cuts[p] * h, w = (cuts[p + 1] - cuts[p]) * h;
      std::fill(P[p], P[p] + 7, 0.0);
      for (Eigen::Index i = 0; i < m; ++i) {
        double c[4] = {H[i][0], H[i][1], H[i][2], H[i][3]};
        shift(c, 3, a);
        for (int x = 0; x < 4; ++x)
          for (int y = 0; y < 4; ++y) P[p][x + y] += c[x] * c[y];
      }
      bernstein(P[p], 6, w, bP);
      max_all = std::max(max_all, *std::max_element(bP, bP + 7));
    }
    if (!(max_all > 0.0) && delta == 0.0) continue;  // e = 0 on the whole interval: no bound
    // ‖e‖² <= ‖H‖² + pad on the interval, if the estimate of e⁽⁴⁾ holds.
    const double pad = delta * (2.0 * std::sqrt(max_all) + delta);
    const double n0 = e.row(k).squaredNorm(), n1 = e.row(k + 1).squaredNorm();
    double m0 = std::min(n0 > 0.0 ? v2 / n0 : inf, start[k]), m1 = std::min(n1 > 0.0 ? v2 / n1 : inf, start[k + 1]);
    const double flat = v2 / (max_all + pad);
    if (!std::isfinite(m0) || !std::isfinite(m1)) m0 = m1 = flat;
    // max over the interval of P ((1 - σ/h) m0 + (σ/h) m1), σ = a + τ, by Bernstein per piece.
    double worst = 0.0;
    for (int p = 0; p < 4; ++p)
      worst = std::max(worst, line_product_bound(P[p], 6, cuts[p] * h, (cuts[p + 1] - cuts[p]) * h, h, m0, m1));
    worst += pad * std::max(m0, m1);
    settle_line(worst, v2, flat, m0, m1, out[k], out[k + 1]);
  }
  return out;
}

}  // namespace pathpace::detail
