#pragma once
/// @file frame_limits.hpp
/// Cartesian limits on a point fixed in a robot link: its translational speed, the per-axis linear or
/// angular velocity, the per-axis linear or angular acceleration, in the world or the link frame
/// (Drake's Toppra::AddFrameTranslationalSpeedLimit, AddFrameVelocityLimit, AddFrameAccelerationLimit).

#include <memory>
#include <string>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/robot_model.hpp"

namespace pathpace {

/// What FrameLimits bounds.
enum class FrameQuantity {
  TranslationalSpeed,   ///< ‖v‖ of the point (m/s)
  LinearVelocity,       ///< per axis, the point's velocity (m/s)
  AngularVelocity,      ///< per axis, the link's angular velocity (rad/s)
  LinearAcceleration,   ///< per axis, the point's classical acceleration (m/s²)
  AngularAcceleration,  ///< per axis, the link's angular acceleration (rad/s²)
};

/// The axes of per-axis limits: the world's, or the link frame's (turning with the link). Either way the
/// quantity is the one seen from the world (the classical acceleration is the second time derivative of
/// the world position), only its components are taken along the chosen axes.
enum class FrameAxes { World, Local };

/// Limits on a point fixed in a link of `robot` as the path moves it. With v = J p', ω = J_ω p' and
/// α_x = J p'' + J̇(p') p' (RobotModel::path_frame_motion), q̇ = p' ṡ and q̈ = p' s̈ + p'' ṡ² give, in
/// x = ṡ² and u = s̈, rows that are exact at every grid point:
///  - translational speed ‖v‖ ṡ <= v_max: one row ‖v‖² x <= v_max²;
///  - velocity lo_j <= (e_j·v) ṡ <= hi_j per axis j: since ṡ >= 0, only one side can bind, so one row
///    (e_j·v)² x <= hi_j² where e_j·v > 0 and (e_j·v)² x <= lo_j² where e_j·v < 0 (none where e_j·v = 0 or
///    the bound is infinite). lo_j <= 0 <= hi_j, so rest is admissible: hi_j = 0 with e_j·v > 0 is the row
///    (e_j·v)² x <= 0, which forces ṡ = 0 there, exactly;
///  - acceleration lo_j <= (e_j·α_x) x + (e_j·v) u <= hi_j per axis: two rows (upper, lower), a half-plane
///    pair as joint acceleration limits (eq. 14). A bound on the norm of the acceleration is not a
///    half-plane in (x, u); it is not offered: bound it per axis.
/// Between grid points the rows are left to guarantee = continuous's audit (joint_rate_limits() order 0),
/// which evaluates them at interior points and cuts where the timing breaks them (speed and velocity limits
/// that bind along long stretches take many rounds at large N: bench/README.md, "Frame limits").
///
/// Labels: "frame tool0 speed", "frame tool0 linear velocity x", "frame tool0 angular velocity local z",
/// "frame tool0 linear acceleration z upper". Family "frame": relaxation() widens the limits about zero.
class FrameLimits : public Constraint {
 public:
  /// lo, hi of size 3 (per-axis quantities; ±inf: no limit on that axis side) or, for TranslationalSpeed,
  /// hi of size 1 (v_max > 0, +inf allowed) and lo empty. Velocity limits need lo <= 0 <= hi, acceleration
  /// limits lo <= hi. `point` is in link coordinates, finite. Throws InvalidInput naming the argument.
  FrameLimits(std::shared_ptr<const RobotModel> robot, std::string link, FrameQuantity quantity, Eigen::VectorXd lo,
              Eigen::VectorXd hi, FrameAxes axes = FrameAxes::World,
              const Eigen::Vector3d& point = Eigen::Vector3d::Zero());

  std::string name() const override { return "frame limits (" + link_ + ")"; }
  ConstraintRows evaluate(const PathSamples& samples) const override;
  std::string family() const override { return "frame"; }
  /// [lo, hi] widened by `scale` about zero (Constraint::relaxed).
  std::shared_ptr<const Constraint> relaxed(double scale) const override;
  std::shared_ptr<const RobotModel> robot() const override { return robot_; }

  const std::string& link() const { return link_; }
  FrameQuantity quantity() const { return quantity_; }
  FrameAxes axes() const { return axes_; }
  const Eigen::VectorXd& lo() const { return lo_; }
  const Eigen::VectorXd& hi() const { return hi_; }
  const Eigen::Vector3d& point() const { return point_; }

 private:
  std::shared_ptr<const RobotModel> robot_;
  std::string link_;
  FrameQuantity quantity_;
  Eigen::VectorXd lo_, hi_;
  FrameAxes axes_;
  Eigen::Vector3d point_;
};

/// "translational_speed", "linear_velocity", "angular_velocity", "linear_acceleration", "angular_acceleration".
std::string to_string(FrameQuantity quantity);
/// The inverse of to_string; throws InvalidInput naming `argument` for any other name.
FrameQuantity frame_quantity(const std::string& name, const std::string& argument = "quantity");
/// "world" or "local"; frame_axes throws InvalidInput naming `argument` for any other name.
std::string to_string(FrameAxes axes);
FrameAxes frame_axes(const std::string& name, const std::string& argument = "frame");

}  // namespace pathpace
