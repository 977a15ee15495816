// Solver contracts on problems with known optima.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "geometry/polygon2d.hpp"
#include "pathpace/pathpace.hpp"
#include "test_util.hpp"

using namespace pathpace;

namespace {

using test::ClosedFormPath;
using test::error_of;

// q(s) = s (length), s in [0, 1]: p' constant, p'' = 0.
std::shared_ptr<Path> line1d(double length) {
  return std::make_shared<ClosedFormPath>(1, [length](double s, auto q, auto dq, auto ddq) {
    q[0] = s * length;
    dq[0] = length;
    ddq[0] = 0.0;
  });
}

// q(s) = (cos 2πs, sin 2πs): a circle, p'' != 0.
std::shared_ptr<Path> circle() {
  return std::make_shared<ClosedFormPath>(2, [](double s, auto q, auto dq, auto ddq) {
    const double w = 2 * M_PI;
    q << std::cos(w * s), std::sin(w * s);
    dq << -w * std::sin(w * s), w * std::cos(w * s);
    ddq << -w * w * std::cos(w * s), -w * w * std::sin(w * s);
  });
}

// q(s) = (sin 3πs, s): the first coordinate reverses three times, where p' is small against p'': the
// acceleration rows there couple θ_k and θ_{k+1} positively (no lattice), so SLP windows are needed.
std::shared_ptr<Path> reversing() {
  return std::make_shared<ClosedFormPath>(2, [](double s, auto q, auto dq, auto ddq) {
    const double w = 3 * M_PI;
    q << std::sin(w * s), s;
    dq << w * std::cos(w * s), 1.0;
    ddq << -w * w * std::sin(w * s), 0.0;
  });
}

}  // namespace

TEST(Polygon, BoxCutByDiagonalKeepsExactVertices) {
  detail::Polygon2d p;
  p.reset(0, 1e15, -1e15, 1e15);
  EXPECT_TRUE(p.clip({1.0, 1.0, 1.0, 7}));     // x + y <= 1
  EXPECT_TRUE(p.clip({1.0, -1.0, 1.0, 8}));    // x - y <= 1
  EXPECT_FALSE(p.clip({1.0, 0.0, 5.0, 9}));    // x <= 5: redundant
  double x_lo, x_hi;
  p.x_range(x_lo, x_hi);
  EXPECT_EQ(x_hi, 1.0);  // exactly, despite the 1e15 box
  EXPECT_EQ(x_lo, 0.0);
  EXPECT_EQ(p.edges().size(), 3u);  // left side, and the two diagonals
}

TEST(Polygon, EmptyGivesThreeLineCertificate) {
  detail::Polygon2d p;
  p.reset(0, 10, -10, 10);
  p.clip({1.0, 1.0, 1.0, 1});
  p.clip({1.0, -1.0, 1.0, 2});
  p.clip({-1.0, 0.0, -2.0, 3});  // x >= 2 contradicts x <= 1 - |y|
  ASSERT_TRUE(p.empty());
  EXPECT_EQ(p.emptied_by().id, 3);
  EXPECT_EQ(std::min(p.certificate_edge(0).id, p.certificate_edge(1).id), 1);
  EXPECT_EQ(std::max(p.certificate_edge(0).id, p.certificate_edge(1).id), 2);
}

TEST(Polygon, SegmentFromEqualityKeepsItsEnds) {
  detail::Polygon2d p;
  p.reset(0, 10, -10, 10);
  p.clip({0.0, 1.0, 1.0, 1});   // y <= 1
  p.clip({0.0, -1.0, -1.0, 2});  // y >= 1
  p.clip({1.0, 1.0, 4.0, 3});    // x + y <= 4 -> x <= 3
  ASSERT_FALSE(p.empty());
  double x_lo, x_hi;
  p.x_range(x_lo, x_hi);
  EXPECT_NEAR(x_hi, 3.0, 1e-12);
  EXPECT_NEAR(x_lo, 0.0, 1e-12);
}

TEST(Solver, LineUnderVelocityAndAccelerationLimitsApproachesFourSeconds) {
  // 0 -> 3 with |v|, |a| <= 1: accelerate 1 s, cruise 1 s, decelerate 1 s... T = 4 s exactly in
  // continuous time (1 + 2 + 1: the cruise covers 2 of the 3 units).
  for (int N : {16, 64, 256, 1024}) {
    TimeScalingProblem prob(line1d(3.0), N);
    prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1));
    prob.add_acceleration_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1));
    const Result r = prob.solve();
    ASSERT_EQ(r.status, Status::Optimal) << r.message;
    EXPECT_TRUE(r.stats.greatest_element);
    EXPECT_GE(r.duration, 4.0 - 1e-12);
    if (N == 1024) EXPECT_LT(r.duration - 4.0, 1e-4);
  }
}

TEST(Solver, SlpMatchesGreatestElementOnLatticeProblem) {
  TimeScalingProblem prob(circle(), 200);
  prob.add_velocity_limits(Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
  prob.add_acceleration_limits(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3));
  const Result fast = prob.solve();
  SolverOptions o;
  o.method = Method::Slp;
  const Result slow = prob.solve(o);
  ASSERT_EQ(fast.status, Status::Optimal) << fast.message;
  ASSERT_EQ(slow.status, Status::Optimal) << slow.message;
  EXPECT_GT(slow.stats.lp_solves, 0);
  EXPECT_NEAR(slow.duration, fast.duration, 1e-9 * fast.duration);
}

TEST(Solver, InfeasibleReportsIndexAndRows) {
  // A linear row that demands s̈ >= 1 at rest at s = 1 while the end speed must be 0 and x <= 0.25...
  TimeScalingProblem prob(line1d(1.0), 10);
  prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(11, 1), B = Eigen::MatrixXd::Ones(11, 1), C = Eigen::MatrixXd::Zero(11, 1);
  Eigen::MatrixXd lo = Eigen::MatrixXd::Constant(11, 1, 1.0), hi = Eigen::MatrixXd::Constant(11, 1, 2.0);
  prob.add_linear_constraint(A, B, C, lo, hi, "push");
  const Result r = prob.solve();
  EXPECT_EQ(r.status, Status::Infeasible);
  EXPECT_GE(r.infeasibility.grid_index, 0);
  EXPECT_FALSE(r.infeasibility.constraints.empty());
  EXPECT_NE(r.message.find("grid index"), std::string::npos) << r.message;
}

TEST(Solver, BadInputNamesArgument) {
  EXPECT_THROW(TimeScalingProblem(line1d(1.0), 0), InvalidInput);
  TimeScalingProblem prob(line1d(1.0), 4);
  EXPECT_EQ(error_of([&] { prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, -2)); }),
            "vmax[0] = -2 must be >= 0");
}

TEST(Paths, CubicSplineThroughWaypointsWithNaturalEnds) {
  Eigen::MatrixXd w(4, 2);
  w << 0, 0, 1, 2, 3, 1, 4, 4;
  CubicSplinePath p(w, KnotSpacing::Uniform, SplineBoundary::Natural);
  Eigen::VectorXd q(2), dq(2), ddq(2);
  for (int i = 0; i < 4; ++i) {
    p.evaluate(i / 3.0, q, dq, ddq);
    EXPECT_NEAR((q - w.row(i).transpose()).norm(), 0.0, 1e-14);
  }
  p.evaluate(0.0, q, dq, ddq);
  EXPECT_NEAR(ddq.norm(), 0.0, 1e-12);
  p.evaluate(1.0, q, dq, ddq);
  EXPECT_NEAR(ddq.norm(), 0.0, 1e-12);
  // Derivatives against central differences in the middle of a piece.
  const double s = 0.41, h = 1e-5;
  Eigen::VectorXd qp(2), qm(2), t1(2), t2(2);
  p.evaluate(s + h, qp, t1, t2);
  p.evaluate(s - h, qm, t1, t2);
  p.evaluate(s, q, dq, ddq);
  EXPECT_NEAR((dq - (qp - qm) / (2 * h)).norm(), 0.0, 1e-8);
}

TEST(Paths, SampledPathReproducesAQuinticExactly) {
  // q(s) = s^5 - 2 s^3 + s: the quintic Hermite interpolant of its own samples is itself.
  auto f = [](double s) { return std::pow(s, 5) - 2 * std::pow(s, 3) + s; };
  auto df = [](double s) { return 5 * std::pow(s, 4) - 6 * s * s + 1; };
  auto ddf = [](double s) { return 20 * std::pow(s, 3) - 12 * s; };
  Eigen::VectorXd s(3);
  s << 0.0, 0.4, 1.0;
  Eigen::MatrixXd q(3, 1), dq(3, 1), ddq(3, 1);
  for (int i = 0; i < 3; ++i) {
    q(i, 0) = f(s[i]);
    dq(i, 0) = df(s[i]);
    ddq(i, 0) = ddf(s[i]);
  }
  SampledPath p(s, q, dq, ddq);
  Eigen::VectorXd a(1), b(1), c(1);
  for (double x : {0.1, 0.33, 0.5, 0.77, 0.99}) {
    p.evaluate(x, a, b, c);
    EXPECT_NEAR(a[0], f(x), 1e-13);
    EXPECT_NEAR(b[0], df(x), 1e-12);
    EXPECT_NEAR(c[0], ddf(x), 1e-11);
  }
}

TEST(Trajectory, TimesFollowEquation25AndEndsAtRest) {
  TimeScalingProblem prob(line1d(3.0), 300);
  prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1));
  prob.add_acceleration_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1));
  const Result r = prob.solve();
  const Trajectory t = r.trajectory();
  EXPECT_DOUBLE_EQ(t.duration(), r.duration);
  Eigen::VectorXd ts(3);
  ts << 0.0, 0.5 * r.duration, r.duration;
  const Eigen::MatrixXd q = t.q(ts), qd = t.qd(ts);
  EXPECT_NEAR(q(0, 0), 0.0, 1e-15);
  EXPECT_NEAR(q(2, 0), 3.0, 1e-12);
  EXPECT_NEAR(qd(0, 0), 0.0, 1e-15);
  EXPECT_NEAR(qd(1, 0), 1.0, 1e-9);  // cruising at the velocity limit
  EXPECT_NEAR(qd(2, 0), 0.0, 1e-12);
  EXPECT_THROW(t.sample_times(0.0), InvalidInput);
}

namespace {

TimeScalingProblem reversing_problem(int N) {
  TimeScalingProblem prob(reversing(), N);
  prob.add_velocity_limits(Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));
  prob.add_acceleration_limits(Eigen::Vector2d(-3, -10), Eigen::Vector2d(3, 10));
  return prob;
}

}  // namespace

TEST(Solver, WindowsGiveTheWholeChainOptimum) {
  // The window argument (solve/slp.hpp): SLP on windows only must find the optimum of the whole chain,
  // which Method::Slp finds by SLP over every grid point. Both are certified to the tolerance.
  for (int N : {60, 300, 1000}) {
    const TimeScalingProblem prob = reversing_problem(N);
    const Result win = prob.solve();
    SolverOptions o;
    o.method = Method::Slp;
    const Result whole = prob.solve(o);
    ASSERT_EQ(win.status, Status::Optimal) << win.message;
    ASSERT_EQ(whole.status, Status::Optimal) << whole.message;
    EXPECT_GT(win.stats.lp_solves, 0) << N;
    EXPECT_GT(win.stats.windows, 0) << N;
    EXPECT_LT(win.stats.window_points, N + 1) << N;
    EXPECT_EQ(whole.stats.window_points, N + 1) << N;
    EXPECT_LE(win.stats.gap, 1e-7);
    EXPECT_NEAR(win.duration, whole.duration, 2e-7 * whole.duration) << N;
  }
}

TEST(Solver, TimeLimitEndsWithAFeasibleTimingAndItsGap) {
  const TimeScalingProblem prob = reversing_problem(300);
  const Result best = prob.solve();
  ASSERT_EQ(best.status, Status::Optimal) << best.message;
  SolverOptions o;
  o.time_limit = 1e-12;  // over before the first LP
  const Result r = prob.solve(o);
  ASSERT_EQ(r.status, Status::TimeLimit) << r.message;
  EXPECT_TRUE(r.ok());
  EXPECT_NE(r.message.find("time_limit"), std::string::npos) << r.message;
  EXPECT_GE(r.duration, best.duration * (1 - 1e-9));
  // The certified gap is an upper bound on the true one.
  EXPECT_TRUE(std::isfinite(r.stats.gap));
  EXPECT_GE(r.stats.gap, (r.duration - best.duration) / best.duration - 1e-9);
  o.time_limit = 0.0;
  EXPECT_THROW(prob.solve(o), InvalidInput);
}

TEST(Solver, ClampedEndsWithVelocityLimitsOnlySolve) {
  // p'(0) = p'(1) = 0: at s_0 and s_N nothing bounds ṡ, but ṡ is given there (0), so the problem is
  // bounded; it used to be reported UNBOUNDED at grid index 0.
  Eigen::MatrixXd wp(4, 2);
  wp << 0, 0, 1, 0.5, 0.5, 1.5, 2, 2;
  auto path = std::make_shared<CubicSplinePath>(wp, KnotSpacing::Uniform, SplineBoundary::Clamped, 0.0, 1.0,
                                                Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  TimeScalingProblem prob(path, 200);
  prob.add_velocity_limits(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  const Result r = prob.solve();
  ASSERT_EQ(r.status, Status::Optimal) << r.message;
  EXPECT_EQ(r.sdot[0], 0.0);
  EXPECT_EQ(r.sdot[200], 0.0);
  EXPECT_TRUE(std::isfinite(r.duration));
}

TEST(Solver, StationaryPieceIsRejectedWithItsRange) {
  // q = s on [0, 1], q = 1 on [1, 2] (the path does not move), q = s - 1 on [2, 3].
  Eigen::MatrixXd c0(2, 1), c1(2, 1), c2(2, 1);
  c0 << 0, 1;
  c1 << 1, 0;
  c2 << 1, 1;
  auto path = std::make_shared<PiecewisePolynomialPath>(Eigen::Vector4d(0, 1, 2, 3), std::vector<Eigen::MatrixXd>{c0, c1, c2});
  TimeScalingProblem prob(path, 30);
  prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1));
  try {
    prob.solve();
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("does not move on s in [1, 1.9"), std::string::npos) << m;
    EXPECT_NE(m.find("grid indices 10..19"), std::string::npos) << m;
  }
  // A constraint that bounds the speed there makes it an ordinary (slow) piece.
  Eigen::MatrixXd A = Eigen::MatrixXd::Ones(31, 1), Z = Eigen::MatrixXd::Zero(31, 1);
  prob.add_linear_constraint(A, Z, Z, Eigen::MatrixXd::Constant(31, 1, -1.0), Eigen::MatrixXd::Constant(31, 1, 4.0), "cap");
  const Result r = prob.solve();
  EXPECT_EQ(r.status, Status::Optimal) << r.message;
}

TEST(Solver, UnboundedOnlyWhereThePathMovesFreely) {
  // A moving path with no constraint at all: nothing bounds ṡ at the interior grid points.
  TimeScalingProblem prob(line1d(1.0), 10);
  prob.add_acceleration_limits(Eigen::VectorXd::Constant(1, -std::numeric_limits<double>::infinity()),
                               Eigen::VectorXd::Constant(1, std::numeric_limits<double>::infinity()));
  const Result r = prob.solve();
  EXPECT_EQ(r.status, Status::Unbounded);
  EXPECT_GT(r.infeasibility.grid_index, 0);
  EXPECT_LT(r.infeasibility.grid_index, 10);
}

TEST(Solver, RestartKeepsEverySettingAndALinearConstraintsRows) {
  // 0 -> 3 under |q̇| <= 1 and, per grid point, |s̈| <= 0.5 + s / 10 (a LinearConstraint); every setting set.
  const int N = 30;
  TimeScalingProblem prob(line1d(3.0), N);
  prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1));
  const Eigen::VectorXd hi = 0.5 + prob.grid().array() / 10;
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(N + 1, 1), one = Eigen::MatrixXd::Ones(N + 1, 1);
  prob.add_linear_constraint(zero, one, zero, -hi, hi, "user");
  prob.set_boundary_speeds(0.0, 0.2);
  prob.set_zero_boundary_accelerations(false, true);
  prob.set_joint_names({"x"});
  const Result r = prob.solve();
  ASSERT_EQ(r.status, Status::Optimal) << r.message;
  const int k = 10;
  const TimeScalingProblem tail = prob.restarted(prob.grid()[k], r.sdot[k]);
  const ProblemSettings s = tail.settings();
  EXPECT_EQ(s.sdot_begin, r.sdot[k]);
  EXPECT_EQ(s.sdot_end, 0.2);
  EXPECT_FALSE(s.zero_sddot_begin);
  EXPECT_TRUE(s.zero_sddot_end);
  EXPECT_EQ(s.joint_names, std::vector<std::string>{"x"});
  const Result t = tail.solve();
  ASSERT_EQ(t.status, Status::Optimal) << t.message;
  EXPECT_NEAR(t.duration, r.duration - r.times[k], 3e-7 * r.duration);  // Bellman: the optimum's tail
  EXPECT_NEAR(t.sddot[N - k - 1], 0.0, 1e-12);  // s̈ = 0 on the last interval, from θ_N = θ_{N-1}
  EXPECT_EQ(error_of([&] { prob.restarted(0.34, 0.1); }),
            "restarted: s0 = 0.34 is not a grid point (nearest: grid[10] = 0.333333333333) and constraint 'user' is given "
            "per grid point (no value between grid points): restart at a grid point");
}
