#pragma once
/// @file acceleration_limits.hpp
/// Joint acceleration limits a_L <= p''(s)·ṡ² + p'(s)·s̈ <= a_U (eq. 14).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"

namespace pathpace {

// docstrings.txt @@ AccelerationLimits
/// @brief Joint acceleration limits amin <= p''ṡ² + p's̈ <= amax (eq. 14).
///
/// Two rows per joint, p''_j x + p'_j u <= amax_j and -p''_j x - p'_j u <= -amin_j; infinite limits give
/// inactive rows.
class AccelerationLimits : public Constraint {
 public:
  // docstrings.txt @@ AccelerationLimits.__init__
  /// @param amin,amax (n,): rad/s² (or m/s²); amin <= amax, ±inf for none; no NaN.
  /// @param joint_names One per joint: they name the joints in row labels and messages ("acceleration panda_joint2
  ///   upper"; default "acceleration joint 1 upper").
  AccelerationLimits(Eigen::VectorXd amin, Eigen::VectorXd amax, std::vector<std::string> joint_names = {});

  std::string name() const override { return "acceleration limits"; }
  ConstraintRows evaluate(const PathSamples& samples) const override;
  std::string family() const override { return "acceleration"; }
  /// [amin, amax] widened by `scale` about zero (Constraint::relaxed).
  std::shared_ptr<const Constraint> relaxed(double scale) const override;

  /// These limits with `names`, if they have none (Constraint::with_joint_names).
  std::shared_ptr<const Constraint> with_joint_names(const std::vector<std::string>& names) const override;
  /// Order 2: q̈ within [amin, amax] between grid points too (Constraint::joint_rate_limits).
  JointRateLimits joint_rate_limits() const override { return {2, amin_, amax_}; }

  const Eigen::VectorXd& amin() const { return amin_; }
  const Eigen::VectorXd& amax() const { return amax_; }
  const std::vector<std::string>& joint_names() const { return joint_names_; }

 private:
  Eigen::VectorXd amin_, amax_;
  std::vector<std::string> joint_names_;
  std::string joint(Eigen::Index j) const;  // "panda_joint2" or "joint 1"
};

}  // namespace pathpace
