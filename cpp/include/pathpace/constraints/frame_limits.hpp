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

// docstrings.txt @@ FrameLimits
/// @brief Cartesian limits on a point fixed in a robot link (issue 22; Drake's Toppra frame limits), exact at the
/// grid points: with v = J p', ω = J_ω p' and the classical acceleration term J p'' + J̇(p') p' of the path,
///
/// - `"translational_speed"`: ‖v‖ ṡ <= v_max, one row ‖v‖² ṡ² <= v_max²;
/// - `"linear_velocity"`, `"angular_velocity"`: lo_j <= (e_j·v) ṡ <= hi_j per axis; as ṡ >= 0 only the
///   side of e_j·v's sign binds, one row (e_j·v)² ṡ² <= hi_j² (or lo_j²); hi_j = 0 where e_j·v > 0 forces
///   ṡ = 0 there;
/// - `"linear_acceleration"`, `"angular_acceleration"`: lo_j <= e_j·(J p' s̈ + (J p'' + J̇ p') ṡ²) <= hi_j
///   per axis, two rows. Per axis only: a bound on the norm of the acceleration is not a half-plane.
///
/// With guarantee='continuous' the audit checks the rows between grid points. Speed and velocity limits also
/// bound ṡ² at the grid points so that the rows hold between them for a cubic Hermite model of the frame
/// velocity (from its values and s-derivatives at the grid points, with a margin for the model's error): where
/// they bind along a stretch the audit then confirms in one round instead of cutting round after round
/// (bench/README.md). Family "frame" (relaxation).
class FrameLimits : public Constraint {
 public:
  // docstrings.txt @@ FrameLimits.__init__
  /// @param link A link of `robot` (merged fixed links too, e.g. a tool frame).
  /// @param quantity One of the five above.
  /// @param lo,hi (3,): Per axis x, y, z (±inf: no limit); velocities need lo <= 0 <= hi (rest admissible),
  ///   accelerations lo <= hi. For "translational_speed": hi is v_max (m/s, > 0) and lo None.
  /// @param point (3,): In the link frame, m.
  FrameLimits(std::shared_ptr<const RobotModel> robot, std::string link, FrameQuantity quantity, Eigen::VectorXd lo,
              Eigen::VectorXd hi, FrameAxes axes = FrameAxes::World,
              const Eigen::Vector3d& point = Eigen::Vector3d::Zero());

  std::string name() const override { return "frame limits (" + link_ + ")"; }
  ConstraintRows evaluate(const PathSamples& samples) const override;
  std::string family() const override { return "frame"; }
  /// [lo, hi] widened by `scale` about zero (Constraint::relaxed).
  std::shared_ptr<const Constraint> relaxed(double scale) const override;
  std::shared_ptr<const RobotModel> robot() const override { return robot_; }
  /// Speed and velocity limits: the bounds of detail::hermite_speed_bounds, from the frame velocity and its
  /// s-derivative (the path acceleration of path_frame_motion) at the grid points; accelerations: none.
  Eigen::VectorXd speed_bounds_between_grid_points(const PathSamples& samples, const ConstraintRows& rows) const override;

  const std::string& link() const { return link_; }
  FrameQuantity quantity() const { return quantity_; }
  FrameAxes axes() const { return axes_; }
  // docstrings.txt @@ FrameLimits.lo
  /// (3,), or (0,) for a speed limit.
  const Eigen::VectorXd& lo() const { return lo_; }
  // docstrings.txt @@ FrameLimits.hi
  /// (3,), or (1,) = v_max for a speed limit.
  const Eigen::VectorXd& hi() const { return hi_; }
  // docstrings.txt @@ FrameLimits.point
  /// (3,): m, link frame.
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
