#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "solve/binding.hpp"
#include "solve/continuous.hpp"
#include "solve/grid_sets.hpp"
#include "solve/reachability.hpp"
#include "solve/slp.hpp"
#include "paths/sub_path.hpp"
#include "base/validate.hpp"
#include "pathpace/constraints/acceleration_limits.hpp"
#include "pathpace/constraints/linear_constraint.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/constraints/velocity_limits.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace {

namespace {

// x · 0 is 0 for every finite x and NaN for ±inf and NaN, so the sum is 0 exactly when all are finite.
// Four running sums so that the loop is not one chain of dependent additions (Eigen's allFinite() was
// the larger part of adding velocity or acceleration limits). With cap, +inf is first mapped to cap
// (allowed), NaN and -inf stay.
template <bool kAllowPlusInf, typename Matrix>
bool finite_entries(const Matrix& m) {
  const double* p = m.data();
  const Eigen::Index n = m.size();
  const double cap = std::numeric_limits<double>::max();
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  auto term = [cap](double x) {
    if (kAllowPlusInf) x = cap < x ? cap : x;
    return x * 0.0;
  };
  Eigen::Index i = 0;
  for (; i + 3 < n; i += 4)
    for (int j = 0; j < 4; ++j) s[j] += term(p[i + j]);
  for (; i < n; ++i) s[0] += term(p[i]);
  return s[0] + s[1] + s[2] + s[3] == 0.0;
}

// p, p', p'' at samples.s (the grid of a new problem, or one with a contact switch inserted), with the entry
// that is not finite named.
void sample_path(const Path& path, PathSamples& samples) {
  path.evaluate(samples.s, samples.q, samples.dq, samples.ddq);
  if (finite_entries<false>(samples.q) && finite_entries<false>(samples.dq) && finite_entries<false>(samples.ddq))
    return;  // the element-wise loop below only names the entry that is not
  for (Eigen::Index k = 0; k < samples.size(); ++k)
    for (Eigen::Index j = 0; j < samples.dof(); ++j)
      if (!std::isfinite(samples.q(k, j)) || !std::isfinite(samples.dq(k, j)) || !std::isfinite(samples.ddq(k, j)))
        detail::fail("path is not finite at grid[" + std::to_string(k) + "] = " + detail::fmt(samples.s[k]) +
                     " (coordinate " + std::to_string(j) + ")");
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A constraint's rows on `samples` with the time they took (summed into SolverStats::time_constraints): every
// evaluation that ends up in the problem's rows goes through here, so that no row keeps another's time.
ConstraintRows timed_evaluate(const Constraint& constraint, const PathSamples& samples) {
  const auto t0 = std::chrono::steady_clock::now();
  ConstraintRows rows = constraint.evaluate(samples);
  rows.seconds = seconds_since(t0);
  return rows;
}

// A greedy profile that stops on an interval is the answer only if it is the greatest element of a
// max-closed feasible set (chain.lattice: then every feasible profile stops there); otherwise it may have
// walked into a trap of the coupling rows, and the profile that does not stop (detail::unstopped_profile)
// replaces it, in theta and reach.theta, when there is one. Returns whether theta moves on every interval.
bool avoid_stopped_profile(const detail::Chain& chain, detail::Reachability& reach, double th0, Eigen::VectorXd& theta) {
  if (!detail::has_stopped_interval(theta)) return true;
  if (chain.lattice) return false;
  Eigen::VectorXd start = detail::unstopped_profile(reach, th0);
  if (detail::has_stopped_interval(start)) return false;
  theta = reach.theta = std::move(start);
  reach.theta_is_greedy = false;
  return true;
}

// An infeasibility with contacts is a claim about the robot, and the polygons are projections: before
// it is reported, one LP on the full (ṡ², s̈, τ, f) polytope at the binding grid point, with every other
// constraint's half-planes there, re-checks it; the message says whether the rest state (0, 0) is
// feasible there. A point whose polygon is empty but whose full LP is not is a projection failure.
void recheck_contacts(const TimeScalingProblem& problem, const std::vector<ConstraintRows>& rows, Eigen::Index k,
                      bool point_empty, const std::shared_ptr<const ContactConstraint>& contacts, Result& res) {
  Eigen::Matrix<double, Eigen::Dynamic, 3> extra(0, 3);
  for (size_t i = 0; i < rows.size(); ++i) {
    const ConstraintRows& cr = rows[i];
    if (problem.constraints()[i] == contacts) continue;
    for (Eigen::Index j = 0; j < cr.rows(); ++j)
      if (std::isfinite(cr.c(k, j))) {
        extra.conservativeResize(extra.rows() + 1, 3);
        extra.row(extra.rows() - 1) << cr.a(k, j), cr.b(k, j), cr.c(k, j);
      }
  }
  const ContactConstraint::PointCheck check = contacts->check_point(problem.samples(), k, extra);
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
  sample_path(*path_, samples_);
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
  sample_path(*path_, samples_);
}

void TimeScalingProblem::add_velocity_limits(const Eigen::VectorXd& vmin, const Eigen::VectorXd& vmax) {
  add_constraint(std::make_shared<VelocityLimits>(vmin, vmax, joint_names_));
}

void TimeScalingProblem::add_acceleration_limits(const Eigen::VectorXd& amin, const Eigen::VectorXd& amax) {
  add_constraint(std::make_shared<AccelerationLimits>(amin, amax, joint_names_));
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
    std::vector<size_t> phases;
    for (size_t i = 0; i < constraints_.size(); ++i)
      if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(constraints_[i]);
          contact && contact->robot() == torque->robot())
        phases.push_back(i);
    if (phases.size() >= 2) {
      // Contact phases (add_contact_phases): the torque limits join every phase, each in its place.
      std::vector<std::shared_ptr<const Constraint>> merged;
      std::vector<ConstraintRows> merged_rows;
      for (size_t i : phases) {
        auto contact = std::dynamic_pointer_cast<const ContactConstraint>(constraints_[i]);
        merged.push_back(contact->with_torque_limits(torque->tau_min(), torque->tau_max()));
        merged_rows.push_back(timed_evaluate(*merged.back(), samples_));
      }
      for (size_t j = 0; j < phases.size(); ++j) {
        constraints_[phases[j]] = std::move(merged[j]);
        rows_[phases[j]] = std::move(merged_rows[j]);
      }
      return;
    }
    if (!phases.empty()) {
      auto contact = std::dynamic_pointer_cast<const ContactConstraint>(constraints_[phases[0]]);
      constraint = contact->with_torque_limits(torque->tau_min(), torque->tau_max());
      replaced.push_back(phases[0]);
    }
  } else if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(constraint)) {
    for (size_t i = 0; i < constraints_.size(); ++i)
      if (auto t = std::dynamic_pointer_cast<const TorqueLimits>(constraints_[i]); t && t->robot() == contact->robot()) {
        contact = contact->with_torque_limits(t->tau_min(), t->tau_max());
        replaced.push_back(i);
      }
    constraint = contact;
  }
  ConstraintRows rows = timed_evaluate(*constraint, samples_);
  check_rows(*constraint, rows, samples_.size());
  for (size_t t = replaced.size(); t-- > 0;) {
    constraints_.erase(constraints_.begin() + static_cast<long>(replaced[t]));
    rows_.erase(rows_.begin() + static_cast<long>(replaced[t]));
  }
  constraints_.push_back(std::move(constraint));
  rows_.push_back(std::move(rows));
  if (joint_names_.empty()) {
    std::shared_ptr<const RobotModel> robot;
    if (auto t = std::dynamic_pointer_cast<const TorqueLimits>(constraints_.back())) robot = t->robot();
    if (auto c = std::dynamic_pointer_cast<const ContactConstraint>(constraints_.back())) robot = c->robot();
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
  if (!finite_entries<false>(rows.a)) detail::require_finite(constraint.name() + " a", rows.a);
  if (!finite_entries<false>(rows.b)) detail::require_finite(constraint.name() + " b", rows.b);
  // c may be +inf (an inactive row), never NaN or -inf: -c < +inf holds exactly for the allowed values.
  if (!finite_entries<true>(rows.c))
    for (Eigen::Index k = 0; k < rows.c.rows(); ++k)
      for (Eigen::Index j = 0; j < r; ++j)
        if (std::isnan(rows.c(k, j)) || rows.c(k, j) == -std::numeric_limits<double>::infinity())
          detail::fail(constraint.name() + " c" + "[" + std::to_string(k) + ", " + std::to_string(j) +
                       "] = " + detail::fmt(rows.c(k, j)) + " must be a number or +inf");
}

void TimeScalingProblem::add_contact_phases(std::shared_ptr<const RobotModel> robot, const std::vector<ContactPhase>& phases,
                                            const ContactOptions& options, const Eigen::VectorXd& tau_min,
                                            const Eigen::VectorXd& tau_max, double impact_tolerance,
                                            double drift_tolerance, DriftPolicy drift) {
  if (!robot) detail::fail("robot must not be None");
  if (robot->nq() != samples_.dof())
    detail::fail("path has " + std::to_string(samples_.dof()) + " coordinates, robot '" + robot->name() + "' has " +
                 std::to_string(robot->nq()) + " joints");
  if (phases.empty()) detail::fail("phases is empty, expected at least one (s_begin, s_end, contacts)");
  if (!(impact_tolerance >= 0.0) || !std::isfinite(impact_tolerance))
    detail::fail("impact_tolerance = " + detail::fmt(impact_tolerance) + " must be >= 0 and finite");
  const Eigen::Index n = intervals();
  const double a = samples_.s[0], b = samples_.s[n], length = b - a;
  const double tol = 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
  auto name = [](size_t i, const char* field) { return "phases[" + std::to_string(i) + "]." + field; };
  for (size_t i = 0; i < phases.size(); ++i) {
    const ContactPhase& ph = phases[i];
    if (!std::isfinite(ph.s_begin)) detail::fail(name(i, "s_begin") + " = " + detail::fmt(ph.s_begin) + " must be finite");
    if (!std::isfinite(ph.s_end)) detail::fail(name(i, "s_end") + " = " + detail::fmt(ph.s_end) + " must be finite");
    if (!(ph.s_begin < ph.s_end))
      detail::fail(name(i, "s_begin") + " = " + detail::fmt(ph.s_begin) + " must be < " + name(i, "s_end") + " = " +
                   detail::fmt(ph.s_end));
    if (i == 0 && std::abs(ph.s_begin - a) > tol)
      detail::fail(name(i, "s_begin") + " = " + detail::fmt(ph.s_begin) + " must equal the path's s_begin = " +
                   detail::fmt(a) + " (the phases cover the path)");
    if (i > 0 && std::abs(ph.s_begin - phases[i - 1].s_end) > tol)
      detail::fail(name(i, "s_begin") + " = " + detail::fmt(ph.s_begin) + " must equal " + name(i - 1, "s_end") + " = " +
                   detail::fmt(phases[i - 1].s_end) + " (the phases are contiguous)");
    if (i + 1 == phases.size() && std::abs(ph.s_end - b) > tol)
      detail::fail(name(i, "s_end") + " = " + detail::fmt(ph.s_end) + " must equal the path's s_end = " + detail::fmt(b) +
                   " (the phases cover the path)");
  }
  // Every contact set and option is checked (and its phase named) before anything changes.
  std::vector<std::shared_ptr<ContactConstraint>> probe;
  for (size_t i = 0; i < phases.size(); ++i) {
    try {
      probe.push_back(std::make_shared<ContactConstraint>(robot, phases[i].contacts, phases[i].options.value_or(options),
                                                          tau_min, tau_max));
    } catch (const InvalidInput& e) {
      throw InvalidInput("phases[" + std::to_string(i) + "]: " + e.what());
    }
  }
  // The switches on the grid: snapped to a grid point within 1e-9 of the length, else inserted.
  std::vector<double> edge(phases.size() + 1);
  edge[0] = a;
  edge[phases.size()] = b;
  // The grid with the switches inserted: a copy of the problem's, made at the first insertion only.
  std::vector<double> grid;
  bool inserted = false;
  for (size_t i = 1; i < phases.size(); ++i) {
    const double sw = phases[i].s_begin;
    const double* g = inserted ? grid.data() : samples_.s.data();
    const size_t size = inserted ? grid.size() : static_cast<size_t>(samples_.s.size());
    size_t k = static_cast<size_t>(std::lower_bound(g, g + size, sw) - g);
    if (k > 0 && (k == size || sw - g[k - 1] < g[k] - sw)) --k;
    if (std::abs(g[k] - sw) <= 1e-9 * length) {
      edge[i] = g[k];
      continue;
    }
    for (size_t c = 0; c < constraints_.size(); ++c)
      if (std::dynamic_pointer_cast<const LinearConstraint>(constraints_[c]))
        detail::fail(name(i, "s_begin") + " = " + detail::fmt(sw) + " is not a grid point (nearest: grid[" +
                     std::to_string(k) + "] = " + detail::fmt(g[k]) + ") and the problem has a constraint given per grid "
                     "point ('" + constraints_[c]->name() + "') that cannot be evaluated on a new grid: add the contact "
                     "phases first, or use a grid with a point at every switch");
    if (!inserted) grid.assign(g, g + size);
    grid.insert(std::upper_bound(grid.begin(), grid.end(), sw), sw);
    edge[i] = sw;
    inserted = true;
  }
  // TorqueLimits of this robot join every phase (as add_constraint merges them into one contact constraint).
  std::vector<size_t> replaced;
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(robot->nq(), -std::numeric_limits<double>::infinity());
  Eigen::VectorXd hi = -lo;
  for (size_t c = 0; c < constraints_.size(); ++c)
    if (auto t = std::dynamic_pointer_cast<const TorqueLimits>(constraints_[c]); t && t->robot() == robot) {
      lo = lo.cwiseMax(t->tau_min());
      hi = hi.cwiseMin(t->tau_max());
      replaced.push_back(c);
    }
  // A switch inserted: the path and every constraint that stays on the new grid, checked as add_constraint
  // checks them (a user's own Constraint may hand back anything there); kept apart until the commit below.
  // Without one the problem's samples and rows serve as they are.
  PathSamples new_samples;
  std::vector<ConstraintRows> new_rows;
  if (inserted) {
    new_samples.s = Eigen::Map<const Eigen::VectorXd>(grid.data(), static_cast<Eigen::Index>(grid.size()));
    sample_path(*path_, new_samples);
    new_rows.resize(constraints_.size());
    for (size_t c = 0; c < constraints_.size(); ++c) {
      if (std::find(replaced.begin(), replaced.end(), c) != replaced.end()) continue;  // merged into the phases
      new_rows[c] = timed_evaluate(*constraints_[c], new_samples);
      check_rows(*constraints_[c], new_rows[c], new_samples.size());
    }
  }
  const PathSamples& samples = inserted ? new_samples : samples_;
  // The no-impact rule at each switch, from the contact points' velocities along the path (eq. 10: c' = J p').
  std::vector<std::string> rest(phases.size());
  for (size_t i = 1; i < phases.size(); ++i) {
    const std::vector<Contact>& now = probe[i]->contacts();
    const std::vector<Contact>& before = probe[i - 1]->contacts();
    std::vector<size_t> made;  // the contacts of phase i that phase i-1 does not have
    for (size_t c = 0; c < now.size(); ++c)
      if (std::none_of(before.begin(), before.end(), [&](const Contact& o) {
            return o.link == now[c].link && o.other_link == now[c].other_link && (o.point - now[c].point).norm() <= 1e-9;
          }))
        made.push_back(c);
    if (made.empty()) continue;  // contacts kept or broken only: nothing to check
    // The approach velocity: c' just before the switch (1e-9 of the length), from the path of the phase that
    // ends there. On a path that is C¹ at the switch a contact held fixed after it has c' = 0 there; a
    // kinked path (p' jumps) can bring the point in at speed.
    PathSamples before_switch;
    before_switch.s = Eigen::VectorXd::Constant(1, edge[i] - 1e-9 * length);
    path_->evaluate(before_switch.s, before_switch.q, before_switch.dq, before_switch.ddq);
    Eigen::MatrixXd normal, speed, unused;
    probe[i]->point_velocities(samples, unused, speed);
    probe[i]->point_velocities(before_switch, normal, unused);
    for (size_t c : made) {
      const Eigen::Index j = static_cast<Eigen::Index>(c);
      const double vn = normal(0, j), scale = speed.col(j).maxCoeff();
      if (!(std::abs(vn) > impact_tolerance * scale) || scale == 0.0) continue;
      std::ostringstream os;
      os.precision(4);
      os << "no impact: contact " << c << " (link '" << now[c].link << "') is made at s = " << edge[i]
         << " moving along its normal (n.c'(s) = " << vn << " m per unit s): sdot = 0 there";
      rest[i] = os.str();
      break;
    }
  }
  std::vector<std::shared_ptr<const Constraint>> added;
  std::vector<ConstraintRows> added_rows;
  std::vector<ContactDrift> drifts;
  for (size_t i = 0; i < phases.size(); ++i) {
    ContactOptions o = phases[i].options.value_or(options);
    o.active_begin = edge[i];
    o.active_end = edge[i + 1];
    o.label = "phases[" + std::to_string(i) + "]";
    o.rest_at_begin = rest[i];
    std::shared_ptr<const ContactConstraint> c = std::make_shared<ContactConstraint>(robot, phases[i].contacts, o, tau_min, tau_max);
    // Each phase keeps its own contacts in place on its own stretch (checked before its projection).
    if (auto d = check_contact_drift(*c, samples, drift_tolerance, drift)) drifts.push_back(std::move(*d));
    if (!replaced.empty()) c = c->with_torque_limits(lo, hi);
    added_rows.push_back(timed_evaluate(*c, samples));
    check_rows(*c, added_rows.back(), samples.size());
    added.push_back(std::move(c));
  }
  // Commit: nothing above changed the problem.
  if (inserted) {
    samples_ = std::move(new_samples);
    rows_ = std::move(new_rows);
  }
  for (size_t t = replaced.size(); t-- > 0;) {
    constraints_.erase(constraints_.begin() + static_cast<long>(replaced[t]));
    rows_.erase(rows_.begin() + static_cast<long>(replaced[t]));
  }
  for (size_t i = 0; i < added.size(); ++i) {
    constraints_.push_back(std::move(added[i]));
    rows_.push_back(std::move(added_rows[i]));
  }
  contact_drift_.insert(contact_drift_.end(), drifts.begin(), drifts.end());
  if (joint_names_.empty() && robot->nq() == samples_.dof()) set_joint_names(robot->joint_names());
}

void TimeScalingProblem::add_contacts(std::shared_ptr<const ContactConstraint> contacts, double drift_tolerance,
                                      DriftPolicy drift) {
  if (!contacts) detail::fail("contacts must not be None");
  if (contacts->robot()->nq() != samples_.dof())
    detail::fail("path has " + std::to_string(samples_.dof()) + " coordinates, robot '" + contacts->robot()->name() +
                 "' has " + std::to_string(contacts->robot()->nq()) + " joints");
  std::optional<ContactDrift> d = check_contact_drift(*contacts, samples_, drift_tolerance, drift);
  add_constraint(std::move(contacts));
  if (d) contact_drift_.push_back(std::move(*d));
}

void TimeScalingProblem::set_joint_names(std::vector<std::string> names) {
  if (static_cast<Eigen::Index>(names.size()) != samples_.dof())
    detail::fail("joint_names has " + std::to_string(names.size()) + " entries, the path has " +
                 std::to_string(samples_.dof()) + " coordinates");
  joint_names_ = std::move(names);
  // Limits added before the names were known take them now (labels and messages name the joint).
  for (size_t i = 0; i < constraints_.size(); ++i) {
    std::shared_ptr<const Constraint> named;
    if (auto v = std::dynamic_pointer_cast<const VelocityLimits>(constraints_[i]); v && v->joint_names().empty())
      named = std::make_shared<VelocityLimits>(v->vmin(), v->vmax(), joint_names_);
    else if (auto a = std::dynamic_pointer_cast<const AccelerationLimits>(constraints_[i]); a && a->joint_names().empty())
      named = std::make_shared<AccelerationLimits>(a->amin(), a->amax(), joint_names_);
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
  // Built in the solve's units (speeds ~1, see detail::Scale), so that the cut of an unbounded set and the
  // polygon's tolerances are relative to the problem, and mapped back: a 1e-12-long path is bounded too.
  detail::Scale scale = detail::problem_scale(samples_.s, rows_);
  scale.cap = detail::kInfinityCap;
  std::vector<detail::Line> scratch;
  const detail::PointSet ps = detail::build_point_set(rows_, k, polygon, scratch, {}, nullptr, scale);
  std::vector<std::string> labels;
  for (const ConstraintRows& cr : rows_) labels.insert(labels.end(), cr.labels.begin(), cr.labels.end());
  auto label = [&](int id) { return id >= 0 ? labels[static_cast<size_t>(id)] : std::string(); };

  FeasibleSet fs;
  fs.index = k;
  fs.s = samples_.s[k];
  fs.x_min = ps.x_lo * scale.x_unit;
  fs.x_max = ps.x_hi_id >= 0 ? ps.x_hi * scale.x_unit : std::numeric_limits<double>::infinity();
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

namespace {

// A timing of a path that moves its contacts (DriftPolicy::Warn) says so in its message as well as in
// Result::contact_drift: its contact forces assume contacts that the path slides.
Result with_drift_note(Result res) {
  if (res.contact_drift.empty()) return res;
  std::string note = "the path moves its contacts, which the contact forces assume fixed: ";
  for (size_t i = 0; i < res.contact_drift.size(); ++i) note += (i ? "; " : "") + res.contact_drift[i].message();
  res.message = res.message.empty() ? note : res.message + "; " + note;
  return res;
}

}  // namespace

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
  if (!(options.time_limit > 0.0))
    detail::fail("time_limit = " + detail::fmt(options.time_limit) + " must be > 0 (seconds)");
  if (zero_sddot_begin_ && sdot_begin_ == 0.0)
    detail::fail("sddot = 0 at s_begin needs sdot_begin > 0: with sddot constant on each interval (eq. 24), a start "
                 "from rest with sddot = 0 never moves");
  if (zero_sddot_end_ && sdot_end_ == 0.0)
    detail::fail("sddot = 0 at s_end needs sdot_end > 0: with sddot constant on each interval (eq. 24), a stop at "
                 "rest with sddot = 0 is never reached");
  if (options.guarantee == Guarantee::Grid) {
    if (!zero_sddot_begin_ && !zero_sddot_end_) return with_drift_note(solve_rows(rows_, nullptr, options));
    std::vector<ConstraintRows> rows = rows_;
    detail::IntervalExtra extra;
    add_boundary_rows(rows, extra);
    return with_drift_note(solve_rows(rows, &extra, options));
  }
  if (options.audit_points < 1 || options.audit_points > 1000)
    detail::fail("audit_points = " + std::to_string(options.audit_points) + " must be in [1, 1000]");
  if (!(options.audit_tolerance >= 0.0 && options.audit_tolerance < 1.0))
    detail::fail("audit_tolerance = " + detail::fmt(options.audit_tolerance) + " must be in [0, 1)");
  if (options.max_audit_rounds < 1)
    detail::fail("max_audit_rounds = " + std::to_string(options.max_audit_rounds) + " must be >= 1");

  // guarantee = continuous (see solve/continuous.hpp): velocity and acceleration rows that hold between
  // grid points by construction, then audit-and-cut rounds for the other constraints.
  std::vector<ConstraintRows> rows = rows_;
  detail::IntervalExtra extra;
  detail::add_kinematic_continuous_rows(*path_, samples_, constraints_, rows, extra);
  add_boundary_rows(rows, extra);
  std::vector<int> offset;
  int id = 0;
  for (const ConstraintRows& cr : rows_) {
    offset.push_back(id);
    id += static_cast<int>(cr.rows());
  }
  Result res;
  int rounds = 0, cuts = 0, audit_lps = 0, audit_projections = 0, audit_reused = 0;
  detail::AuditMemory memory;
  // The time budget covers all rounds: each solve gets what is left.
  const auto started = std::chrono::steady_clock::now();
  SolverOptions round_options = options;
  for (;;) {
    round_options.time_limit = std::max(options.time_limit - seconds_since(started), 1e-3);
    res = solve_rows(rows, &extra, round_options);
    if (!res.ok() || res.status == Status::TimeLimit) break;
    const Eigen::VectorXd theta = res.sdot.array().square();
    const detail::Audit audit = detail::audit_and_cut(*path_, samples_.s, theta, constraints_, rows_, offset,
                                                      options.audit_points, options.audit_tolerance, extra, memory);
    ++rounds;
    cuts += audit.cuts;
    audit_lps += audit.lps;
    audit_projections += audit.projections;
    audit_reused += audit.reused;
    res.stats.audit_worst = audit.worst;
    if (audit.cuts == 0) break;
    if (rounds >= options.max_audit_rounds) {
      res.status = Status::IterationLimit;
      res.message = "guarantee = 'continuous': after " + std::to_string(rounds) +
                    " audit rounds a limit is still exceeded between grid points by " + detail::fmt(audit.worst) +
                    " (relative); raise max_audit_rounds or refine the grid";
      break;
    }
  }
  res.stats.audit_rounds = rounds;
  res.stats.audit_cuts = cuts;
  res.stats.audit_lps = audit_lps;
  res.stats.audit_projections = audit_projections;
  res.stats.audit_reused = audit_reused;
  return with_drift_note(std::move(res));
}

Result TimeScalingProblem::solve_rows(const std::vector<ConstraintRows>& constraint_rows,
                                      const detail::IntervalExtra* extra, const SolverOptions& options) const {
  const auto started = std::chrono::steady_clock::now();
  const double budget = std::min(options.time_limit, 1e9);  // +inf: no limit (a billion seconds)
  const auto deadline = started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(budget));

  Result res;
  res.path = path_;
  res.contact_drift = contact_drift_;
  bool own_torque_limits = false;  // a TorqueLimits' limits are the ones shown, else a contact constraint's
  for (const auto& c : constraints_) {
    if (auto torque = std::dynamic_pointer_cast<const TorqueLimits>(c)) {
      res.robot = torque->robot();
      res.tau_min = torque->tau_min();
      res.tau_max = torque->tau_max();
      own_torque_limits = true;
    }
    if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(c)) {
      res.robot = contact->robot();
      res.contacts = contact;
      if (!own_torque_limits) {
        res.tau_min = contact->tau_min();
        res.tau_max = contact->tau_max();
      }
      if (std::isfinite(contact->options().active_begin) || std::isfinite(contact->options().active_end))
        res.contact_phases.push_back(contact);
    }
  }
  std::stable_sort(res.contact_phases.begin(), res.contact_phases.end(), [](const auto& x, const auto& y) {
    return x->options().active_begin < y->options().active_begin;
  });
  res.s = samples_.s;
  const Eigen::Index n = intervals();

  for (size_t i = 0; i < rows_.size(); ++i) {
    res.stats.time_constraints += rows_[i].seconds;
    res.stats.inexact_points += static_cast<int>(rows_[i].inexact_points.size());
    if (std::dynamic_pointer_cast<const ContactConstraint>(constraints_[i])) {
      res.stats.time_projection += rows_[i].seconds;
      res.stats.projection_lp_solves += rows_[i].lp_solves;
      const LpCounts& by = rows_[i].lp_by_cause;
      res.stats.projection_lps_initial += by.initial;
      res.stats.projection_lps_vertex += by.vertex;
      res.stats.projection_lps_certificate += by.certificate;
      res.stats.projection_lps_cap_growth += by.cap_growth;
      res.stats.projection_lps_cold_retry += by.cold_retry;
    }
  }
  auto t0 = std::chrono::steady_clock::now();
  // Solved in units where the speeds are ~1 (see detail::Scale): T then scales exactly with the path's
  // length and its limits, with no cap on ṡ² that a bounded problem could reach.
  const detail::Scale scale = detail::problem_scale(samples_.s, constraint_rows);
  const detail::GridSets sets = detail::build_grid_sets(samples_, constraint_rows, scale);
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
    if (st == Status::Infeasible && options.explain) {
      res.relaxation = relaxation(1e3, 1e-3, options.guarantee);
      os << "; " << describe_relaxation(res.relaxation);
    }
    res.message = os.str();
    if (st == Status::Infeasible && res.contacts) {
      // With contact phases: the phase that holds at k (the first of two at a switch; the other's rows
      // enter the check as half-planes).
      std::shared_ptr<const ContactConstraint> at_k;
      for (const auto& c : constraints_)
        if (auto contact = std::dynamic_pointer_cast<const ContactConstraint>(c); contact && contact->active_at(samples_.s[k])) {
          at_k = contact;
          break;
        }
      if (at_k) recheck_contacts(*this, rows_, k, sets.points[static_cast<size_t>(k)].empty, at_k, res);
    }
    return res;
  };

  // A stationary piece of path (p' = 0 on a stretch of the grid) that no constraint bounds would be crossed
  // in zero time: the discretised problem has no optimum there (T* is not attained). That is an input
  // error, named by its s-range; a single grid point with p' = 0 (a cusp) is just an unbounded point.
  auto stationary_check = [&](Eigen::Index k) {
    const double tol = 1e-12 * std::max(1.0, samples_.dq.cwiseAbs().maxCoeff());
    auto still = [&](Eigen::Index i) { return samples_.dq.row(i).cwiseAbs().maxCoeff() <= tol; };
    if (k < 0 || k > n || !still(k)) return;
    Eigen::Index a = k, b = k;
    while (a > 0 && still(a - 1)) --a;
    while (b < n && still(b + 1)) ++b;
    if (a == b) return;
    detail::fail("path does not move on s in [" + detail::fmt(samples_.s[a]) + ", " + detail::fmt(samples_.s[b]) +
                 "] (p'(s) = 0 at grid indices " + std::to_string(a) + ".." + std::to_string(b) +
                 ") and no constraint bounds the speed there: it would be crossed in zero time; remove that piece "
                 "from the path");
  };

  for (Eigen::Index k = 0; k <= n; ++k) {
    const detail::PointSet& p = sets.points[static_cast<size_t>(k)];
    if (p.empty) return report(Status::Infeasible, k, p.certificate, "no (sdot^2, sddot) satisfies the constraints");
  }

  // A boundary speed beyond the speed bound of its end point: say so in the user's terms (the
  // reachability analysis would only find that no speed is admissible one grid point further on).
  for (const auto& [k, sdot, name] : {std::make_tuple(Eigen::Index(0), sdot_begin_, "sdot_begin"),
                                      std::make_tuple(n, sdot_end_, "sdot_end")}) {
    const detail::PointSet& p = sets.points[static_cast<size_t>(k)];
    if (sdot * sdot / scale.x_unit > p.x_hi * (1 + 1e-12) && p.x_hi_id >= 0)
      return report(Status::Infeasible, k, {p.x_hi_id},
                    std::string(name) + " = " + detail::fmt(sdot) + " is faster than the constraints allow at " +
                        (k == 0 ? "s_begin" : "s_end") + " (sdot <= " + detail::fmt(std::sqrt(p.x_hi * scale.x_unit)) +
                        ")");
  }

  t0 = std::chrono::steady_clock::now();
  const detail::Chain chain = detail::build_chain(samples_.s, sets, extra, scale);
  const double th0 = sdot_begin_ * sdot_begin_ / scale.x_unit, thN = sdot_end_ * sdot_end_ / scale.x_unit;
  res.status = Status::Optimal;
  bool proven = false;  // θ is the optimum, or within the tolerance of it, without SLP
  Eigen::VectorXd theta;
  detail::Reachability relaxed, reach;
  bool have_full = false;
  double T_relaxed = std::numeric_limits<double>::quiet_NaN();  // T(θ'), when the relaxed analysis ran
  if (!chain.lattice && options.method == Method::Auto) {
    // Rows coupling θ_k and θ_{k+1} positively appear wherever p'_j is small against p''_j (near a
    // joint's reversal). Without them the feasible set is max-closed and its greatest element θ' has
    // T(θ') <= T* (a lower bound); the full greedy θ is feasible (an upper bound). If θ' satisfies the
    // coupling rows it is the optimum; if the bracket is within the tolerance, θ is optimal to it.
    if (detail::reachability_pair(chain, th0, thN, relaxed, reach)) {
      have_full = true;
      T_relaxed = detail::duration(chain.ds, relaxed.theta);  // a lower bound on T*
      if (detail::coupled_violation(chain, relaxed.theta) <= 1e-12) {
        theta = relaxed.theta;
        proven = true;
      } else {
        theta = reach.theta;
        const double upper = detail::duration(chain.ds, theta);
        if (upper - T_relaxed <= options.tolerance * T_relaxed) {
          res.stats.gap = std::max(0.0, upper - T_relaxed) / T_relaxed;
          proven = true;
        }
      }
    }
  }
  if (!have_full) {
    reach = detail::reachability(chain, th0, thN);
    if (reach.outcome == detail::Reachability::Outcome::Infeasible)
      return report(Status::Infeasible, reach.failed_index, reach.binding, reach.reason);
    if (reach.outcome == detail::Reachability::Outcome::Unbounded) {
      stationary_check(reach.failed_index);
      return report(Status::Unbounded, reach.failed_index, reach.binding, reach.reason);
    }
    theta = reach.theta;
    // Greatest element of a max-closed feasible set: optimal with no LP at all (see Chain::lattice).
    if (chain.lattice && options.method == Method::Auto) proven = true;
  }
  res.stats.greatest_element = proven && res.stats.gap == 0.0;
  // A proven θ is the answer even if it stops on an interval (every feasible profile does, then).
  if (!proven) avoid_stopped_profile(chain, reach, th0, theta);
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
    // SLP on windows around the intervals where θ' breaks a coupling row (see solve/slp.hpp); without
    // θ' (Method::Slp, or the relaxed analysis did not end feasible) one window, the whole chain, under θ_hi.
    // Every feasible θ_k is also below the backward-controllable bound K_k (tighter than x_hi, which is the
    // solve's cap where nothing bounds ṡ² alone: a column bound of 1e100 would not help GLPK).
    const detail::SlpOutcome out = detail::windowed_slp(chain, reach,
                                                        have_full ? relaxed.theta : chain.x_hi.cwiseMin(reach.k_hi),
                                                        have_full, th0, options, deadline, T_relaxed);
    res.stats.time_slp = seconds_since(t0);
    res.stats.slp_iterations = out.iterations;
    res.stats.lp_solves = out.lp_solves;
    res.stats.windows = out.windows;
    res.stats.window_points = static_cast<int>(out.window_points);
    res.stats.newton_steps = out.newton_steps;
    theta = out.theta;
    double T_increase = 0.0;
    const double grid_excess = detail::exact_feasibility_step(chain, sets, theta, nullptr, &T_increase);
    const double T = out.T * (1.0 + T_increase);
    res.stats.gap = out.lower > 0.0 ? std::max(0.0, T - out.lower) / out.lower : std::numeric_limits<double>::infinity();
    // The repair (forward_pass) returns a profile that meets every row to rounding; checked, not assumed,
    // before a message calls it feasible (in the pass that labels the binding rows, and in the grid points' own
    // terms by the exact-feasibility step, which scales it down where rounding breaks a row).
    double violation = 0.0;
    res.binding = detail::binding_labels(chain, sets, theta, &violation);
    violation = std::max(violation, grid_excess);
    const std::string bound =
        violation <= 1e-9 ? "the timing is feasible, T exceeds the optimum by at most " + detail::fmt(res.stats.gap) +
                                " (relative, certified)"
                          : "the timing returned is NOT feasible: it breaks a constraint by " + detail::fmt(violation) +
                                " (relative); T exceeds the optimum by at most " + detail::fmt(res.stats.gap);
    switch (out.status) {
      case detail::SlpOutcome::Status::Converged:
        if (res.stats.gap > options.tolerance) {
          res.status = Status::IterationLimit;
          res.message = "SLP converged on its windows, but the certified gap stayed above the tolerance; " + bound;
        }
        break;
      case detail::SlpOutcome::Status::IterationLimit:
        res.status = Status::IterationLimit;
        res.message = "SLP stopped after max_iterations = " + std::to_string(options.max_iterations) +
                      " iterations in a window; " + bound;
        break;
      case detail::SlpOutcome::Status::TimeLimit:
        res.status = Status::TimeLimit;
        res.message = "time_limit = " + detail::fmt(options.time_limit) + " s reached during SLP; " + bound;
        break;
      case detail::SlpOutcome::Status::LpFailed:
        res.status = Status::NumericalError;
        res.message = "GLPK failed in SLP; the timing returned is the last feasible one, " + bound;
        break;
    }
    if (violation > 1e-9) {
      // Whatever ended the SLP, a timing that breaks a row is not a result to execute (ok() is false).
      if (res.status == Status::Optimal)
        res.message = "SLP converged, but its repaired timing breaks a constraint by " + detail::fmt(violation) +
                      " (relative)";
      res.status = Status::NumericalError;
    }
  } else {
    res.binding = detail::binding_labels(chain, sets, theta);
    // The greatest element and the bracketed profile are read off the reachability polygons: checked in the
    // grid points' own terms (eq. 26), not assumed, before they are called optimal.
    Eigen::Index at = -1;
    double T_increase = 0.0;
    const double violation = detail::exact_feasibility_step(chain, sets, theta, &at, &T_increase);
    // Its cost in T is part of the gap (the greatest element is then within T_increase of the optimum).
    if (T_increase > 0.0) {
      res.stats.gap += T_increase;
      res.stats.greatest_element = false;
      if (res.stats.gap > options.tolerance) {
        res.status = Status::IterationLimit;
        res.message = "the exact-feasibility step cost " + detail::fmt(T_increase) + " of T, beyond the tolerance";
      }
    }
    if (violation > 1e-9) {
      res.status = Status::NumericalError;
      res.message = "the reachability analysis's profile breaks a constraint by " + detail::fmt(violation) +
                    " (relative) at grid index " + std::to_string(at) + " (s = " + detail::fmt(samples_.s[at]) +
                    "): rounding on this grid; a coarser or more uniform grid avoids it";
    }
    // The budget is checked inside the SLP; a problem proven without it can still have spent it on the
    // feasible sets and the reachability analysis: then the time limit is what the status says.
    if (res.status == Status::Optimal && std::chrono::steady_clock::now() >= deadline) {
      res.status = Status::TimeLimit;
      res.message = "time_limit = " + detail::fmt(options.time_limit) + " s reached before the SLP (the feasible sets "
                    "and the reachability analysis took " + detail::fmt(seconds_since(started)) +
                    " s); the timing is feasible, T exceeds the optimum by at most " + detail::fmt(res.stats.gap) +
                    " (relative, certified)";
    }
  }
  theta *= scale.x_unit;  // back to ṡ² (a power of two: exact)
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

void TimeScalingProblem::set_zero_boundary_accelerations(bool at_begin, bool at_end) {
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

bool TimeScalingProblem::feasible_with(const std::vector<std::shared_ptr<const Constraint>>& constraints,
                                       std::vector<ConstraintRows> rows, Guarantee guarantee) const {
  detail::IntervalExtra extra;
  if (guarantee == Guarantee::Continuous)
    detail::add_kinematic_continuous_rows(*path_, samples_, constraints, rows, extra);
  add_boundary_rows(rows, extra);
  const detail::Scale scale = detail::problem_scale(samples_.s, rows);
  const detail::GridSets sets = detail::build_grid_sets(samples_, rows, scale);
  for (const detail::PointSet& p : sets.points)
    if (p.empty) return false;
  const detail::Chain chain = detail::build_chain(samples_.s, sets, &extra, scale);
  // Unbounded is not infeasible: some timing exists (and a relaxation cannot make it less bounded).
  const double th0 = sdot_begin_ * sdot_begin_ / scale.x_unit;
  detail::Reachability reach = detail::reachability(chain, th0, sdot_end_ * sdot_end_ / scale.x_unit);
  if (reach.outcome != detail::Reachability::Outcome::Feasible) return reach.outcome == detail::Reachability::Outcome::Unbounded;
  // As solve() judges it: a speed forced to zero on an interval means the path cannot be traversed.
  return avoid_stopped_profile(chain, reach, th0, reach.theta);
}

std::map<std::string, double> TimeScalingProblem::relaxation(double max_scale, double rel_tolerance,
                                                             Guarantee guarantee) const {
  if (!(max_scale > 1.0) || !std::isfinite(max_scale))
    detail::fail("max_scale = " + detail::fmt(max_scale) + " must be > 1 and finite");
  if (!(rel_tolerance > 0.0 && rel_tolerance < 1.0))
    detail::fail("rel_tolerance = " + detail::fmt(rel_tolerance) + " must be in (0, 1)");
  std::vector<std::string> families;
  for (const auto& c : constraints_)
    for (const std::string& f : c->families())
      if (std::find(families.begin(), families.end(), f) == families.end()) families.push_back(f);
  if (families.size() >= 2) families.push_back("all");
  std::map<std::string, double> out;
  if (families.empty()) return out;
  if (feasible_with(constraints_, rows_, guarantee)) {
    for (const std::string& f : families) out[f] = 1.0;
    return out;
  }
  for (const std::string& f : families) {
    auto feasible = [&](double scale) {
      std::vector<ConstraintRows> rows = rows_;
      std::vector<std::shared_ptr<const Constraint>> cons = constraints_;
      for (size_t i = 0; i < constraints_.size(); ++i) {
        // "all": every family of the constraint at once (relaxed one after the other).
        std::shared_ptr<const Constraint> r;
        for (const std::string& fi : constraints_[i]->families()) {
          if (f != "all" && fi != f) continue;
          if (auto next = (r ? r : constraints_[i])->relaxed(fi, scale)) r = std::move(next);
        }
        if (r) {
          rows[i] = r->evaluate(samples_);
          cons[i] = std::move(r);
        }
      }
      return feasible_with(cons, std::move(rows), guarantee);
    };
    // Feasibility grows with the scale (each relaxed set contains the last): double until feasible,
    // then bisect on log(scale).
    double lo = 1.0, hi = 2.0;
    while (hi < max_scale && !feasible(hi)) {
      lo = hi;
      hi = std::min(4.0 * hi, max_scale);
    }
    if (hi >= max_scale && !feasible(max_scale)) {
      out[f] = std::numeric_limits<double>::infinity();
      continue;
    }
    while (hi > lo * (1.0 + rel_tolerance)) {
      const double mid = std::sqrt(lo * hi);
      (feasible(mid) ? hi : lo) = mid;
    }
    out[f] = hi;
  }
  return out;
}

std::string TimeScalingProblem::describe_relaxation(const std::map<std::string, double>& relaxation) {
  std::ostringstream os;
  std::vector<std::pair<double, std::string>> finite;
  for (const auto& [f, scale] : relaxation)
    if (std::isfinite(scale) && f != "all") finite.emplace_back(scale, f);
  std::sort(finite.begin(), finite.end());
  if (finite.empty()) {
    auto all = relaxation.find("all");
    if (all != relaxation.end() && std::isfinite(all->second))
      os << "feasible only with every family of limits x " << detail::fmt(std::ceil(all->second * 1e3) / 1e3);
    else if (relaxation.empty())
      os << "no constraint family can be relaxed to explain it";
    else
      os << "no single family of limits scaled up to x 1000 makes it feasible";
    return os.str();
  }
  // Four digits say enough, rounded up so that the printed scale is a feasible one.
  auto up4 = [](double v) {
    const double e = std::pow(10.0, std::floor(std::log10(v)) - 3);
    return detail::fmt(std::ceil(v / e) * e);
  };
  os << "feasible with ";
  for (size_t i = 0; i < finite.size(); ++i)
    os << (i ? " or " : "") << finite[i].second << " limits x " << up4(finite[i].first);
  return os.str();
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
  set_boundary_speeds(s.sdot_begin, s.sdot_end);
  set_zero_boundary_accelerations(s.zero_sddot_begin, s.zero_sddot_end);
  if (!s.joint_names.empty()) set_joint_names(s.joint_names);
}

namespace {

// A LinearConstraint's rows at the grid indices `kept` (the points a restart keeps).
std::shared_ptr<const Constraint> restricted_rows(const LinearConstraint& c, const std::vector<Eigen::Index>& kept) {
  const auto pick = [&kept](const Eigen::MatrixXd& m) {
    Eigen::MatrixXd out(static_cast<Eigen::Index>(kept.size()), m.cols());
    for (size_t i = 0; i < kept.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = m.row(kept[i]);
    return out;
  };
  return std::make_shared<LinearConstraint>(pick(c.A()), pick(c.B()), pick(c.C()), pick(c.lo()), pick(c.hi()), c.label());
}

}  // namespace

TimeScalingProblem TimeScalingProblem::restarted(double s0, double sdot0) const {
  const Eigen::Index n = intervals();
  const double a = samples_.s[0], b = samples_.s[n];
  if (!std::isfinite(s0) || s0 < a || s0 >= b)
    detail::fail("s0 = " + detail::fmt(s0) + " must be in [s_begin, s_end) = [" + detail::fmt(a) + ", " +
                 detail::fmt(b) + ")");
  if (!std::isfinite(sdot0) || sdot0 < 0.0) detail::fail("sdot0 = " + detail::fmt(sdot0) + " must be >= 0 and finite");
  // The new grid and, for each of its points, the old grid index (-1: s0 is not an old grid point).
  const Eigen::Index k0 = static_cast<Eigen::Index>(std::upper_bound(samples_.s.data(), samples_.s.data() + n + 1, s0) -
                                                    samples_.s.data()) - 1;
  std::vector<double> g{s0};
  std::vector<Eigen::Index> kept{samples_.s[k0] == s0 ? k0 : -1};
  for (Eigen::Index k = k0 + 1; k <= n; ++k) {
    // A grid point a hair beyond s0 would make an interval of width ~0 (a wasted, ill-conditioned row
    // pair); the end point always stays.
    if (k < n && samples_.s[k] - s0 <= 1e-9 * (samples_.s[k] - samples_.s[k - 1])) continue;
    g.push_back(samples_.s[k]);
    kept.push_back(k);
  }
  std::shared_ptr<const Path> tail;
  if (s0 == a) tail = path_;
  else if (auto pp = std::dynamic_pointer_cast<const PiecewisePolynomialPath>(path_)) tail = detail::polynomial_tail(*pp, s0);
  else tail = std::make_shared<detail::SubPath>(path_, s0);
  TimeScalingProblem p(std::move(tail), Eigen::Map<const Eigen::VectorXd>(g.data(), static_cast<Eigen::Index>(g.size())));
  for (const auto& c : constraints_) {
    auto linear = std::dynamic_pointer_cast<const LinearConstraint>(c);
    if (!linear) {
      p.add_constraint(c);
      continue;
    }
    // Rows given per grid point have no value between grid points (they may come from any dynamics).
    if (kept[0] < 0) {
      const Eigen::Index near = k0 < n && samples_.s[k0 + 1] - s0 < s0 - samples_.s[k0] ? k0 + 1 : k0;
      detail::fail("restarted: s0 = " + detail::fmt(s0) + " is not a grid point (nearest: grid[" + std::to_string(near) +
                   "] = " + detail::fmt(samples_.s[near]) + ") and constraint '" + c->name() +
                   "' is given per grid point (LinearConstraint): restart at a grid point");
    }
    p.add_constraint(restricted_rows(*linear, kept));
  }
  ProblemSettings s = settings();
  s.sdot_begin = sdot0;
  if (s0 != a) s.zero_sddot_begin = false;  // a running trajectory's s̈ at s0 is free
  p.set_settings(s);
  return p;
}

}  // namespace pathpace
