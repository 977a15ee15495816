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
  /// timing's own s̈, two per sample point) and polygons they projected (one per cut point).
  int audit_lps = 0;
  int audit_projections = 0;
  int audit_reused = 0;  ///< contact samples settled by the slices of an earlier round (no LP)
};

class Result {
 public:
  Status status = Status::NumericalError;
  std::string message;
  double duration = std::numeric_limits<double>::quiet_NaN();  ///< T
  Eigen::VectorXd s;      ///< grid s_0..s_N
  Eigen::VectorXd sdot;   ///< ṡ_k (N+1)
  Eigen::VectorXd times;  ///< t_k (N+1), t_0 = 0
  Eigen::VectorXd sddot;  ///< s̈ on interval k (N)
  Infeasibility infeasibility;
  /// For an Infeasible result (when SolverOptions::explain): the smallest scale of each constraint
  /// family's limits that makes the problem feasible, e.g. {"torque": 1.18, "velocity": inf}; see
  /// TimeScalingProblem::relaxation.
  std::map<std::string, double> relaxation;
  /// For a timed result: per interval k (N entries), the label of the constraint that binds on it
  /// (the row with the least relative slack at the solution, if below 1e-6), "" if none does: typically
  /// the interval of a bang-bang switch, whose end speeds are set by its neighbours' limits.
  BindingLabels binding;
  SolverStats stats;
  std::shared_ptr<const Path> path;
  std::shared_ptr<const RobotModel> robot;  ///< from the problem's torque limits or contacts, if any
  std::shared_ptr<const ContactConstraint> contacts;  ///< the problem's contact constraint, if any (the last one)
  /// The problem's contact constraints that hold on a stretch of s only (the phases of add_contact_phases),
  /// in order of s; empty without phases. Trajectory::contact_forces then uses the phase at each time
  /// (and only it: a contact constraint of the whole path added besides the phases is not in its LP).
  std::vector<std::shared_ptr<const ContactConstraint>> contact_phases;
  /// Contacts that the path moves although they should hold (TimeScalingProblem::add_contacts with
  /// DriftPolicy::Warn or Auto): the contact forces of this timing assume they stay; message says so too.
  std::vector<ContactDrift> contact_drift;
  /// The torque limits this solve held (N·m or N, after scale and margin): the problem's TorqueLimits, or
  /// those of its (last) contact constraint; empty without torque limits. What a plot "against the limits" shows.
  Eigen::VectorXd tau_min, tau_max;

  /// True for Optimal (and for IterationLimit and TimeLimit, whose timing is feasible).
  bool ok() const {
    return status == Status::Optimal || status == Status::IterationLimit || status == Status::TimeLimit;
  }
  /// The timed trajectory; throws pathpace::Error if there is no timing (e.g. infeasible).
  Trajectory trajectory() const;
};

}  // namespace pathpace
