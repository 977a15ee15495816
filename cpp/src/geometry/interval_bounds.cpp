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
  std::vector<double> t, E(static_cast<size_t>(dq) + 1), F(static_cast<size_t>(dq) + 1), bE(E.size()), bF(F.size()),
      bP(static_cast<size_t>(2 * dd) + 1);
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
      for (const Sub& sub : subs) {
        std::fill(E.begin(), E.end(), 0.0);
        std::fill(F.begin(), F.end(), 0.0);
        for (int x = 0; x <= 2 * dd; ++x) {
          const double p = sub.P[static_cast<size_t>(x)];
          F[static_cast<size_t>(x)] += p * sub.s0 / h;
          F[static_cast<size_t>(x) + 1] += p / h;
          E[static_cast<size_t>(x)] += p - p * sub.s0 / h;
          E[static_cast<size_t>(x) + 1] -= p / h;
        }
        bernstein(E.data(), dq, sub.w, bE.data());
        bernstein(F.data(), dq, sub.w, bF.data());
        for (int i = 0; i <= dq; ++i) worst = std::max(worst, m0 * bE[static_cast<size_t>(i)] + m1 * bF[static_cast<size_t>(i)]);
      }
      if (worst > v2) {
        m0 *= v2 / worst;
        m1 *= v2 / worst;
      }
      // The flat bound (max p'² over the whole interval at both ends) is valid too: keep it if it allows
      // more speed at both ends.
      if (m0 < flat && m1 < flat) m0 = m1 = flat;
      out[k] = std::min(out[k], m0);
      out[k + 1] = std::min(out[k + 1], m1);
    }
  }
  return out;
}

}  // namespace pathpace::detail
