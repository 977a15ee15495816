#pragma once
/// @file result.hpp
/// What a solve returns: a status, the timing at the grid points and where a failure happened.

#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/binding_labels.hpp"
#include "pathpace/contact_drift.hpp"
#include "pathpace/path.hpp"

namespace pathpace {

class Trajectory;
class RobotModel;
class ContactConstraint;

// docstrings.txt @@ Status
/// @brief How a solve ended: OPTIMAL, INFEASIBLE, ITERATION_LIMIT, NUMERICAL_ERROR, UNBOUNDED or TIME_LIMIT (see
/// Result.status).
enum class Status {
  Optimal,         ///< the optimum of the discretised problem (eq. 26-27)
  Infeasible,      ///< no timing satisfies the constraints; see Result::infeasibility
  IterationLimit,  ///< SLP stopped at max_iterations (or could not certify the tolerance); the timing is
                   ///< feasible, SolverStats::gap bounds its distance to the optimum
  NumericalError,  ///< the LP solver failed; the timing (if any) is the last feasible one
  Unbounded,       ///< nothing bounds the speed at some grid point where the path moves (T* not attained)
  TimeLimit,       ///< SolverOptions::time_limit reached; the timing is feasible, SolverStats::gap bounds
                   ///< its distance to the optimum
};

const char* to_string(Status status);

/// Where and why a path cannot be timed.
struct Infeasibility {
  Eigen::Index grid_index = -1;                        ///< first grid index where it fails
  double s = std::numeric_limits<double>::quiet_NaN();  ///< s at that index
  std::vector<std::string> constraints;                 ///< the constraint rows that bind there
};

struct SolverStats {
  int slp_iterations = 0;
  int lp_solves = 0;              ///< LPs solved: by the chain simplex (solve/chain_simplex.hpp) or GLPK
  bool greatest_element = false;  ///< the optimum is a max-closed set's greatest element (exact, no SLP)
  double gap = 0.0;               ///< certified bound on (T - T*) / T* (0 when exact)
  int windows = 0;                ///< SLP windows (disjoint stretches of the grid solved by LPs)
  int window_points = 0;          ///< grid points inside them (N + 1 for Method::Slp)
  /// Newton steps of the log-barrier window solver (Method::Auto: windows far from their bound or of 2000+
  /// points, or whose SLP did not certify them in two iterations; see docs/method.md)
  int newton_steps = 0;
  double average_halfplanes = 0;  ///< supporting half-planes per grid point after pruning
  double time_constraints = 0;    ///< seconds: path samples and constraint rows
  double time_feasible_sets = 0;  ///< seconds: polygons and pruning
  double time_reachability = 0;   ///< seconds: controllable sets and forward pass
  double time_slp = 0;            ///< seconds
  int audit_rounds = 0;           ///< guarantee = continuous: solve-audit rounds
  int audit_cuts = 0;             ///< guarantee = continuous: interval rows added by the audits
  /// guarantee = continuous: the largest relative violation the last audit found (<= audit_tolerance
  /// when it passed; negative = the smallest relative slack, i.e. the margin reached)
  double audit_worst = 0;
  /// Contact polygons (sec. IV.C): computed when the contacts were added (add_constraint), reported here.
  double time_projection = 0;     ///< seconds, included in time_constraints
  int projection_lp_solves = 0;   ///< LPs of the projection
  int inexact_points = 0;         ///< grid points whose polygon is only an inner approximation (see FeasibleSet::exact)
  /// projection_lp_solves by cause (they sum to it): the initial triangle, edge LPs that found a vertex
  /// (or failed), edge LPs that certified an edge, stand-in bound growth, cold retries of a grid point.
  int projection_lps_initial = 0;
  int projection_lps_vertex = 0;
  int projection_lps_certificate = 0;
  int projection_lps_cap_growth = 0;
  int projection_lps_cold_retry = 0;
  /// guarantee = continuous: LPs the audits spent on contact constraints (the polygon's slice at the
  /// timing's own s̈, at most two per sample point, cuts included) and polygons they projected (one per
  /// cut point whose slice is empty: a cut elsewhere is the polygon's edge from the slice's LP).
  int audit_lps = 0;
  int audit_projections = 0;
  int audit_reused = 0;  ///< contact samples settled by the slice edges of an earlier round (no LP)
  /// Jerk limits (add_jerk_limits): linearisation rounds, the gap bound to the convex problem linearised at the
  /// final timing ((T - T_lin*) / T, see Status::Optimal there), and T of the same problem without jerk limits
  /// (the second-order timing the rounds start from; a lower bound on the continuous-time optimum, not on this
  /// grid's), 0 without jerk limits.
  int jerk_iterations = 0;
  double jerk_linearised_gap = 0.0;
  double second_order_duration = 0.0;
  /// Contact projections, beside projection_lp_solves: edges certified by an endpoint's optimal basis (no
  /// LP), LPs the dense simplex solved and certified, LPs it gave back to GLPK, and the simplex iterations
  /// of every projection LP.
  int projection_ranged_certificates = 0;
  int projection_lps_dense = 0;
  int projection_lps_dense_fallback = 0;
  int projection_pivots = 0;
  /// projection_lps_dense_fallback by cause (LpCounts::fallback_*): the dense simplex's pivot cap, a step
  /// bounded only by too small pivots, an unbounded ray, a singular refactorisation, a failed certificate.
  int projection_fallback_cap = 0;
  int projection_fallback_small_pivot = 0;
  int projection_fallback_unbounded = 0;
  int projection_fallback_singular = 0;
  int projection_fallback_certificate = 0;
  /// Of audit_lps, the slice LPs GLPK answered: a call's first sample per constraint and what the dense
  /// simplex, warm-started from a nearby sample's optimal basis, gave up on (lp/slice_lp.hpp).
  int audit_lps_glpk = 0;
  /// Solves of the rows (ContactOptions::project_on_demand): each after the polygons were refined where the
  /// timing before needed them (1: none was refined after the first; 0: nothing is projected on demand).
  int projection_rounds = 0;
};

// docstrings.txt @@ Result
/// @brief What a solve returns.
class Result {
 public:
  // docstrings.txt @@ Result.status
  /// OPTIMAL, INFEASIBLE (see infeasible_*), ITERATION_LIMIT (feasible, maybe not optimal),
  /// TIME_LIMIT (`time_limit` reached: feasible, stats['gap'] bounds its distance to the optimum),
  /// NUMERICAL_ERROR (the LP solver failed) or UNBOUNDED (nothing bounds the speed).
  Status status = Status::NumericalError;
  // docstrings.txt @@ Result.message
  /// Why a solve failed, with grid index, s and binding constraint; for a timing whose path moves its
  /// contacts (`contact_drift`), which contacts move.
  std::string message;
  // docstrings.txt @@ Result.duration
  /// T in s (nan without a timing).
  double duration = std::numeric_limits<double>::quiet_NaN();
  // docstrings.txt @@ Result.s
  /// (N+1,): The grid s_0..s_N.
  Eigen::VectorXd s;
  // docstrings.txt @@ Result.sdot
  /// (N+1,): ṡ_k at the grid points, 1/s.
  Eigen::VectorXd sdot;
  // docstrings.txt @@ Result.times
  /// (N+1,): t_k at the grid points, s; t_0 = 0.
  Eigen::VectorXd times;
  // docstrings.txt @@ Result.sddot
  /// (N,): s̈ on each interval, 1/s².
  Eigen::VectorXd sddot;
  // docstrings.txt @@ Result.sddot_points
  /// (N+1,): s̈ at the grid points of a jerk-limited timing (s̈ linear in s between them; `sddot` is then each
  /// interval's mean); None (C++: empty) otherwise.
  Eigen::VectorXd sddot_points;
  Infeasibility infeasibility;
  // docstrings.txt @@ Result.relaxation
  /// For an INFEASIBLE result (when solved with explain): family -> smallest scale of that family's limits
  /// that makes the problem feasible, e.g. {'torque': 1.18, 'velocity': inf} (see
  /// TimeScalingProblem.relaxation).
  std::map<std::string, double> relaxation;
  // docstrings.txt @@ Result.binding
  /// For a timed result: per interval (N entries) the label of the constraint that binds there (the row
  /// with the least relative slack at the solution, if below 1e-6), '' where none does: typically the
  /// interval of a bang-bang switch, whose end speeds are set by its neighbours' limits (to colour a
  /// phase-plane plot by the active limit).
  BindingLabels binding;
  // docstrings.txt @@ Result.stats
  /// slp_iterations, lp_solves, greatest_element (exact optimum without SLP), gap (certified bound on
  /// (T - T*) / T*), average_halfplanes, time_feasible_sets, time_reachability, time_slp (s).
  /// With jerk limits: jerk_iterations (linearisation rounds), jerk_linearised_gap (bound on (T - T_lin*) / T,
  /// T_lin* the optimum of the convex problem linearised at the final timing; also in gap: not a bound to
  /// the global optimum of this non-convex problem) and second_order_duration (T without jerk limits on the
  /// same grid: a lower bound of the continuous-time optimum as N grows, not of this grid's; 0 without jerk limits).
  SolverStats stats;
  std::shared_ptr<const Path> path;
  std::shared_ptr<const RobotModel> robot;  ///< from the problem's torque limits or contacts, if any
  std::shared_ptr<const ContactConstraint> contacts;  ///< the problem's contact constraint, if any (the last one)
  /// The problem's contact constraints that hold on a stretch of s only (the phases of add_contact_phases),
  /// in order of s; empty without phases. Trajectory::contact_forces then uses the phase at each time
  /// (and only it: a contact constraint of the whole path added besides the phases is not in its LP).
  std::vector<std::shared_ptr<const ContactConstraint>> contact_phases;
  // docstrings.txt @@ Result.contact_drift
  /// Contacts that the path moves although they should hold (drift='warn', or 'auto' within 10x
  /// drift_tolerance): constraint, contact, link, s, drift (m), tolerance (m), message. The contact forces
  /// of this timing assume they stay; message says so too.
  std::vector<ContactDrift> contact_drift;
  // docstrings.txt @@ Result.tau_min Result.tau_max
  /// (nq,): The torque limits the solve held (N·m or N, after scale and margin; the problem's TorqueLimits, else
  /// its (last) contact constraint's), None (C++: empty) without torque limits: what a plot "against the
  /// limits" shows.
  Eigen::VectorXd tau_min, tau_max;

  // docstrings.txt @@ Result.ok
  /// True for OPTIMAL, ITERATION_LIMIT and TIME_LIMIT (a feasible timing).
  bool ok() const {
    return status == Status::Optimal || status == Status::IterationLimit || status == Status::TimeLimit;
  }
  // docstrings.txt @@ Result.trajectory
  /// @brief The timed trajectory (Trajectory); raises pathpace.Error when there is no timing.
  Trajectory trajectory() const;
};

}  // namespace pathpace
