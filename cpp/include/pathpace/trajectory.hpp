#pragma once
/// @file trajectory.hpp
/// q(t) = p(s(t)) with s(t) piecewise quadratic (eq. 24) through the grid.

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "pathpace/contact_forces.hpp"
#include "pathpace/contact_wrenches.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/path.hpp"

namespace pathpace {

class RobotModel;
class ContactConstraint;

// docstrings.txt @@ Trajectory
/// @brief The timed path: q(t) = p(s(t)) with s(t) piecewise quadratic through the grid (eq. 24).
class Trajectory {
 public:
  // docstrings.txt @@ Trajectory.__init__
  /// @param s The grid s_0..s_N.
  /// @param sdot ṡ_k >= 0 with ṡ_k + ṡ_{k+1} > 0 on every interval.
  Trajectory(std::shared_ptr<const Path> path, Eigen::VectorXd s, Eigen::VectorXd sdot);
  // docstrings.txt @@ Trajectory.__init__
  /// @param s The grid s_0..s_N.
  /// @param sdot ṡ_k >= 0 with ṡ_k + ṡ_{k+1} > 0 on every interval.
  /// @param sddot_points (N+1,): s̈ at the grid points of a jerk-limited timing (add_jerk_limits): s̈ is linear in s
  ///   between them, with θ = ṡ² consistent (θ_{k+1} = θ_k + Δs_k (s̈_k + s̈_{k+1}), to 1e-9 relative), and an end at
  ///   rest (ṡ = 0) has constant s⃛ on its interval (s̈ = 0 there, θ_1 = 1.5 Δs_0 s̈_1).
  Trajectory(std::shared_ptr<const Path> path, Eigen::VectorXd s, Eigen::VectorXd sdot, Eigen::VectorXd sddot_points);

  // docstrings.txt @@ Trajectory.duration
  /// T in s.
  double duration() const { return times_[times_.size() - 1]; }
  // docstrings.txt @@ Trajectory.times
  /// (N+1,): t_k of the grid points, s.
  const Eigen::VectorXd& times() const { return times_; }
  // docstrings.txt @@ Trajectory.grid
  /// (N+1,): s at the grid points, s_0..s_N.
  const Eigen::VectorXd& grid() const { return s_; }
  // docstrings.txt @@ Trajectory.sdot_grid
  /// (N+1,): ṡ at the grid points, 1/s.
  const Eigen::VectorXd& sdot_grid() const { return sdot_; }
  const std::shared_ptr<const Path>& path() const { return path_; }
  // docstrings.txt @@ Trajectory.sddot_points
  /// (N+1,): s̈ at the grid points of a jerk-limited timing (s̈ continuous); None (C++: empty) otherwise.
  const Eigen::VectorXd& sddot_points() const { return sddot_points_; }
  // docstrings.txt @@ Trajectory.qddd
  /// @brief The jerk q⃛(t) = p' s⃛ + 3 p'' ṡ s̈ + p''' ṡ³, rad/s³: (len(t), n). Needs a path of polynomial pieces
  ///   (p''').
  ///
  /// For a jerk-limited timing s⃛ is finite; for the piecewise-constant s̈ of other timings s⃛ = 0 inside each
  /// interval and a jump of q̈ at grid points is not shown.
  Eigen::MatrixXd qddd(const Eigen::Ref<const Eigen::VectorXd>& t) const;

  // docstrings.txt @@ Trajectory.s
  /// @brief (s, ṡ, s̈) at t: floats for a scalar t, arrays (m,) otherwise; ṡ in 1/s, s̈ in 1/s².
  ///
  /// t is clamped to [0, T]; s̈ is that of the interval to the right of t (to the left at t = T).
  ///
  /// Into s, sd, sdd, one entry per t.
  void evaluate_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::VectorXd& sd,
                  Eigen::VectorXd& sdd) const;

  // docstrings.txt @@ Trajectory.evaluate
  /// @brief (q, q̇ = p'ṡ, q̈ = p''ṡ² + p's̈) at t; shapes as `q`.
  ///
  /// Into q, qd, qdd, each (len(t), n).
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::MatrixXd& q, Eigen::MatrixXd& qd,
                Eigen::MatrixXd& qdd) const;
  // docstrings.txt @@ Trajectory.q
  /// @brief q(t), rad (m).
  ///
  /// @param t (m,): Times in s, clamped to [0, duration].
  /// @return (len(t), n): row i at t[i].
  Eigen::MatrixXd q(const Eigen::Ref<const Eigen::VectorXd>& t) const;
  // docstrings.txt @@ Trajectory.qd
  /// @brief q̇(t) = p'(s) ṡ (eq. 10), rad/s; shapes as `q`.
  Eigen::MatrixXd qd(const Eigen::Ref<const Eigen::VectorXd>& t) const;
  // docstrings.txt @@ Trajectory.qdd
  /// @brief q̈(t) = p''(s) ṡ² + p'(s) s̈ (eq. 11), rad/s²; s̈ of the interval to the right of t.
  Eigen::MatrixXd qdd(const Eigen::Ref<const Eigen::VectorXd>& t) const;

  // docstrings.txt @@ Trajectory.torques
  /// @brief τ(t) = RNEA(q, q̇, q̈) along the timing, so that usage can be plotted against the limits.
  ///
  /// @param t (m,): Times in s.
  /// @param robot The robot whose inverse dynamics to take.
  /// @return (len(t), nq), N·m.
  Eigen::MatrixXd torques(const Eigen::Ref<const Eigen::VectorXd>& t, const RobotModel& robot) const;

  // docstrings.txt @@ Trajectory.robot
  /// The robot whose torque limits or contacts shaped it; None (C++: null) if none did.
  const std::shared_ptr<const RobotModel>& robot() const { return robot_; }
  void set_robot(std::shared_ptr<const RobotModel> robot) { robot_ = std::move(robot); }

  /// The contact constraint that shaped this trajectory (null if none did).
  const std::shared_ptr<const ContactConstraint>& contacts() const { return contacts_; }
  void set_contacts(std::shared_ptr<const ContactConstraint> contacts) { contacts_ = std::move(contacts); }

  // docstrings.txt @@ Trajectory.contact_phases
  /// The ContactConstraint of each phase (add_contact_phases), in order of s; [] without phases.
  const std::vector<std::shared_ptr<const ContactConstraint>>& contact_phases() const { return contact_phases_; }
  void set_contact_phases(std::vector<std::shared_ptr<const ContactConstraint>> phases) {
    contact_phases_ = std::move(phases);
  }
  // docstrings.txt @@ Trajectory.contact_phase
  /// @brief Index into contact_phases of the phase at each t (the later one at a switch); -1 without phases.
  ///
  /// contact_phase_of_s(contact_phases, s(t)): the phase whose [active_begin, active_end] holds s(t); at a
  /// switch the later one, the contacts that hold after it.
  Eigen::VectorXi contact_phase(const Eigen::Ref<const Eigen::VectorXd>& t) const;

  // docstrings.txt @@ Trajectory.contact_forces
  /// @brief Contact forces at t that realise the motion (the solver looked only at grid points).
  ///
  /// With contact phases (`add_contact_phases`) each t uses the contacts of its phase, the later one at a
  /// switch time; `.phase` gives the phase of each t and `forces` has as many rows as the largest phase
  /// has contacts (NaN beyond a phase's own). Raises Error if no contact constraint shaped the trajectory.
  ///
  /// @param t Times, s.
  /// @param phase If given, receives contact_phase(t), the phase that served each t, from the same
  ///   evaluation (-1 everywhere without phases).
  /// @param distribution "centre" (default): at each t the analytic centre of the physical force set, continuous in t
  ///   wherever the motion is (the LP's vertex where that set has no interior; `centred` says which);
  ///   "vertex": the force-distribution LP's optimum (ForceDistribution).
  /// @return One ContactForces per t; with phases, its forces have that phase's number of rows.
  std::vector<ContactForces> contact_forces(const Eigen::Ref<const Eigen::VectorXd>& t,
                                            Eigen::VectorXi* phase = nullptr,
                                            ForceDistribution distribution = ForceDistribution::Centre) const;

  // docstrings.txt @@ Trajectory.contact_wrenches
  /// @brief Per-link wrenches and centres of pressure of `contact_forces(t)`: what a controller or a balance check
  /// reads (the centre of pressure inside each sole). Raises Error if no contact constraint shaped the
  /// trajectory.
  ///
  /// For every link on either side of a contact (first appearance over the contacts and phases): the total
  /// force (world frame, N), its moment about the link's origin (world axes, N·m), the sum of the normal
  /// forces into the link (N), and the centre of pressure Σ (n·f_i) p_i / Σ n·f_i (world frame, m; NaN
  /// where the link does not push, or its contacts have several normals). A link its phase does not hold
  /// has zero force there; an infeasible sample is NaN.
  ///
  /// @param t Times, s.
  /// @param distribution As for contact_forces (default "centre").
  /// @return ContactWrenches
  ContactWrenches contact_wrenches(const Eigen::Ref<const Eigen::VectorXd>& t,
                                   ForceDistribution distribution = ForceDistribution::Centre) const;

  // docstrings.txt @@ Trajectory.time_spline
  /// @brief A C² cubic spline in time through the grid (toppra's ParametrizeSpline).
  ///
  /// @return Parameter t in s (knots = `times`), through q(t_k) = p(s_k), clamped to q̇ = p'(s) ṡ at both ends;
  ///   its `q`, `dq`, `ddq` are q(t), q̇(t), q̈(t) with q̈ continuous. Between grid points it departs
  ///   from the exact timing by O(Δt⁴), so check it against the limits.
  /// @return For controllers that interpolate between points: unlike the exact timing, its q̈ is continuous, and its
  /// @return q̇, q̈ may exceed the limits by a little between grid points; check it with the problem's limits before
  /// @return sending it to a robot.
  CubicSplinePath time_spline() const;

  // docstrings.txt @@ Trajectory.sample_times
  /// @brief The times 0, dt, 2 dt, ... of `sample`, in s, with T appended when it is not a multiple of dt.
  Eigen::VectorXd sample_times(double dt) const;

  /// t (m,) in s and q, q̇, q̈ (m, n) of sample() and sample_at().
  struct Samples {
    Eigen::VectorXd t;
    Eigen::MatrixXd q, qd, qdd;
  };
  /// q, q̇, q̈ at the times t: of the exact timing (evaluate), or of time_spline() when `spline`.
  Samples sample_at(Eigen::VectorXd t, bool spline = false) const;
  // docstrings.txt @@ Trajectory.sample
  /// @brief Uniform resampling.
  ///
  /// sample_at(sample_times(dt), spline).
  ///
  /// @param dt Period in s; T is appended when it is not a multiple of dt.
  /// @param max_memory Bytes (> 0): a dt that would need more (t, q, q̇, q̈ and the path's own p, p', p'' while
  ///   evaluating) is an InvalidInput saying how much, before anything is allocated (a dt meant in ms but given in
  ///   s would otherwise fill the memory).
  /// @param spline As resample's: the samples of time_spline() instead of the exact timing.
  /// @return t (m,) in s and q, q̇, q̈ (m, n) (Samples).
  Samples sample(double dt, double max_memory = 1e9, bool spline = false) const;

 private:
  Eigen::Index interval(double t) const;
  // evaluate() that also hands back s(t), for contact_phase_of_s: contact_forces needs both of one t.
  void evaluate_with_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::MatrixXd& q,
                       Eigen::MatrixXd& qd, Eigen::MatrixXd& qdd) const;
  std::shared_ptr<const Path> path_;
  std::shared_ptr<const RobotModel> robot_;
  std::shared_ptr<const ContactConstraint> contacts_;
  std::vector<std::shared_ptr<const ContactConstraint>> contact_phases_;
  Eigen::VectorXd s_, sdot_, times_, sddot_;
  Eigen::VectorXd sddot_points_;  // jerk-limited timing: s̈ at the grid points (else empty)
  // (s, ṡ, s̈, s⃛) at one t on interval k of a jerk-limited timing.
  void jerk_motion(Eigen::Index k, double t, double& s, double& sd, double& sdd, double& sddd) const;
  // evaluate_s, and s⃛ into *sddd if given (qddd).
  void evaluate_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::VectorXd& sd,
                  Eigen::VectorXd& sdd, Eigen::VectorXd* sddd) const;
};

}  // namespace pathpace
