// Scaling laws of the discretised problem (eq. 25-27), which is homogeneous: with x = ṡ² and u = s̈
// scaled by σ every half-plane a x + b u <= c keeps its shape with c / σ, and T scales by 1/√σ. So
//   velocity limits:     T(L p) = L T(p),          T(p, c vmax) = T(p, vmax) / c;
//   acceleration limits: T(p, a amax) = T(p, amax) / √a;
//   reparametrising s by λ (knots λ t) leaves T unchanged.
// The solver works in units where the speeds are ~1 (detail::Scale); before, a cap ṡ² <= 1e15 made
// L = 1e-9 UNBOUNDED and absolute tolerances left T 7e-4 short at a = 1e-9 (issue 10).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "solve/grid_sets.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/time_scaling_problem.hpp"

using namespace pathpace;

namespace {

Eigen::MatrixXd waypoints(int seed) {
  // Fixed pseudo-random waypoints, two joints (no RNG dependence across platforms).
  Eigen::MatrixXd w(5, 2);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 2; ++j) w(i, j) = std::sin(12.9898 * (i + 1) + 78.233 * (j + 1) + 37.719 * seed);
  return w;
}

Result solve(const Eigen::MatrixXd& w, double vmax, double amax, int grid = 60, double knot_scale = 1.0) {
  Eigen::VectorXd knots = Eigen::VectorXd::LinSpaced(w.rows(), 0.0, knot_scale);
  TimeScalingProblem p(std::make_shared<CubicSplinePath>(w, knots), grid);
  if (vmax > 0) p.add_velocity_limits(-vmax * Eigen::VectorXd::Ones(2), vmax * Eigen::VectorXd::Ones(2));
  if (amax > 0) p.add_acceleration_limits(-amax * Eigen::VectorXd::Ones(2), amax * Eigen::VectorXd::Ones(2));
  return p.solve();
}

const double kExponents[] = {-12, -9, -6, -3, 3, 6, 9, 12};

}  // namespace

TEST(Scaling, VelocityLimitedTimeIsProportionalToPathLength) {
  for (int seed = 0; seed < 3; ++seed) {
    const Result ref = solve(waypoints(seed), 1.0, 0.0);
    ASSERT_EQ(ref.status, Status::Optimal) << ref.message;
    for (double e : kExponents) {
      const double L = std::pow(10.0, e);
      const Result r = solve(L * waypoints(seed), 1.0, 0.0);
      ASSERT_EQ(r.status, Status::Optimal) << "L = " << L << ": " << r.message;  // was UNBOUNDED at L <= 1e-9
      EXPECT_NEAR(r.duration / (L * ref.duration), 1.0, 1e-12) << "L = " << L;
    }
  }
}

TEST(Scaling, VelocityLimitedTimeIsInverseToTheLimit) {
  for (int seed = 0; seed < 3; ++seed) {
    const Result ref = solve(waypoints(seed), 1.0, 0.0);
    for (double e : kExponents) {
      const double c = std::pow(10.0, e);
      const Result r = solve(waypoints(seed), c, 0.0);
      ASSERT_EQ(r.status, Status::Optimal) << "vmax = " << c << ": " << r.message;  // was UNBOUNDED at >= 1e8
      EXPECT_NEAR(r.duration * c / ref.duration, 1.0, 1e-12) << "vmax = " << c;
    }
  }
}

TEST(Scaling, AccelerationLimitedTimeScalesWithOneOverSqrtA) {
  for (int seed = 0; seed < 3; ++seed) {
    const Result ref = solve(waypoints(seed), 0.0, 1.0);
    ASSERT_EQ(ref.status, Status::Optimal) << ref.message;
    for (double e : kExponents) {
      const double a = std::pow(10.0, e);
      const Result r = solve(waypoints(seed), 0.0, a);
      ASSERT_EQ(r.status, Status::Optimal) << "amax = " << a << ": " << r.message;
      // The solves are certified to the default tolerance 1e-7 only; the scaled problems are the same
      // problem up to powers of two and rounding, so they agree far closer than that.
      EXPECT_NEAR(r.duration * std::sqrt(a) / ref.duration, 1.0, 1e-11) << "amax = " << a;
    }
  }
}

TEST(Scaling, ReparametrisingTheLengthOfSLeavesTheTimingUnchanged) {
  // Knots at λ t: p'(s) scales by 1/λ, the grid's Δs by λ, so s̈ by 1/λ² (the s̈ box of the feasible
  // sets is in units of the path's length too).
  for (int seed = 0; seed < 2; ++seed) {
    const Result ref = solve(waypoints(seed), 1.0, 1.0);
    ASSERT_EQ(ref.status, Status::Optimal) << ref.message;
    for (double e : {-9.0, -6.0, 6.0, 9.0}) {
      const double lambda = std::pow(10.0, e);
      const Result r = solve(waypoints(seed), 1.0, 1.0, 60, lambda);
      ASSERT_EQ(r.status, Status::Optimal) << "lambda = " << lambda << ": " << r.message;
      EXPECT_NEAR(r.duration / ref.duration, 1.0, 1e-11) << "lambda = " << lambda;
    }
  }
}

TEST(Scaling, BoundedProblemsAreNeverUnbounded) {
  // The two reproducers: path length 1e-9 with vmax 1, vmax 1e8 on a unit path; and limits
  // over twenty decades (the backward-controllable speeds reach 1e18 of the typical ones).
  Eigen::MatrixXd w = waypoints(0);
  EXPECT_EQ(solve(1e-9 * w, 1.0, 0.0).status, Status::Optimal);
  EXPECT_EQ(solve(w, 1e8, 0.0).status, Status::Optimal);
  TimeScalingProblem p(std::make_shared<CubicSplinePath>(w), 200);
  p.add_velocity_limits(-Eigen::Vector2d(2.7e6, 3e5), Eigen::Vector2d(2.7e6, 3e5));
  p.add_acceleration_limits(-Eigen::Vector2d(1.7e-6, 3.5e12), Eigen::Vector2d(1.7e13, 2.7e8));
  EXPECT_EQ(p.solve().status, Status::Optimal);
}

TEST(Scaling, ProblemScaleIsAPowerOfTwoThatFollowsTheProblem) {
  // Units are powers of two (exact rescaling) and homogeneous: 4x the limits, 16x the speed unit.
  const Eigen::VectorXd s = Eigen::VectorXd::LinSpaced(11, 0.0, 3.0);
  std::vector<ConstraintRows> rows(1);
  rows[0].resize(11, 1);
  rows[0].a.setConstant(1.0);
  rows[0].c.setConstant(1e-20);
  const detail::Scale a = detail::problem_scale(s, rows);
  rows[0].c.setConstant(16e-20);
  const detail::Scale b = detail::problem_scale(s, rows);
  EXPECT_EQ(a.s_unit, 2.0);
  int exponent = 0;
  EXPECT_EQ(std::frexp(a.x_unit, &exponent), 0.5);
  EXPECT_EQ(b.x_unit, 16.0 * a.x_unit);
  EXPECT_LE(a.x_unit, 1e-20);
  EXPECT_GT(a.x_unit, 0.5e-20);
  EXPECT_EQ(a.u_unit, a.x_unit / a.s_unit);
}
