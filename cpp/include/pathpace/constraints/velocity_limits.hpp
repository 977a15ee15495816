#pragma once
/// @file velocity_limits.hpp
/// Joint velocity limits v_L <= p'(s)·ṡ <= v_U (eq. 13), as the squared-rate bound of eq. (16).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"

namespace pathpace {

/// Asymmetric joint velocity limits. Since ṡ >= 0, joint j bounds x = ṡ² by (v_U,j / p'_j)² where
/// p'_j > 0 and by (v_L,j / p'_j)² where p'_j < 0; a joint with p'_j = 0 imposes nothing.
/// One row per joint, a = 1, b = 0 (a pure bound on x).
class VelocityLimits : public Constraint {
 public:
  /// vmin[j] <= 0 <= vmax[j]; vmin[j] may be -inf and vmax[j] +inf (no limit). No NaN.
  /// joint_names (optional, one per joint) name the joints in row labels and messages
  /// ("velocity panda_joint2"); without them, "velocity joint 1".
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
