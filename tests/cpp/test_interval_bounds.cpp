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

// hermite_speed_bounds: ‖e(s)‖² θ(s) <= v² between grid points for θ linear between the bounds. With e a
// cubic the Hermite model is e itself, so the check is exact; the bounds lose O(Δs²) against v²/‖e‖².
namespace {

Eigen::Vector3d cubic_e(double s) { return {0.3 + s - 0.8 * s * s * s, -0.5 + 0.4 * s * s, 0.2 - 0.7 * s + 0.3 * s * s * s}; }
Eigen::Vector3d cubic_de(double s) { return {1.0 - 2.4 * s * s, 0.8 * s, -0.7 + 0.9 * s * s}; }

// The largest ‖e‖² θ / v² over dense samples of every interval, and the smallest bound / (v²/‖e_k‖²).
void sweep(const Eigen::VectorXd& grid, const Eigen::VectorXd& bound, double v, int axis, double lo,
           double& over, double& tight) {
  over = 0.0;
  tight = INFINITY;
  for (Eigen::Index k = 0; k + 1 < grid.size(); ++k) {
    for (int m = 0; m <= 400; ++m) {
      const double l = m / 400.0, s = grid[k] + (grid[k + 1] - grid[k]) * l;
      const Eigen::Vector3d e = cubic_e(s);
      const double th = (1 - l) * bound[k] + l * bound[k + 1];
      const double lim = axis < 0 ? v : (e[axis] > 0 ? v : -lo);
      const double val = axis < 0 ? e.squaredNorm() : e[axis] * e[axis];
      over = std::max(over, val * th / (lim * lim));
    }
    const Eigen::Vector3d e = cubic_e(grid[k]);
    const double val = axis < 0 ? e.squaredNorm() : e[axis] * e[axis];
    const double lim = axis < 0 ? v : (e[axis] > 0 ? v : -lo);
    // Away from zeros of e (|e| > 0.1): an interval where one axis changes sign takes its tighter limit, and
    // near a zero v²/e² is strongly convex (the O(Δs²) loss grows as e'²/e²).
    if (val > 1e-2) tight = std::min(tight, bound[k] * val / (lim * lim));
  }
}

}  // namespace

TEST(IntervalBounds, HermiteSpeedBoundsHoldBetweenGridPointsAndAreTight) {
  for (int N : {10, 100, 1000}) {
    const Eigen::VectorXd grid = Eigen::VectorXd::LinSpaced(N + 1, 0.0, 1.0);
    Eigen::MatrixXd e(N + 1, 3), de(N + 1, 3);
    for (int k = 0; k <= N; ++k) {
      e.row(k) = cubic_e(grid[k]).transpose();
      de.row(k) = cubic_de(grid[k]).transpose();
    }
    const Eigen::VectorXd none = Eigen::VectorXd::Constant(N + 1, INFINITY);
    double over, tight;
    // The norm (a translational speed limit).
    sweep(grid, detail::hermite_speed_bounds(grid, e, de, -0.4, 0.4, none), 0.4, -1, -0.4, over, tight);
    EXPECT_LE(over, 1.0 + 1e-12) << "N = " << N;
    const double h = 1.0 / N;
    EXPECT_GE(tight, 1.0 - 20.0 * h * h) << "N = " << N;  // O(Δs²): not the flat bound, O(Δs)
    // One axis with different limits on its two sides (component 0 and 2 change sign on [0, 1]).
    for (int axis : {0, 1, 2}) {
      sweep(grid, detail::hermite_speed_bounds(grid, e.col(axis), de.col(axis), -0.25, 0.6, none), 0.6, axis, -0.25,
            over, tight);
      EXPECT_LE(over, 1.0 + 1e-12) << "N = " << N << ", axis " << axis;
      if (N == 1000) EXPECT_GE(tight, 1.0 - 1e-3) << "axis " << axis;
    }
  }
}

TEST(IntervalBounds, HermiteSpeedBoundsRespectTheStartBoundsAndMissingLimits) {
  const int N = 20;
  const Eigen::VectorXd grid = Eigen::VectorXd::LinSpaced(N + 1, 0.0, 2.0);
  Eigen::MatrixXd e(N + 1, 1), de(N + 1, 1);
  for (int k = 0; k <= N; ++k) {
    e(k, 0) = 1.0 + grid[k];  // > 0 everywhere: only hi applies
    de(k, 0) = 1.0;
  }
  Eigen::VectorXd start = Eigen::VectorXd::Constant(N + 1, INFINITY);
  start[7] = 0.01;
  const Eigen::VectorXd b = detail::hermite_speed_bounds(grid, e, de, -1.0, 2.0, start);
  EXPECT_LE(b[7], 0.01);
  // v²/e² is convex here, so the chord of the exact end values would exceed it between them: scaled below.
  for (int k = 0; k < N; ++k) {
    EXPECT_LT(b[k], 4.0 / (e(k, 0) * e(k, 0))) << k;
    for (int m = 1; m < 50; ++m) {
      const double l = m / 50.0, ee = e(k, 0) + l * (e(k + 1, 0) - e(k, 0));
      EXPECT_LE(ee * ee * ((1 - l) * b[k] + l * b[k + 1]), 4.0 * (1 + 1e-12)) << k;
    }
  }
  EXPECT_GE(b[0], 0.99 * 4.0);  // the loss is O(Δs²) = 1e-2 here, not the flat bound's 4/e(0.1)² = 3.3
  EXPECT_TRUE(std::isinf(detail::hermite_speed_bounds(grid, e, de, -1.0, INFINITY, start)[0]));  // no upper limit
  EXPECT_TRUE(std::isinf(detail::hermite_speed_bounds(grid, Eigen::MatrixXd::Zero(N + 1, 1), Eigen::MatrixXd::Zero(N + 1, 1),
                                                      -1.0, 2.0, start)[3]));  // e = 0: no bound
}
