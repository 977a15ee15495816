#include "detail/interval_bounds.hpp"

#include <algorithm>
#include <cmath>

#include "detail/validate.hpp"

namespace pathpace::detail {

void bernstein(const double* c, int d, double h, double* b) {
  // a_j = c_j h^j are the coefficients in t = τ / h on [0, 1]; b_i = Σ_{j<=i} C(i, j) / C(d, j) a_j.
  double a[16];
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
  std::vector<double> taylor(static_cast<size_t>(D) + 1), dp(static_cast<size_t>(d) + 1), ddp(static_cast<size_t>(d) + 1),
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
      const double hi = (piece + 1 < bp.size() - 1) ? std::min(sk1, bp[piece + 1]) : sk1;
      const double w = hi - lo;
      if (w <= 0.0) { ++piece; continue; }
      const Eigen::MatrixXd& c = path.coefficients()[static_cast<size_t>(piece)];
      const double x0 = lo - bp[piece], s0 = lo - sk;  // piece-local start; σ at the start
      const bool first_sub = lo == sk, last_sub = hi == sk1;
      for (Eigen::Index j = 0; j < n; ++j) {
        // Taylor coefficients of p_j at the sub-piece start: p_j(lo + τ) = Σ taylor[m] τ^m.
        for (int m = 0; m <= D; ++m) {
          double v = 0.0, binom = 1.0;  // Σ_{i>=m} c_i C(i, m) x0^(i - m)
          // Horner over i from D down to m of c_i C(i, m) x0^(i-m).
          v = 0.0;
          for (int i = D; i >= m; --i) {
            binom = 1.0;
            for (int r = 0; r < m; ++r) binom = binom * static_cast<double>(i - r) / static_cast<double>(r + 1);
            v = v * x0 + c(i, j) * binom;
          }
          taylor[static_cast<size_t>(m)] = v;
        }
        // p' and p'' in τ (degree d, zero-padded).
        std::fill(dp.begin(), dp.end(), 0.0);
        std::fill(ddp.begin(), ddp.end(), 0.0);
        for (int m = 1; m <= D; ++m) dp[static_cast<size_t>(m - 1)] = m * taylor[static_cast<size_t>(m)];
        for (int m = 2; m <= D; ++m) ddp[static_cast<size_t>(m - 2)] = m * (m - 1) * taylor[static_cast<size_t>(m)];
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

}  // namespace pathpace::detail
