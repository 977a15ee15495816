#pragma once
/// @file time_scaling_problem.hpp
/// The time-scaling problem: a path, a grid, constraints and boundary speeds (sec. V).

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/constraints/second_order_constraint.hpp"
#include "pathpace/constraints/frame_limits.hpp"
#include "pathpace/constraints/jerk_limits.hpp"
#include "pathpace/contact_drift.hpp"
#include "pathpace/contact_phase.hpp"
#include "pathpace/feasible_set.hpp"
#include "pathpace/path.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/result.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/solver_options.hpp"

namespace pathpace {

namespace detail {
struct IntervalExtra;
struct Scale;

/// How many callers read (solve, feasible_set, ...) and modify (add_*, set_*) one problem: the state of
/// TimeScalingProblem::Use. A copy of a problem starts unused.
struct UseCount {
  UseCount() = default;
  UseCount(const UseCount&) noexcept {}
  UseCount& operator=(const UseCount&) noexcept { return *this; }
  std::mutex mutex;
  int readers = 0, writers = 0;
  std::thread::id writer;  ///< the thread that modifies it (which may read it, and modify it again, meanwhile)
};
}  // namespace detail

/// The settings of a problem beside its path, grid and constraints: what pickling stores and what
/// restarted() carries over, both read through for_each, so that a setting added here reaches both.
struct ProblemSettings {
  double sdot_begin = 0.0, sdot_end = 0.0;             ///< set_boundary_speeds
  bool zero_sddot_begin = false, zero_sddot_end = false;  ///< set_zero_boundary_accelerations
  std::vector<std::string> joint_names;                ///< set_joint_names (empty: none set)

  /// f(name, field) for every field, in a fixed order.
  template <typename Self, typename F>
  static void for_each(Self& s, F&& f) {
    f("sdot_begin", s.sdot_begin);
    f("sdot_end", s.sdot_end);
    f("zero_sddot_begin", s.zero_sddot_begin);
    f("zero_sddot_end", s.zero_sddot_end);
    f("joint_names", s.joint_names);
  }
};

// docstrings.txt @@ TimeScalingProblem
/// @brief Time-optimal timing of a path under constraints (sec. V).
///
/// Minimises T = Σ 2Δs_k / (ṡ_k + ṡ_{k+1}) (eq. 25, 27) over the speeds at the grid points, with every
/// constraint enforced at every grid point with the s̈ of the interval on each side (eq. 26). Build once,
/// then `solve`: a built problem may be solved from several threads.
///
/// Threads: a problem is either read (any number of solve, feasible_set, relaxation, restarted at once)
/// or modified (one add_* / set_* at a time), never both. A call that would overlap the other kind in
/// another thread raises Error at once instead of waiting (a program that does this has a race it
/// should know about): "add_contacts: this TimeScalingProblem is being solved in another thread; ...".
///
/// Adding constraints mutates the problem; solve() and feasible_set() are const and keep their scratch
/// space local.
class TimeScalingProblem {
 public:
  /// Holds a problem for reading or modifying while it lives (see "Threads" above); every const method
  /// that reads the rows takes Read and every add_* / set_* takes Write, so callers need it only to keep
  /// a problem still across several calls (e.g. while copying constraints()). `what` names the caller
  /// in the Error.
  class Use {
   public:
    enum Kind { Read, Write };
    Use(const TimeScalingProblem& problem, Kind kind, const char* what);
    ~Use();
    Use(const Use&) = delete;
    Use& operator=(const Use&) = delete;

   private:
    detail::UseCount& count_;
    Kind kind_;
  };

  // docstrings.txt @@ TimeScalingProblem.__init__
  /// @param path The path, shared (immutable: the problem keeps the pointer).
  /// @param intervals N >= 1 uniform intervals over [s_begin, s_end] of the path.
  TimeScalingProblem(std::shared_ptr<const Path> path, int intervals);
  // docstrings.txt @@ TimeScalingProblem.__init__
  /// @param path The path, shared (immutable: the problem keeps the pointer).
  /// @param grid A strictly increasing grid; its ends must be the path's s_begin and s_end (to 1e-12 relative).
  TimeScalingProblem(std::shared_ptr<const Path> path, Eigen::VectorXd grid);

  // docstrings.txt @@ TimeScalingProblem.add_velocity_limits
  /// @brief Joint velocity limits (eq. 13); see VelocityLimits.
  ///
  /// @param vmin,vmax (n,): rad/s (m/s); vmin <= 0 <= vmax, ±inf for none.
  void add_velocity_limits(const Eigen::VectorXd& vmin, const Eigen::VectorXd& vmax);
  // docstrings.txt @@ TimeScalingProblem.add_acceleration_limits
  /// @brief Joint acceleration limits (eq. 14); see AccelerationLimits.
  ///
  /// @param amin,amax (n,): rad/s² (m/s²); amin <= amax.
  void add_acceleration_limits(const Eigen::VectorXd& amin, const Eigen::VectorXd& amax);
  // docstrings.txt @@ TimeScalingProblem.add_jerk_limits
  /// @brief Joint jerk limits jmin <= q⃛ <= jmax (see JerkLimits): the timing's s̈ becomes continuous.
  ///
  /// s̈ is then linear in s between grid points (ṡ² quadratic), so q̈ is continuous; an end at rest starts or
  /// stops with constant s⃛ on its interval (s̈ = 0 there). Every other constraint's rows hold at the grid points
  /// with the s̈ there; the jerk limits hold at the grid points on both sides (the s⃛ of each adjacent interval).
  /// solve() first solves the problem without jerk limits, then linearises the jerk rows (an inner
  /// approximation, so every round's timing is feasible) and improves T round by round (docs/method.md).
  /// OPTIMAL means a first-order (KKT) point of this non-convex problem: within `tolerance` of the optimum of the
  /// convex problem linearised there (stats["jerk_linearised_gap"]); not a global optimum. A second call
  /// replaces the limits. Needs a path of polynomial pieces (p''') and N >= 4; guarantee = 'continuous' and
  /// restarted() are not implemented with jerk limits yet (InvalidInput).
  ///
  /// @param jmin,jmax (n,): rad/s³ (m/s³); jmin < 0 < jmax, ∓inf for none.
  void add_jerk_limits(const Eigen::VectorXd& jmin, const Eigen::VectorXd& jmax);
  /// The jerk limits (add_jerk_limits), or null.
  const std::shared_ptr<const JerkLimits>& jerk_limits() const { return jerk_; }

  // docstrings.txt @@ TimeScalingProblem.add_frame_translational_speed_limit
  /// @brief ‖v‖ <= v_max for a point on a link (Drake's AddFrameTranslationalSpeedLimit); see FrameLimits.
  ///
  /// @param v_max m/s, > 0.
  /// @param point (3,): In the link frame, m.
  void add_frame_translational_speed_limit(std::shared_ptr<const RobotModel> robot, const std::string& link, double v_max,
                                           const Eigen::Vector3d& point = Eigen::Vector3d::Zero());
  // docstrings.txt @@ TimeScalingProblem.add_frame_velocity_limits
  /// @brief lo <= v <= hi per axis for a point's linear velocity or a link's angular velocity (Drake's
  /// AddFrameVelocityLimit, which takes [ω, v] together); see FrameLimits.
  ///
  /// @param lo,hi (3,): m/s (rad/s if angular), lo <= 0 <= hi; ±inf: no limit.
  /// @param angular Bound the angular velocity of the link instead of the point's linear velocity.
  /// @param point (3,): In the link frame, m.
  void add_frame_velocity_limits(std::shared_ptr<const RobotModel> robot, const std::string& link, const Eigen::VectorXd& lo,
                                 const Eigen::VectorXd& hi, bool angular = false, FrameAxes axes = FrameAxes::World,
                                 const Eigen::Vector3d& point = Eigen::Vector3d::Zero());
  // docstrings.txt @@ TimeScalingProblem.add_frame_acceleration_limits
  /// @brief lo <= a <= hi per axis for a point's classical acceleration or a link's angular acceleration (Drake's
  /// AddFrameAccelerationLimit); see FrameLimits. Per axis only (a norm bound is not a half-plane).
  ///
  /// @param lo,hi (3,): m/s² (rad/s² if angular), lo <= hi; ±inf: no limit.
  /// @param point (3,): In the link frame, m.
  void add_frame_acceleration_limits(std::shared_ptr<const RobotModel> robot, const std::string& link,
                                     const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, bool angular = false,
                                     FrameAxes axes = FrameAxes::World, const Eigen::Vector3d& point = Eigen::Vector3d::Zero());
  // docstrings.txt @@ TimeScalingProblem.add_linear_constraint
  /// @brief lo <= A·ṡ² + B·s̈ + C <= hi per grid point; arrays (N+1, r). See LinearConstraint.
  void add_linear_constraint(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                             const Eigen::MatrixXd& lo, const Eigen::MatrixXd& hi,
                             const std::string& label = "linear");
  // docstrings.txt @@ TimeScalingProblem.add_torque_limits
  /// @brief Torque limits τ_min <= τ <= τ_max along the path (eq. 12, 15), from the robot's model or from your own
  /// inverse dynamics.
  ///
  /// @param inverse_dynamics τ = f(q, qd, qdd) of your own model (MuJoCo, Drake, pinocchio, ...), vectorised: arrays
  ///   (m, n) in, (m, n) out, one call for all 3(N+1) evaluations of eq. 12. The rows are
  ///   SecondOrderConstraint.torque_limits' (family "torque", labels "torque <joint> upper/lower").
  /// @param tau_min,tau_max (nq,): N·m; default ∓ the URDF effort (required with inverse_dynamics).
  /// @param scale Multiplies the limits (sec. V.D).
  /// @param margin N·m taken off each side.
  void add_torque_limits(SecondOrderFunctions::InverseDynamics inverse_dynamics, const Eigen::VectorXd& tau_min,
                         const Eigen::VectorXd& tau_max, double scale = 1.0, double margin = 0.0);
  // docstrings.txt @@ TimeScalingProblem.add_second_order_constraint
  /// @brief F(q) w <= g(q) with w = inverse_dynamics(q, q̇, q̈) along the path: a SecondOrderConstraint (see it for the
  /// arguments and what the callables receive), added as add_constraint does.
  ///
  /// starts from `min_intervals` uniform intervals plus the breakpoints of a piecewise-polynomial path.
  /// Returns the grid points s_0..s_N (the N used is len - 1). InvalidInput past `max_intervals`.
  void add_second_order_constraint(SecondOrderFunctions::InverseDynamics inverse_dynamics, SecondOrderFunctions::OfQ F,
                                   SecondOrderFunctions::OfQ g, const SecondOrderOptions& options = SecondOrderOptions());
  // docstrings.txt @@ TimeScalingProblem.add_constraint
  /// @brief Adds any Constraint; its rows are evaluated now, so errors surface here.
  void add_constraint(std::shared_ptr<const Constraint> constraint);

  // docstrings.txt @@ TimeScalingProblem.add_contact_phases
  /// @brief Contacts that change along the path: one contact set per phase.
  ///
  /// Phase i holds its contacts (a ContactConstraint with torque limits, eq. 17-18) on the grid points of
  /// [s_begin, s_end], both ends included: at a switch both adjacent stances hold. Phases must be contiguous,
  /// cover the path and have s_begin < s_end (errors name the phase). A switch that is not a grid point is
  /// inserted into the grid (one more interval; constraints already added are re-evaluated; a switch within
  /// 1e-9 of the path's length of a grid point snaps to it); with an `add_linear_constraint` (rows per grid
  /// point) a switch off the grid is an InvalidInput naming the nearest grid point. TorqueLimits of the
  /// robot are merged into every phase. Row labels and `Result.binding` name the phase ("phases[1]: ...").
  ///
  /// No impact: a contact that phase i has and phase i-1 has not is made at the switch; if its point arrives
  /// moving along its normal (|n·c'| > impact_tolerance × the point's largest |c'| on the grid, c' = J p' just
  /// before the switch), ṡ = 0 there (row "phases[i]: no impact: ..."). Breaking contact needs nothing.
  ///
  /// Phases are contiguous when phases[i].s_begin = phases[i-1].s_end; errors name the phase index and value.
  /// A contact is new at a switch when phase i-1 has none with the same link, other_link and point (to
  /// 1e-9 m); its c' is taken at s - 1e-9 of the path's length (the approach, which a path with a kink there
  /// can have). The grid point at a switch takes p', p'' from the path's own evaluate there. Each phase is
  /// one ContactConstraint with active_begin/active_end set and label "phases[i]", which prefixes its row
  /// labels. Each phase must keep its contacts in place on its own stretch: check_contact_drift with
  /// drift_tolerance (m) and `drift`, as add_contacts.
  ///
  /// @param phases Each a ContactPhase: s_begin, s_end, its contacts and, optionally, its own options.
  /// @param options The margins of every phase without options of its own (ContactOptions).
  /// @param tau_min,tau_max As in ContactConstraint, for every phase.
  /// @param impact_tolerance Relative tolerance of the no-impact rule (default 1e-6).
  /// @param drift_tolerance,drift As in `add_contacts`, for each phase's contacts on that phase's stretch.
  /// @return The drifts it let through, as add_contacts.
  std::vector<ContactDrift> add_contact_phases(std::shared_ptr<const RobotModel> robot, const std::vector<ContactPhase>& phases,
                          const ContactOptions& options = ContactOptions(), const Eigen::VectorXd& tau_min = Eigen::VectorXd(),
                          const Eigen::VectorXd& tau_max = Eigen::VectorXd(), double impact_tolerance = 1e-6,
                          double drift_tolerance = 1e-6, DriftPolicy drift = DriftPolicy::Auto);
  // docstrings.txt @@ TimeScalingProblem.add_contacts
  /// @brief Torque limits with frictional contact forces (eq. 17-18), projected to (ṡ², s̈) per grid point
  /// (sec. IV.C; each polygon is the hull of LP optima with every edge certified by its own LP); see
  /// ContactConstraint. add_torque_limits on the same robot, before or after, merges into this one projection
  /// (both limits hold).
  ///
  /// add_constraint for contacts, after checking that the path keeps them in place (check_contact_drift); a
  /// drift that is timed anyway is kept in contact_drift() and reported by every Result (Result::contact_drift).
  ///
  /// @param contacts The ContactConstraint (robot, contacts, options, torque limits).
  /// @param drift_tolerance m: how far a contact point may move along the path (it should not: eq. 17-18 hold it in
  ///   place).
  /// @param drift DriftPolicy: Warn times it anyway; Error throws InvalidInput naming the contact, s and the
  ///   drift; Auto warns up to 10 x drift_tolerance and throws beyond.
  /// @return The drifts this call let through (empty, or the one of these contacts): what a caller warns
  ///   about (the Python module as a UserWarning each).
  std::vector<ContactDrift> add_contacts(std::shared_ptr<const ContactConstraint> contacts, double drift_tolerance = 1e-6,
                    DriftPolicy drift = DriftPolicy::Auto);
  /// The contacts that add_contacts / add_contact_phases let through although they move (DriftPolicy::Warn
  /// or Auto within 10x the tolerance); set_contact_drift restores them (pickling).
  const std::vector<ContactDrift>& contact_drift() const { return contact_drift_; }
  void set_contact_drift(std::vector<ContactDrift> drift) {
    const Use use(*this, Use::Write, "set_contact_drift");
    contact_drift_ = std::move(drift);
  }

  // docstrings.txt @@ TimeScalingProblem.set_joint_names
  /// @brief Names of the path's coordinates for the labels and messages of velocity and acceleration limits.
  ///
  /// Names the limits added before as well as after. Set automatically from the robot of the first
  /// add_torque_limits / add_contacts whose robot has one joint per coordinate.
  void set_joint_names(std::vector<std::string> names);
  // docstrings.txt @@ TimeScalingProblem.joint_names
  /// See `set_joint_names`.
  const std::vector<std::string>& joint_names() const { return joint_names_; }

  // docstrings.txt @@ TimeScalingProblem.set_boundary_speeds
  /// @brief ṡ at s_begin and s_end.
  ///
  /// @param sdot_begin,sdot_end 1/s, >= 0 and finite (default 0: rest to rest). For joint velocities use
  ///   `set_boundary_velocities`.
  void set_boundary_speeds(double sdot_begin, double sdot_end);
  // docstrings.txt @@ TimeScalingProblem.set_zero_boundary_accelerations
  /// @brief sddot = 0 at s_begin and/or s_end (q̈ = p'' ṡ² there: no jump of q̈ from or to a cruise).
  ///
  /// With sddot constant per interval (eq. 24) it holds on the whole first/last interval, so the boundary
  /// speed there must be > 0 (set_boundary_speeds); solve() raises InvalidInput otherwise.
  ///
  /// @param at_begin,at_end Whether at s_begin, at s_end.
  void set_zero_boundary_accelerations(bool at_begin, bool at_end);
  bool zero_sddot_begin() const { return zero_sddot_begin_; }
  bool zero_sddot_end() const { return zero_sddot_end_; }
  // docstrings.txt @@ TimeScalingProblem.set_boundary_velocities
  /// @brief Boundary conditions as joint velocities q̇ (rad/s or m/s) at s_begin and s_end.
  ///
  /// q̇ = p'(s) ṡ (eq. 10): each must be a non-negative multiple of the path tangent p'; the speeds
  /// ṡ = p'·q̇ / |p'|² are then set as by `set_boundary_speeds`.
  ///
  /// @param qd_begin,qd_end (n,): Joint velocities at the ends.
  /// @param tolerance Allowed |q̇ - p' ṡ|∞ relative to |q̇|.
  /// @throws InvalidInput Naming the joint index where q̇ is not along p'.
  void set_boundary_velocities(const Eigen::VectorXd& qd_begin, const Eigen::VectorXd& qd_end,
                               double tolerance = 1e-6);
  // docstrings.txt @@ TimeScalingProblem.sdot_begin
  /// ṡ at s_begin in 1/s (set_boundary_speeds).
  double sdot_begin() const { return sdot_begin_; }
  // docstrings.txt @@ TimeScalingProblem.sdot_end
  /// ṡ at s_end in 1/s (set_boundary_speeds).
  double sdot_end() const { return sdot_end_; }
  /// Every setting at once (pickling); set_settings applies each through its own setter (and checks).
  ProblemSettings settings() const;
  void set_settings(const ProblemSettings& settings);

  const std::shared_ptr<const Path>& path() const { return path_; }
  const Eigen::VectorXd& grid() const { return samples_.s; }
  Eigen::Index intervals() const { return samples_.s.size() - 1; }
  const PathSamples& samples() const { return samples_; }
  const std::vector<std::shared_ptr<const Constraint>>& constraints() const { return constraints_; }

  // docstrings.txt @@ TimeScalingProblem.feasible_set
  /// @brief The pruned feasible polygon at grid index k (0 <= k <= N): a FeasibleSet.
  FeasibleSet feasible_set(Eigen::Index k) const;

  // docstrings.txt @@ TimeScalingProblem.solve
  /// @brief Solves the problem.
  ///
  /// `max_iterations` bounds the SLP iterations per window, `time_limit` the whole solve: either ends
  /// with the best feasible timing found (ITERATION_LIMIT / TIME_LIMIT, stats["gap"] is its certified bound).
  /// UNBOUNDED means that nothing bounds the speed at a grid point where the path moves (the ends, whose
  /// speeds are given, never count). A stationary piece of path (p'(s) = 0 on a stretch of the grid) that no
  /// constraint bounds raises InvalidInput naming its s-range: it would be crossed in zero time; remove
  /// it from the path.
  ///
  /// @param options method, max_iterations, tolerance and the rest (SolverOptions), checked here, once.
  /// @return Never raises for an infeasible problem: see `status` and `message`.
  Result solve(const SolverOptions& options = SolverOptions()) const;

  // docstrings.txt @@ TimeScalingProblem.relaxation
  /// @brief Smallest uniform relaxation of each constraint family that makes the problem feasible.
  ///
  /// Returns a dict (C++: std::map) family -> scale >= 1 ('velocity', 'acceleration', 'torque', and 'all' = every
  /// family together when there are several): the family's limit intervals widened by that factor about zero, the
  /// others unchanged, give a feasible problem; within `tolerance` (relative) of the smallest such factor;
  /// inf if `max_scale` is not enough (e.g. velocity limits cannot fix what acceleration limits forbid).
  /// 1.0 for every family of a feasible problem.
  ///
  /// Each family is Constraint.family(); the scale is found by bisection on a geometric scale (the returned
  /// scale is feasible, scale / (1 + tolerance) is not), feasibility decided by the reachability analysis
  /// (O(N) per trial, no SLP). With guarantee = 'continuous', feasibility counts the rows that hold velocity
  /// and acceleration limits between grid points (not the audit's cuts, which depend on the solution: a
  /// lower bound then).
  ///
  /// @param max_scale The largest scale tried.
  /// @param rel_tolerance The relative tolerance of the bisection.
  /// @param guarantee As SolverOptions::guarantee.
  std::map<std::string, double> relaxation(double max_scale = 1e3, double rel_tolerance = 1e-3,
                                           Guarantee guarantee = Guarantee::Grid) const;

  // docstrings.txt @@ TimeScalingProblem.restarted
  /// @brief The problem that continues a running trajectory from path parameter s0 at speed sdot0 (>= 0).
  ///
  /// The path's tail [s0, s_end] on the grid points beyond s0, the same constraints and every setting
  /// pickling keeps (end speed, sddot = 0 at the end, joint names; sddot = 0 at the start only when
  /// s0 = s_begin: inside the path the restart continues a running trajectory, whose sddot there is free),
  /// with boundary speeds (sdot0, sdot_end). s0 itself becomes the first grid point; a grid point closer to
  /// s0 than 1e-9 of the interval is dropped. A LinearConstraint keeps its rows at the kept grid points (s0
  /// must then be a grid point: InvalidInput naming s0 and the nearest grid point otherwise). Its result
  /// starts at q = p(s0), qd = p'(s0)*sdot0 (no jump in position or velocity); its times count from the
  /// restart (t = 0 at s0).
  TimeScalingProblem restarted(double s0, double sdot0) const;

  /// "feasible with torque limits x 1.18 or acceleration limits x 1.4" for a relaxation() map.
  static std::string describe_relaxation(const std::map<std::string, double>& relaxation);

 private:
  /// Throws InvalidInput unless `rows` fit the grid (a user's own Constraint may return anything).
  static void check_rows(const Constraint& constraint, const ConstraintRows& rows, Eigen::Index points);
  /// Appends the rows of set_zero_boundary_accelerations (a labels-only ConstraintRows to `rows`, the
  /// interval rows θ_1 = θ_0 / θ_N = θ_{N-1} to `extra`, sized here).
  void add_boundary_rows(std::vector<ConstraintRows>& rows, detail::IntervalExtra& extra) const;
  /// True if the reachability analysis finds a timing for these rows (one ConstraintRows per constraint).
  bool feasible_with(const std::vector<std::shared_ptr<const Constraint>>& constraints,
                     std::vector<ConstraintRows> rows, Guarantee guarantee) const;
  /// solve() on these rows (one ConstraintRows per constraint, then any extra ones), plus rows of single
  /// intervals if `extra` (guarantee = continuous): the stages of solve/pipeline.hpp, in order.
  /// `scale`: the units to solve in (default: from `rows`; see solve/pipeline.hpp's grid_sets_stage).
  Result solve_rows(const std::vector<ConstraintRows>& rows, const detail::IntervalExtra* extra,
                    const SolverOptions& options, const detail::Scale* scale = nullptr) const;
  /// solve_rows, and while a constraint that refines its rows on demand (Constraint::refines) finds the
  /// timing beyond what it knows, its rows refined there and solved again: `rows` end refined, `memory` (one
  /// per constraint) carries each constraint's state to the next call, and the ids of `extra`'s rows follow
  /// the rows a refinement adds.
  Result solve_refined(std::vector<ConstraintRows>& rows, detail::IntervalExtra* extra, const SolverOptions& options,
                       std::vector<RefineMemory>& memory) const;
  /// True if some constraint refines its rows on demand (Constraint::refines).
  bool refines() const;
  std::shared_ptr<const Path> path_;
  PathSamples samples_;
  std::vector<std::shared_ptr<const Constraint>> constraints_;
  std::vector<ConstraintRows> rows_;
  double sdot_begin_ = 0.0, sdot_end_ = 0.0;
  bool zero_sddot_begin_ = false, zero_sddot_end_ = false;
  std::vector<std::string> joint_names_;
  std::vector<ContactDrift> contact_drift_;
  std::shared_ptr<const JerkLimits> jerk_;
  /// solve() with jerk limits: the second-order solve, then the linearisation rounds (solve/jerk_scp.hpp); with
  /// adapt_grid, first on the grid whose rest-end intervals are the jerk ramps (problem/solve_jerk.cpp).
  Result solve_jerk(const SolverOptions& options, bool adapt_grid = true) const;
  /// The grid with each rest end's first interval as long as its estimated jerk ramp (problem/solve_jerk.cpp).
  Eigen::VectorXd jerk_grid(const Result& second_order) const;
  mutable detail::UseCount use_;
};

}  // namespace pathpace
