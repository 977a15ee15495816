#include "pathpace/constraints/frame_limits.hpp"

#include <cmath>
#include <limits>

#include "base/validate.hpp"
#include "geometry/interval_bounds.hpp"

namespace pathpace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const char* const kAxis[3] = {"x", "y", "z"};

bool is_velocity(FrameQuantity q) { return q == FrameQuantity::LinearVelocity || q == FrameQuantity::AngularVelocity; }

std::string quantity_label(FrameQuantity q) {
  switch (q) {
    case FrameQuantity::TranslationalSpeed: return "speed";
    case FrameQuantity::LinearVelocity: return "linear velocity";
    case FrameQuantity::AngularVelocity: return "angular velocity";
    case FrameQuantity::LinearAcceleration: return "linear acceleration";
    case FrameQuantity::AngularAcceleration: return "angular acceleration";
  }
  return "";
}

void check_limits(FrameQuantity quantity, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  if (quantity == FrameQuantity::TranslationalSpeed) {
    detail::require_size("lo", lo.size(), 0, "a speed limit has no lower bound");
    detail::require_size("v_max", hi.size(), 1);
    if (!(hi[0] > 0.0)) detail::fail("v_max = " + detail::fmt(hi[0]) + " must be > 0");
    return;
  }
  detail::require_not_nan("lo", lo);
  detail::require_not_nan("hi", hi);
  detail::require_size("lo", lo.size(), 3, "one per axis x, y, z");
  detail::require_size("hi", hi.size(), 3, "one per axis x, y, z");
  for (Eigen::Index j = 0; j < 3; ++j) {
    if (!(lo[j] <= hi[j]))
      detail::fail(detail::at("lo", j) + " = " + detail::fmt(lo[j]) + " must be <= " + detail::at("hi", j) + " = " +
                   detail::fmt(hi[j]));
    // ṡ = 0 (rest at the ends) must be admissible, as for joint velocity limits.
    if (is_velocity(quantity) && !(lo[j] <= 0.0))
      detail::fail(detail::at("lo", j) + " = " + detail::fmt(lo[j]) + " must be <= 0 (rest must be admissible)");
    if (is_velocity(quantity) && !(hi[j] >= 0.0))
      detail::fail(detail::at("hi", j) + " = " + detail::fmt(hi[j]) + " must be >= 0 (rest must be admissible)");
  }
}

// Row k of a (samples, 3) matrix, in the chosen axes: R^T v for the link frame's (R column-major in `rot`).
Eigen::Vector3d to_axes(const Eigen::Vector3d& v, const Eigen::MatrixXd& rot, Eigen::Index k, FrameAxes axes) {
  if (axes == FrameAxes::World) return v;
  Eigen::Matrix3d R;
  for (int j = 0; j < 9; ++j) R(j % 3, j / 3) = rot(k, j);
  return R.transpose() * v;
}
Eigen::Vector3d in_axes(const Eigen::MatrixXd& m, const Eigen::MatrixXd& rot, Eigen::Index k, FrameAxes axes) {
  return to_axes(m.row(k).transpose(), rot, k, axes);
}

}  // namespace

std::string to_string(FrameQuantity quantity) {
  std::string s = quantity_label(quantity);
  for (char& c : s)
    if (c == ' ') c = '_';
  return s == "speed" ? "translational_speed" : s;
}

FrameQuantity frame_quantity(const std::string& name, const std::string& argument) {
  for (FrameQuantity q : {FrameQuantity::TranslationalSpeed, FrameQuantity::LinearVelocity, FrameQuantity::AngularVelocity,
                          FrameQuantity::LinearAcceleration, FrameQuantity::AngularAcceleration})
    if (to_string(q) == name) return q;
  detail::fail(argument + " = '" + name +
               "' must be 'translational_speed', 'linear_velocity', 'angular_velocity', 'linear_acceleration' or "
               "'angular_acceleration'");
}

std::string to_string(FrameAxes axes) { return axes == FrameAxes::World ? "world" : "local"; }

FrameAxes frame_axes(const std::string& name, const std::string& argument) {
  if (name == "world") return FrameAxes::World;
  if (name == "local") return FrameAxes::Local;
  detail::fail(argument + " = '" + name + "' must be 'world' or 'local'");
}

FrameLimits::FrameLimits(std::shared_ptr<const RobotModel> robot, std::string link, FrameQuantity quantity,
                         Eigen::VectorXd lo, Eigen::VectorXd hi, FrameAxes axes, const Eigen::Vector3d& point)
    : robot_(std::move(robot)), link_(std::move(link)), quantity_(quantity), lo_(std::move(lo)), hi_(std::move(hi)),
      axes_(axes), point_(point) {
  if (!robot_) detail::fail("robot must not be None");
  Eigen::Isometry3d in_body;
  robot_->body_of_link(link_, in_body);  // an unknown link throws, naming it and the robot
  detail::require_finite("point", point_);
  check_limits(quantity_, lo_, hi_);
}

ConstraintRows FrameLimits::evaluate(const PathSamples& samples) const {
  if (samples.dof() != robot_->nq())
    detail::fail("path has " + std::to_string(samples.dof()) + " coordinates, robot '" + robot_->name() + "' has " +
                 std::to_string(robot_->nq()) + " joints");
  const RobotModel::FrameMotion f = robot_->path_frame_motion(samples.q, samples.dq, samples.ddq, link_, point_);
  const Eigen::Index m = samples.size();
  const bool angular = quantity_ == FrameQuantity::AngularVelocity || quantity_ == FrameQuantity::AngularAcceleration;
  const Eigen::MatrixXd& vel = angular ? f.angular_velocity : f.velocity;
  const Eigen::MatrixXd& acc = angular ? f.angular_acceleration : f.acceleration;
  const std::string head = "frame " + link_ + " " + quantity_label(quantity_) + (axes_ == FrameAxes::Local ? " local " : " ");
  // valid_by_construction stays false: the square of a huge (finite) velocity in `a` could overflow, and the
  // problem's scan of the entries costs little beside the forward passes.
  ConstraintRows rows;
  if (quantity_ == FrameQuantity::TranslationalSpeed) {
    rows.resize(m, 1);
    rows.labels[0] = "frame " + link_ + " speed";
    for (Eigen::Index k = 0; k < m; ++k) {
      rows.a(k, 0) = f.velocity.row(k).squaredNorm();
      rows.c(k, 0) = hi_[0] * hi_[0];
    }
    return rows;
  }
  if (is_velocity(quantity_)) {
    rows.resize(m, 3);  // a = b = 0, c = +inf: inactive until written
    for (int j = 0; j < 3; ++j) rows.labels[static_cast<size_t>(j)] = head + kAxis[j];
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Vector3d v = in_axes(vel, f.rotation, k, axes_);
      for (int j = 0; j < 3; ++j) {
        const double bound = v[j] > 0.0 ? hi_[j] : lo_[j];  // ṡ >= 0: the sign of e·v picks the side
        if (v[j] == 0.0 || !std::isfinite(bound)) continue;
        rows.a(k, j) = v[j] * v[j];
        rows.c(k, j) = bound * bound;
      }
    }
    return rows;
  }
  rows.allocate(m, 6);
  for (int j = 0; j < 3; ++j) {
    rows.labels[static_cast<size_t>(2 * j)] = head + kAxis[j] + " upper";
    rows.labels[static_cast<size_t>(2 * j + 1)] = head + kAxis[j] + " lower";
  }
  for (Eigen::Index k = 0; k < m; ++k) {
    const Eigen::Vector3d a = in_axes(acc, f.rotation, k, axes_), b = in_axes(vel, f.rotation, k, axes_);
    for (int j = 0; j < 3; ++j) {
      rows.a(k, 2 * j) = a[j];
      rows.b(k, 2 * j) = b[j];
      rows.c(k, 2 * j) = hi_[j];  // +inf: inactive
      rows.a(k, 2 * j + 1) = -a[j];
      rows.b(k, 2 * j + 1) = -b[j];
      rows.c(k, 2 * j + 1) = -lo_[j];
    }
  }
  return rows;
}

Eigen::VectorXd FrameLimits::speed_bounds_between_grid_points(const PathSamples& samples,
                                                              const ConstraintRows& grid) const {
  if (quantity_ != FrameQuantity::TranslationalSpeed && !is_velocity(quantity_)) return {};
  if (samples.dof() != robot_->nq()) return {};  // evaluate() has reported it
  const RobotModel::FrameMotion f = robot_->path_frame_motion(samples.q, samples.dq, samples.ddq, link_, point_);
  const Eigen::Index m = samples.size();
  const bool angular = quantity_ == FrameQuantity::AngularVelocity;
  const Eigen::MatrixXd& vel = angular ? f.angular_velocity : f.velocity;
  // f's accelerations at ṡ = 1, s̈ = 0 are the s-derivatives of its velocities (d/ds of J p' = J p'' + J̇ p').
  const Eigen::MatrixXd& dvel = angular ? f.angular_acceleration : f.acceleration;
  // The grid rows' own bound per grid point (over every axis): no line needs to start above it.
  Eigen::VectorXd start = Eigen::VectorXd::Constant(m, std::numeric_limits<double>::infinity());
  for (Eigen::Index k = 0; k < m && grid.a.rows() == m; ++k)
    for (Eigen::Index j = 0; j < grid.rows(); ++j)
      if (grid.a(k, j) > 0.0 && grid.c(k, j) < kInf) start[k] = std::min(start[k], grid.c(k, j) / grid.a(k, j));
  if (quantity_ == FrameQuantity::TranslationalSpeed)
    return detail::hermite_speed_bounds(samples.s, vel, dvel, -hi_[0], hi_[0], start);
  // Components along the chosen axes, and their derivatives: d/ds (Rᵀ v) = Rᵀ (v' - ω × v), ω the link's
  // angular velocity per unit s (for v = ω itself the cross term vanishes).
  Eigen::MatrixXd e(m, 3), de(m, 3);
  for (Eigen::Index k = 0; k < m; ++k) {
    const Eigen::Vector3d v = vel.row(k).transpose(), w = f.angular_velocity.row(k).transpose();
    Eigen::Vector3d d = dvel.row(k).transpose();
    if (axes_ == FrameAxes::Local) d -= w.cross(v);
    e.row(k) = to_axes(v, f.rotation, k, axes_).transpose();
    de.row(k) = to_axes(d, f.rotation, k, axes_).transpose();
  }
  Eigen::VectorXd out = Eigen::VectorXd::Constant(m, kInf);
  for (Eigen::Index j = 0; j < 3; ++j)
    out = out.cwiseMin(detail::hermite_speed_bounds(samples.s, e.col(j), de.col(j), lo_[j], hi_[j], start));
  return out;
}

std::shared_ptr<const Constraint> FrameLimits::relaxed(double scale) const {
  Eigen::VectorXd lo = lo_, hi = hi_;
  for (Eigen::Index j = 0; j < lo.size(); ++j) lo[j] = widen_lower(lo[j], scale);
  for (Eigen::Index j = 0; j < hi.size(); ++j) hi[j] = widen_upper(hi[j], scale);
  return std::make_shared<FrameLimits>(robot_, link_, quantity_, lo, hi, axes_, point_);
}

}  // namespace pathpace
