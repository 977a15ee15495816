#pragma once
/// @file jerk_limits.hpp
/// Joint jerk limits jmin <= q⃛ <= jmax, q⃛ = p' s⃛ + 3 p'' ṡ s̈ + p''' ṡ³ (TimeScalingProblem::add_jerk_limits).

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace pathpace {

// docstrings.txt @@ JerkLimits
/// @brief Joint jerk limits jmin <= q⃛ <= jmax, with q⃛ = p' s⃛ + 3 p'' ṡ s̈ + p''' ṡ³.
///
/// Not a Constraint: in (θ = ṡ², b = s̈) a jerk limit reads |p' b' + 3 p'' b + p''' θ| <= J / √θ (b' = ds̈/ds),
/// which is neither a half-plane nor a function of one grid point. TimeScalingProblem::add_jerk_limits keeps
/// it beside the constraints, and solve() linearises it at each iterate (docs/method.md, "Jerk limits").
class JerkLimits {
 public:
  // docstrings.txt @@ JerkLimits.__init__
  /// @param jmin,jmax (n,): rad/s³ (or m/s³); jmin < 0 < jmax, -inf / inf for none; no NaN.
  /// @param joint_names One per joint for messages (default "joint 1").
  JerkLimits(Eigen::VectorXd jmin, Eigen::VectorXd jmax, std::vector<std::string> joint_names = {});

  const Eigen::VectorXd& jmin() const { return jmin_; }
  const Eigen::VectorXd& jmax() const { return jmax_; }
  const std::vector<std::string>& joint_names() const { return joint_names_; }

 private:
  Eigen::VectorXd jmin_, jmax_;
  std::vector<std::string> joint_names_;
};

}  // namespace pathpace
