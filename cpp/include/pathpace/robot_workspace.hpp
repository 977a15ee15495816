#pragma once
/// @file robot_workspace.hpp
/// Scratch space for RobotModel's algorithms: one per thread, reused across calls (pinocchio's Data).

#include <vector>

#include <Eigen/Core>
#include <Eigen/StdVector>

namespace pathpace {

class RobotModel;

class RobotWorkspace {
 public:
  explicit RobotWorkspace(const RobotModel& model);

  using Vector6 = Eigen::Matrix<double, 6, 1>;
  std::vector<Eigen::Matrix3d> E;   // body i: rotation parent -> body coordinates
  std::vector<Eigen::Vector3d> r;   // body i: its origin in parent coordinates
  std::vector<Vector6> v, a, f;     // spatial velocity, acceleration, force (body coordinates)
  std::vector<Vector6> S;           // joint motion subspace
  std::vector<unsigned char> abc_buffer;  // path_torque_coefficients' per-body scratch (see robot_model.cpp)
  Eigen::VectorXd tmp;              // nq scratch
  Eigen::VectorXd zero;             // nq zeros
};

}  // namespace pathpace
