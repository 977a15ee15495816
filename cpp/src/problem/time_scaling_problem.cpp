#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "solve/grid_sets.hpp"
#include "solve/reachability.hpp"
#include "base/validate.hpp"
#include "pathpace/constraints/acceleration_limits.hpp"
#include "pathpace/constraints/linear_constraint.hpp"
#include "pathpace/constraints/velocity_limits.hpp"
#include "problem/sampling.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"
#include "paths/third_derivatives.hpp"

namespace pathpace {

TimeScalingProblem::TimeScalingProblem(std::shared_ptr<const Path> path, int intervals) : path_(std::move(path)) {
  if (!path_) detail::fail("path must not be None");
  if (intervals < 1) detail::fail("grid = " + std::to_string(intervals) + " must be >= 1 (number of intervals N)");
  samples_.s = Eigen::VectorXd::LinSpaced(intervals + 1, path_->s_begin(), path_->s_end());
  detail::sample_path(*path_, samples_);
}

TimeScalingProblem::TimeScalingProblem(std::shared_ptr<const Path> path, Eigen::VectorXd grid) : path_(std::move(path)) {
  if (!path_) detail::fail("path must not be None");
  if (grid.size() < 2) detail::fail("grid has " + std::to_string(grid.size()) + " points, expected at least 2");
  detail::require_finite("grid", grid);
  detail::require_increasing("grid", grid);
  const double a = path_->s_begin(), b = path_->s_end(), tol = 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
  if (std::abs(grid[0] - a) > tol)
    detail::fail("grid[0] = " + detail::fmt(grid[0]) + " must equal the path's s_begin = " + detail::fmt(a));
  const Eigen::Index n = grid.size() - 1;
  if (std::abs(grid[n] - b) > tol)
    detail::fail(detail::at("grid", n) + " = " + detail::fmt(grid[n]) + " must equal the path's s_end = " + detail::fmt(b));
  grid[0] = a;
  grid[n] = b;
  samples_.s = std::move(grid);
  detail::sample_path(*path_, samples_);
}

void TimeScalingProblem::add_velocity_limits(const Eigen::VectorXd& vmin, const Eigen::VectorXd& vmax) {
  const Use use(*this, Use::Write, "add_velocity_limits");
  add_constraint(std::make_shared<VelocityLimits>(vmin, vmax, joint_names_));
}

void TimeScalingProblem::add_acceleration_limits(const Eigen::VectorXd& amin, const Eigen::VectorXd& amax) {
  const Use use(*this, Use::Write, "add_acceleration_limits");
  add_constraint(std::make_shared<AccelerationLimits>(amin, amax, joint_names_));
}

void TimeScalingProblem::add_jerk_limits(const Eigen::VectorXd& jmin, const Eigen::VectorXd& jmax) {
  const Use use(*this, Use::Write, "add_jerk_limits");
  auto limits = std::make_shared<JerkLimits>(jmin, jmax, joint_names_);
  detail::require_size("jmax", jmax.size(), path_->dof(), "one entry per path coordinate");
  Eigen::MatrixXd l, r;
  detail::third_derivatives(*path_, samples_.s.head(1), l, r);  // InvalidInput now for a path without pieces
  jerk_ = std::move(limits);
}

void TimeScalingProblem::add_frame_translational_speed_limit(std::shared_ptr<const RobotModel> robot,
                                                             const std::string& link, double v_max,
                                                             const Eigen::Vector3d& point) {
  const Use use(*this, Use::Write, "add_frame_translational_speed_limit");
  add_constraint(std::make_shared<FrameLimits>(std::move(robot), link, FrameQuantity::TranslationalSpeed, Eigen::VectorXd(),
                                               Eigen::VectorXd::Constant(1, v_max), FrameAxes::World, point));
}

void TimeScalingProblem::add_frame_velocity_limits(std::shared_ptr<const RobotModel> robot, const std::string& link,
                                                   const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, bool angular,
                                                   FrameAxes axes, const Eigen::Vector3d& point) {
  const Use use(*this, Use::Write, "add_frame_velocity_limits");
  add_constraint(std::make_shared<FrameLimits>(std::move(robot), link,
                                               angular ? FrameQuantity::AngularVelocity : FrameQuantity::LinearVelocity, lo, hi,
                                               axes, point));
}

void TimeScalingProblem::add_frame_acceleration_limits(std::shared_ptr<const RobotModel> robot, const std::string& link,
                                                       const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, bool angular,
                                                       FrameAxes axes, const Eigen::Vector3d& point) {
  const Use use(*this, Use::Write, "add_frame_acceleration_limits");
  add_constraint(std::make_shared<FrameLimits>(
      std::move(robot), link, angular ? FrameQuantity::AngularAcceleration : FrameQuantity::LinearAcceleration, lo, hi, axes,
      point));
}

void TimeScalingProblem::add_linear_constraint(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                               const Eigen::MatrixXd& C, const Eigen::MatrixXd& lo,
                                               const Eigen::MatrixXd& hi, const std::string& label) {
  const Use use(*this, Use::Write, "add_linear_constraint");
  add_constraint(std::make_shared<LinearConstraint>(A, B, C, lo, hi, label));
}

void TimeScalingProblem::add_torque_limits(SecondOrderFunctions::InverseDynamics inverse_dynamics,
                                           const Eigen::VectorXd& tau_min, const Eigen::VectorXd& tau_max, double scale,
                                           double margin) {
  const Use use(*this, Use::Write, "add_torque_limits");
  auto f = std::make_shared<SecondOrderFunctions>();
  f->inverse_dynamics = std::move(inverse_dynamics);
  add_constraint(SecondOrderConstraint::torque_limits(std::move(f), tau_min, tau_max, scale, margin, joint_names_));
}

void TimeScalingProblem::add_second_order_constraint(SecondOrderFunctions::InverseDynamics inverse_dynamics,
                                                     SecondOrderFunctions::OfQ F, SecondOrderFunctions::OfQ g,
                                                     const SecondOrderOptions& options) {
  const Use use(*this, Use::Write, "add_second_order_constraint");
  add_constraint(std::make_shared<SecondOrderConstraint>(std::move(inverse_dynamics), std::move(F), std::move(g), options));
}

void TimeScalingProblem::add_constraint(std::shared_ptr<const Constraint> constraint) {
  const Use use(*this, Use::Write, "add_constraint");
  if (!constraint) detail::fail("constraint must not be None");
  // A constraint that can hold another's limits in its projection takes them (Constraint::can_absorb: a
  // contact constraint its robot's torque limits, eq. 17-18). Both limits hold; the merged constraint
  // replaces the ones it absorbs (once it has evaluated without error).
  std::vector<size_t> takers;
  for (size_t i = 0; i < constraints_.size(); ++i)
    if (constraints_[i]->can_absorb(*constraint)) takers.push_back(i);
  std::vector<size_t> replaced;
  if (takers.size() >= 2) {
    // Contact phases (add_contact_phases): the new limits join every phase, each in its place.
    std::vector<std::shared_ptr<const Constraint>> merged;
    std::vector<ConstraintRows> merged_rows;
    for (size_t i : takers) {
      merged.push_back(constraints_[i]->absorb(*constraint));
      merged_rows.push_back(detail::timed_evaluate(*merged.back(), samples_));
    }
    for (size_t j = 0; j < takers.size(); ++j) {
      constraints_[takers[j]] = std::move(merged[j]);
      rows_[takers[j]] = std::move(merged_rows[j]);
    }
    return;
  }
  if (takers.size() == 1) {
    constraint = constraints_[takers[0]]->absorb(*constraint);
    replaced.push_back(takers[0]);
  } else {
    for (size_t i = 0; i < constraints_.size(); ++i)
      if (constraint->can_absorb(*constraints_[i])) {
        constraint = constraint->absorb(*constraints_[i]);
        replaced.push_back(i);
      }
  }
  ConstraintRows rows = detail::timed_evaluate(*constraint, samples_);
  check_rows(*constraint, rows, samples_.size());
  for (size_t t = replaced.size(); t-- > 0;) {
    constraints_.erase(constraints_.begin() + static_cast<long>(replaced[t]));
    rows_.erase(rows_.begin() + static_cast<long>(replaced[t]));
  }
  constraints_.push_back(std::move(constraint));
  rows_.push_back(std::move(rows));
  if (joint_names_.empty()) {
    const std::shared_ptr<const RobotModel> robot = constraints_.back()->robot();
    if (robot && robot->nq() == samples_.dof()) set_joint_names(robot->joint_names());
  }
}

void TimeScalingProblem::check_rows(const Constraint& constraint, const ConstraintRows& rows, Eigen::Index points) {
  // The shapes always (a user's own Constraint subclass may hand back anything); the entries unless the rows
  // are valid by construction (ConstraintRows::valid_by_construction: the velocity and acceleration limits).
  const Eigen::Index r = rows.rows();
  if (rows.a.rows() != points || rows.b.rows() != points || rows.c.rows() != points ||
      rows.b.cols() != r || rows.c.cols() != r || static_cast<Eigen::Index>(rows.labels.size()) != r)
    detail::fail("constraint '" + constraint.name() + "' returned rows of inconsistent shapes");
  if (rows.valid_by_construction) return;
  // The vectorised check first; the element-wise one (which names the entry) only if it fails.
  if (!detail::finite_entries<false>(rows.a)) detail::require_finite(constraint.name() + " a", rows.a);
  if (!detail::finite_entries<false>(rows.b)) detail::require_finite(constraint.name() + " b", rows.b);
  // c may be +inf (an inactive row), never NaN or -inf: -c < +inf holds exactly for the allowed values.
  if (!detail::finite_entries<true>(rows.c))
    for (Eigen::Index k = 0; k < rows.c.rows(); ++k)
      for (Eigen::Index j = 0; j < r; ++j)
        if (std::isnan(rows.c(k, j)) || rows.c(k, j) == -std::numeric_limits<double>::infinity())
          detail::fail(constraint.name() + " c" + "[" + std::to_string(k) + ", " + std::to_string(j) +
                       "] = " + detail::fmt(rows.c(k, j)) + " must be a number or +inf");
}

void TimeScalingProblem::set_joint_names(std::vector<std::string> names) {
  const Use use(*this, Use::Write, "set_joint_names");
  if (static_cast<Eigen::Index>(names.size()) != samples_.dof())
    detail::fail("joint_names has " + std::to_string(names.size()) + " entries, the path has " +
                 std::to_string(samples_.dof()) + " coordinates");
  joint_names_ = std::move(names);
  // Limits added before the names were known take them now (labels and messages name the joint).
  for (size_t i = 0; i < constraints_.size(); ++i) {
    std::shared_ptr<const Constraint> named = constraints_[i]->with_joint_names(joint_names_);
    if (!named) continue;
    // Only the labels change (the rows do not depend on the names): they come from an evaluation at no
    // grid point, instead of evaluating every point again.
    PathSamples none;
    none.q.resize(0, samples_.dof());
    none.dq = none.ddq = none.q;
    rows_[i].labels = named->evaluate(none).labels;
    constraints_[i] = std::move(named);
  }
}

void TimeScalingProblem::set_boundary_speeds(double sdot_begin, double sdot_end) {
  const Use use(*this, Use::Write, "set_boundary_speeds");
  if (!std::isfinite(sdot_begin) || sdot_begin < 0.0)
    detail::fail("sdot_begin = " + detail::fmt(sdot_begin) + " must be >= 0 and finite");
  if (!std::isfinite(sdot_end) || sdot_end < 0.0)
    detail::fail("sdot_end = " + detail::fmt(sdot_end) + " must be >= 0 and finite");
  sdot_begin_ = sdot_begin;
  sdot_end_ = sdot_end;
}

FeasibleSet TimeScalingProblem::feasible_set(Eigen::Index k) const {
  const Use use(*this, Use::Read, "feasible_set");
  if (k < 0 || k >= samples_.size())
    detail::fail("k = " + std::to_string(k) + " must be in [0, " + std::to_string(samples_.size() - 1) + "]");
  detail::Polygon2d polygon;
  // Built in the solve's units (speeds ~1, see detail::Scale), so that the cut of an unbounded set and the
  // polygon's tolerances are relative to the problem, and mapped back: a 1e-12-long path is bounded too.
  detail::Scale scale = detail::problem_scale(samples_.s, rows_);
  scale.cap = detail::kInfinityCap;
  // Rows refined on demand (Constraint::refines) bound their constraint from outside until a solve refines
  // them: the set shown is the exact one, from the exact constraint at this point alone.
  const bool outer = refines();
  std::vector<ConstraintRows> at_k;
  if (outer) at_k = detail::exact_rows_at(constraints_, rows_, samples_, k);
  const std::vector<ConstraintRows>& rows = outer ? at_k : rows_;
  const Eigen::Index row = outer ? 0 : k;
  std::vector<detail::Line> scratch;
  const detail::PointSet ps = detail::build_point_set(rows, row, polygon, scratch, {}, nullptr, scale);
  std::vector<std::string> labels;
  for (const ConstraintRows& cr : rows) labels.insert(labels.end(), cr.labels.begin(), cr.labels.end());
  auto label = [&](int id) { return id >= 0 ? labels[static_cast<size_t>(id)] : std::string(); };

  FeasibleSet fs;
  fs.index = k;
  fs.s = samples_.s[k];
  fs.x_min = ps.x_lo * scale.x_unit;
  fs.x_max = ps.x_hi_id >= 0 ? ps.x_hi * scale.x_unit : std::numeric_limits<double>::infinity();
  fs.x_max_label = label(ps.x_hi_id);
  fs.empty = ps.empty;
  for (const ConstraintRows& cr : rows)
    if (std::find(cr.inexact_points.begin(), cr.inexact_points.end(), row) != cr.inexact_points.end()) fs.exact = false;
  if (ps.empty) {
    for (int id : ps.certificate)
      if (id >= 0) fs.labels.push_back(label(id));
    return fs;
  }
  fs.halfplanes.resize(static_cast<Eigen::Index>(ps.rows.size()), 3);
  for (size_t i = 0; i < ps.rows.size(); ++i) {
    fs.halfplanes.row(static_cast<Eigen::Index>(i)) << ps.rows[i].a / scale.x_unit, ps.rows[i].b / scale.u_unit,
        ps.rows[i].c;
    fs.labels.push_back(label(ps.rows[i].id));
  }
  const auto& vs = polygon.vertices();
  fs.vertices.resize(static_cast<Eigen::Index>(vs.size()), 2);
  for (size_t i = 0; i < vs.size(); ++i)
    fs.vertices.row(static_cast<Eigen::Index>(i)) << vs[i].x * scale.x_unit, vs[i].y * scale.u_unit;
  for (const detail::Line& e : polygon.edges())
    if (e.id == detail::kBoxYLow || e.id == detail::kBoxYHigh || (e.id == detail::kBoxXHigh && ps.x_hi_id < 0))
      fs.bounded = false;
  return fs;
}

void TimeScalingProblem::set_zero_boundary_accelerations(bool at_begin, bool at_end) {
  const Use use(*this, Use::Write, "set_zero_boundary_accelerations");
  zero_sddot_begin_ = at_begin;
  zero_sddot_end_ = at_end;
}

void TimeScalingProblem::add_boundary_rows(std::vector<ConstraintRows>& rows, detail::IntervalExtra& extra) const {
  const Eigen::Index n = intervals();
  extra.rows.resize(static_cast<size_t>(n));
  if (!zero_sddot_begin_ && !zero_sddot_end_) return;
  int id = 0;
  for (const ConstraintRows& cr : rows) id += static_cast<int>(cr.rows());
  ConstraintRows labels;  // inactive at every grid point: the rows act on the end intervals
  labels.resize(samples_.size(), 2);
  labels.labels = {"sddot = 0 at s_begin", "sddot = 0 at s_end"};
  rows.push_back(std::move(labels));
  // s̈ on interval k is (θ_{k+1} - θ_k) / (2Δs_k): zero is θ_{k+1} <= θ_k and θ_k <= θ_{k+1}.
  if (zero_sddot_begin_) {
    extra.rows[0].push_back({-1.0, 1.0, 0.0, id});
    extra.rows[0].push_back({1.0, -1.0, 0.0, id});
  }
  if (zero_sddot_end_) {
    extra.rows[static_cast<size_t>(n - 1)].push_back({-1.0, 1.0, 0.0, id + 1});
    extra.rows[static_cast<size_t>(n - 1)].push_back({1.0, -1.0, 0.0, id + 1});
  }
}

ProblemSettings TimeScalingProblem::settings() const {
  ProblemSettings s;
  s.sdot_begin = sdot_begin_;
  s.sdot_end = sdot_end_;
  s.zero_sddot_begin = zero_sddot_begin_;
  s.zero_sddot_end = zero_sddot_end_;
  s.joint_names = joint_names_;
  return s;
}

void TimeScalingProblem::set_settings(const ProblemSettings& s) {
  const Use use(*this, Use::Write, "set_settings");
  set_boundary_speeds(s.sdot_begin, s.sdot_end);
  set_zero_boundary_accelerations(s.zero_sddot_begin, s.zero_sddot_end);
  if (!s.joint_names.empty()) set_joint_names(s.joint_names);
}
}  // namespace pathpace
