// The C++ side of the front-door API: time spline, boundary velocities, rebuilding a model from its
// source, centre of mass, mimic joints (virtual work), joint names in limit labels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "pathpace/pathpace.hpp"

using namespace pathpace;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

std::shared_ptr<CubicSplinePath> spline() {
  MatrixXd w(4, 2);
  w << 0.0, 0.0, 1.0, 0.5, 0.2, 1.5, 0.8, 1.0;
  return std::make_shared<CubicSplinePath>(w);
}

TimeScalingProblem kinematic(int N) {
  TimeScalingProblem p(spline(), N);
  p.add_velocity_limits(-VectorXd::Ones(2), VectorXd::Ones(2));
  p.add_acceleration_limits(-2.0 * VectorXd::Ones(2), 2.0 * VectorXd::Ones(2));
  return p;
}

// A chain j1 -> j2 where j2 mimics j1 with multiplier -0.5 and offset 0.2; the same chain without mimic.
std::string chain(bool mimic) {
  return std::string(R"(<robot name="chain"><link name="a"/>
  <link name="b"><inertial><origin xyz="0.3 0 0"/><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="c"><inertial><origin xyz="0.2 0.1 0"/><mass value="1"/><inertia ixx="0.05" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="b"/><child link="c"/><origin xyz="0.6 0 0"/><axis xyz="0 0.6 0.8"/>
    <limit lower="-3" upper="3" effort="50" velocity="2"/>)") +
         (mimic ? R"(<mimic joint="j1" multiplier="-0.5" offset="0.2"/>)" : "") + "</joint></robot>";
}

}  // namespace

TEST(TimeSpline, InterpolatesTheGridAndIsClampedToTheEndVelocities) {
  TimeScalingProblem p = kinematic(200);
  p.set_boundary_speeds(0.1, 0.05);
  const Result r = p.solve();
  ASSERT_TRUE(r.ok());
  const Trajectory t = r.trajectory();
  const CubicSplinePath s = t.time_spline();
  MatrixXd q, dq, ddq, qt, qdt, qddt;
  s.evaluate(t.times(), q, dq, ddq);
  t.evaluate(t.times(), qt, qdt, qddt);
  EXPECT_LT((q - qt).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((dq.row(0) - qdt.row(0)).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::Index last = q.rows() - 1;
  EXPECT_LT((dq.row(last) - qdt.row(last)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_DOUBLE_EQ(s.s_end(), t.duration());
}

TEST(BoundaryVelocities, SetSpeedsAlongTheTangentAndNameTheJointOtherwise) {
  TimeScalingProblem p = kinematic(100);
  const VectorXd d0 = p.samples().dq.row(0).transpose(), d1 = p.samples().dq.row(100).transpose();
  p.set_boundary_velocities(0.25 * d0, 0.5 * d1);
  EXPECT_NEAR(p.sdot_begin(), 0.25, 1e-14);
  EXPECT_NEAR(p.sdot_end(), 0.5, 1e-14);
  VectorXd off = 0.25 * d0;
  off[1] += 0.1;
  try {
    p.set_boundary_velocities(off, VectorXd::Zero(2));
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("qd_begin[1] = "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("non-negative multiple of the path tangent"), std::string::npos) << e.what();
  }
}

TEST(RobotModelSource, RebuildGivesTheSameModel) {
  const RobotModel a = RobotModel::from_urdf_string(chain(false));
  const RobotModel box = RobotModel::free_object("box", 2.0, Eigen::Vector3d(0, 0, 0.1), 0.01 * Eigen::Matrix3d::Identity());
  const RobotModel both = RobotModel::combine({a, box}, "both");
  for (const RobotModel* m : {&a, &box, &both}) {
    const RobotModel r = RobotModel::rebuild(m->source());
    ASSERT_EQ(r.joint_names(), m->joint_names());
    const VectorXd q = VectorXd::LinSpaced(m->nq(), -0.5, 0.7), qd = VectorXd::Constant(m->nq(), 0.3);
    EXPECT_EQ(r.inverse_dynamics(q, qd, q), m->inverse_dynamics(q, qd, q));
  }
}

TEST(CenterOfMass, OfAFreeObjectIsItsPosition) {
  const RobotModel box = RobotModel::free_object("box", 2.0, Eigen::Vector3d(0, 0, 0.1));
  VectorXd q = VectorXd::Zero(6);
  q.head<3>() << 1.0, 2.0, 3.0;
  q[5] = M_PI;  // turned over about x: the centre of mass goes below the origin
  const Eigen::Vector3d c = box.center_of_mass(q);
  EXPECT_NEAR((c - Eigen::Vector3d(1.0, 2.0, 2.9)).norm(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(box.mass(), 2.0);
}

TEST(MimicJoints, FollowTheirJointAndPassTheirTorqueByVirtualWork) {
  const RobotModel mimic = RobotModel::from_urdf_string(chain(true));
  const RobotModel free = RobotModel::from_urdf_string(chain(false));
  ASSERT_EQ(mimic.nq(), 1);
  ASSERT_EQ(mimic.mimic_joints().size(), 1u);
  EXPECT_EQ(mimic.mimic_joints()[0].joint, "j1");
  const double q1 = 0.7, qd1 = -0.4, qdd1 = 1.3;
  const VectorXd q = VectorXd::Constant(1, q1), qd = VectorXd::Constant(1, qd1), qdd = VectorXd::Constant(1, qdd1);
  // The same motion of the two-coordinate chain: q2 = -0.5 q1 + 0.2.
  VectorXd Q(2), QD(2), QDD(2);
  Q << q1, -0.5 * q1 + 0.2;
  QD << qd1, -0.5 * qd1;
  QDD << qdd1, -0.5 * qdd1;
  const VectorXd tau = free.inverse_dynamics(Q, QD, QDD);
  EXPECT_NEAR(mimic.inverse_dynamics(q, qd, qdd)[0], tau[0] - 0.5 * tau[1], 1e-12);
  EXPECT_LT((mimic.frame_placement(q, "c") - free.frame_placement(Q, "c")).cwiseAbs().maxCoeff(), 1e-14);
  const MatrixXd J = free.point_jacobian(Q, "c", Eigen::Vector3d(0.1, 0, 0));
  EXPECT_LT((mimic.point_jacobian(q, "c", Eigen::Vector3d(0.1, 0, 0)).col(0) - (J.col(0) - 0.5 * J.col(1))).norm(), 1e-14);
}

// RobotModel::moving_joints: exactly the columns add_point_jacobian writes (the contact LPs fill only
// those rows), on a branched tree, with a mimic joint, and for the world.
TEST(RobotModel, MovingJointsAreTheColumnsAPointJacobianWrites) {
  const std::string branched = R"(<robot name="y"><link name="a"/>
  <link name="b"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="c"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="d"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="5" velocity="2"/></joint>
  <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0.5 0 0"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="5" velocity="2"/></joint>
  <joint name="j3" type="revolute"><parent link="a"/><child link="d"/><origin xyz="0 0.3 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="5" velocity="2"/></joint>
  </robot>)";
  const RobotModel y = RobotModel::from_urdf_string(branched);
  auto col = [&](const RobotModel& r, const std::string& j) {
    const auto& names = r.joint_names();
    return static_cast<int>(std::find(names.begin(), names.end(), j) - names.begin());
  };
  auto sorted = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  Eigen::Isometry3d in_body;
  const std::vector<std::pair<std::string, std::vector<int>>> expect = {
      {"b", {col(y, "j1")}}, {"c", sorted({col(y, "j1"), col(y, "j2")})}, {"d", {col(y, "j3")}}};
  const VectorXd q = (VectorXd(3) << 0.4, 0.2, -0.7).finished();
  std::vector<Eigen::Isometry3d> T;
  y.body_placements(q, T);
  for (const auto& [link, joints] : expect) {
    const int body = y.body_of_link(link, in_body);
    EXPECT_EQ(y.moving_joints(body), joints) << link;
    MatrixXd J = MatrixXd::Zero(3, y.nq());
    y.add_point_jacobian(T, body, T[static_cast<size_t>(body)] * Eigen::Vector3d(0.1, 0.2, 0.3), 1.0, J);
    for (int j = 0; j < y.nq(); ++j) {
      const bool moving = std::count(joints.begin(), joints.end(), j) > 0;
      EXPECT_EQ(J.col(j).norm() > 0.0, moving) << link << " column " << j;
    }
  }
  EXPECT_TRUE(y.moving_joints(-1).empty());
  // A mimic body moves with its joint: link c of the mimic chain with j1's coordinate alone.
  const RobotModel mimic = RobotModel::from_urdf_string(chain(true));
  EXPECT_EQ(mimic.moving_joints(mimic.body_of_link("c", in_body)), std::vector<int>{0});
  EXPECT_EQ(mimic.moving_joints(mimic.body_of_link("b", in_body)), std::vector<int>{0});
}

// add_point_jacobian with the axes of joint_axes (the contact LPs' form, one axis pass for many points)
// is the plain form bit for bit, with either sign, on a branched tree with a prismatic joint and on a
// mimic chain; it adds to J like the plain form.
TEST(RobotModel, PointJacobianFromJointAxesIsThePlainOneExactly) {
  const RobotModel y = RobotModel::from_urdf_string(R"(<robot name="y"><link name="a"/>
  <link name="b"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="c"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="d"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0.6 0.8"/><limit lower="-3" upper="3" effort="5" velocity="2"/></joint>
  <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0.5 0 0" rpy="0.1 0.2 0.3"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="5" velocity="2"/></joint>
  <joint name="j3" type="revolute"><parent link="a"/><child link="d"/><origin xyz="0 0.3 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="5" velocity="2"/></joint>
  </robot>)");
  const RobotModel mimic = RobotModel::from_urdf_string(chain(true));
  const std::vector<std::pair<const RobotModel*, std::string>> cases = {{&y, "b"}, {&y, "c"}, {&y, "d"}, {&mimic, "c"}};
  for (const auto& [robot, link] : cases) {
    const VectorXd q = VectorXd::LinSpaced(robot->nq(), 0.4, -0.7);
    std::vector<Eigen::Isometry3d> T;
    robot->body_placements(q, T);
    Eigen::Matrix3Xd axes;
    robot->joint_axes(T, axes);
    EXPECT_EQ(axes.cols(), static_cast<Eigen::Index>(T.size())) << link;
    Eigen::Isometry3d in_body;
    const int body = robot->body_of_link(link, in_body);
    const Eigen::Vector3d p = T[static_cast<size_t>(body)] * Eigen::Vector3d(0.1, -0.2, 0.3);
    for (double sign : {1.0, -0.5}) {
      MatrixXd plain = MatrixXd::Constant(3, robot->nq(), 0.25), with_axes = plain;  // both add to what is there
      robot->add_point_jacobian(T, body, p, sign, plain);
      robot->add_point_jacobian(T, axes, body, p, sign, with_axes);
      EXPECT_EQ(plain, with_axes) << link << " sign " << sign;
      EXPECT_GT((plain.array() - 0.25).abs().maxCoeff(), 0.1) << link;  // it wrote something
    }
  }
}

TEST(LimitLabels, NameTheJointsWhenGiven) {
  const VelocityLimits v(-VectorXd::Ones(2), VectorXd::Ones(2), {"shoulder", "elbow"});
  TimeScalingProblem p(spline(), 10);
  const ConstraintRows rows = v.evaluate(p.samples());
  EXPECT_EQ(rows.labels[1], "velocity elbow");
  const AccelerationLimits a(-VectorXd::Ones(2), VectorXd::Ones(2));
  EXPECT_EQ(a.evaluate(p.samples()).labels[3], "acceleration joint 1 lower");
}
