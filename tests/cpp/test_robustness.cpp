// Reproducers of issue 10 at the C++ level: deep URDF trees, unchecked inertials and limits, path
// samples shorter than the robot, absurd trajectory speeds, NaN points.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/feasible_set.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/trajectory.hpp"
#include "test_util.hpp"

using namespace pathpace;
using test::error_of;

namespace {

std::string chain_urdf(int links) {
  std::string xml = "<robot name=\"chain\"><link name=\"l0\"/>";
  for (int i = 1; i < links; ++i) {
    const std::string a = std::to_string(i - 1), b = std::to_string(i);
    xml += "<link name=\"l" + b + "\"><inertial><mass value=\"0.1\"/><inertia ixx=\"1e-3\" ixy=\"0\" ixz=\"0\" "
           "iyy=\"1e-3\" iyz=\"0\" izz=\"1e-3\"/></inertial></link><joint name=\"j" + b + "\" type=\"revolute\">"
           "<parent link=\"l" + a + "\"/><child link=\"l" + b + "\"/><origin xyz=\"0 0 0.01\"/><axis xyz=\"0 1 0\"/>"
           "<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/></joint>";
  }
  return xml + "</robot>";
}

const char* kPendulum =
    "<robot name=\"pendulum\"><link name=\"base\"/><link name=\"arm\"><inertial><origin xyz=\"0 0 -1\"/>"
    "<mass value=\"MASS\"/><inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial></link>"
    "<joint name=\"hinge\" type=\"continuous\"><parent link=\"base\"/><child link=\"arm\"/><axis xyz=\"0 1 0\"/>"
    "<limit effort=\"EFFORT\" velocity=\"100\"/></joint></robot>";

std::string pendulum(const std::string& mass, const std::string& effort) {
  std::string s = kPendulum;
  s.replace(s.find("MASS"), 4, mass);
  s.replace(s.find("EFFORT"), 6, effort);
  return s;
}

}  // namespace

TEST(Robustness, DeepUrdfChainLoadsWithoutRecursionInUrdfOrder) {
  // A recursive builder overflowed the stack at ~10,000 links.
  const RobotModel m = RobotModel::from_urdf_string(chain_urdf(20000));
  ASSERT_EQ(m.nq(), 19999);
  EXPECT_EQ(m.joint_names().front(), "j1");
  EXPECT_EQ(m.joint_names().back(), "j19999");
}

TEST(Robustness, UrdfInertialsAndLimitsAreValidated) {
  EXPECT_NO_THROW(RobotModel::from_urdf_string(pendulum("1", "5")));
  EXPECT_EQ(error_of([] { RobotModel::from_urdf_string(pendulum("-1", "5")); }),
            "urdf link 'arm' inertial mass = -1 must be >= 0 and finite");
  // urdfdom logs "nan" as unparsable and kept the link with mass 0: now an error naming both.
  const std::string nan_mass = error_of([] { RobotModel::from_urdf_string(pendulum("nan", "5")); });
  EXPECT_NE(nan_mass.find("mass [nan]"), std::string::npos) << nan_mass;
  EXPECT_NE(nan_mass.find("Link [arm]"), std::string::npos) << nan_mass;
  EXPECT_EQ(error_of([] { RobotModel::from_urdf_string(pendulum("1", "-5")); }),
            "urdf joint 'hinge' limit effort = -5 must be >= 0");
}

TEST(Robustness, ContactDriftOfAPathShorterThanTheRobotIsAnError) {
  const auto robot = std::make_shared<RobotModel>(RobotModel::from_urdf_string(pendulum("1", "5")));
  Contact c;
  c.link = "arm";
  ContactConstraint cc(robot, {c});
  PathSamples ps;  // zero coordinates for a one-joint robot: read past the end before
  ps.s = Eigen::VectorXd::LinSpaced(3, 0.0, 1.0);
  ps.q = ps.dq = ps.ddq = Eigen::MatrixXd::Zero(3, 0);
  EXPECT_EQ(error_of([&] { cc.max_drift(ps, nullptr); }), "q has size 0, robot 'pendulum' has 1 joints");
}

TEST(Robustness, TrajectoryRejectsNegativeAndAbsurdSpeeds) {
  Eigen::MatrixXd w(2, 1);
  w << 0.0, 1.0;
  const auto path = std::make_shared<CubicSplinePath>(w);
  const Eigen::Vector2d s(0.0, 1.0);
  EXPECT_EQ(error_of([&] { Trajectory(path, s, Eigen::Vector2d(1.0, -1.0)); }), "sdot[1] = -1 must be >= 0");
  const std::string big = error_of([&] { Trajectory(path, s, Eigen::Vector2d(1.0, 1e300)); });
  EXPECT_EQ(big.rfind("sdot[1] = 1e+300 is too large for interval 0", 0), 0u) << big;
}

TEST(Robustness, FeasibleSetHoldsNoNanOrInfinitePoint) {
  FeasibleSet fs;
  fs.x_min = 0.0;
  fs.x_max = std::numeric_limits<double>::infinity();
  fs.halfplanes.resize(0, 3);
  EXPECT_TRUE(fs.contains(1.0, 0.0));
  EXPECT_FALSE(fs.contains(std::nan(""), 0.0));
  EXPECT_FALSE(fs.contains(1.0, std::nan("")));
  EXPECT_FALSE(fs.contains(std::numeric_limits<double>::infinity(), 0.0));
  EXPECT_THROW(fs.contains(1.0, 0.0, std::nan("")), InvalidInput);
}
