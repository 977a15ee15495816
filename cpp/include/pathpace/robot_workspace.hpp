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
  // Three RNEA channels at once (eq. 12's a, b, c): angular and linear parts, one column per channel.
  // The gravity channel never has an angular acceleration, so AW keeps channels 0 and 1 only.
  std::vector<Eigen::Matrix<double, 3, 2>> AW;
  std::vector<Eigen::Matrix3d> AL, FW, FL;
  /// Plain-array scratch of path_torque_coefficients, per body: channel c of a 3-row block at [3c, 3c+3).
  struct AbcScratch {
    double aw[6], al[9], fw[9], fl[9], v[6];
  };
  std::vector<AbcScratch> abc;
  Eigen::VectorXd tmp;              // nq scratch
  Eigen::VectorXd zero;             // nq zeros
};

}  // namespace pathpace
