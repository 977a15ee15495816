// FrameLimits (issue 22 item 3) against closed forms: an RP arm (a revolute joint, then a prismatic one along
// the link) whose point moves in polar coordinates, so its velocity and classical acceleration along a
// path, Coriolis term included, are known exactly; a circle at constant tool speed; the validation messages.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "pathpace/pathpace.hpp"
#include "test_util.hpp"

using namespace pathpace;
using namespace pathpace::test;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

// Joint 1 turns about z at the base; joint 2 slides along the link's x: the tip (link "tip", at x = 0.2
// beyond the slider) is at radius r = q2 + 0.2 and angle q1.
std::shared_ptr<const RobotModel> rp_arm() {
  const std::string inertial =
      "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>";
  const std::string lim = "<limit lower=\"-5\" upper=\"5\" effort=\"100\" velocity=\"10\"/>";
  const std::string xml =
      "<robot name=\"rp\"><link name=\"base\"/><link name=\"l1\">" + inertial + "</link><link name=\"l2\">" + inertial +
      "</link><link name=\"tip\"/>"
      "<joint name=\"turn\" type=\"revolute\"><parent link=\"base\"/><child link=\"l1\"/><axis xyz=\"0 0 1\"/>" + lim +
      "</joint><joint name=\"slide\" type=\"prismatic\"><parent link=\"l1\"/><child link=\"l2\"/><axis xyz=\"1 0 0\"/>" +
      lim + "</joint><joint name=\"t\" type=\"fixed\"><parent link=\"l2\"/><child link=\"tip\"/><origin xyz=\"0.2 0 0\"/>"
            "</joint></robot>";
  return std::make_shared<RobotModel>(RobotModel::from_urdf_string(xml));
}

// q1 = a s, q2 = r0 + b s: the tip at x(s) = r(s) (cos as, sin as), r = r0 + 0.2 + b s, so
// x' = b e_r + a r e_t and x'' = 2 a b e_t - a² r e_r (e_r = (cos, sin), e_t = (-sin, cos)).
constexpr double kA = 1.3, kB = 0.4, kR0 = 0.3;

std::shared_ptr<const Path> polar_path() {
  return std::make_shared<ClosedFormPath>(2, [](double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                                               Eigen::Ref<Eigen::VectorXd> ddq) {
    q << kA * s, kR0 + kB * s;
    dq << kA, kB;
    ddq << 0.0, 0.0;
  });
}

TEST(FrameLimits, RowsOfAPrismaticArmAreItsPolarClosedForm) {
  const auto robot = rp_arm();
  TimeScalingProblem prob(polar_path(), 8);
  const PathSamples& ps = prob.samples();
  const Eigen::Vector3d lo(-1.0, -2.0, -3.0), hi(1.5, 2.5, 3.5);
  for (FrameAxes axes : {FrameAxes::World, FrameAxes::Local}) {
    const ConstraintRows acc = FrameLimits(robot, "tip", FrameQuantity::LinearAcceleration, lo, hi, axes).evaluate(ps);
    const ConstraintRows vel = FrameLimits(robot, "tip", FrameQuantity::LinearVelocity, lo, hi, axes).evaluate(ps);
    const ConstraintRows ang = FrameLimits(robot, "tip", FrameQuantity::AngularVelocity, lo, hi, axes).evaluate(ps);
    for (Eigen::Index k = 0; k < ps.size(); ++k) {
      const double s = ps.s[k], th = kA * s, r = kR0 + 0.2 + kB * s;
      const Eigen::Vector3d er(std::cos(th), std::sin(th), 0.0), et(-std::sin(th), std::cos(th), 0.0);
      Eigen::Vector3d v = kB * er + kA * r * et, a = 2 * kA * kB * et - kA * kA * r * er;
      if (axes == FrameAxes::Local) {  // the link's axes are (e_r, e_t, z)
        v = Eigen::Vector3d(kB, kA * r, 0.0);
        a = Eigen::Vector3d(-kA * kA * r, 2 * kA * kB, 0.0);
      }
      for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(acc.a(k, 2 * j), a[j], 1e-13) << k << " " << j;
        EXPECT_NEAR(acc.b(k, 2 * j), v[j], 1e-13);
        EXPECT_EQ(acc.c(k, 2 * j), hi[j]);
        EXPECT_EQ(acc.a(k, 2 * j + 1), -acc.a(k, 2 * j));
        EXPECT_EQ(acc.c(k, 2 * j + 1), -lo[j]);
        EXPECT_NEAR(vel.a(k, j), v[j] * v[j], 1e-13);
        if (std::abs(v[j]) > 1e-12) EXPECT_EQ(vel.c(k, j), v[j] > 0 ? hi[j] * hi[j] : lo[j] * lo[j]);
      }
      // The angular velocity is a about z; the x, y rows have e·ω = 0: no bound.
      EXPECT_NEAR(ang.a(k, 2), kA * kA, 1e-13);
      EXPECT_EQ(ang.c(k, 2), hi[2] * hi[2]);
      EXPECT_EQ(ang.c(k, 0), kInf);
      EXPECT_EQ(ang.a(k, 0), 0.0);
    }
  }
}

// Only the slider moves (q1 = 0): v = (b, 0, 0) along world x. The point moves towards +x, so [lo, hi] =
// [-1, 0] forces ṡ = 0 (rows b² x <= 0, exactly), and [0, 1] leaves ṡ <= 1 / b (rows b² x <= 1).
TEST(FrameLimits, TheSignOfThePointsVelocityPicksTheBound) {
  const auto robot = rp_arm();
  auto slide = std::make_shared<ClosedFormPath>(2, [](double s, Eigen::Ref<Eigen::VectorXd> q,
                                                      Eigen::Ref<Eigen::VectorXd> dq, Eigen::Ref<Eigen::VectorXd> ddq) {
    q << 0.0, kB * s;
    dq << 0.0, kB;
    ddq << 0.0, 0.0;
  });
  TimeScalingProblem prob(slide, 4);
  const ConstraintRows stop =
      FrameLimits(robot, "tip", FrameQuantity::LinearVelocity, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(0, 1, 1))
          .evaluate(prob.samples());
  const ConstraintRows free =
      FrameLimits(robot, "tip", FrameQuantity::LinearVelocity, Eigen::Vector3d(0, -1, -1), Eigen::Vector3d(1, 1, 1))
          .evaluate(prob.samples());
  for (Eigen::Index k = 0; k < 5; ++k) {
    EXPECT_DOUBLE_EQ(stop.a(k, 0), kB * kB);
    EXPECT_EQ(stop.c(k, 0), 0.0);
    EXPECT_EQ(free.c(k, 0), 1.0);
  }
  prob.add_frame_velocity_limits(robot, "tip", Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(0, 1, 1));
  EXPECT_EQ(prob.feasible_set(2).x_max, 0.0);
  EXPECT_EQ(prob.feasible_set(2).x_max_label, "frame tip linear velocity x");
}

// The tip on a circle about the base (the slider still, q1 = φ): tool speed r per unit s. With only a speed
// limit v the inner grid points run at ṡ = v / r; rest to rest the end intervals take 2Δs / ṡ_1 each
// (no acceleration limit): T = (N + 2) Δs r / v (eq. 25).
TEST(FrameLimits, ACircleAtConstantToolSpeed) {
  const auto robot = rp_arm();
  const double arc = 2.0, r = kR0 + 0.2, v = 0.3;
  auto circle = std::make_shared<ClosedFormPath>(2, [arc](double s, Eigen::Ref<Eigen::VectorXd> q,
                                                          Eigen::Ref<Eigen::VectorXd> dq, Eigen::Ref<Eigen::VectorXd> ddq) {
    q << arc * s, kR0;
    dq << arc, 0.0;
    ddq << 0.0, 0.0;
  });
  const int N = 50;
  TimeScalingProblem prob(circle, N);
  prob.add_frame_translational_speed_limit(robot, "tip", v);
  const Result res = prob.solve();
  ASSERT_TRUE(res.ok());
  EXPECT_NEAR(res.duration, (N + 2) * (arc * r / N) / v, 1e-9);
  for (Eigen::Index k = 1; k < N; ++k) EXPECT_NEAR(res.sdot[k], v / (arc * r), 1e-9);
}

TEST(FrameLimits, HooksAndRelaxation) {
  const auto robot = rp_arm();
  const FrameLimits f(robot, "tip", FrameQuantity::LinearAcceleration, Eigen::Vector3d(-1, 0.5, -kInf),
                      Eigen::Vector3d(2, 3, kInf), FrameAxes::Local, Eigen::Vector3d(0.1, 0, 0));
  EXPECT_EQ(f.family(), "frame");
  EXPECT_EQ(f.robot(), robot);
  EXPECT_EQ(f.joint_rate_limits().order, 0);  // left to the audit under guarantee = continuous
  const auto wide = std::dynamic_pointer_cast<const FrameLimits>(f.relaxed(2.0));
  ASSERT_TRUE(wide);
  EXPECT_EQ(wide->lo(), Eigen::Vector3d(-2, 0.25, -kInf));
  EXPECT_EQ(wide->hi(), Eigen::Vector3d(4, 6, kInf));
  EXPECT_EQ(wide->axes(), FrameAxes::Local);
  EXPECT_EQ(wide->point(), Eigen::Vector3d(0.1, 0, 0));
  const FrameLimits speed(robot, "tip", FrameQuantity::TranslationalSpeed, Eigen::VectorXd(), Eigen::VectorXd::Constant(1, 0.5));
  EXPECT_EQ(std::dynamic_pointer_cast<const FrameLimits>(speed.relaxed(3.0))->hi()[0], 1.5);
  EXPECT_EQ(frame_quantity("angular_acceleration"), FrameQuantity::AngularAcceleration);
  EXPECT_EQ(to_string(FrameQuantity::TranslationalSpeed), "translational_speed");
}

TEST(FrameLimits, ValidationNamesArgumentAndValue) {
  const auto robot = rp_arm();
  const Eigen::Vector3d lo(-1, -1, -1), hi(1, 1, 1);
  TimeScalingProblem prob(polar_path(), 4);
  EXPECT_EQ(error_of([&] { prob.add_frame_translational_speed_limit(robot, "tool9", 1.0); }),
            "link 'tool9' is not a link of robot 'rp'");
  EXPECT_EQ(error_of([&] { prob.add_frame_translational_speed_limit(robot, "tip", 0.0); }), "v_max = 0 must be > 0");
  EXPECT_EQ(error_of([&] { prob.add_frame_translational_speed_limit(nullptr, "tip", 1.0); }), "robot must not be None");
  EXPECT_EQ(error_of([&] { prob.add_frame_acceleration_limits(robot, "tip", Eigen::Vector3d(-1, 2, -1), hi); }),
            "lo[1] = 2 must be <= hi[1] = 1");
  EXPECT_EQ(error_of([&] { prob.add_frame_velocity_limits(robot, "tip", Eigen::Vector3d(-1, -1, 0.5), hi); }),
            "lo[2] = 0.5 must be <= 0 (rest must be admissible)");
  EXPECT_EQ(error_of([&] { prob.add_frame_velocity_limits(robot, "tip", lo, Eigen::Vector3d(1, -0.5, 1), true); }),
            "hi[1] = -0.5 must be >= 0 (rest must be admissible)");
  EXPECT_EQ(error_of([&] { prob.add_frame_velocity_limits(robot, "tip", Eigen::Vector2d(-1, -1), hi); }),
            "lo has size 2, expected 3 (one per axis x, y, z)");
  EXPECT_EQ(error_of([&] { prob.add_frame_velocity_limits(robot, "tip", lo, hi, false, FrameAxes::World,
                                                          Eigen::Vector3d(0, kInf, 0)); }),
            "point[1] = inf must be finite");
  EXPECT_EQ(error_of([] { frame_axes("body"); }), "frame = 'body' must be 'world' or 'local'");
  EXPECT_EQ(error_of([] { frame_quantity("jerk"); }),
            "quantity = 'jerk' must be 'translational_speed', 'linear_velocity', 'angular_velocity', "
            "'linear_acceleration' or 'angular_acceleration'");
  EXPECT_TRUE(prob.constraints().empty());
}

}  // namespace
