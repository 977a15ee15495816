// TimeScalingProblem::solve: options checked, then the rows through the pipeline (grid sets -> reachability ->
// SLP windows, sec. V), and for guarantee = continuous the audit-and-cut rounds.
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
#include "base/validate.hpp"
#include "problem/sampling.hpp"
#include "pathpace/constraints/contact_constraint.hpp"

namespace pathpace {

namespace {

// An infeasibility with contacts is a claim about the robot, and the polygons are projections: before
// it is reported, one LP on the full (ṡ², s̈, τ, f) polytope at the binding grid point, with every other
// constraint's half-planes there, re-checks it; the message says whether the rest state (0, 0) is
// feasible there. A point whose polygon is empty but whose full LP is not is a projection failure.
void recheck_projection(const TimeScalingProblem& problem, const std::vector<ConstraintRows>& rows, Eigen::Index k,
                        bool point_empty, const Constraint& projected, Result& res) {
  Eigen::Matrix<double, Eigen::Dynamic, 3> extra(0, 3);
  for (size_t i = 0; i < rows.size(); ++i) {
    const ConstraintRows& cr = rows[i];
    if (problem.constraints()[i].get() == &projected) continue;
    for (Eigen::Index j = 0; j < cr.rows(); ++j)
      if (std::isfinite(cr.c(k, j))) {
        extra.conservativeResize(extra.rows() + 1, 3);
        extra.row(extra.rows() - 1) << cr.a(k, j), cr.b(k, j), cr.c(k, j);
      }
  }
  const PointCheck check = projected.check_point(problem.samples(), k, extra);
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
    round_options.time_limit = std::max(options.time_limit - detail::seconds_since(started), 1e-3);
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
  int torque_rank = 0;  // Constraint::report: a problem's own torque limits are shown over a contact's copy
  for (const auto& c : constraints_) c->report(res, torque_rank);
  std::stable_sort(res.contact_phases.begin(), res.contact_phases.end(), [](const auto& x, const auto& y) {
    return x->options().active_begin < y->options().active_begin;
  });
  res.s = samples_.s;
  const Eigen::Index n = intervals();

  for (size_t i = 0; i < rows_.size(); ++i) {
    res.stats.time_constraints += rows_[i].seconds;
    res.stats.inexact_points += static_cast<int>(rows_[i].inexact_points.size());
    if (constraints_[i]->projected()) {
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
  res.stats.time_feasible_sets = detail::seconds_since(t0);
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
    if (st == Status::Infeasible) {
      // A projected constraint (contacts) is re-checked on its full polytope; with contact phases, the phase
      // that holds at k (the first of two at a switch; the other's rows enter the check as half-planes).
      for (const auto& c : constraints_)
        if (c->projected() && c->active_at(samples_.s[k])) {
          recheck_projection(*this, rows_, k, sets.points[static_cast<size_t>(k)].empty, *c, res);
          break;
        }
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
  if (!proven) detail::avoid_stopped_profile(chain, reach, th0, theta);
  res.stats.time_reachability = detail::seconds_since(t0);
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
    res.stats.time_slp = detail::seconds_since(t0);
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
                    "and the reachability analysis took " + detail::fmt(detail::seconds_since(started)) +
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
}  // namespace pathpace
