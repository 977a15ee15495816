// SecondOrderConstraint (issue 22, items 2 and 4): rows F(q) w <= g(q) from a user's inverse dynamics by eq. 12's
// three evaluations. Oracles: TorqueLimits' rows (our SIMD sweep) against a std::function looping over the scalar
// RNEA, and a one-joint model whose rows are known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "pathpace/pathpace.hpp"
#include "test_util.hpp"

using namespace pathpace;
using namespace pathpace::test;

namespace {

// Three revolute joints on different axes, each link with an offset centre of mass and a full inertia.
const char* kArm = R"(<robot name="arm3">
  <link name="base"/>
  <link name="l1"><inertial><origin xyz="0.1 0 0.2"/><mass value="3"/>
    <inertia ixx="0.05" ixy="0.001" ixz="0" iyy="0.04" iyz="0.002" izz="0.03"/></inertial></link>
  <link name="l2"><inertial><origin xyz="0.25 0.02 0"/><mass value="2"/>
    <inertia ixx="0.02" ixy="0" ixz="0.001" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
  <link name="l3"><inertial><origin xyz="0.15 0 0.01"/><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="60" velocity="3"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.3"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="40" velocity="3"/></joint>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/><origin xyz="0.5 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="15" velocity="3"/></joint>
</robot>)";

std::shared_ptr<const RobotModel> arm() { return std::make_shared<RobotModel>(RobotModel::from_urdf_string(kArm)); }

std::shared_ptr<const Path> arm_path() {
  Eigen::MatrixXd w(4, 3);
  w << 0.0, -0.5, 0.8, 0.7, 0.3, -0.4, 1.2, -0.2, 0.5, 0.4, 0.6, 1.0;
  return std::make_shared<CubicSplinePath>(w);
}

// The user's dynamics: a loop over the scalar RNEA (RobotModel::inverse_dynamics), one batch per call.
SecondOrderFunctions::InverseDynamics rnea_of(std::shared_ptr<const RobotModel> robot) {
  return [robot](const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd, const Eigen::MatrixXd& qdd) {
    Eigen::MatrixXd w(q.rows(), q.cols());
    for (Eigen::Index i = 0; i < q.rows(); ++i)
      w.row(i) = robot->inverse_dynamics(q.row(i).transpose(), qd.row(i).transpose(), qdd.row(i).transpose()).transpose();
    return w;
  };
}

double max_relative_difference(const ConstraintRows::Matrix& x, const ConstraintRows::Matrix& y) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < x.rows(); ++k)
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      if (std::isinf(x(k, j)) || std::isinf(y(k, j))) {
        if (x(k, j) != y(k, j)) return std::numeric_limits<double>::infinity();
        continue;
      }
      worst = std::max(worst, std::abs(x(k, j) - y(k, j)) / std::max(1.0, std::abs(y(k, j))));
    }
  return worst;
}

TEST(SecondOrder, CallbackTorqueLimitsGiveTorqueLimitsRowsAndDuration) {
  auto robot = arm();
  const Eigen::Vector3d hi(30.0, 25.0, 8.0), lo = -Eigen::Vector3d(35.0, 20.0, 9.0);
  TimeScalingProblem ours(arm_path(), 200), theirs(arm_path(), 200);
  ours.add_constraint(std::make_shared<TorqueLimits>(robot, lo, hi));
  theirs.set_joint_names(robot->joint_names());
  theirs.add_torque_limits(rnea_of(robot), lo, hi);
  const ConstraintRows a = ours.constraints()[0]->evaluate(ours.samples());
  const ConstraintRows b = theirs.constraints()[0]->evaluate(theirs.samples());
  EXPECT_EQ(b.labels, a.labels);  // "torque j1 upper", ... in TorqueLimits' order
  // Two RNEA codes (the SIMD sweep of eq. 12 and the scalar one, differenced): rounding apart only.
  EXPECT_LT(max_relative_difference(b.a, a.a), 1e-12);
  EXPECT_LT(max_relative_difference(b.b, a.b), 1e-12);
  EXPECT_LT(max_relative_difference(b.c, a.c), 1e-12);
  const Result ra = ours.solve(), rb = theirs.solve();
  ASSERT_EQ(ra.status, Status::Optimal);
  ASSERT_EQ(rb.status, Status::Optimal);
  EXPECT_NEAR(rb.duration, ra.duration, 1e-12 * ra.duration);
  const std::vector<std::string> binding = ra.binding.strings();
  EXPECT_TRUE(std::any_of(binding.begin(), binding.end(), [](const std::string& b) { return b.rfind("torque", 0) == 0; }));
  EXPECT_EQ(theirs.constraints()[0]->family(), "torque");
}

TEST(SecondOrder, LabelsTakeTheJointNamesSetLater) {
  TimeScalingProblem p(arm_path(), 20);
  p.add_torque_limits(rnea_of(arm()), -Eigen::Vector3d::Constant(50), Eigen::Vector3d::Constant(50));
  EXPECT_EQ(p.constraints()[0]->evaluate(p.samples()).labels[5], "torque joint 2 lower");
  p.set_joint_names({"a", "b", "c"});
  EXPECT_EQ(p.constraints()[0]->evaluate(p.samples()).labels[2], "torque b upper");
}

// One joint, w = m q̈ + k q̇² + m·9.81 (a point mass with quadratic drag), F = [1; -2], g = [W; W2]: on the
// path q = 0.3 s², p' = 0.6 s, p'' = 0.6, the rows are a = F (m p'' + k p'²), b = F m p', c = g - F m·9.81.
TEST(SecondOrder, RowsOfAOneJointModelAreItsClosedForm) {
  const double m = 2.0, k = 0.7, W = 40.0, W2 = 15.0;
  auto id = [=](const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd, const Eigen::MatrixXd& qdd) {
    return Eigen::MatrixXd((m * qdd.array() + k * qd.array().square() + m * 9.81 + 0.0 * q.array()).matrix());
  };
  auto F = [](const Eigen::MatrixXd& q) {
    Eigen::MatrixXd out(2 * q.rows(), 1);
    for (Eigen::Index i = 0; i < q.rows(); ++i) out(2 * i, 0) = 1.0, out(2 * i + 1, 0) = -2.0;
    return out;
  };
  auto g = [=](const Eigen::MatrixXd& q) {
    Eigen::MatrixXd out(q.rows(), 2);
    out.col(0).setConstant(W);
    out.col(1).setConstant(W2);
    return out;
  };
  Eigen::MatrixXd coeffs(3, 1);
  coeffs << 0.0, 0.0, 0.3;  // lowest degree first: q = 0.3 s²
  auto path = std::make_shared<PiecewisePolynomialPath>(Eigen::Vector2d(0.0, 1.0), std::vector<Eigen::MatrixXd>{coeffs});
  TimeScalingProblem prob(path, 10);
  SecondOrderOptions o;
  o.labels = {"push", "pull"};
  prob.add_second_order_constraint(id, F, g, o);
  const ConstraintRows r = prob.constraints()[0]->evaluate(prob.samples());
  ASSERT_EQ(r.rows(), 2);
  EXPECT_EQ(r.labels, (std::vector<std::string>{"push", "pull"}));
  for (Eigen::Index i = 0; i <= 10; ++i) {
    const double s = prob.grid()[i], d = 0.6 * s, dd = 0.6;
    const double a = m * dd + k * d * d, b = m * d, c = m * 9.81;
    EXPECT_NEAR(r.a(i, 0), a, 1e-13);
    EXPECT_NEAR(r.b(i, 0), b, 1e-13);
    EXPECT_NEAR(r.c(i, 0), W - c, 1e-12);
    EXPECT_NEAR(r.a(i, 1), -2.0 * a, 1e-13);
    EXPECT_NEAR(r.b(i, 1), -2.0 * b, 1e-13);
    EXPECT_NEAR(r.c(i, 1), W2 + 2.0 * c, 1e-12);
  }
  // A constant F and g give the same rows as the callables.
  auto fc = std::make_shared<SecondOrderFunctions>();
  fc->inverse_dynamics = id;
  fc->F_constant = Eigen::Vector2d(1.0, -2.0);
  fc->g_constant = Eigen::Vector2d(W, W2);
  const ConstraintRows rc = SecondOrderConstraint(fc, SecondOrderOptions()).evaluate(prob.samples());
  EXPECT_EQ(rc.a, r.a);
  EXPECT_EQ(rc.b, r.b);
  EXPECT_EQ(rc.c, r.c);
  EXPECT_EQ(rc.labels[1], "second-order constraint row 1");
  // Relaxed: g widened about zero (W > 0: W·2).
  const auto relaxed = prob.constraints()[0]->relaxed(2.0);
  ASSERT_TRUE(relaxed);
  EXPECT_NEAR(relaxed->evaluate(prob.samples()).c(4, 0), 2.0 * W - m * 9.81, 1e-12);
}

TEST(SecondOrder, WhatTheFunctionsReturnIsCheckedAndNamed) {
  TimeScalingProblem prob(arm_path(), 10);
  const auto rnea = rnea_of(arm());
  auto wrong_rows = [](const Eigen::MatrixXd& q, const Eigen::MatrixXd&, const Eigen::MatrixXd&) {
    return Eigen::MatrixXd::Zero(q.rows() / 3, 3).eval();
  };
  const Eigen::Vector3d lim = Eigen::Vector3d::Constant(50.0);
  EXPECT_NE(error_of([&] { prob.add_torque_limits(wrong_rows, -lim, lim); })
                .find("inverse_dynamics(q, qd, qdd) returned shape (11, 3), expected (33, nw)"),
            std::string::npos);
  auto nan_at_7 = [rnea](const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd, const Eigen::MatrixXd& qdd) {
    Eigen::MatrixXd w = rnea(q, qd, qdd);
    w(2 * 11 + 7, 1) = std::nan("");
    return w;
  };
  const std::string nan_msg = error_of([&] { prob.add_torque_limits(nan_at_7, -lim, lim); });
  EXPECT_NE(nan_msg.find("w[1] = nan at grid point 7 (s = "), std::string::npos) << nan_msg;
  EXPECT_NE(nan_msg.find("id(p, p', p'')"), std::string::npos) << nan_msg;
  EXPECT_NE(error_of([&] { prob.add_torque_limits(rnea, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 1, 3)); })
                .find("tau_min[1] = 2 must be <= tau_max[1] = 1"),
            std::string::npos);
  EXPECT_NE(error_of([&] { prob.add_torque_limits(rnea, Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)); })
                .find("path has 3 coordinates, constraint 'torque limits' has 2 joints"),
            std::string::npos);
  EXPECT_NE(error_of([&] { prob.add_torque_limits(rnea, Eigen::VectorXd(), lim); }).find("tau_min must be given"),
            std::string::npos);
  auto F_bad = [](const Eigen::MatrixXd& q) { return Eigen::MatrixXd::Ones(2 * q.rows(), 2).eval(); };
  auto g_ok = [](const Eigen::MatrixXd& q) { return Eigen::MatrixXd::Ones(q.rows(), 2).eval(); };
  EXPECT_NE(error_of([&] { prob.add_second_order_constraint(rnea, F_bad, g_ok); })
                .find("F(q) returned shape (22, 2), expected (11·r, 3)"),
            std::string::npos);
  auto F_ok = [](const Eigen::MatrixXd& q) { return Eigen::MatrixXd::Ones(2 * q.rows(), 3).eval(); };
  auto g_minus_inf = [](const Eigen::MatrixXd& q) {
    Eigen::MatrixXd g = Eigen::MatrixXd::Ones(q.rows(), 2);
    g(4, 1) = -std::numeric_limits<double>::infinity();
    return g;
  };
  EXPECT_NE(error_of([&] { prob.add_second_order_constraint(rnea, F_ok, g_minus_inf); })
                .find("g(q) returned g[1] = -inf at grid point 4"),
            std::string::npos);
  SecondOrderOptions three_labels;
  three_labels.labels = {"a", "b", "c"};
  EXPECT_NE(error_of([&] { prob.add_second_order_constraint(rnea, F_ok, g_ok, three_labels); })
                .find("labels has 3 entries, F(q) has 2 rows"),
            std::string::npos);
  EXPECT_TRUE(prob.constraints().empty());
}

// Relaxation scales the callback's torque family as it scales TorqueLimits.
TEST(SecondOrder, RelaxationOfCallbackTorqueIsTorqueLimits) {
  auto robot = arm();
  const Eigen::Vector3d hi(30.0, 4.0, 8.0);  // j2 cannot hold the arm up: infeasible
  TimeScalingProblem ours(arm_path(), 60), theirs(arm_path(), 60);
  ours.add_constraint(std::make_shared<TorqueLimits>(robot, -hi, hi));
  theirs.add_torque_limits(rnea_of(robot), -hi, hi);
  ASSERT_EQ(ours.solve().status, Status::Infeasible);
  const auto ra = ours.relaxation(), rb = theirs.relaxation();
  ASSERT_EQ(rb.count("torque"), 1u);
  EXPECT_NEAR(rb.at("torque"), ra.at("torque"), 1e-9 * ra.at("torque"));
  EXPECT_GT(ra.at("torque"), 1.0);
}

}  // namespace
