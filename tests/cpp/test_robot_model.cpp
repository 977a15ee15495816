// RobotModel: analytic pendulum, structural properties of the dynamics, finite-difference Jacobians.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Eigenvalues>

#include "pathpace/pathpace.hpp"
#include "test_util.hpp"
#include "robot/torque_lanes.hpp"

using namespace pathpace;

namespace {

const char* kPendulum = R"(<robot name="pendulum">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="0 0 -1"/><mass value="1"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="hinge" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit effort="5.6" velocity="100"/></joint>
</robot>)";

// Two revolute links and a prismatic one, with a fixed tool link merged into the last body.
const char* kArm = R"(<robot name="arm">
  <link name="base"/>
  <link name="l1"><inertial><origin xyz="0.1 0 0.2" rpy="0.1 0.2 0.3"/><mass value="2"/>
    <inertia ixx="0.1" ixy="0.01" ixz="0" iyy="0.2" iyz="0.02" izz="0.15"/></inertial></link>
  <link name="l2"><inertial><origin xyz="0 0.3 0"/><mass value="1.5"/>
    <inertia ixx="0.05" ixy="0" ixz="0.01" iyy="0.04" iyz="0" izz="0.06"/></inertial></link>
  <link name="l3"><inertial><origin xyz="0 0 0.1"/><mass value="0.5"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="tool"><inertial><mass value="0.3"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.4" rpy="0.3 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="40" velocity="2"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/><origin xyz="0 0.5 0"/>
    <axis xyz="0.6 0 0.8"/><limit lower="0" upper="0.3" effort="100" velocity="0.5"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="l3"/><child link="tool"/><origin xyz="0.05 0 0.2"/></joint>
</robot>)";

}  // namespace

TEST(RobotModel, PendulumMatchesTheTextbook) {
  const RobotModel r = RobotModel::from_urdf_string(kPendulum);
  ASSERT_EQ(r.nq(), 1);
  for (double q : {0.0, 0.4, 2.0}) {
    const Eigen::VectorXd tau = r.inverse_dynamics(Eigen::VectorXd::Constant(1, q), Eigen::VectorXd::Constant(1, 1.3),
                                                   Eigen::VectorXd::Constant(1, -0.7));
    EXPECT_NEAR(tau[0], -0.7 + 9.81 * std::sin(q), 1e-12);  // m l² q̈ + m g l sin q
  }
  EXPECT_EQ(r.effort_limits()[0], 5.6);
}

TEST(RobotModel, DynamicsAreConsistent) {
  const RobotModel r = RobotModel::from_urdf_string(kArm);
  ASSERT_EQ(r.nq(), 3);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd q(3), qd(3), qdd(3);
    for (int j = 0; j < 3; ++j) {
      q[j] = U(gen);
      qd[j] = U(gen);
      qdd[j] = U(gen);
    }
    const Eigen::MatrixXd M = r.mass_matrix(q);
    EXPECT_NEAR((M - M.transpose()).norm(), 0.0, 1e-12);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0);
    const Eigen::VectorXd z = Eigen::VectorXd::Zero(3);
    // RNEA(q, q̇, q̈) = M q̈ + RNEA(q, q̇, 0) and RNEA(q, 0, 0) = g(q)
    EXPECT_NEAR((r.inverse_dynamics(q, qd, qdd) - (M * qdd + r.inverse_dynamics(q, qd, z))).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r.inverse_dynamics(q, z, z) - r.gravity_torques(q)).norm(), 0.0, 1e-14);
    // eq. (12) coefficients reproduce RNEA at (q, p' ṡ, p'' ṡ² + p' s̈)
    RobotWorkspace ws(r);
    Eigen::VectorXd a(3), b(3), c(3);
    r.path_torque_coefficients(ws, q, qd, qdd, a, b, c);
    const double sd = 1.7, sdd = -0.4;
    EXPECT_NEAR((a * sd * sd + b * sdd + c - r.inverse_dynamics(q, qd * sd, qdd * sd * sd + qd * sdd)).norm(), 0.0, 1e-11);
    // Point Jacobian of a point on the merged tool link against central differences.
    const Eigen::Vector3d p(0.02, -0.01, 0.03);
    const Eigen::MatrixXd J = r.point_jacobian(q, "tool", p);
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j) {
      Eigen::VectorXd qp = q, qm = q;
      qp[j] += h;
      qm[j] -= h;
      const Eigen::Vector3d xp = (r.frame_placement(qp, "tool") * p.homogeneous()).head<3>();
      const Eigen::Vector3d xm = (r.frame_placement(qm, "tool") * p.homogeneous()).head<3>();
      EXPECT_NEAR((J.col(j) - (xp - xm) / (2 * h)).norm(), 0.0, 1e-8);
    }
  }
}

TEST(RobotModel, ValidationNamesWhatIsWrong) {
  try {
    RobotModel::from_urdf_string("<robot");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not a valid URDF"), std::string::npos);
  }
  RobotModelOptions o;
  o.locked_joints["nope"] = 0.0;
  EXPECT_EQ(test::error_of([&] { RobotModel::from_urdf_string(kArm, o); }),
            "locked_joints: 'nope' is not a movable joint of robot 'arm'");
  const RobotModel r = RobotModel::from_urdf_string(kArm);
  EXPECT_THROW(r.frame_placement(Eigen::VectorXd::Zero(2), "tool"), InvalidInput);
  EXPECT_THROW(r.frame_placement(Eigen::VectorXd::Zero(3), "hand"), InvalidInput);
}

TEST(TorqueLimits, LockedJointAndFloatingBaseShapes) {
  RobotModelOptions o;
  o.locked_joints["j3"] = 0.1;
  o.floating_base = true;
  const auto r = std::make_shared<RobotModel>(RobotModel::from_urdf_string(kArm, o));
  ASSERT_EQ(r->nq(), 8);  // six virtual joints, j1, j2
  EXPECT_EQ(r->joint_names()[0], "floating_x");
  EXPECT_EQ(r->effort_limits()[0], 0.0);  // unactuated
  TorqueLimits t(r);
  EXPECT_EQ(t.tau_min()[0], 0.0);
  EXPECT_EQ(t.tau_max()[7], 40.0);
}

TEST(TorqueLimits, RowsAreTheCoefficientsOfEquation15) {
  // The row pair of joint j at sample k: (a, b, τ_U - c) and (-a, -b, c - τ_L), written from the lanes;
  // an infinite limit is an inactive row (c = +inf). 13 samples: a partial last group of lanes.
  const auto r = std::make_shared<RobotModel>(RobotModel::from_urdf_string(kArm));
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lo(3), hi(3);
  lo << -50.0, -inf, -100.0;
  hi << 45.0, 40.0, inf;
  const TorqueLimits t(r, lo, hi, 0.5, 1.0);
  PathSamples smp;
  const int count = 13;
  smp.s = Eigen::VectorXd::LinSpaced(count, 0.0, 1.0);
  smp.q.resize(count, 3);
  smp.dq.resize(count, 3);
  smp.ddq.resize(count, 3);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int k = 0; k < count; ++k)
    for (int j = 0; j < 3; ++j) smp.q(k, j) = U(gen), smp.dq(k, j) = U(gen), smp.ddq(k, j) = U(gen);
  const ConstraintRows rows = t.evaluate(smp);
  ASSERT_EQ(rows.rows(), 6);
  EXPECT_EQ(rows.labels[2], "torque j2 upper");
  EXPECT_EQ(rows.labels[3], "torque j2 lower");
  RobotWorkspace ws(*r);
  for (int k = 0; k < count; ++k) {
    Eigen::VectorXd a(3), b(3), c(3);
    r->path_torque_coefficients(ws, smp.q.row(k).transpose(), smp.dq.row(k).transpose(), smp.ddq.row(k).transpose(), a,
                                b, c);
    for (int j = 0; j < 3; ++j) {
      const double tol = 1e-12 * (1.0 + std::abs(a[j]) + std::abs(b[j]) + std::abs(c[j]));
      EXPECT_NEAR(rows.a(k, 2 * j), a[j], tol) << k << " " << j;
      EXPECT_EQ(rows.a(k, 2 * j + 1), -rows.a(k, 2 * j));
      EXPECT_NEAR(rows.b(k, 2 * j), b[j], tol);
      EXPECT_EQ(rows.b(k, 2 * j + 1), -rows.b(k, 2 * j));
      if (std::isfinite(hi[j])) EXPECT_NEAR(rows.c(k, 2 * j), 0.5 * hi[j] - 1.0 - c[j], tol);
      else EXPECT_EQ(rows.c(k, 2 * j), inf);
      if (std::isfinite(lo[j])) EXPECT_NEAR(rows.c(k, 2 * j + 1), c[j] - (0.5 * lo[j] + 1.0), tol);
      else EXPECT_EQ(rows.c(k, 2 * j + 1), inf);
    }
  }
}

TEST(RobotModel, TorqueCoefficientsReproduceInverseDynamicsOnEveryJointKind) {
  // eq. (12) against the separate RNEA of inverse_dynamics: revolute and prismatic joints on coordinate
  // axes (the sweep's specialised path) and on tilted ones, and a floating base, one sample at a time and
  // in the lanes of the batch.
  std::string tilted = kArm, straight = kArm;
  tilted.replace(tilted.find("<axis xyz=\"0 1 0\"/>"), 19, "<axis xyz=\"0 0.6 0.8\"/>");
  straight.replace(straight.find("<axis xyz=\"0.6 0 0.8\"/>"), 23, "<axis xyz=\"1 0 0\"/>");
  RobotModelOptions floating;
  floating.floating_base = true;
  const std::vector<RobotModel> models = {RobotModel::from_urdf_string(kArm), RobotModel::from_urdf_string(tilted),
                                          RobotModel::from_urdf_string(straight),
                                          RobotModel::from_urdf_string(kArm, floating)};
  for (const RobotModel& r : models) {
    RobotWorkspace ws(r);
    const int n = r.nq(), count = 11;
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> U(-1.5, 1.5);
    Eigen::MatrixXd q(count, n), dq(count, n), ddq(count, n), A, B, C;
    for (int s = 0; s < count; ++s)
      for (int j = 0; j < n; ++j) q(s, j) = U(gen), dq(s, j) = U(gen), ddq(s, j) = U(gen);
    r.path_torque_coefficients_batch(ws, q, dq, ddq, A, B, C);
    for (int s = 0; s < count; ++s) {
      const Eigen::VectorXd qs = q.row(s).transpose(), dqs = dq.row(s).transpose(), ddqs = ddq.row(s).transpose();
      Eigen::VectorXd a(n), b(n), c(n);
      r.path_torque_coefficients(ws, qs, dqs, ddqs, a, b, c);
      const double sd = 0.3 + 0.2 * s, sdd = 1.1 - 0.25 * s;
      const Eigen::VectorXd tau = r.inverse_dynamics(qs, dqs * sd, ddqs * sd * sd + dqs * sdd);
      EXPECT_NEAR((a * sd * sd + b * sdd + c - tau).norm(), 0.0, 1e-11 * (1.0 + tau.norm())) << n << " " << s;
      const Eigen::VectorXd batch = A.row(s).transpose() * sd * sd + B.row(s).transpose() * sdd + C.row(s).transpose();
      EXPECT_NEAR((batch - tau).norm(), 0.0, 1e-11 * (1.0 + tau.norm())) << n << " " << s;
    }
  }
}

TEST(RobotWorkspace, CopiedMovedAndAssignedWorkspacesComputeAsAFreshOne) {
  // The buffers sit behind a pointer (robot/bodies.hpp): a copy must own buffers of its own, a move must
  // carry them, and each must give what a fresh workspace gives, in the RNEA and in the torque sweep.
  const RobotModel r = RobotModel::from_urdf_string(kArm);
  const Eigen::VectorXd q = Eigen::Vector3d(0.3, -0.7, 0.1), qd = Eigen::Vector3d(1.1, 0.4, -0.2),
                        qdd = Eigen::Vector3d(-0.5, 0.9, 0.3);
  auto results = [&](RobotWorkspace& ws) {
    Eigen::VectorXd tau(3), a(3), b(3), c(3);
    r.inverse_dynamics(ws, q, qd, qdd, true, tau);
    r.path_torque_coefficients(ws, q, qd, qdd, a, b, c);
    Eigen::MatrixXd out(3, 4);
    out << tau, a, b, c;
    return out;
  };
  RobotWorkspace fresh(r);
  const Eigen::MatrixXd expected = results(fresh);
  RobotWorkspace copy(fresh);
  EXPECT_EQ(results(copy), expected);
  EXPECT_EQ(results(fresh), expected);
  RobotWorkspace moved(std::move(copy));
  EXPECT_EQ(results(moved), expected);
  RobotWorkspace assigned(RobotModel::from_urdf_string(kPendulum));  // sized for another model
  assigned = moved;
  EXPECT_EQ(results(assigned), expected);
  RobotWorkspace move_assigned(RobotModel::from_urdf_string(kPendulum));
  move_assigned = std::move(assigned);
  EXPECT_EQ(results(move_assigned), expected);
}

TEST(RobotWorkspace, AMovedFromOrMismatchedWorkspaceThrowsInsteadOfReadingOutOfBounds) {
  const RobotModel arm = RobotModel::from_urdf_string(kArm);
  const Eigen::VectorXd q = Eigen::Vector3d(0.3, -0.7, 0.1);
  Eigen::VectorXd tau(3), a(3), b(3), c(3);
  RobotWorkspace ws(arm);
  RobotWorkspace taken(std::move(ws));
  // NOLINTNEXTLINE(bugprone-use-after-move): a moved-from workspace is what is tested
  EXPECT_EQ(test::error_of([&] { arm.inverse_dynamics(ws, q, q, q, true, tau); }), "workspace: it was moved from; make one with RobotWorkspace(model)");
  EXPECT_EQ(test::error_of([&] { arm.path_torque_coefficients(ws, q, q, q, a, b, c); }), "workspace: it was moved from; make one with RobotWorkspace(model)");
  RobotWorkspace other(RobotModel::from_urdf_string(kPendulum));
  EXPECT_EQ(test::error_of([&] { arm.inverse_dynamics(other, q, q, q, true, tau); }), "workspace: made for a model with 1 bodies, robot 'arm' has 3; make one with RobotWorkspace(model)");
  EXPECT_EQ(test::error_of([&] { arm.path_torque_coefficients(other, q, q, q, a, b, c); }), "workspace: made for a model with 1 bodies, robot 'arm' has 3; make one with RobotWorkspace(model)");
  arm.inverse_dynamics(taken, q, q, q, true, tau);  // the moved-to workspace computes
  EXPECT_TRUE(tau.allFinite());
}

TEST(RobotModel, AMovedModelCarriesEverythingAndLeavesTheEmptyModel) {
  const RobotModel original = RobotModel::from_urdf_string(kArm);
  const Eigen::VectorXd q = Eigen::Vector3d(0.3, -0.7, 0.1), qd = Eigen::Vector3d(1.1, 0.4, -0.2);
  auto same_as_original = [&](const RobotModel& m) {
    EXPECT_EQ(m.name(), original.name());
    EXPECT_EQ(m.joint_names(), original.joint_names());
    EXPECT_EQ(m.link_names(), original.link_names());
    EXPECT_EQ(m.velocity_limits(), original.velocity_limits());
    EXPECT_EQ(m.effort_limits(), original.effort_limits());
    EXPECT_EQ(m.source().urdf, original.source().urdf);
    EXPECT_EQ(m.inverse_dynamics(q, qd, q), original.inverse_dynamics(q, qd, q));
  };
  auto is_empty = [](const RobotModel& m) {
    EXPECT_EQ(m.nq(), 0);
    EXPECT_TRUE(m.link_names().empty());
    EXPECT_EQ(m.inverse_dynamics(Eigen::VectorXd(0), Eigen::VectorXd(0), Eigen::VectorXd(0)).size(), 0);
    EXPECT_EQ(RobotModel::rebuild(m.source()).nq(), 0);
  };
  RobotModel source = original;
  RobotModel moved(std::move(source));
  same_as_original(moved);
  is_empty(source);  // NOLINT(bugprone-use-after-move): what a moved-from model is, is the contract
  RobotModel assigned = RobotModel::from_urdf_string(kPendulum);
  assigned = std::move(moved);
  same_as_original(assigned);
  is_empty(moved);  // NOLINT(bugprone-use-after-move)
  is_empty(RobotModel::rebuild(RobotModel().source()));
}

TEST(RobotModel, DefaultConstructedModelIsEmpty) {
  const RobotModel r;
  EXPECT_EQ(r.nq(), 0);
  EXPECT_TRUE(r.link_names().empty());
  EXPECT_EQ(r.mass(), 0.0);
  EXPECT_TRUE(r.mimic_joints().empty());
  EXPECT_EQ(r.inverse_dynamics(Eigen::VectorXd(0), Eigen::VectorXd(0), Eigen::VectorXd(0)).size(), 0);
}

TEST(RobotModel, BatchTorqueCoefficientsEqualOneSampleAtATime) {
  // kArm: coordinate-axis revolute joints and a tilted prismatic one; the same tree with a tilted
  // revolute axis (the general rotation in each lane). Every lane width this CPU runs (SSE2, AVX2 + FMA,
  // AVX-512: the batch takes the widest), and 43 samples leave a partial last group for each (1 of 2,
  // 3 of 4 and of 8 lanes).
  std::string tilted = kArm;
  tilted.replace(tilted.find("<axis xyz=\"0 1 0\"/>"), 19, "<axis xyz=\"0 0.6 0.8\"/>");
  std::vector<int> widths;
  for (int lanes = 1; lanes <= detail::torque_lanes_supported(); lanes *= 2) widths.push_back(lanes);
  for (const std::string& xml : {std::string(kArm), tilted}) {
    const RobotModel r = RobotModel::from_urdf_string(xml);
    RobotWorkspace ws(r);
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> U(-2.0, 2.0);
    // The lanes take sin and cos from their own kernel (to 2 ulp of libm's): angles in every quadrant and
    // many turns, and multiples of pi/2. A joint with any |q| > 1e5 (beyond the kernel's range) takes libm's
    // in every lane: that is a second batch, so that the first one reaches the kernel on every joint.
    const int count = 43;
    Eigen::MatrixXd q(count, 3), dq(count, 3), ddq(count, 3);
    for (int s = 0; s < count; ++s)
      for (int j = 0; j < 3; ++j) {
        q(s, j) = U(gen) * (s < 7 ? 1.0 : s < 30 ? 50.0 : 1e4);
        dq(s, j) = U(gen);
        ddq(s, j) = U(gen);
      }
    for (int j = 0; j < 3; ++j) {
      q(30, j) = (j - 1) * 1.5707963267948966;
      q(31, j) = 3.141592653589793 * (j + 1);
    }
    Eigen::MatrixXd far = q;
    far.row(32).setConstant(2.5e5);
    Eigen::MatrixXd A, B, C;
    for (const Eigen::MatrixXd* qs : {&q, &far}) {
      // One sample at a time, the reference.
      Eigen::MatrixXd a1(count, 3), b1(count, 3), c1(count, 3);
      for (int s = 0; s < count; ++s) {
        Eigen::VectorXd a(3), b(3), c(3);
        r.path_torque_coefficients(ws, qs->row(s).transpose(), dq.row(s).transpose(), ddq.row(s).transpose(), a, b,
                                   c);
        a1.row(s) = a.transpose();
        b1.row(s) = b.transpose();
        c1.row(s) = c.transpose();
        EXPECT_GT(a.norm() + b.norm(), 1e-3);
      }
      // The batch (the widest lanes), then each width.
      for (size_t w = 0; w <= widths.size(); ++w) {
        const int lanes = w == 0 ? 0 : widths[w - 1];
        if (w == 0) r.path_torque_coefficients_batch(ws, *qs, dq, ddq, A, B, C);
        else detail::path_torque_coefficients_lanes(r, ws, *qs, dq, ddq, A, B, C, lanes);
        ASSERT_EQ(A.rows(), count);
        for (int s = 0; s < count; ++s)
          for (const auto& [X, R] : {std::pair{&A, &a1}, std::pair{&B, &b1}, std::pair{&C, &c1}})
            EXPECT_NEAR((X->row(s) - R->row(s)).norm(), 0.0, 1e-12 * (1.0 + R->row(s).norm())) << s << " lanes " << lanes;
      }
    }
    EXPECT_THROW(r.path_torque_coefficients_batch(ws, q.leftCols(2), dq, ddq, A, B, C), InvalidInput);
    EXPECT_EQ(test::error_of([&] { detail::path_torque_coefficients_lanes(r, ws, q, dq, ddq, A, B, C, 3); }),
              "lanes = 3 must be a power of 2 <= " + std::to_string(detail::torque_lanes_supported()));
  }
}
