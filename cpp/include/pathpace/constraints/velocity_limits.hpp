#pragma once
/// @file velocity_limits.hpp
/// Joint velocity limits v_L <= p'(s)·ṡ <= v_U (eq. 13), as the squared-rate bound of eq. (16).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"

namespace pathpace {

// docstrings.txt @@ VelocityLimits
/// @brief Joint velocity limits vmin <= p'(s) ṡ <= vmax (eq. 13, as the bound on ṡ² of eq. 16).
///
/// Since ṡ >= 0, joint j bounds x = ṡ² by (vmax_j / p'_j)² where p'_j > 0 and by (vmin_j / p'_j)² where
/// p'_j < 0; a joint with p'_j = 0 imposes nothing. One row per joint, a = 1, b = 0 (a pure bound on x).
class VelocityLimits : public Constraint {
 public:
  // docstrings.txt @@ VelocityLimits.__init__
  /// @param vmin,vmax (n,): rad/s (or m/s); vmin <= 0 <= vmax, ±inf for none; no NaN.
  /// @param joint_names One per joint: they name the joints in row labels and messages ("velocity panda_joint2";
  ///   default "velocity joint 1").
  VelocityLimits(Eigen::VectorXd vmin, Eigen::VectorXd vmax, std::vector<std::string> joint_names = {});

  std::string name() const override { return "velocity limits"; }
  ConstraintRows evaluate(const PathSamples& samples) const override;
  std::string family() const override { return "velocity"; }
  /// vmin·scale, vmax·scale.
  std::shared_ptr<const Constraint> relaxed(double scale) const override;
  /// These limits with `names`, if they have none (Constraint::with_joint_names).
  std::shared_ptr<const Constraint> with_joint_names(const std::vector<std::string>& names) const override;
  /// Order 1: |q̇| within [vmin, vmax] between grid points too (Constraint::joint_rate_limits).
  JointRateLimits joint_rate_limits() const override { return {1, vmin_, vmax_}; }

  const Eigen::VectorXd& vmin() const { return vmin_; }
  const Eigen::VectorXd& vmax() const { return vmax_; }
  const std::vector<std::string>& joint_names() const { return joint_names_; }

 private:
  Eigen::VectorXd vmin_, vmax_;
  std::vector<std::string> joint_names_;
  std::string joint(Eigen::Index j) const;  // "panda_joint2" or "joint 1"
};

}  // namespace pathpace
