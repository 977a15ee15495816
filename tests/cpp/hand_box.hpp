#pragma once
// The hand that pushes a box and then brakes it (tests/data/hand_box.urdf), shared by the C++ tests of contact
// phases and of constraint hooks (header-only).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/pathpace.hpp"

namespace pathpace::test {

inline std::shared_ptr<RobotModel> load(const std::string& name) {
  return std::make_shared<RobotModel>(RobotModel::from_urdf_file(std::string(PATHPACE_TEST_DATA_DIR) + "/" + name));
}

inline Contact hand_on_box(double nx) {
  Contact c;
  c.link = "box";
  c.other_link = "hand";
  c.normal = Eigen::Vector3d(nx, 0, 0);  // +1: the hand behind the box pushes it, -1: in front, brakes it
  return c;
}

// Hand and box together, x = s on s in [0, 2].
inline std::shared_ptr<Path> together(int knots = 3) {
  const Eigen::VectorXd s = Eigen::VectorXd::LinSpaced(knots, 0.0, 2.0);
  Eigen::MatrixXd q(knots, 2);
  q << s, s;
  return std::make_shared<CubicSplinePath>(q, s);
}

inline std::vector<ContactPhase> push_then_brake(double split = 1.0) {
  return {{0.0, split, {hand_on_box(1.0)}, std::nullopt}, {split, 2.0, {hand_on_box(-1.0)}, std::nullopt}};
}

}  // namespace pathpace::test
