// Bernstein bounds of q̈ and p' over grid intervals (guarantee = continuous) against dense sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/interval_bounds.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/sampled_path.hpp"

using namespace pathpace;

namespace {

// q̈_j(s) on interval k for θ_k, θ_{k+1}, by eq. (11) with θ(s) linear and s̈ constant.
double qdd(const Path& path, const Eigen::VectorXd& grid, Eigen::Index k, double s, double th0, double th1, int j) {
  Eigen::VectorXd q(path.dof()), dq(path.dof()), ddq(path.dof());
  path.evaluate(s, q, dq, ddq);
  const double h = grid[k + 1] - grid[k], u = (th1 - th0) / (2 * h);
  return ddq[j] * (th0 + 2 * u * (s - grid[k])) + dq[j] * u;
}

double check(const PiecewisePolynomialPath& path, const Eigen::VectorXd& grid, std::mt19937& rng) {
  const auto rows = detail::interval_rows(path, grid);
  std::uniform_real_distribution<double> U(0.0, 4.0), R(-0.3, 0.3);
  const int n = path.dof();
  double worst_gap = 0.0;
  for (Eigen::Index k = 0; k + 1 < grid.size(); ++k) {
    // Speeds of a timing: θ changes by s̈ Δs with s̈ of order θ (relative steps of a few tens of percent
    // on the coarse grid).
    const double th0 = U(rng), th1 = th0 * (1 + R(rng) * (grid[k + 1] - grid[k]) * 10);
    Eigen::VectorXd q(n), dq(n), ddq(n);
    for (int j = 0; j < n; ++j) {
      // The largest form bounds q̈_j everywhere on the interval; the end values are the eq. (26) rows.
      double bound = std::max(qdd(path, grid, k, grid[k], th0, th1, j), qdd(path, grid, k, grid[k + 1], th0, th1, j));
      double low = std::min(qdd(path, grid, k, grid[k], th0, th1, j), qdd(path, grid, k, grid[k + 1], th0, th1, j));
      for (size_t i = rows.offset[static_cast<size_t>(k)]; i < rows.offset[static_cast<size_t>(k) + 1]; ++i)
        if (rows.joint[i] == j) {
          bound = std::max(bound, rows.A[i] * th0 + rows.B[i] * th1);
          low = std::min(low, rows.A[i] * th0 + rows.B[i] * th1);
        }
      double top = -INFINITY;
      for (int m = 0; m <= 200; ++m) {
        const double s = grid[k] + (grid[k + 1] - grid[k]) * m / 200.0;
        const double v = qdd(path, grid, k, s, th0, th1, j);
        top = std::max(top, v);
        EXPECT_LE(v, bound + 1e-12 * (1 + std::abs(bound))) << "k = " << k << ", j = " << j;
        EXPECT_GE(v, low - 1e-12 * (1 + std::abs(low)));
        path.evaluate(s, q, dq, ddq);
        EXPECT_LE(dq[j], rows.dq_max(k, j) + 1e-12);
        EXPECT_GE(dq[j], rows.dq_min(k, j) - 1e-12);
      }
      worst_gap = std::max(worst_gap, (bound - top) / (1 + std::abs(top)));
    }
  }
  return worst_gap;
}

}  // namespace

TEST(IntervalBounds, BernsteinOfAPowerPolynomial) {
  // 1 - 2t + 3t² on [0, 2]: in t/2 it is 1 - 4x + 12x², Bernstein coefficients 1, -1, 9.
  const double c[3] = {1.0, -2.0, 3.0};
  double b[3];
  detail::bernstein(c, 2, 2.0, b);
  EXPECT_NEAR(b[0], 1.0, 1e-15);
  EXPECT_NEAR(b[1], -1.0, 1e-15);
  EXPECT_NEAR(b[2], 9.0, 1e-15);
}

TEST(IntervalBounds, CubicSplineOnGridsThatStraddleKnots) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::MatrixXd w(6, 3);
    for (Eigen::Index i = 0; i < w.size(); ++i) w.data()[i] = U(rng);
    CubicSplinePath path(w);
    // 13 intervals: most contain a knot of the 5-piece spline.
    // Conservative by O(Δs²) relative to q̈'s scale (often 0: the maximum is at an end); measured worst
    // 2e-2 at N = 13, 4e-4 at N = 100, 4e-6 at N = 1000.
    EXPECT_LT(check(path, Eigen::VectorXd::LinSpaced(14, 0.0, 1.0), rng), 0.05);
    EXPECT_LT(check(path, Eigen::VectorXd::LinSpaced(101, 0.0, 1.0), rng), 2e-3);
    EXPECT_LT(check(path, Eigen::VectorXd::LinSpaced(1001, 0.0, 1.0), rng), 2e-5);
  }
}

TEST(IntervalBounds, QuinticSampledPath) {
  std::mt19937 rng(5);
  const Eigen::VectorXd s = Eigen::VectorXd::LinSpaced(7, 0.0, 2.0);
  Eigen::MatrixXd q(7, 2), dq(7, 2), ddq(7, 2);
  for (Eigen::Index i = 0; i < 7; ++i) {
    q.row(i) << std::sin(s[i]), std::cos(2 * s[i]);
    dq.row(i) << std::cos(s[i]), -2 * std::sin(2 * s[i]);
    ddq.row(i) << -std::sin(s[i]), -4 * std::cos(2 * s[i]);
  }
  SampledPath path(s, q, dq, ddq);
  check(path, Eigen::VectorXd::LinSpaced(10, 0.0, 2.0), rng);
}
