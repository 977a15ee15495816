#pragma once
/// @file torque_limits.hpp
/// Joint torque limits τ_L <= τ <= τ_U along the path through inverse dynamics (eq. 12, 15).

#include <memory>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/robot_model.hpp"

namespace pathpace {

// docstrings.txt @@ TorqueLimits
/// @brief Joint torque limits τ_min <= τ <= τ_max along the path (eq. 12, 15), by our RNEA.
///
/// At each grid point τ = a·x + b·u + c (RobotModel.path_torque_coefficients); two rows per joint,
/// a x + b u <= τ_max - c and -a x - b u <= c - τ_min. The limits are scaled by `scale` and shrunk by
/// `margin` on each side: the safety margins of sec. V.D. A joint with τ_min = τ_max = 0 (a floating base)
/// gives an equality pair: without contact forces such a path can generally not be timed.
class TorqueLimits : public Constraint {
 public:
  // docstrings.txt @@ TorqueLimits.__init__
  /// @param tau_min,tau_max (nq,): N·m (N for prismatic joints); default (None; C++: empty) ∓ the URDF effort.
  /// @param scale Multiplies the limits (sec. V.D's safety margin).
  /// @param margin N·m subtracted from each side after scaling.
  TorqueLimits(std::shared_ptr<const RobotModel> robot, Eigen::VectorXd tau_min = Eigen::VectorXd(),
               Eigen::VectorXd tau_max = Eigen::VectorXd(), double scale = 1.0, double margin = 0.0);

  std::string name() const override { return "torque limits"; }
  ConstraintRows evaluate(const PathSamples& samples) const override;
  std::string family() const override { return "torque"; }
  /// [tau_min, tau_max] (after scale and margin) widened by `scale` about zero (Constraint::relaxed).
  std::shared_ptr<const Constraint> relaxed(double scale) const override;

  // docstrings.txt @@ TorqueLimits.tau_min
  /// (nq,): After scale and margin.
  const Eigen::VectorXd& tau_min() const { return tau_min_; }
  // docstrings.txt @@ TorqueLimits.tau_max
  /// (nq,): After scale and margin.
  const Eigen::VectorXd& tau_max() const { return tau_max_; }
  std::shared_ptr<const RobotModel> robot() const override { return robot_; }
  /// Result::robot and tau_min/tau_max (rank 2: a problem's own torque limits, Constraint::report).
  void report(Result& result, int& torque_rank) const override;

 private:
  std::shared_ptr<const RobotModel> robot_;
  Eigen::VectorXd tau_min_, tau_max_;
};

}  // namespace pathpace
