#include "pathpace/constraints/torque_limits.hpp"

#include <cmath>

#include "robot/torque_lanes.hpp"
#include "base/validate.hpp"
#include "pathpace/result.hpp"
#include "pathpace/robot_workspace.hpp"

namespace pathpace {

TorqueLimits::TorqueLimits(std::shared_ptr<const RobotModel> robot, Eigen::VectorXd tau_min, Eigen::VectorXd tau_max,
                           double scale, double margin)
    : robot_(std::move(robot)) {
  if (!robot_) detail::fail("robot must not be None");
  const int n = robot_->nq();
  if (tau_max.size() == 0) tau_max = robot_->effort_limits();
  if (tau_min.size() == 0) tau_min = -robot_->effort_limits();
  detail::require_size("tau_min", tau_min.size(), n, "one per joint of robot '" + robot_->name() + "'");
  detail::require_size("tau_max", tau_max.size(), n, "one per joint of robot '" + robot_->name() + "'");
  detail::require_not_nan("tau_min", tau_min);
  detail::require_not_nan("tau_max", tau_max);
  if (!(scale > 0.0) || !std::isfinite(scale)) detail::fail("scale = " + detail::fmt(scale) + " must be > 0 and finite");
  if (!(margin >= 0.0) || !std::isfinite(margin)) detail::fail("margin = " + detail::fmt(margin) + " must be >= 0 and finite");
  for (int j = 0; j < n; ++j)
    if (!(tau_min[j] <= tau_max[j]))
      detail::fail(detail::at("tau_min", j) + " = " + detail::fmt(tau_min[j]) + " must be <= " + detail::at("tau_max", j) +
                   " = " + detail::fmt(tau_max[j]));
  tau_min_ = scale * tau_min.array() + margin;
  tau_max_ = scale * tau_max.array() - margin;
  for (int j = 0; j < n; ++j)
    if (tau_min_[j] > tau_max_[j])
      detail::fail("margin = " + detail::fmt(margin) + " closes the torque range of joint '" + robot_->joint_names()[j] +
                   "' ([" + detail::fmt(scale * tau_min[j]) + ", " + detail::fmt(scale * tau_max[j]) + "])");
}

ConstraintRows TorqueLimits::evaluate(const PathSamples& samples) const {
  const int n = robot_->nq();
  if (samples.dof() != n)
    detail::fail("path has " + std::to_string(samples.dof()) + " coordinates, robot '" + robot_->name() + "' has " +
                 std::to_string(n) + " joints");
  ConstraintRows rows;
  rows.allocate(samples.size(), 2 * n);  // every entry is written below
  for (int j = 0; j < n; ++j) {
    rows.labels[static_cast<size_t>(2 * j)] = "torque " + robot_->joint_names()[static_cast<size_t>(j)] + " upper";
    rows.labels[static_cast<size_t>(2 * j + 1)] = "torque " + robot_->joint_names()[static_cast<size_t>(j)] + " lower";
  }
  // eq. (15): τ_L <= a x + b u + c <= τ_U as the rows (a, b, τ_U - c) and (-a, -b, c - τ_L), written
  // straight from the sweeps' lanes; an infinite limit gives c = +inf: an inactive row.
  RobotWorkspace ws(*robot_);
  detail::TorqueOutput out{rows.a.data(), rows.b.data(), rows.c.data(), 2 * n, 2, tau_max_.data(), tau_min_.data()};
  detail::path_torque_coefficients_into(*robot_, ws, samples.q, samples.dq, samples.ddq, out);
  return rows;
}

std::shared_ptr<const Constraint> TorqueLimits::relaxed(double scale) const {
  Eigen::VectorXd lo = tau_min_, hi = tau_max_;
  for (Eigen::Index j = 0; j < lo.size(); ++j) {
    lo[j] = widen_lower(lo[j], scale);
    hi[j] = widen_upper(hi[j], scale);
  }
  return std::make_shared<TorqueLimits>(robot_, lo, hi);
}

void TorqueLimits::report(Result& result, int& torque_rank) const {
  result.robot = robot_;
  result.tau_min = tau_min_;
  result.tau_max = tau_max_;
  torque_rank = 2;
}

}  // namespace pathpace
