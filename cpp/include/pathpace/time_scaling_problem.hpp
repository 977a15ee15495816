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
#include "pathpace/constraints/frame_limits.hpp"
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

/// Minimise T = Σ 2Δs_k / (ṡ_k + ṡ_{k+1}) (eq. 25, 27) over the speeds at the grid points subject to
/// every constraint's half-planes at every grid point, on both sides of each grid point (eq. 26:
/// s̈ of interval k at s_k and of interval k-1 at s_k).
///
/// Adding constraints mutates the problem; solve() and feasible_set() are const and keep their scratch
/// space local, so one problem may be solved from several threads once it is built.
///
/// Threads: a problem is either read (any number of solve, feasible_set, relaxation, restarted at once)
/// or modified (one add_* / set_* at a time), never both. A call that would overlap the other kind in
/// another thread throws Error at once instead of waiting (a program that does this has a race it
/// should know about): "add_contacts: this TimeScalingProblem is being solved in another thread; ...".
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

  /// N uniform intervals over [s_begin, s_end] of the path (N >= 1).
  TimeScalingProblem(std::shared_ptr<const Path> path, int intervals);
  /// A strictly increasing grid; its ends must be the path's s_begin and s_end (to 1e-12 relative).
  TimeScalingProblem(std::shared_ptr<const Path> path, Eigen::VectorXd grid);

  /// See VelocityLimits.
  void add_velocity_limits(const Eigen::VectorXd& vmin, const Eigen::VectorXd& vmax);
  /// See AccelerationLimits.
  void add_acceleration_limits(const Eigen::VectorXd& amin, const Eigen::VectorXd& amax);
  /// ‖v‖ <= v_max (m/s) for `point` (link coordinates) on `link` of `robot`. See FrameLimits.
  void add_frame_translational_speed_limit(std::shared_ptr<const RobotModel> robot, const std::string& link, double v_max,
                                           const Eigen::Vector3d& point = Eigen::Vector3d::Zero());
  /// lo <= v <= hi per axis (3 entries each) for the point's linear velocity (m/s) or, if `angular`, the
  /// link's angular velocity (rad/s), along the world's or the link's axes. See FrameLimits.
  void add_frame_velocity_limits(std::shared_ptr<const RobotModel> robot, const std::string& link, const Eigen::VectorXd& lo,
                                 const Eigen::VectorXd& hi, bool angular = false, FrameAxes axes = FrameAxes::World,
                                 const Eigen::Vector3d& point = Eigen::Vector3d::Zero());
  /// lo <= a <= hi per axis for the point's classical acceleration (m/s²) or, if `angular`, the link's
  /// angular acceleration (rad/s²). See FrameLimits.
  void add_frame_acceleration_limits(std::shared_ptr<const RobotModel> robot, const std::string& link,
                                     const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, bool angular = false,
                                     FrameAxes axes = FrameAxes::World, const Eigen::Vector3d& point = Eigen::Vector3d::Zero());
  /// lo <= A·x + B·u + C <= hi at each grid point; arrays of shape (N+1, r). See LinearConstraint.
  void add_linear_constraint(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                             const Eigen::MatrixXd& lo, const Eigen::MatrixXd& hi,
                             const std::string& label = "linear");
  /// Any constraint; its rows are evaluated now, so errors surface here.
  void add_constraint(std::shared_ptr<const Constraint> constraint);

  /// A path whose contacts change: phase i holds its contacts (a ContactConstraint, eq. 17-18) on the grid
  /// points of [s_begin, s_end], both ends included, so at a switch both adjacent stances hold. Phases
  /// must be contiguous (phases[i].s_begin = phases[i-1].s_end), cover [s_begin, s_end] of the path and
  /// have s_begin < s_end; errors name the phase index and value. A switch that is not a grid point is
  /// inserted into the grid (one more interval; the constraints already added are evaluated again) unless
  /// it lies within 1e-9 of the path's length of a grid point, which then becomes the switch. A constraint
  /// whose rows are given per grid point (add_linear_constraint) cannot be re-evaluated: then a switch off
  /// the grid is an InvalidInput naming the switch and the nearest grid point.
  ///
  /// No impact: a contact of phase i (i >= 1) that phase i-1 does not have (same link, other_link and
  /// point to 1e-9 m) is made at the switch; if its point still moves along its normal as it arrives,
  /// |n·c'| > impact_tolerance · (the point's largest speed |c'| over the grid), with c' = J p' taken just
  /// before the switch (at s - 1e-9 of the path's length: the approach, which a path with a kink there
  /// can have), then ṡ = 0 at the switch (a row ṡ² <= 0 labelled "phases[i]: no impact: ..."). Breaking a
  /// contact needs nothing. The grid point at a switch takes p', p'' from the path's own evaluate there.
  ///
  /// Each phase is one ContactConstraint with active_begin/active_end set (label "phases[i]", which prefixes
  /// its row labels, so Result::binding and messages name the phase); TorqueLimits of the same robot are
  /// merged into every phase. tau_min / tau_max as in ContactConstraint.
  ///
  /// Each phase must keep its contacts in place on its own stretch: check_contact_drift with
  /// drift_tolerance (m) and `drift`, as add_contacts; returns the drifts it let through likewise.
  std::vector<ContactDrift> add_contact_phases(std::shared_ptr<const RobotModel> robot, const std::vector<ContactPhase>& phases,
                          const ContactOptions& options = ContactOptions(), const Eigen::VectorXd& tau_min = Eigen::VectorXd(),
                          const Eigen::VectorXd& tau_max = Eigen::VectorXd(), double impact_tolerance = 1e-6,
                          double drift_tolerance = 1e-6, DriftPolicy drift = DriftPolicy::Auto);
  /// add_constraint for contacts, after checking that the path keeps them in place (check_contact_drift:
  /// an InvalidInput under DriftPolicy::Error, or Auto beyond 10 x drift_tolerance); a drift that is
  /// timed anyway is kept in contact_drift() and reported by every Result (Result::contact_drift).
  /// Returns the drifts this call let through (empty, or the one of these contacts): what a caller warns
  /// about (the Python module as a UserWarning each).
  std::vector<ContactDrift> add_contacts(std::shared_ptr<const ContactConstraint> contacts, double drift_tolerance = 1e-6,
                    DriftPolicy drift = DriftPolicy::Auto);
  /// The contacts that add_contacts / add_contact_phases let through although they move (DriftPolicy::Warn
  /// or Auto within 10x the tolerance); set_contact_drift restores them (pickling).
  const std::vector<ContactDrift>& contact_drift() const { return contact_drift_; }
  void set_contact_drift(std::vector<ContactDrift> drift) {
    const Use use(*this, Use::Write, "set_contact_drift");
    contact_drift_ = std::move(drift);
  }

  /// Names of the path's coordinates, used in the row labels and messages of the velocity and
  /// acceleration limits (those added before as well as after). Set automatically from the robot of the
  /// first torque or contact constraint whose robot has one joint per path coordinate.
  void set_joint_names(std::vector<std::string> names);
  const std::vector<std::string>& joint_names() const { return joint_names_; }

  /// ṡ at s_begin and s_end (default 0, rest to rest). Must be >= 0 and finite.
  void set_boundary_speeds(double sdot_begin, double sdot_end);
  /// s̈ = 0 at s_begin and/or s_end on request: then q̈ = p''ṡ² there (eq. 11), no jump of q̈ from or to a
  /// cruise. With s̈ constant on each interval (eq. 24) this holds on the whole first (last) interval, so it
  /// needs a nonzero boundary speed at that end: solve() raises InvalidInput for a start or stop at rest.
  void set_zero_boundary_accelerations(bool at_begin, bool at_end);
  bool zero_sddot_begin() const { return zero_sddot_begin_; }
  bool zero_sddot_end() const { return zero_sddot_end_; }
  /// The boundary speeds from joint velocities q̇ at s_begin and s_end (rad/s or m/s): q̇ = p'(s) ṡ
  /// (eq. 10), so q̇ must be a non-negative multiple of the path tangent p'; ṡ = p'·q̇ / |p'|². Throws
  /// InvalidInput naming the joint where q̇ is not parallel to p' (relative tolerance `tolerance`).
  void set_boundary_velocities(const Eigen::VectorXd& qd_begin, const Eigen::VectorXd& qd_end,
                               double tolerance = 1e-6);
  double sdot_begin() const { return sdot_begin_; }
  double sdot_end() const { return sdot_end_; }
  /// Every setting at once (pickling); set_settings applies each through its own setter (and checks).
  ProblemSettings settings() const;
  void set_settings(const ProblemSettings& settings);

  const std::shared_ptr<const Path>& path() const { return path_; }
  const Eigen::VectorXd& grid() const { return samples_.s; }
  Eigen::Index intervals() const { return samples_.s.size() - 1; }
  const PathSamples& samples() const { return samples_; }
  const std::vector<std::shared_ptr<const Constraint>>& constraints() const { return constraints_; }

  /// The pruned feasible polygon at grid index k (0 <= k <= N).
  FeasibleSet feasible_set(Eigen::Index k) const;

  Result solve(const SolverOptions& options = SolverOptions()) const;

  /// Why an infeasible problem is infeasible, as the smallest uniform relaxation that fixes it: for
  /// each constraint family (Constraint::family(): "velocity", "acceleration", "torque", ...) the
  /// smallest scale >= 1 of that family's limit intervals (Constraint::relaxed, the others unchanged)
  /// that makes the problem feasible, found by bisection on a geometric scale to `rel_tolerance`
  /// (the returned scale is feasible, scale / (1 + rel_tolerance) is not); +inf if even `max_scale`
  /// is not enough (e.g. velocity limits cannot fix what acceleration limits forbid). With two or more
  /// families, "all" scales every family together. A feasible problem gives 1 for each family.
  /// Feasibility is decided by the reachability analysis (O(N) per trial, no SLP).
  /// With guarantee = Continuous, feasibility counts the rows that hold velocity and acceleration limits
  /// between grid points (not the audit's cuts, which depend on the solution: a lower bound then).
  std::map<std::string, double> relaxation(double max_scale = 1e3, double rel_tolerance = 1e-3,
                                           Guarantee guarantee = Guarantee::Grid) const;

  /// The problem that continues a running trajectory from s0 at speed sdot0 (>= 0): the path from s0
  /// to s_end, the grid points beyond s0 (s0 itself becomes the first one; a grid point closer to s0
  /// than 1e-9 of the interval is dropped), the same constraints and every setting (ProblemSettings),
  /// with boundary speeds (sdot0, sdot_end). Its solution starts at q = p(s0), q̇ = p'(s0)·sdot0: the
  /// continuation has no jump in position or velocity. Times in its result count from the restart (t = 0
  /// at s0). s̈ = 0 at the start (set_zero_boundary_accelerations) is kept for a restart at s_begin only:
  /// inside the path the restart continues a running trajectory, whose s̈ there is free.
  /// A LinearConstraint (rows given per grid point) keeps the rows of the grid points the restart keeps;
  /// s0 must then be a grid point (InvalidInput naming s0 and the nearest grid point otherwise).
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
  Result solve_rows(const std::vector<ConstraintRows>& rows, const detail::IntervalExtra* extra,
                    const SolverOptions& options) const;
  std::shared_ptr<const Path> path_;
  PathSamples samples_;
  std::vector<std::shared_ptr<const Constraint>> constraints_;
  std::vector<ConstraintRows> rows_;
  double sdot_begin_ = 0.0, sdot_end_ = 0.0;
  bool zero_sddot_begin_ = false, zero_sddot_end_ = false;
  std::vector<std::string> joint_names_;
  std::vector<ContactDrift> contact_drift_;
  mutable detail::UseCount use_;
};

}  // namespace pathpace
