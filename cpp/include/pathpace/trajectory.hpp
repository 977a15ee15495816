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

class Trajectory {
 public:
  /// grid s_0..s_N, speeds ṡ_k >= 0 with ṡ_k + ṡ_{k+1} > 0 on every interval.
  Trajectory(std::shared_ptr<const Path> path, Eigen::VectorXd s, Eigen::VectorXd sdot);

  double duration() const { return times_[times_.size() - 1]; }
  const Eigen::VectorXd& times() const { return times_; }
  const Eigen::VectorXd& grid() const { return s_; }
  const Eigen::VectorXd& sdot_grid() const { return sdot_; }
  const std::shared_ptr<const Path>& path() const { return path_; }

  /// s(t), ṡ(t), s̈(t) at each t (clamped to [0, T]). s̈ is taken on the interval to the right of t
  /// (to the left at t = T).
  void evaluate_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::VectorXd& sd,
                  Eigen::VectorXd& sdd) const;

  /// q, q̇ = p'ṡ, q̈ = p''ṡ² + p's̈ at each t: shapes (len(t), n).
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::MatrixXd& q, Eigen::MatrixXd& qd,
                Eigen::MatrixXd& qdd) const;
  Eigen::MatrixXd q(const Eigen::Ref<const Eigen::VectorXd>& t) const;
  Eigen::MatrixXd qd(const Eigen::Ref<const Eigen::VectorXd>& t) const;
  Eigen::MatrixXd qdd(const Eigen::Ref<const Eigen::VectorXd>& t) const;

  /// Joint torques τ(t) = RNEA(q, q̇, q̈) of `robot` at each t: shape (len(t), nq), so that usage can be
  /// plotted against the limits.
  Eigen::MatrixXd torques(const Eigen::Ref<const Eigen::VectorXd>& t, const RobotModel& robot) const;

  /// The robot whose torque limits shaped this trajectory (null if none did).
  const std::shared_ptr<const RobotModel>& robot() const { return robot_; }
  void set_robot(std::shared_ptr<const RobotModel> robot) { robot_ = std::move(robot); }

  /// The contact constraint that shaped this trajectory (null if none did).
  const std::shared_ptr<const ContactConstraint>& contacts() const { return contacts_; }
  void set_contacts(std::shared_ptr<const ContactConstraint> contacts) { contacts_ = std::move(contacts); }

  /// The contact phases that shaped this trajectory (TimeScalingProblem::add_contact_phases), in order
  /// of s; empty if there were none.
  const std::vector<std::shared_ptr<const ContactConstraint>>& contact_phases() const { return contact_phases_; }
  void set_contact_phases(std::vector<std::shared_ptr<const ContactConstraint>> phases) {
    contact_phases_ = std::move(phases);
  }
  /// The index into contact_phases() of the phase at each t: the one whose [active_begin, active_end]
  /// holds s(t), the later one at a switch (the contacts that hold after it). -1 without phases.
  Eigen::VectorXi contact_phase(const Eigen::Ref<const Eigen::VectorXd>& t) const;

  /// The force-distribution LP at each t (see ContactForces): contact forces and their margin between
  /// the grid points, where the solver did not look. With contact phases, each t uses its phase (see
  /// contact_phase: the later one at a switch), so the number of rows of `forces` is that phase's number
  /// of contacts. Throws Error if no contact constraint shaped it. If `phase` is given it receives
  /// contact_phase(t), the phase that served each t, from the same evaluation (-1 everywhere without phases).
  std::vector<ContactForces> contact_forces(const Eigen::Ref<const Eigen::VectorXd>& t,
                                            Eigen::VectorXi* phase = nullptr) const;

  /// Per-link wrenches and centres of pressure of contact_forces(t) (see ContactWrenches): what a
  /// controller or a balance check reads (the centre of pressure inside each sole). Throws Error if no
  /// contact constraint shaped the trajectory.
  ContactWrenches contact_wrenches(const Eigen::Ref<const Eigen::VectorXd>& t) const;

  /// A C² cubic spline in time through the grid (as toppra's ParametrizeSpline): a CubicSplinePath whose
  /// parameter is t in [0, T], through q(t_k) = p(s_k) at every grid time, clamped to q̇ = p'(s) ṡ at
  /// both ends. For controllers that interpolate between points: unlike evaluate(), its q̈ is continuous;
  /// between grid points it departs from the exact timing (by O(Δt⁴) in q), so its q̇, q̈ may exceed
  /// the limits by a little — check it with the problem's limits before sending it to a robot.
  CubicSplinePath time_spline() const;

  /// Uniform times 0, dt, 2dt, ..., with T appended if it is not a multiple of dt.
  Eigen::VectorXd sample_times(double dt) const;

  /// t (m,) in s and q, q̇, q̈ (m, n) of sample() and sample_at().
  struct Samples {
    Eigen::VectorXd t;
    Eigen::MatrixXd q, qd, qdd;
  };
  /// q, q̇, q̈ at the times t: of the exact timing (evaluate), or of time_spline() when `spline`.
  Samples sample_at(Eigen::VectorXd t, bool spline = false) const;
  /// sample_at(sample_times(dt), spline), refused before anything is allocated (InvalidInput saying how
  /// many GB) when t, q, q̇, q̈ and the path's own p, p', p'' while evaluating would take more than
  /// max_memory bytes (> 0): a dt meant in ms but given in s would otherwise fill the memory.
  Samples sample(double dt, double max_memory = 1e9, bool spline = false) const;

 private:
  Eigen::Index interval(double t) const;
  // evaluate() that also hands back s(t), and contact_phase() from s: contact_forces needs both of one t.
  void evaluate_with_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::MatrixXd& q,
                       Eigen::MatrixXd& qd, Eigen::MatrixXd& qdd) const;
  Eigen::VectorXi phase_of_s(const Eigen::VectorXd& s) const;
  std::shared_ptr<const Path> path_;
  std::shared_ptr<const RobotModel> robot_;
  std::shared_ptr<const ContactConstraint> contacts_;
  std::vector<std::shared_ptr<const ContactConstraint>> contact_phases_;
  Eigen::VectorXd s_, sdot_, times_, sddot_;
};

}  // namespace pathpace
