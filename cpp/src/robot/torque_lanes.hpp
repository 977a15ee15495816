#pragma once
// Internal: the SIMD variants of RobotModel::path_torque_coefficients_batch (torque_lanes.cpp), exposed
// so that tests can compare them on one machine.

#include <Eigen/Core>

#include "pathpace/robot_model.hpp"
#include "pathpace/robot_workspace.hpp"

namespace pathpace::detail {

/// Samples per sweep of the widest variant this CPU runs: 8 (AVX-512), 4 (AVX2 + FMA), 2 (SSE2 or
/// another compiler-vector target) or 1 (no vector types).
int torque_lanes_supported();

/// The width a call with lanes = 0 takes: torque_lanes_supported(), unless the environment variable
/// PATHPACE_TORQUE_LANES forces a narrower one (1, 2, 4 or 8; InvalidInput if the CPU does not run it).
/// Tests set it to exercise, on one machine, every path another CPU of this kind could pick.
int default_torque_lanes();

/// Where path_torque_coefficients_into writes sample s, joint j: a[s * sample_stride + j * joint_stride]
/// (and b, c likewise); each a distinct entry. With `upper` and `lower` (one per joint), the entry and the
/// next one get TorqueLimits' row pair of eq. (15) instead: (a, -a), (b, -b), (upper - c, c - lower),
/// +inf for an infinite limit (an inactive row).
struct TorqueOutput {
  double *a, *b, *c;
  Eigen::Index sample_stride, joint_stride;
  const double* upper = nullptr;
  const double* lower = nullptr;
};

/// Throws InvalidInput unless q, dq and ddq all have shape (samples, n).
void check_sample_shapes(Eigen::Index n, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq);

/// path_torque_coefficients_batch into caller-laid-out arrays (TorqueLimits writes its rows directly),
/// with `lanes` samples per sweep: 0 = default_torque_lanes(), 1 = one sample at a time, else a power of
/// 2 up to torque_lanes_supported() (InvalidInput beyond). A robot with mimic joints takes the widest.
void path_torque_coefficients_into(const RobotModel& robot, RobotWorkspace& ws, const Eigen::MatrixXd& q,
                                   const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, const TorqueOutput& out,
                                   int lanes = 0);

/// The same into (samples, nq) matrices, resized here.
void path_torque_coefficients_lanes(const RobotModel& robot, RobotWorkspace& ws, const Eigen::MatrixXd& q,
                                    const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, Eigen::MatrixXd& a,
                                    Eigen::MatrixXd& b, Eigen::MatrixXd& c, int lanes = 0);

}  // namespace pathpace::detail
