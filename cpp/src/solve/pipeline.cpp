#include "solve/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "base/clock.hpp"
#include "base/validate.hpp"
#include "solve/binding.hpp"
#include "solve/line_reachability.hpp"
#include "solve/slp.hpp"

namespace pathpace::detail {

Budget Budget::from(double time_limit) {
  Budget b;
  b.started = std::chrono::steady_clock::now();
  const double seconds = std::min(time_limit, 1e9);  // +inf: no limit (a billion seconds)
  b.deadline = b.started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                               std::chrono::duration<double>(seconds));
  b.time_limit = time_limit;
  return b;
}

SetsStage grid_sets_stage(const PathSamples& samples, const std::vector<ConstraintRows>& rows, double sdot_begin,
                          double sdot_end, const Scale* scale) {
  const auto t0 = std::chrono::steady_clock::now();
  // Solved in units where the speeds are ~1 (see Scale): T then scales exactly with the path's length and its
  // limits, with no cap on ṡ² that a bounded problem could reach.
  SetsStage out{scale ? *scale : problem_scale(samples.s, rows), {}, 0.0, std::nullopt};
  out.sets = build_grid_sets(samples, rows, out.scale);
  out.seconds = seconds_since(t0);
  const Eigen::Index n = samples.s.size() - 1;
  for (Eigen::Index k = 0; k <= n; ++k) {
    const PointSet& p = out.sets.points[static_cast<size_t>(k)];
    if (p.empty) {
      out.stop = Stop{Status::Infeasible, k, p.certificate, "no (sdot^2, sddot) satisfies the constraints"};
      return out;
    }
  }
  // A boundary speed beyond the speed bound of its end point: said in the user's terms (the reachability
  // analysis would only find that no speed is admissible one grid point further on).
  for (const auto& [k, sdot, name] : {std::make_tuple(Eigen::Index(0), sdot_begin, "sdot_begin"),
                                      std::make_tuple(n, sdot_end, "sdot_end")}) {
    const PointSet& p = out.sets.points[static_cast<size_t>(k)];
    if (sdot * sdot / out.scale.x_unit > p.x_hi * (1 + 1e-12) && p.x_hi_id >= 0) {
      out.stop = Stop{Status::Infeasible, k, {p.x_hi_id},
                      std::string(name) + " = " + fmt(sdot) + " is faster than the constraints allow at " +
                          (k == 0 ? "s_begin" : "s_end") + " (sdot <= " + fmt(std::sqrt(p.x_hi * out.scale.x_unit)) +
                          ")"};
      return out;
    }
  }
  return out;
}

namespace {

// How far from feasible (relative) a timing from the analyses by lines may be: rounding.
constexpr double kLineViolation = 1e-12;

// A stationary piece of path (p' = 0 on a stretch of the grid) that no constraint bounds would be crossed in
// zero time: the discretised problem has no optimum there (T* is not attained). That is an input error, named
// by its s-range; a single grid point with p' = 0 (a cusp) is just an unbounded point.
void stationary_check(const PathSamples& samples, Eigen::Index k) {
  const Eigen::Index n = samples.s.size() - 1;
  const double tol = 1e-12 * std::max(1.0, samples.dq.cwiseAbs().maxCoeff());
  auto still = [&](Eigen::Index i) { return samples.dq.row(i).cwiseAbs().maxCoeff() <= tol; };
  if (k < 0 || k > n || !still(k)) return;
  Eigen::Index a = k, b = k;
  while (a > 0 && still(a - 1)) --a;
  while (b < n && still(b + 1)) ++b;
  if (a == b) return;
  fail("path does not move on s in [" + fmt(samples.s[a]) + ", " + fmt(samples.s[b]) + "] (p'(s) = 0 at grid indices " +
       std::to_string(a) + ".." + std::to_string(b) +
       ") and no constraint bounds the speed there: it would be crossed in zero time; remove that piece from the "
       "path");
}

// Rows coupling θ_k and θ_{k+1} positively appear wherever p'_j is small against p''_j (near a joint's
// reversal). Without them the feasible set is max-closed and its greatest element θ' has T(θ') <= T* (a lower
// bound); the full greedy θ is feasible (an upper bound). If θ' satisfies the coupling rows it is the optimum;
// if the bracket is within the tolerance, θ is optimal to it.
void bracket(ReachStage& out, double tolerance) {
  out.relaxed = std::make_unique<Reachability>();
  if (!reachability_pair(out.chain, out.th0, out.thN, *out.relaxed, out.reach)) return;
  out.have_full = true;
  out.T_relaxed = duration(out.chain.ds, out.relaxed->theta);  // a lower bound on T*
  if (coupled_violation(out.chain, out.relaxed->theta) <= 1e-12) {
    out.theta = out.relaxed->theta;
    out.proven = true;
    return;
  }
  out.theta = out.reach.theta;
  const double upper = duration(out.chain.ds, out.theta);
  if (upper - out.T_relaxed <= tolerance * out.T_relaxed) {
    out.gap = std::max(0.0, upper - out.T_relaxed) / out.T_relaxed;
    out.proven = true;
  }
}

// The analyses by lines (solve/line_reachability.hpp) in their common case, instead of the polygons: the
// greatest element on a lattice, else the bracket, and where it does not prove the optimum the full
// analysis for the SLP (ReachStage::lines). A profile they prove is made to meet the grid points' own rows
// (eq. 26) to rounding (kLineViolation) by the exact-feasibility step, whose cost in T joins the gap (on a
// fine grid a line's value is exact to eps θ, which is eps θ / (2Δs) in s̈: 1e-11 of a row at N = 10^6).
// False, with `out` untouched, where they do not apply, or a profile stops on an interval
// (avoid_stopped_profile reads the polygons): the polygons then decide.
bool line_stage(const GridSets& sets, double tolerance, ReachStage& out) {
  const Chain& chain = out.chain;
  LineAnalysis relaxed, full;
  if (!line_analysis(chain, true, out.th0, out.thN, relaxed)) return false;
  // A proven profile, made exact: T's growth (relative) that the step cost, or NaN if it does not make it.
  auto exact = [&](Eigen::VectorXd& theta) {
    double T_increase = 0.0;
    const bool ok = !has_stopped_interval(theta) &&
                    exact_feasibility_step(chain, sets, theta, nullptr, &T_increase, kLineViolation) <= kLineViolation;
    return ok ? T_increase : std::numeric_limits<double>::quiet_NaN();
  };
  if (chain.lattice) {
    // Greatest element of a max-closed feasible set: optimal with no LP at all (see Chain::lattice).
    const double cost = exact(relaxed.theta);
    if (!(cost <= tolerance)) return false;
    out.theta = std::move(relaxed.theta);
    out.gap = cost;
    out.proven = out.exact = true;
    return true;
  }
  const double T_relaxed = duration(chain.ds, relaxed.theta);
  Eigen::VectorXd theta;
  double gap = std::numeric_limits<double>::quiet_NaN();
  if (coupled_violation(chain, relaxed.theta) <= 1e-12) {
    theta = relaxed.theta;  // the optimum: θ' meets the rows it was relaxed of
    gap = exact(theta);
  }
  if (!(gap <= tolerance)) {
    if (!line_analysis(chain, false, out.th0, out.thN, full, &relaxed) || has_stopped_interval(full.theta))
      return false;
    theta = full.theta;
    const double upper = duration(chain.ds, theta);
    gap = std::numeric_limits<double>::quiet_NaN();
    if (upper - T_relaxed <= tolerance * T_relaxed)
      gap = std::max(0.0, upper * (1.0 + exact(theta)) - T_relaxed) / T_relaxed;  // NaN if not made exact
    if (!(gap <= tolerance)) theta = full.theta;  // the SLP starts from the greedy profile itself
  }
  const bool proven = gap <= tolerance;
  out.relaxed = std::make_unique<Reachability>();
  out.relaxed->theta = std::move(relaxed.theta);
  out.have_full = true;
  out.T_relaxed = T_relaxed;
  out.theta = std::move(theta);
  out.gap = proven ? gap : 0.0;
  out.proven = out.exact = proven;
  if (!proven) out.lines = std::make_unique<LineAnalysis>(std::move(full));
  return true;
}

// The full analysis alone (no bracket: a lattice, Method::Slp, or the relaxed analysis did not end feasible);
// false with out.stop set if it finds no timing.
bool full_analysis(const PathSamples& samples, ReachStage& out, Method method) {
  out.reach = reachability(out.chain, out.th0, out.thN);
  if (out.reach.outcome == Reachability::Outcome::Infeasible) {
    out.stop = Stop{Status::Infeasible, out.reach.failed_index, out.reach.binding, out.reach.reason};
    return false;
  }
  if (out.reach.outcome == Reachability::Outcome::Unbounded) {
    stationary_check(samples, out.reach.failed_index);
    out.stop = Stop{Status::Unbounded, out.reach.failed_index, out.reach.binding, out.reach.reason};
    return false;
  }
  out.theta = out.reach.theta;
  // Greatest element of a max-closed feasible set: optimal with no LP at all (see Chain::lattice).
  if (out.chain.lattice && method == Method::Auto) out.proven = true;
  return true;
}

// The bound that pins the speed to zero on an interval of theta, if one does (e.g. a zero velocity limit on a
// joint that the path moves): a Stop, since no timing crosses that interval.
std::optional<Stop> stopped_interval(const Chain& chain, const Eigen::VectorXd& theta) {
  for (Eigen::Index k = 0; k < chain.intervals(); ++k)
    if (theta[k] + theta[k + 1] <= 0.0) {
      const Eigen::Index at = (theta[k] <= 0.0 && k > 0) ? k : k + 1;
      std::vector<int> ids;
      if (chain.x_hi[at] <= 0.0) ids.push_back(chain.x_hi_id[static_cast<size_t>(at)]);
      return Stop{Status::Infeasible, at, ids,
                  "the constraints force the speed to zero on an interval (the path cannot be traversed)"};
    }
  return std::nullopt;
}

}  // namespace

ReachStage reachability_stage(const PathSamples& samples, const SetsStage& sets, const IntervalExtra* extra,
                              double sdot_begin, double sdot_end, const SolverOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  ReachStage out;
  out.chain = build_chain(samples.s, sets.sets, extra, sets.scale);
  out.th0 = sdot_begin * sdot_begin / sets.scale.x_unit;
  out.thN = sdot_end * sdot_end / sets.scale.x_unit;
  out.T_relaxed = std::numeric_limits<double>::quiet_NaN();
  if (options.method == Method::Auto && line_stage(sets.sets, options.tolerance, out)) {
    out.seconds = seconds_since(t0);
    return out;
  }
  if (!out.chain.lattice && options.method == Method::Auto) bracket(out, options.tolerance);
  if (!out.have_full && !full_analysis(samples, out, options.method)) return out;
  // A proven θ is the answer even if it stops on an interval (every feasible profile does, then).
  if (!out.proven) avoid_stopped_profile(out.chain, out.reach, out.th0, out.theta);
  out.seconds = seconds_since(t0);
  out.stop = stopped_interval(out.chain, out.theta);
  return out;
}

namespace {

// The SLP's status in the Result's terms; `bound` says whether the timing is feasible and its certified gap.
void slp_status(SlpOutcome::Status st, const SolverOptions& options, const std::string& bound, Certified& out) {
  switch (st) {
    case SlpOutcome::Status::Converged:
      if (out.gap > options.tolerance) {
        out.status = Status::IterationLimit;
        out.message = "SLP converged on its windows, but the certified gap stayed above the tolerance; " + bound;
      }
      break;
    case SlpOutcome::Status::IterationLimit:
      out.status = Status::IterationLimit;
      out.message = "SLP stopped after max_iterations = " + std::to_string(options.max_iterations) +
                    " iterations in a window; " + bound;
      break;
    case SlpOutcome::Status::TimeLimit:
      out.status = Status::TimeLimit;
      out.message = "time_limit = " + fmt(options.time_limit) + " s reached during SLP; " + bound;
      break;
    case SlpOutcome::Status::LpFailed:
      out.status = Status::NumericalError;
      out.message = "GLPK failed in SLP; the timing returned is the last feasible one, " + bound;
      break;
  }
}

// The SLP's timing (solve/slp.hpp) checked in the grid points' own terms, made exact to `target` (the
// exact-feasibility step) and labelled. `excess`: how far the timing is from feasible then (relative).
Certified slp_certified(const SetsStage& sets, const Chain& chain, const SlpOutcome& slp, const SolverOptions& options,
                        double target, double& excess) {
  Certified out;
  out.slp_iterations = slp.iterations;
  out.lp_solves = slp.lp_solves;
  out.windows = slp.windows;
  out.window_points = static_cast<int>(slp.window_points);
  out.newton_steps = slp.newton_steps;
  out.theta = slp.theta;
  double T_increase = 0.0;
  const double grid_excess = exact_feasibility_step(chain, sets.sets, out.theta, nullptr, &T_increase, target);
  const double T = slp.T * (1.0 + T_increase);
  out.gap = slp.lower > 0.0 ? std::max(0.0, T - slp.lower) / slp.lower : std::numeric_limits<double>::infinity();
  // The repair (forward_pass) returns a profile that meets every row to rounding; checked, not assumed, before a
  // message calls it feasible (in the pass that labels the binding rows, and in the grid points' own terms by
  // the exact-feasibility step, which scales it down where rounding breaks a row).
  double violation = 0.0;
  out.binding = binding_labels(chain, sets.sets, out.theta, &violation);
  violation = std::max(violation, grid_excess);
  const std::string bound =
      violation <= 1e-9 ? "the timing is feasible, T exceeds the optimum by at most " + fmt(out.gap) +
                              " (relative, certified)"
                        : "the timing returned is NOT feasible: it breaks a constraint by " + fmt(violation) +
                              " (relative); T exceeds the optimum by at most " + fmt(out.gap);
  excess = violation;
  slp_status(slp.status, options, bound, out);
  if (violation > 1e-9) {
    // Whatever ended the SLP, a timing that breaks a row is not a result to execute (ok() is false).
    if (out.status == Status::Optimal)
      out.message = "SLP converged, but its repaired timing breaks a constraint by " + fmt(violation) + " (relative)";
    out.status = Status::NumericalError;
  }
  return out;
}

// SLP on windows around the intervals where θ' breaks a coupling row (see solve/slp.hpp); without θ'
// (Method::Slp, or the relaxed analysis did not end feasible) one window, the whole chain, under θ_hi. Every
// feasible θ_k is also below the backward-controllable bound K_k (tighter than x_hi, which is the solve's cap
// where nothing bounds ṡ² alone: a column bound of 1e100 would not help GLPK). Repaired by the lines (when
// they stand in for the polygons) the timing is made to meet every row to rounding (kLineViolation), as
// line_stage's; where the exact-feasibility step cannot, the polygons' analysis is built and repairs the same
// iterates again (their slices interpolate between exact vertices).
Certified by_slp(const SetsStage& sets, const ReachStage& reach, const SolverOptions& options, const Budget& budget) {
  const auto t0 = std::chrono::steady_clock::now();
  const Chain& chain = reach.chain;
  const double th0 = reach.th0;
  const LineAnalysis* lines = reach.lines.get();
  const Eigen::VectorXd upper = reach.have_full ? reach.relaxed->theta : chain.x_hi.cwiseMin(reach.reach.k_hi);
  auto repair = [&](const Eigen::VectorXd& caps) {
    return lines ? line_forward_pass(chain, *lines, th0, caps) : forward_pass(reach.reach, th0, &caps);
  };
  SlpOutcome slp = windowed_slp(chain, {lines ? lines->theta : reach.reach.theta, repair, upper, reach.have_full,
                                        reach.T_relaxed},
                                slp_limits(options, budget.deadline));
  double seconds = seconds_since(t0);
  double excess = 0.0;
  Certified out = slp_certified(sets, chain, slp, options, lines ? kLineViolation : 1e-9, excess);
  // The windows' iterates and their bound stand; only the repair is done again, on the polygons.
  Reachability relaxed, polygons;
  const auto t1 = std::chrono::steady_clock::now();
  if (lines && excess > kLineViolation && reachability_pair(chain, th0, reach.thN, relaxed, polygons)) {
    slp.theta = forward_pass(polygons, th0, &slp.caps);
    slp.T = duration(chain.ds, slp.theta);
    seconds += seconds_since(t1);
    out = slp_certified(sets, chain, slp, options, 1e-9, excess);
  }
  out.seconds = seconds;
  return out;
}

// The greatest element and the bracketed profile are read off the reachability polygons: checked in the grid
// points' own terms (eq. 26), not assumed, before they are called optimal.
Certified proven(const PathSamples& samples, const SetsStage& sets, const ReachStage& reach,
                 const SolverOptions& options, const Budget& budget) {
  Certified out;
  out.gap = reach.gap;
  out.greatest_element = reach.gap == 0.0;
  out.theta = reach.theta;
  out.binding = binding_labels(reach.chain, sets.sets, out.theta);
  Eigen::Index at = -1;
  double T_increase = 0.0;
  // line_stage's profiles come made exact to kLineViolation already (ReachStage::exact).
  const double violation =
      reach.exact ? 0.0 : exact_feasibility_step(reach.chain, sets.sets, out.theta, &at, &T_increase);
  // Its cost in T is part of the gap (the greatest element is then within T_increase of the optimum).
  if (T_increase > 0.0) {
    out.gap += T_increase;
    out.greatest_element = false;
    if (out.gap > options.tolerance) {
      out.status = Status::IterationLimit;
      out.message = "the exact-feasibility step cost " + fmt(T_increase) + " of T, beyond the tolerance";
    }
  }
  if (violation > 1e-9) {
    out.status = Status::NumericalError;
    out.message = "the reachability analysis's profile breaks a constraint by " + fmt(violation) +
                  " (relative) at grid index " + std::to_string(at) + " (s = " + fmt(samples.s[at]) +
                  "): rounding on this grid; a coarser or more uniform grid avoids it";
  }
  // The budget is checked inside the SLP; a problem proven without it can still have spent it on the feasible
  // sets and the reachability analysis: then the time limit is what the status says.
  if (out.status == Status::Optimal && std::chrono::steady_clock::now() >= budget.deadline) {
    out.status = Status::TimeLimit;
    out.message = "time_limit = " + fmt(budget.time_limit) + " s reached before the SLP (the feasible sets and the "
                  "reachability analysis took " + fmt(seconds_since(budget.started)) +
                  " s); the timing is feasible, T exceeds the optimum by at most " + fmt(out.gap) +
                  " (relative, certified)";
  }
  return out;
}

}  // namespace

Certified certify_stage(const PathSamples& samples, const SetsStage& sets, const ReachStage& reach,
                        const SolverOptions& options, const Budget& budget) {
  return reach.proven ? proven(samples, sets, reach, options, budget) : by_slp(sets, reach, options, budget);
}

void assemble(const Eigen::VectorXd& s, const Scale& scale, Eigen::VectorXd theta, Result& res) {
  const Eigen::Index n = s.size() - 1;
  theta *= scale.x_unit;  // back to ṡ² (a power of two: exact)
  res.sdot = theta.cwiseMax(0.0).cwiseSqrt();
  res.times.resize(n + 1);
  res.sddot.resize(n);
  res.times[0] = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double ds = s[k + 1] - s[k];
    res.times[k + 1] = res.times[k] + 2.0 * ds / (res.sdot[k] + res.sdot[k + 1]);
    res.sddot[k] = (theta[k + 1] - theta[k]) / (2.0 * ds);
  }
  res.duration = res.times[n];
}

}  // namespace pathpace::detail
