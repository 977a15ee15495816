#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "detail/grid_sets.hpp"
#include "detail/reachability.hpp"
#include "detail/slp.hpp"
#include "detail/validate.hpp"
#include "pathpace/constraints/acceleration_limits.hpp"
#include "pathpace/constraints/linear_constraint.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/constraints/velocity_limits.hpp"

namespace pathpace {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// An infeasibility with contacts is a claim about the robot, and the polygons are projections: before
// it is reported, one LP on the full (ṡ², s̈, τ, f) polytope at the binding grid point, with every other
// constraint's half-planes there, re-checks it; the message says whether the rest state (0, 0) is
// feasible there. A point whose polygon is empty but whose full LP is not is a projection failure.
void recheck_contacts(const TimeScalingProblem& problem, const std::vector<ConstraintRows>& rows, Eigen::Index k,
                      bool point_empty, Result& res) {
  Eigen::Matrix<double, Eigen::Dynamic, 3> extra(0, 3);
  for (size_t i = 0; i < rows.size(); ++i) {
    const ConstraintRows& cr = rows[i];
    if (problem.constraints()[i] == res.contacts) continue;
    for (Eigen::Index j = 0; j < cr.rows(); ++j)
      if (std::isfinite(cr.c(k, j))) {
        extra.conservativeResize(extra.rows() + 1, 3);
        extra.row(extra.rows() - 1) << cr.a(k, j), cr.b(k, j), cr.c(k, j);
      }
  }
  const ContactConstraint::PointCheck check = res.contacts->check_point(problem.samples(), k, extra);
  auto word = [](int v, const char* yes, const char* no) { return v > 0 ? yes : v == 0 ? no : "unknown (LP failed)"; };
  if (point_empty && check.feasible > 0) {
    res.status = Status::NumericalError;
    res.message = "the feasible set is empty at grid index " + std::to_string(k) + " (s = " +
                  detail::fmt(problem.samples().s[k]) +
                  "), but one LP on the full (sdot^2, sddot, torque, force) polytope there is feasible: the projection failed";
    return;
  }
  res.message += std::string("; re-checked by one LP on the full (sdot^2, sddot, torque, force) polytope at that point: ") +
                 word(check.feasible, "feasible", "infeasible") + ", rest state (0, 0) " +
                 word(check.rest_feasible, "feasible", "infeasible");
}

}  // namespace

TimeScalingProblem::TimeScalingProblem(std::shared_ptr<const Path> path, int intervals) : path_(std::move(path)) {
  if (!path_) detail::fail("path must not be None");
  if (intervals < 1) detail::fail("grid = " + std::to_string(intervals) + " must be >= 1 (number of intervals N)");
  samples_.s = Eigen::VectorXd::LinSpaced(intervals + 1, path_->s_begin(), path_->s_end());
  init_samples();
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
  init_samples();
}

void TimeScalingProblem::init_samples() {
  path_->evaluate(samples_.s, samples_.q, samples_.dq, samples_.ddq);
  for (Eigen::Index k = 0; k < samples_.size(); ++k)
    for (Eigen::Index j = 0; j < samples_.dof(); ++j)
      if (!std::isfinite(samples_.q(k, j)) || !std::isfinite(samples_.dq(k, j)) || !std::isfinite(samples_.ddq(k, j)))
        detail::fail("path is not finite at grid[" + std::to_string(k) + "] = " + detail::fmt(samples_.s[k]) +
                     " (coordinate " + std::to_string(j) + ")");
}

void TimeScalingProblem::add_velocity_limits(const Eigen::VectorXd& vmin, const Eigen::VectorXd& vmax) {
  add_constraint(std::make_shared<VelocityLimits>(vmin, vmax));
}

void TimeScalingProblem::add_acceleration_limits(const Eigen::VectorXd& amin, const Eigen::VectorXd& amax) {
  add_constraint(std::make_shared<AccelerationLimits>(amin, amax));
}

void TimeScalingProblem::add_linear_constraint(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                               const Eigen::MatrixXd& C, const Eigen::MatrixXd& lo,
                                               const Eigen::MatrixXd& hi, const std::string& label) {
  add_constraint(std::make_shared<LinearConstraint>(A, B, C, lo, hi, label));
}

void TimeScalingProblem::add_constraint(std::shared_ptr<const Constraint> constraint) {
  if (!constraint) detail::fail("constraint must not be None");
  // Torque limits and contacts of one robot are one projection (eq. 17-18): alone, the torque limits
  // would demand τ = 0 of an unactuated floating base that only contact forces can hold. Both limits
  // hold; the merged constraint replaces the ones it absorbs (once it has evaluated without error).
  std::vector<size_t> replaced;
  if (auto torque = std::dynamic_pointer_cast<const TorqueLimits>(constraint)) {
    for (size_t i = 0; i < constraints_.size(); ++i)
      if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(constraints_[i]);
          contact && contact->robot() == torque->robot()) {
        constraint = contact->with_torque_limits(torque->tau_min(), torque->tau_max());
        replaced.push_back(i);
        break;
      }
  } else if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(constraint)) {
    for (size_t i = 0; i < constraints_.size(); ++i)
      if (auto t = std::dynamic_pointer_cast<const TorqueLimits>(constraints_[i]); t && t->robot() == contact->robot()) {
        contact = contact->with_torque_limits(t->tau_min(), t->tau_max());
        replaced.push_back(i);
      }
    constraint = contact;
  }
  const auto t0 = std::chrono::steady_clock::now();
  ConstraintRows rows = constraint->evaluate(samples_);
  rows.seconds = seconds_since(t0);
  // A constraint of ours is trusted, but a user's own Constraint subclass may hand back anything.
  const Eigen::Index r = rows.rows();
  if (rows.a.rows() != samples_.size() || rows.b.rows() != samples_.size() || rows.c.rows() != samples_.size() ||
      rows.b.cols() != r || rows.c.cols() != r || static_cast<Eigen::Index>(rows.labels.size()) != r)
    detail::fail("constraint '" + constraint->name() + "' returned rows of inconsistent shapes");
  // The vectorised check first; the element-wise one (which names the entry) only if it fails.
  if (!rows.a.allFinite()) detail::require_finite(constraint->name() + " a", rows.a);
  if (!rows.b.allFinite()) detail::require_finite(constraint->name() + " b", rows.b);
  // c may be +inf (an inactive row), never NaN or -inf: -c < +inf holds exactly for the allowed values.
  if (!((-rows.c.array()) < std::numeric_limits<double>::infinity()).all())
    for (Eigen::Index k = 0; k < rows.c.rows(); ++k)
      for (Eigen::Index j = 0; j < r; ++j)
        if (std::isnan(rows.c(k, j)) || rows.c(k, j) == -std::numeric_limits<double>::infinity())
          detail::fail(constraint->name() + " c" + "[" + std::to_string(k) + ", " + std::to_string(j) +
                       "] = " + detail::fmt(rows.c(k, j)) + " must be a number or +inf");
  for (size_t t = replaced.size(); t-- > 0;) {
    constraints_.erase(constraints_.begin() + static_cast<long>(replaced[t]));
    rows_.erase(rows_.begin() + static_cast<long>(replaced[t]));
  }
  constraints_.push_back(std::move(constraint));
  rows_.push_back(std::move(rows));
}

void TimeScalingProblem::set_boundary_speeds(double sdot_begin, double sdot_end) {
  if (!std::isfinite(sdot_begin) || sdot_begin < 0.0)
    detail::fail("sdot_begin = " + detail::fmt(sdot_begin) + " must be >= 0 and finite");
  if (!std::isfinite(sdot_end) || sdot_end < 0.0)
    detail::fail("sdot_end = " + detail::fmt(sdot_end) + " must be >= 0 and finite");
  sdot_begin_ = sdot_begin;
  sdot_end_ = sdot_end;
}

FeasibleSet TimeScalingProblem::feasible_set(Eigen::Index k) const {
  if (k < 0 || k >= samples_.size())
    detail::fail("k = " + std::to_string(k) + " must be in [0, " + std::to_string(samples_.size() - 1) + "]");
  detail::Polygon2d polygon;
  const detail::PointSet ps = detail::build_point_set(rows_, k, polygon);
  std::vector<std::string> labels;
  for (const ConstraintRows& cr : rows_) labels.insert(labels.end(), cr.labels.begin(), cr.labels.end());
  auto label = [&](int id) { return id >= 0 ? labels[static_cast<size_t>(id)] : std::string(); };

  FeasibleSet fs;
  fs.index = k;
  fs.s = samples_.s[k];
  fs.x_min = ps.x_lo;
  fs.x_max = ps.x_hi_id >= 0 ? ps.x_hi : std::numeric_limits<double>::infinity();
  fs.x_max_label = label(ps.x_hi_id);
  fs.empty = ps.empty;
  for (const ConstraintRows& cr : rows_)
    if (std::find(cr.inexact_points.begin(), cr.inexact_points.end(), k) != cr.inexact_points.end()) fs.exact = false;
  if (ps.empty) {
    for (int id : ps.certificate)
      if (id >= 0) fs.labels.push_back(label(id));
    return fs;
  }
  fs.halfplanes.resize(static_cast<Eigen::Index>(ps.rows.size()), 3);
  for (size_t i = 0; i < ps.rows.size(); ++i) {
    fs.halfplanes.row(static_cast<Eigen::Index>(i)) << ps.rows[i].a, ps.rows[i].b, ps.rows[i].c;
    fs.labels.push_back(label(ps.rows[i].id));
  }
  const auto& vs = polygon.vertices();
  fs.vertices.resize(static_cast<Eigen::Index>(vs.size()), 2);
  for (size_t i = 0; i < vs.size(); ++i) fs.vertices.row(static_cast<Eigen::Index>(i)) << vs[i].x, vs[i].y;
  for (const detail::Line& e : polygon.edges())
    if (e.id == detail::kBoxYLow || e.id == detail::kBoxYHigh || (e.id == detail::kBoxXHigh && ps.x_hi_id < 0))
      fs.bounded = false;
  return fs;
}

Result TimeScalingProblem::solve(const SolverOptions& options) const {
  if (options.max_iterations < 0)
    detail::fail("max_iterations = " + std::to_string(options.max_iterations) + " must be >= 0");
  if (!(options.tolerance > 0.0 && options.tolerance < 1.0))
    detail::fail("tolerance = " + detail::fmt(options.tolerance) + " must be in (0, 1)");
  if (!(options.initial_trust_region > 0.0) || !std::isfinite(options.initial_trust_region))
    detail::fail("initial_trust_region = " + detail::fmt(options.initial_trust_region) + " must be > 0 and finite");
  if (!(options.lp_feasibility_tolerance > 0.0 && options.lp_feasibility_tolerance < 1e-3))
    detail::fail("lp_feasibility_tolerance = " + detail::fmt(options.lp_feasibility_tolerance) +
                 " must be in (0, 1e-3)");

  Result res;
  res.path = path_;
  for (const auto& c : constraints_) {
    if (auto torque = std::dynamic_pointer_cast<const TorqueLimits>(c)) res.robot = torque->robot();
    if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(c)) {
      res.robot = contact->robot();
      res.contacts = contact;
    }
  }
  res.s = samples_.s;
  const Eigen::Index n = intervals();

  for (size_t i = 0; i < rows_.size(); ++i) {
    res.stats.time_constraints += rows_[i].seconds;
    res.stats.inexact_points += static_cast<int>(rows_[i].inexact_points.size());
    if (std::dynamic_pointer_cast<const ContactConstraint>(constraints_[i])) {
      res.stats.time_projection += rows_[i].seconds;
      res.stats.projection_lp_solves += rows_[i].lp_solves;
    }
  }
  auto t0 = std::chrono::steady_clock::now();
  const detail::GridSets sets = detail::build_grid_sets(samples_, rows_);
  res.stats.time_feasible_sets = seconds_since(t0);
  res.stats.average_halfplanes = sets.average_rows;

  auto report = [&](Status st, Eigen::Index k, const std::vector<int>& ids, const std::string& why) {
    res.status = st;
    res.infeasibility.grid_index = k;
    res.infeasibility.s = samples_.s[k];
    for (int id : ids) res.infeasibility.constraints.push_back(sets.label(id));
    std::ostringstream os;
    os << why << " at grid index " << k << " (s = " << detail::fmt(samples_.s[k]) << ")";
    if (!ids.empty()) {
      os << "; binding: ";
      for (size_t i = 0; i < res.infeasibility.constraints.size(); ++i)
        os << (i ? ", " : "") << res.infeasibility.constraints[i];
    }
    res.message = os.str();
    if (st == Status::Infeasible && res.contacts) recheck_contacts(*this, rows_, k, sets.points[static_cast<size_t>(k)].empty, res);
    return res;
  };

  for (Eigen::Index k = 0; k <= n; ++k) {
    const detail::PointSet& p = sets.points[static_cast<size_t>(k)];
    if (p.empty) return report(Status::Infeasible, k, p.certificate, "no (sdot^2, sddot) satisfies the constraints");
  }

  t0 = std::chrono::steady_clock::now();
  const detail::Chain chain = detail::build_chain(samples_.s, sets);
  const double th0 = sdot_begin_ * sdot_begin_, thN = sdot_end_ * sdot_end_;
  res.status = Status::Optimal;
  bool proven = false;  // θ is the optimum, or within the tolerance of it, without SLP
  Eigen::VectorXd theta;
  double lower = 0.0;  // T of the lattice relaxation's greatest element: a lower bound on T*
  detail::Reachability reach;
  bool have_full = false;
  if (!chain.lattice && options.method == Method::Auto) {
    // Rows coupling θ_k and θ_{k+1} positively appear wherever p'_j is small against p''_j (near a
    // joint's reversal). Without them the feasible set is max-closed and its greatest element θ' has
    // T(θ') <= T* (a lower bound); the full greedy θ is feasible (an upper bound). If θ' satisfies the
    // coupling rows it is the optimum; if the bracket is within the tolerance, θ is optimal to it.
    detail::Reachability relaxed;
    if (detail::reachability_pair(chain, th0, thN, relaxed, reach)) {
      have_full = true;
      lower = detail::duration(chain.ds, relaxed.theta);
      if (detail::coupled_violation(chain, relaxed.theta) <= 1e-12) {
        theta = relaxed.theta;
        proven = true;
      } else {
        theta = reach.theta;
        const double upper = detail::duration(chain.ds, theta);
        if (upper - lower <= options.tolerance * lower) {
          res.stats.gap = std::max(0.0, upper - lower) / lower;
          proven = true;
        }
      }
    }
  }
  if (!have_full) {
    reach = detail::reachability(chain, th0, thN);
    if (reach.outcome == detail::Reachability::Outcome::Infeasible)
      return report(Status::Infeasible, reach.failed_index, reach.binding, reach.reason);
    if (reach.outcome == detail::Reachability::Outcome::Unbounded)
      return report(Status::Unbounded, reach.failed_index, reach.binding, reach.reason);
    theta = reach.theta;
    // Greatest element of a max-closed feasible set: optimal with no LP at all (see Chain::lattice).
    if (chain.lattice && options.method == Method::Auto) proven = true;
  }
  res.stats.greatest_element = proven && res.stats.gap == 0.0;
  res.stats.time_reachability = seconds_since(t0);
  for (Eigen::Index k = 0; k < n; ++k)
    if (theta[k] + theta[k + 1] <= 0.0) {
      // Name the bound that pins the speed to zero, if one does (e.g. a zero velocity limit on a joint
      // that the path moves).
      const Eigen::Index at = (theta[k] <= 0.0 && k > 0) ? k : k + 1;
      std::vector<int> ids;
      if (chain.x_hi[at] <= 0.0) ids.push_back(chain.x_hi_id[static_cast<size_t>(at)]);
      return report(Status::Infeasible, at, ids,
                    "the constraints force the speed to zero on an interval (the path cannot be traversed)");
    }

  if (!proven) {
    t0 = std::chrono::steady_clock::now();
    const detail::SlpOutcome out = detail::slp(chain, theta, options);
    res.stats.time_slp = seconds_since(t0);
    res.stats.slp_iterations = out.iterations;
    res.stats.gap = out.gap;
    res.stats.lp_solves = out.lp_solves;
    // The LP's vertices satisfy rows only to GLPK's tolerance; a capped greedy pass returns the nearest
    // point below the SLP iterate that satisfies every row to rounding.
    theta = detail::forward_pass(reach, th0, &out.theta);
    // The repair can only slow the iterate down; the certified gap grows by what it cost.
    const double t_slp = detail::duration(chain.ds, out.theta), t_final = detail::duration(chain.ds, theta);
    if (t_final > t_slp) res.stats.gap += (t_final - t_slp) / t_slp;
    switch (out.status) {
      case detail::SlpOutcome::Status::Converged:
        if (res.stats.gap > options.tolerance) {
          res.status = Status::IterationLimit;
          res.message = "SLP converged, but making its LP solution exactly feasible cost " + detail::fmt(res.stats.gap) +
                        " (relative), more than the tolerance; the timing is feasible";
        }
        break;
      case detail::SlpOutcome::Status::IterationLimit:
        res.status = Status::IterationLimit;
        res.message = "SLP stopped after " + std::to_string(out.iterations) +
                      " iterations; the timing is feasible, T exceeds the optimum by at most " +
                      detail::fmt(out.gap) + " (relative)";
        break;
      case detail::SlpOutcome::Status::LpFailed:
        res.status = Status::NumericalError;
        res.message = "GLPK failed in SLP iteration " + std::to_string(out.iterations) +
                      "; the timing returned is the last feasible one";
        break;
    }
  }
  res.sdot = theta.cwiseMax(0.0).cwiseSqrt();
  res.times.resize(n + 1);
  res.sddot.resize(n);
  res.times[0] = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double ds = samples_.s[k + 1] - samples_.s[k];
    res.times[k + 1] = res.times[k] + 2.0 * ds / (res.sdot[k] + res.sdot[k + 1]);
    res.sddot[k] = (theta[k + 1] - theta[k]) / (2.0 * ds);
  }
  res.duration = res.times[n];
  return res;
}

}  // namespace pathpace
