// TimeScalingProblem::add_contact_phases and add_contacts: contact constraints joined to a problem (sec. IV).
#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "solve/grid_sets.hpp"
#include "solve/reachability.hpp"
#include "base/validate.hpp"
#include "problem/sampling.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace {

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
      if (constraints_[c]->per_grid_point())
        detail::fail(name(i, "s_begin") + " = " + detail::fmt(sw) + " is not a grid point (nearest: grid[" +
                     std::to_string(k) + "] = " + detail::fmt(g[k]) + ") and the problem has a constraint given per grid "
                     "point ('" + constraints_[c]->name() + "') that cannot be evaluated on a new grid: add the contact "
                     "phases first, or use a grid with a point at every switch");
    if (!inserted) grid.assign(g, g + size);
    grid.insert(std::upper_bound(grid.begin(), grid.end(), sw), sw);
    edge[i] = sw;
    inserted = true;
  }
  // What a phase can absorb (its robot's torque limits) joins every phase, as add_constraint merges it.
  std::vector<size_t> replaced;
  for (size_t c = 0; c < constraints_.size(); ++c)
    if (probe[0]->can_absorb(*constraints_[c])) replaced.push_back(c);
  // A switch inserted: the path and every constraint that stays on the new grid, checked as add_constraint
  // checks them (a user's own Constraint may hand back anything there); kept apart until the commit below.
  // Without one the problem's samples and rows serve as they are.
  PathSamples new_samples;
  std::vector<ConstraintRows> new_rows;
  if (inserted) {
    new_samples.s = Eigen::Map<const Eigen::VectorXd>(grid.data(), static_cast<Eigen::Index>(grid.size()));
    detail::sample_path(*path_, new_samples);
    new_rows.resize(constraints_.size());
    for (size_t c = 0; c < constraints_.size(); ++c) {
      if (std::find(replaced.begin(), replaced.end(), c) != replaced.end()) continue;  // merged into the phases
      new_rows[c] = detail::timed_evaluate(*constraints_[c], new_samples);
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
    std::shared_ptr<const Constraint> phase = c;
    for (size_t r : replaced) phase = phase->absorb(*constraints_[r]);
    added_rows.push_back(detail::timed_evaluate(*phase, samples));
    check_rows(*phase, added_rows.back(), samples.size());
    added.push_back(std::move(phase));
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
}  // namespace pathpace
