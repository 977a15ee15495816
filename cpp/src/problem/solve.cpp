// TimeScalingProblem::solve: options checked, then the rows through the stages of solve/pipeline.hpp (grid sets
// -> reachability -> certify -> assemble, sec. V), and for guarantee = continuous the audit-and-cut rounds.
#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "base/clock.hpp"
#include "base/validate.hpp"
#include "problem/sampling.hpp"
#include "solve/continuous.hpp"
#include "solve/grid_sets.hpp"
#include "solve/options.hpp"
#include "solve/pipeline.hpp"
#include "pathpace/constraints/contact_constraint.hpp"

namespace pathpace {

namespace {

// Whether the full polytope at k holds a point (x, u) that the discretised problem can use. Both adjacent
// intervals' s̈ must lie in the polygon at k (eq. 24-25, both adjacent s̈ rows), and u of the interval to
// neighbour j is the difference quotient ±(θ_j - x) / (2 |s_j - s_k|) with θ_j in [0, X_j], X_j the largest
// ṡ² of j's rows (outer rows where they are refined on demand: a bound still). So each side adds two rows,
// 0 <= x ± 2Δs u <= X_j, and each side's LP must be feasible. It tells a projection that failed (its shadow
// only at |s̈| ~ 1e13, where p'(s_k) ~ 1e-11 is a turning point's rounding residue and b = M p' with it) from
// a point the problem could reach. False only when a side's LP is empty (confirmed in exact arithmetic).
bool reachable_at(const TimeScalingProblem& problem, const std::vector<ConstraintRows>& rows, Eigen::Index k,
                  const Eigen::Matrix<double, Eigen::Dynamic, 3>& extra, const Constraint& projected) {
  const Eigen::VectorXd& s = problem.samples().s;
  detail::Polygon2d polygon;
  for (const Eigen::Index j : {k - 1, k + 1}) {
    if (j < 0 || j >= s.size()) continue;
    const detail::PointSet set = detail::build_point_set(rows, j, polygon);
    if (set.empty) continue;  // no bound from an empty neighbour (it is reported in its own right)
    double x_lo = 0.0, x_hi = 0.0;
    polygon.x_range(x_lo, x_hi);
    const double h = 2.0 * (s[j] - s[k]);  // θ_j = x + h u
    Eigen::Matrix<double, Eigen::Dynamic, 3> side(extra.rows() + 2, 3);
    side.topRows(extra.rows()) = extra;
    side.row(extra.rows()) << 1.0, h, x_hi;
    side.row(extra.rows() + 1) << -1.0, -h, 0.0;
    if (projected.check_point(problem.samples(), k, side).feasible == 0) return false;
  }
  return true;
}

// An infeasibility with contacts is a claim about the robot, and the polygons are projections: before
// it is reported, one LP on the full (ṡ², s̈, τ, f) polytope at the binding grid point, with every other
// constraint's half-planes there, re-checks it; the message says whether the rest state (0, 0) is
// feasible there. A point whose polygon is empty but whose full LP is not is a projection failure.
void recheck_projection(const TimeScalingProblem& problem, const std::vector<ConstraintRows>& rows, Eigen::Index k,
                        bool point_empty, const Constraint& projected, Result& res) {
  Eigen::Matrix<double, Eigen::Dynamic, 3> extra(0, 3);
  // The other constraints exactly (rows refined on demand bound theirs from outside: another contact phase's
  // at a switch made a plainly infeasible point look like a failed projection).
  const std::vector<ConstraintRows> at_k = detail::exact_rows_at(problem.constraints(), rows, problem.samples(), k);
  for (size_t i = 0; i < at_k.size(); ++i) {
    const ConstraintRows& cr = at_k[i];
    if (problem.constraints()[i].get() == &projected) continue;
    for (Eigen::Index j = 0; j < cr.rows(); ++j)
      if (std::isfinite(cr.c(0, j))) {
        extra.conservativeResize(extra.rows() + 1, 3);
        extra.row(extra.rows() - 1) << cr.a(0, j), cr.b(0, j), cr.c(0, j);
      }
  }
  const PointCheck check = projected.check_point(problem.samples(), k, extra);
  auto word = [](int v, const char* yes, const char* no) { return v > 0 ? yes : v == 0 ? no : "unknown (LP failed)"; };
  if (point_empty && check.feasible > 0 && !reachable_at(problem, rows, k, extra, projected)) {
    res.message += "; re-checked by one LP on the full (sdot^2, sddot, torque, force) polytope at that point: feasible "
                   "only at an sddot that no adjacent interval reaches (as at a turning point of the path, where p' ~ 0 "
                   "leaves the sddot coefficients at rounding residues)";
    return;
  }
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

// A timing of a path that moves its contacts (DriftPolicy::Warn) says so in its message as well as in
// Result::contact_drift: its contact forces assume contacts that the path slides.
Result with_drift_note(Result res) {
  if (res.contact_drift.empty()) return res;
  std::string note = "the path moves its contacts, which the contact forces assume fixed: ";
  for (size_t i = 0; i < res.contact_drift.size(); ++i) note += (i ? "; " : "") + res.contact_drift[i].message();
  res.message = res.message.empty() ? note : res.message + "; " + note;
  return res;
}

// A projection's LPs into the stats, by cause.
void add_projection_lps(SolverStats& st, int lps, const LpCounts& by) {
  st.projection_lp_solves += lps;
  st.projection_lps_initial += by.initial;
  st.projection_lps_vertex += by.vertex;
  st.projection_lps_certificate += by.certificate;
  st.projection_lps_cap_growth += by.cap_growth;
  st.projection_lps_cold_retry += by.cold_retry;
  st.projection_ranged_certificates += by.ranged;
  st.projection_lps_dense += by.dense;
  st.projection_lps_dense_fallback += by.dense_fallback;
  st.projection_pivots += by.pivots;
  st.projection_fallback_cap += by.fallback_cap;
  st.projection_fallback_small_pivot += by.fallback_small_pivot;
  st.projection_fallback_unbounded += by.fallback_unbounded;
  st.projection_fallback_singular += by.fallback_singular;
  st.projection_fallback_certificate += by.fallback_certificate;
}

// The Result's robot, torque limits and contacts, and the stats of the constraints' rows (computed when they
// were added).
Result with_constraints(const TimeScalingProblem& problem, const std::vector<ConstraintRows>& rows) {
  Result res;
  int torque_rank = 0;  // Constraint::report: a problem's own torque limits are shown over a contact's copy
  for (const auto& c : problem.constraints()) c->report(res, torque_rank);
  std::stable_sort(res.contact_phases.begin(), res.contact_phases.end(), [](const auto& x, const auto& y) {
    return x->options().active_begin < y->options().active_begin;
  });
  for (size_t i = 0; i < rows.size(); ++i) {
    res.stats.time_constraints += rows[i].seconds;
    res.stats.inexact_points += static_cast<int>(rows[i].inexact_points.size());
    if (problem.constraints()[i]->projected()) {
      res.stats.time_projection += rows[i].seconds;
      add_projection_lps(res.stats, rows[i].lp_solves, rows[i].lp_by_cause);
    }
  }
  return res;
}

// A stage's Stop as the Result: its status, the grid point and the binding rows by label, the relaxation that
// would make an infeasible problem feasible (SolverOptions::explain), and with contacts the re-check by one LP.
Result report(const TimeScalingProblem& problem, const std::vector<ConstraintRows>& rows, const detail::GridSets& sets,
              const detail::Stop& stop, const SolverOptions& options, Result res) {
  const Eigen::Index k = stop.k;
  const Eigen::VectorXd& s = problem.samples().s;
  res.status = stop.status;
  res.infeasibility.grid_index = k;
  res.infeasibility.s = s[k];
  for (int id : stop.ids) res.infeasibility.constraints.push_back(sets.label(id));
  std::ostringstream os;
  os << stop.why << " at grid index " << k << " (s = " << detail::fmt(s[k]) << ")";
  if (!stop.ids.empty()) {
    os << "; binding: ";
    for (size_t i = 0; i < res.infeasibility.constraints.size(); ++i)
      os << (i ? ", " : "") << res.infeasibility.constraints[i];
  }
  if (stop.status == Status::Infeasible && options.explain) {
    res.relaxation = problem.relaxation(1e3, 1e-3, options.guarantee);
    os << "; " << TimeScalingProblem::describe_relaxation(res.relaxation);
  }
  res.message = os.str();
  if (stop.status == Status::Infeasible) {
    // A projected constraint (contacts) is re-checked on its full polytope; with contact phases, the phase
    // that holds at k (the first of two at a switch; the other's rows enter the check as half-planes).
    for (const auto& c : problem.constraints())
      if (c->projected() && c->active_at(s[k])) {
        recheck_projection(problem, rows, k, sets.points[static_cast<size_t>(k)].empty, *c, res);
        break;
      }
  }
  return res;
}

}  // namespace

Result TimeScalingProblem::solve(const SolverOptions& options) const {
  const Use use(*this, Use::Read, "solve");
  detail::validate(options);
  if (jerk_) return with_drift_note(solve_jerk(options));
  if (zero_sddot_begin_ && sdot_begin_ == 0.0)
    detail::fail("sddot = 0 at s_begin needs sdot_begin > 0: with sddot constant on each interval (eq. 24), a start "
                 "from rest with sddot = 0 never moves");
  if (zero_sddot_end_ && sdot_end_ == 0.0)
    detail::fail("sddot = 0 at s_end needs sdot_end > 0: with sddot constant on each interval (eq. 24), a stop at "
                 "rest with sddot = 0 is never reached");
  if (options.guarantee == Guarantee::Grid) {
    if (!zero_sddot_begin_ && !zero_sddot_end_ && !refines()) return with_drift_note(solve_rows(rows_, nullptr, options));
    std::vector<ConstraintRows> rows = rows_;
    detail::IntervalExtra extra;
    add_boundary_rows(rows, extra);
    std::vector<RefineMemory> memory;
    return with_drift_note(solve_refined(rows, &extra, options, memory));
  }

  // guarantee = continuous (see solve/continuous.hpp): velocity and acceleration rows that hold between
  // grid points by construction, then audit-and-cut rounds for the other constraints.
  std::vector<ConstraintRows> rows = rows_;
  detail::IntervalExtra extra;
  detail::add_kinematic_continuous_rows(*path_, samples_, constraints_, rows, extra);
  add_boundary_rows(rows, extra);
  std::vector<int> offset;
  Result res;
  int rounds = 0, cuts = 0, audit_lps = 0, audit_lps_glpk = 0, audit_projections = 0, audit_reused = 0;
  int projection_rounds = 0;
  detail::AuditMemory memory;
  std::vector<RefineMemory> refined;
  // The time budget covers all rounds: each solve gets what is left.
  const auto started = std::chrono::steady_clock::now();
  SolverOptions round_options = options;
  for (;;) {
    round_options.time_limit = std::max(options.time_limit - detail::seconds_since(started), 1e-3);
    res = solve_refined(rows, &extra, round_options, refined);
    projection_rounds += res.stats.projection_rounds;
    if (!res.ok() || res.status == Status::TimeLimit) break;
    const Eigen::VectorXd theta = res.sdot.array().square();
    // The label ids of each constraint's first row (rows refined on demand may have grown since the last round).
    offset.clear();
    int id = 0;
    for (size_t i = 0; i < constraints_.size(); ++i) {
      offset.push_back(id);
      id += static_cast<int>(rows[i].rows());
    }
    const detail::Audit audit = detail::audit_and_cut(*path_, samples_.s, theta, constraints_, rows, offset,
                                                      options.audit_points, options.audit_tolerance, extra, memory);
    ++rounds;
    cuts += audit.cuts;
    audit_lps += audit.lps;
    audit_lps_glpk += audit.glpk_lps;
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
  // The loop ends when a round adds no cut, which an interval whose speeds came back bitwise unchanged never
  // does: its last cuts were met to the solver's own feasibility tolerance, which in θ-space (a cut's terms
  // are ~ b θ / Δs) can exceed audit_tolerance (bench/README.md: 1.8e-9 on demand), or its violation had no
  // cut. Said, not hidden.
  if (res.status == Status::Optimal && res.stats.audit_worst > options.audit_tolerance)
    res.message += std::string(res.message.empty() ? "" : "; ") +
                   "guarantee = 'continuous': a limit is exceeded between grid points by " + detail::fmt(res.stats.audit_worst) +
                   " (relative), above audit_tolerance = " + detail::fmt(options.audit_tolerance) +
                   ": no further cut changed the timing there";
  res.stats.audit_rounds = rounds;
  res.stats.audit_cuts = cuts;
  res.stats.audit_lps = audit_lps;
  res.stats.audit_lps_glpk = audit_lps_glpk;
  res.stats.audit_projections = audit_projections;
  res.stats.audit_reused = audit_reused;
  res.stats.projection_rounds = projection_rounds;
  return with_drift_note(std::move(res));
}

bool TimeScalingProblem::refines() const {
  return std::any_of(constraints_.begin(), constraints_.end(), [](const auto& c) { return c->refines(); });
}

Result TimeScalingProblem::solve_refined(std::vector<ConstraintRows>& rows, detail::IntervalExtra* extra,
                                         const SolverOptions& options, std::vector<RefineMemory>& memory) const {
  if (!refines()) return solve_rows(rows, extra, options);
  memory.resize(constraints_.size());
  // Each round refines at least one grid point's polygon towards a point beyond an uncertified edge (a new
  // vertex or a certified edge): finitely many, so the rounds end; this cap only guards against a bug.
  constexpr int kMaxRounds = 1000;
  // One scale for every round and every call (the problem's own rows'): a refinement then leaves the timing of
  // the points it does not touch as it was, to the bit, which the continuous audit's memory relies on.
  const detail::Scale scale = detail::problem_scale(samples_.s, rows_);
  const auto started = std::chrono::steady_clock::now();
  SolverOptions round_options = options;
  Result res;
  int rounds = 0;
  for (;;) {
    round_options.time_limit = std::max(options.time_limit - detail::seconds_since(started), 1e-3);
    res = solve_rows(rows, extra, round_options, &scale);
    ++rounds;
    if (!res.ok() || res.status == Status::TimeLimit) break;
    const Eigen::VectorXd theta = res.sdot.array().square();
    int changed = 0, first_id = 0;
    for (size_t i = 0; i < constraints_.size(); ++i) {
      const Eigen::Index before = rows[i].rows();
      if (constraints_[i]->refines()) changed += constraints_[i]->refine(samples_, theta, nullptr, rows[i], memory[i]);
      first_id += static_cast<int>(before);
      const int grown = static_cast<int>(rows[i].rows() - before);
      if (grown > 0 && extra)  // the ids after this constraint's rows move up by what it added
        for (auto& interval : extra->rows)
          for (detail::Line& l : interval)
            if (l.id >= first_id) l.id += grown;
      first_id += grown;
    }
    if (changed == 0) break;
    if (rounds >= kMaxRounds) {
      res.status = Status::IterationLimit;
      res.message = "the contact polygons were refined " + std::to_string(rounds) +
                    " times and the timing still needs more (project_on_demand)";
      break;
    }
  }
  res.stats.projection_rounds = rounds;
  for (const RefineMemory& m : memory) add_projection_lps(res.stats, m.lp_solves, m.lp_by_cause);
  return res;
}

Result TimeScalingProblem::solve_rows(const std::vector<ConstraintRows>& constraint_rows,
                                      const detail::IntervalExtra* extra, const SolverOptions& options,
                                      const detail::Scale* scale) const {
  const detail::Budget budget = detail::Budget::from(options.time_limit);
  Result res = with_constraints(*this, rows_);
  res.path = path_;
  res.contact_drift = contact_drift_;
  res.s = samples_.s;

  const detail::SetsStage sets = detail::grid_sets_stage(samples_, constraint_rows, sdot_begin_, sdot_end_, scale);
  res.stats.time_feasible_sets = sets.seconds;
  res.stats.average_halfplanes = sets.sets.average_rows;
  if (sets.stop) return report(*this, rows_, sets.sets, *sets.stop, options, std::move(res));

  const detail::ReachStage reach = detail::reachability_stage(samples_, sets, extra, sdot_begin_, sdot_end_, options);
  res.stats.time_reachability = reach.seconds;
  res.stats.gap = reach.gap;
  res.stats.greatest_element = reach.proven && reach.gap == 0.0;
  if (reach.stop) return report(*this, rows_, sets.sets, *reach.stop, options, std::move(res));

  const detail::Certified timing = detail::certify_stage(samples_, sets, reach, options, budget);
  res.status = timing.status;
  res.message = timing.message;
  res.binding = timing.binding;
  res.stats.gap = timing.gap;
  res.stats.greatest_element = timing.greatest_element;
  res.stats.time_slp = timing.seconds;
  res.stats.slp_iterations = timing.slp_iterations;
  res.stats.lp_solves = timing.lp_solves;
  res.stats.windows = timing.windows;
  res.stats.window_points = timing.window_points;
  res.stats.newton_steps = timing.newton_steps;
  detail::assemble(samples_.s, sets.scale, timing.theta, res);
  return res;
}
}  // namespace pathpace
