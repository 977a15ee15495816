#pragma once
/// @file contact_constraint.hpp
/// Torque limits with frictional contact forces (eq. 17-18): the feasible (ṡ², s̈) polygon at each grid
/// point is the projection of the polytope in (ṡ², s̈, contact forces) (sec. IV.B-C).

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/contact.hpp"
#include "pathpace/contact_forces.hpp"
#include "pathpace/robot_model.hpp"

namespace pathpace {

namespace detail {
struct PolytopeLp;  // the projection's LP data (internal)
struct Projection;
struct Line;
}

struct ContactOptions {
  int cone_edges = 8;  ///< polyhedral friction cone with k edges at multiples of 2π/k, inscribed in the true cone
  /// The cone is that of μ (1 - friction_margin) (sec. V.D): every force keeps at least this fraction of
  /// the friction it could use in reserve (0.5: tangential force at most half of what would slip).
  double friction_margin = 0.0;
  /// N, per contact point: every point pushes at least this hard along its normal (sec. V.D). With an even
  /// cone_edges a flat foot still reduces exactly: its hull corners' cones plus, per point, the k/2
  /// tangential weights of its minimal force (docs/method.md); with an odd cone_edges every point enters.
  double min_normal_force = 0.0;
  /// N, per link: the normal forces of all of a link's contact points sum to at least this (a foot
  /// pushes at least this hard in total, however it spreads it over its points).
  double min_link_normal_force = 0.0;
  /// N, per contact point: the shifted cone (the paper's "small offset to each friction cone in the normal
  /// direction", sec. V.D; Klampt's forceRobustness). Every force f_i is cone_offset·n_i plus a force inside
  /// the friction cone: each point pushes at least this hard and keeps its friction reserve on top. Unlike
  /// min_normal_force it keeps the flat-sole reduction exact (the offsets are a constant wrench;
  /// docs/method.md).
  double cone_offset = 0.0;
  double torque_scale = 1.0;       ///< multiplies the torque limits (sec. V.D)
  double torque_margin = 0.0;      ///< N·m subtracted from each side (unactuated joints stay at 0)
  /// Stand-in bounds on ṡ² and |s̈| for the projection LPs: polygon edges on them are not limits and are
  /// dropped (a direction in which nothing else bounds the set).
  double cap = 1e6;
  /// LPs allowed per grid point. When they run out, the polygon is the inner hull found so far and the
  /// grid point is reported inexact (FeasibleSet::exact, SolverStats::inexact_points).
  int max_lps = 2000;
  /// Relative ε of a certified approximation (0: exact). The polygon is an inner set whose support function
  /// is within ε times its size (its larger extent in ṡ² or s̈) of the exact projection's in every
  /// direction: the timing stays executable, only slower. An edge is final without its LP when the outer
  /// bound beyond it (the apex of the support lines at its two ends) lies within that of it.
  double projection_tolerance = 0.0;
  /// Project each grid point's polygon only where the timing needs it. evaluate() gives an outer polygon
  /// (the support lines of three LPs per point), and each solve refines it round by round: where the
  /// timing's (ṡ², s̈), with both adjacent s̈, lies beyond an edge not yet certified, the expansion (sec.
  /// IV.C) goes on towards that point only, until it lies inside the certified inner polygon or beyond a
  /// certified edge. The optimum of the outer rows is then feasible for the exact ones: the same T as the
  /// full projection, from the few edges the optimum touches. feasible_set(k) projects point k in full.
  bool project_on_demand = false;
  /// The stretch of s where these contacts hold (one phase of TimeScalingProblem::add_contact_phases): grid
  /// points with s outside [active_begin, active_end] (1e-12 relative) get only inactive rows, and
  /// max_drift looks only inside. Default: the whole path.
  double active_begin = -std::numeric_limits<double>::infinity();
  double active_end = std::numeric_limits<double>::infinity();
  /// Prefix of every row label ("phases[1]" gives "phases[1]: torque knee upper"); empty: none.
  std::string label;
  /// If not empty: ṡ = 0 at s = active_begin (the row ṡ² <= 0 there, with this label). A contact made at
  /// the switch while its point still moves along its normal would need an impact (eq. 17 has no impulses).
  std::string rest_at_begin;
};

// docstrings.txt @@ ContactConstraint
/// @brief Torque limits with frictional contact forces (eq. 17-18), projected onto (ṡ², s̈).
///
/// Includes the torque limits: do not add TorqueLimits to the same problem (TimeScalingProblem merges
/// TorqueLimits of the same robot into it: both limits hold, the tighter side of each is kept).
///
/// At grid point k: τ = a x + b u + c - Σ_i J_iᵀ f_i (J_i the contact point's Jacobian on `link`, minus
/// the same world point's Jacobian on `other_link` for a robot–robot contact) with τ_min <= τ <= τ_max
/// (τ_min = τ_max = 0 for an unactuated floating base), f_i = Σ_e λ_ie g_ie with λ >= 0 (the cone's
/// generators g_ie = n_i + μ (cos φ_e t1 + sin φ_e t2), so that n·f_i = Σ_e λ_ie), and Σ_e λ_ie >=
/// min_normal_force. The polygon's edges become this constraint's half-planes (a varying number per
/// point; inactive padding).
///
/// The polygon is the convex hull of LP optima with every edge certified by its own LP (sec. IV.C), so
/// it is exact to 1e-9 of its size. Points of one link with one normal and one μ that lie in a plane
/// (a flat sole) span the same wrench cone as the vertices of their convex hull (a force at a convex
/// combination of points is that combination of forces at the points), so only those vertices' cones
/// enter the LPs: an exact reduction (the per-link minimum is kept exactly, as the sum of normal forces
/// does not change). A per-point min_normal_force d splits each point's force into its part on the
/// cone's cross-section at n·f = d (a regular k-gon around d·n) plus a force in the cone; the cone parts
/// reduce to the hull vertices as before, and for an even k each point's cross-section part is d·n (a
/// constant) plus k/2 bounded weights (the k-gon is a zonotope): exact, with no per-point rows.
class ContactConstraint : public Constraint, public std::enable_shared_from_this<ContactConstraint> {
 public:
  // docstrings.txt @@ ContactConstraint.__init__
  /// @param options cone_edges, friction_margin, min_normal_force, torque_scale, torque_margin and the rest
  ///   (ContactOptions).
  /// @param tau_min,tau_max (nq,): default (empty) ∓ the URDF effort limits.
  ContactConstraint(std::shared_ptr<const RobotModel> robot, std::vector<Contact> contacts,
                    const ContactOptions& options = {}, Eigen::VectorXd tau_min = Eigen::VectorXd(),
                    Eigen::VectorXd tau_max = Eigen::VectorXd());

  std::string name() const override { return "contact"; }
  /// "torque" (its torque limits) and "friction" (μ of every contact widened by the scale, the minimum
  /// normal forces divided by it) for TimeScalingProblem::relaxation.
  std::vector<std::string> families() const override { return {"torque", "friction"}; }
  std::shared_ptr<const Constraint> relaxed(const std::string& family, double scale) const override;
  ConstraintRows evaluate(const PathSamples& samples) const override;

  // docstrings.txt @@ ContactConstraint.max_drift
  /// @brief How far contact points move along a path (they should not).
  ///
  /// The largest distance a contact point moves (0 for a path that keeps every contact in place): in the
  /// world for a world contact, relative to `other_link` for a robot–robot contact, over the samples where
  /// the constraint is active (a phase: its own stretch).
  ///
  /// @param samples The path at the samples where to look.
  /// @param contact Receives the index of the worst contact.
  /// @param at_s Receives the s where it is farthest.
  /// @return The largest distance, m.
  double max_drift(const PathSamples& samples, int* contact = nullptr, double* at_s = nullptr) const;

  /// True if s lies in [active_begin, active_end] (to 1e-12 relative): the rows hold there.
  bool active_at(double s) const override;

  /// Velocities of the contact points per unit of s along the path, at every sample: normal(k, i) =
  /// n_i · c_i'(s_k) (c_i' = J_i p'(s_k), the world normal; relative to other_link for a robot–robot
  /// contact) and speed(k, i) = |c_i'(s_k)| (m per unit s), for every sample whether active or not.
  /// A contact made with normal(k, i) != 0 hits its surface (see add_contact_phases).
  void point_velocities(const PathSamples& samples, Eigen::MatrixXd& normal, Eigen::MatrixXd& speed) const;

  // docstrings.txt @@ ContactConstraint.force_distribution
  /// @brief Contact forces that realise each configuration, with the force-distribution LP's margin, at each row of
  /// q, qd, qdd (how a timing is audited between grid points).
  ///
  /// @param q,qd,qdd (samples, nq): Positions (rad, m), velocities (per s), accelerations (per s²).
  /// @param distribution "centre" (default): the analytic centre of the physical force set, continuous in the motion
  ///   (the vertex where that set has no interior); "vertex": the LP's optimum (ForceDistribution). margin and
  ///   feasible are the LP's either way.
  /// @return One ContactForces per row.
  std::vector<ContactForces> force_distribution(const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd,
                                                const Eigen::MatrixXd& qdd,
                                                ForceDistribution distribution = ForceDistribution::Centre) const;

  std::shared_ptr<const RobotModel> robot() const override { return robot_; }
  /// Torque limits of the same robot (a TorqueLimits) join the projection: absorb(t) is
  /// with_torque_limits(t.tau_min(), t.tau_max()) (Constraint::can_absorb).
  bool can_absorb(const Constraint& other) const override;
  std::shared_ptr<const Constraint> absorb(const Constraint& other) const override;
  /// The rows are the projection of the (ṡ², s̈, τ, f) polytope (sec. IV.C).
  bool projected() const override { return true; }
  double projection_cap() const override { return options_.cap; }
  /// The label of the row that marks a grid point where no contact forces balance the robot (0 <= -1 there).
  static constexpr const char* kNoBalance = "contact forces cannot balance the robot";
  bool refines() const override { return options_.project_on_demand; }
  int refine(const PathSamples& samples, const Eigen::VectorXd& theta, const Eigen::VectorXd* sddot,
             ConstraintRows& rows, RefineMemory& memory) const override;
  /// With project_on_demand: a copy without it (every polygon projected in full).
  std::shared_ptr<const Constraint> exact() const override;
  /// Result::robot, contacts, contact_phases (a phase of add_contact_phases) and, unless the problem has
  /// torque limits of its own, tau_min/tau_max (rank 1, Constraint::report).
  void report(Result& result, int& torque_rank) const override;
  // docstrings.txt @@ ContactConstraint.tau_min
  /// (nq,): After scale and margin (and any merged TorqueLimits).
  const Eigen::VectorXd& tau_min() const { return tau_min_; }
  // docstrings.txt @@ ContactConstraint.tau_max
  /// (nq,): After scale and margin (and any merged TorqueLimits).
  const Eigen::VectorXd& tau_max() const { return tau_max_; }

  // docstrings.txt @@ ContactConstraint.physical_tau_min
  /// @brief (nq,): The torque limits before torque_scale and torque_margin (tightened by any merged TorqueLimits):
  /// the torque rows of the centred force distribution.
  const Eigen::VectorXd& physical_tau_min() const { return phys_tau_min_; }
  // docstrings.txt @@ ContactConstraint.physical_tau_max
  /// @brief (nq,): The torque limits before torque_scale and torque_margin (see physical_tau_min).
  const Eigen::VectorXd& physical_tau_max() const { return phys_tau_max_; }
  /// This constraint with physical_tau_min/max set to lo, hi (a copy restored from its pickled state).
  std::shared_ptr<ContactConstraint> with_physical_torque_limits(const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) const;

  /// This constraint with torque limits tightened to [max(tau_min, lo), min(tau_max, hi)] (e.g. from a
  /// TorqueLimits of the same robot): one projection for both.
  std::shared_ptr<ContactConstraint> with_torque_limits(const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) const;

  using PointCheck = pathpace::PointCheck;
  /// One LP on the full (ṡ², s̈, τ, forces) polytope at grid point k of `samples`, all contact points
  /// and both minimum normal forces, intersected with `extra` half-planes a x + b u <= c (rows [a, b,
  /// c]: the other constraints there). feasible / rest_feasible ((x, u) = (0, 0)): 1 yes, 0 no
  /// (confirmed in exact arithmetic), -1 the solver failed. This confirms an infeasibility before it is
  /// reported.
  PointCheck check_point(const PathSamples& samples, Eigen::Index k,
                         const Eigen::Matrix<double, Eigen::Dynamic, 3>& extra) const override;

  /// The feasible polygon's slice at a given s̈, without projecting it: for each sample p, the smallest
  /// and largest ṡ² with (ṡ², u[p]) in the polygon at samples.s[p], by two LPs on the projection's
  /// polytope (max and min of its x column with its u column fixed; warm-started from sample to
  /// sample). This is how guarantee = continuous audits the timing's own (x(s), u(s)) between grid
  /// points (the membership of one point, not the whole polygon). x_hi = +inf where only the stand-in
  /// cap bounds x; an empty slice gives x_lo = +inf, x_hi = -inf; inactive samples (a phase) give
  /// [-inf, +inf]; NaN where an LP failed; with `x`, x_lo = -inf without its LP where x > x_hi; with
  /// `edges`, each end's edge from its LP's sensitivity to u's bound (no further LP). Returns the number
  /// of LPs solved.
  int slice(const PathSamples& samples, const Eigen::VectorXd& u, Eigen::VectorXd& x_lo,
            Eigen::VectorXd& x_hi, const Eigen::VectorXd* x = nullptr, SliceEdges* edges = nullptr,
            SliceStarts* starts = nullptr) const override;

  // docstrings.txt @@ ContactConstraint.projected_contacts
  /// Indices of the contacts whose cone weights enter the projection LPs: all of them, or the convex-hull
  /// vertices of each flat group.
  const std::vector<int>& projected_contacts() const { return reduced_.cone; }
  // docstrings.txt @@ ContactConstraint.section_contacts
  /// Indices of the contacts whose per-point minimum enters the projection LPs as k/2 bounded tangential
  /// weights, the tangential part of their force on the cone's cross-section at the minimum
  /// (min_normal_force > cone_offset, even cone_edges: every point of a reduced flat group); empty
  /// otherwise.
  const std::vector<int>& section_contacts() const { return reduced_.section; }

  const std::vector<Contact>& contacts() const { return contacts_; }
  const ContactOptions& options() const { return options_; }

 private:
  // True if s is active_begin (to active_at's tolerance): a phase's first point, where its no-impact row
  // ṡ² <= 0 holds (options().rest_at_begin; evaluate writes it, check_point imposes it).
  bool at_active_begin(double s) const;
  // Which variables an LP of this constraint has: k cone weights for each contact of `cone` (with its own
  // minimum-normal-force row where point_row says so), then k/2 weights in [-d, d] for each contact of
  // `section` (d = min_normal_force - cone_offset): the tangential part of its force on the cone's
  // cross-section at n·f = d, a regular k-gon written as a zonotope (docs/method.md). `jacobians` is cone
  // then section, the order of contact_jacobians' rows.
  struct LpLayout {
    std::vector<int> cone;
    std::vector<char> point_row;
    std::vector<int> section;
    std::vector<int> jacobians;
  };
  std::shared_ptr<const RobotModel> robot_;
  std::vector<Contact> contacts_;
  // Fills J (3·m x nq: the stacked J_i) and the cone generators in world coordinates (3 x m·k) at q.
  // With `use`, only those contacts, in that order.
  // Names of what can bind a projected edge (see detail::Projection::binding), in lp_structure's layout.
  std::vector<std::string> binding_names(const LpLayout& layout) const;
  // evaluate() on every sample of `samples`, without the phase's range, prefix or rest row.
  ConstraintRows project(const PathSamples& samples) const;
  // A projection's half-planes as rows (those on the stand-in bounds left out), each named by what binds it.
  void polygon_rows(const detail::Projection& pr, const std::vector<std::string>& what, std::vector<detail::Line>& out,
                    std::vector<std::string>& names) const;

  std::string binding_label(const LpLayout& layout, const std::vector<std::string>& names, int code) const;
  // `placed`: T already holds q's body placements (not computed again).
  void contact_jacobians(const Eigen::Ref<const Eigen::VectorXd>& q, std::vector<Eigen::Isometry3d>& T,
                         Eigen::MatrixXd& J, Eigen::Matrix3Xd& gen, const std::vector<int>* use = nullptr,
                         bool placed = false) const;
  // Contact u's J_u (eq. 17: its point's Jacobian, minus other_link's at the same point) into the columns
  // moving_[u] of Ji (3 x nq), given q's placements T and joint axes (RobotModel::joint_axes); Ji's other
  // columns are left as they were.
  void chain_jacobian(size_t u, const std::vector<Eigen::Isometry3d>& T, const Eigen::Matrix3Xd& axes,
                      Eigen::Ref<Eigen::MatrixXd> Ji) const;
  // Every contact with its cone weights, no reduction (the force distribution, the infeasibility check);
  // every_point_row: a per-point row even where min_normal_force is 0 (the force distribution's margin
  // counts each point's normal force).
  LpLayout full_layout(bool every_point_row) const;
  // The exact reduction of the contacts into reduced_ (the constructor's last step; see contact_lp.cpp).
  void reduce_contacts();
  // The projection LP's fixed part for `layout`: bounds, minimum-normal-force rows; `extra` more rows
  // (zero, free) after them.
  void lp_structure(const LpLayout& layout, int extra, detail::PolytopeLp& lp) const;
  /// cone_offset Σ_i J_iᵀ n_i over every contact at q: the generalized force of the shifted cones' offsets.
  /// `placed`: q's body placements if the caller has them (lp_point's), else computed here.
  Eigen::VectorXd offset_torques(const Eigen::Ref<const Eigen::VectorXd>& q,
                                 const std::vector<Eigen::Isometry3d>* placed = nullptr) const;
  // The sample's part of the projection LP (eq. 17): x's and u's coefficients a and b, each contact's
  // -J_iᵀ g_ie, the torque rows' bounds. lp must come from lp_structure(layout) with no writer but
  // lp_point since: a contact's weights are written on its chain's rows only (moving_), the other
  // coefficients of the torque rows are lp_structure's zeros.
  void lp_point(const LpLayout& layout, const Eigen::Ref<const Eigen::VectorXd>& q,
                const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
                const Eigen::Ref<const Eigen::VectorXd>& c, detail::PolytopeLp& lp) const;
  // The physical rows of the force set at q with inverse-dynamics torques tau (variables: the 3 m world
  // forces): A f = b for unactuated joints, G f <= h (rows of unit norm) for each friction facet of μ,
  // each finite torque limit (phys_tau_*) and a stand-in ceiling n·f <= cap per point (contact_centre.cpp).
  void physical_rows(const std::vector<Eigen::Isometry3d>& T, const Eigen::MatrixXd& J, const Eigen::VectorXd& tau,
                     Eigen::MatrixXd& A, Eigen::VectorXd& b, Eigen::MatrixXd& G, Eigen::VectorXd& h) const;
  // The rotation from contact i's normal frame (the world, or other_link) to the world, at placements T.
  Eigen::Matrix3d normal_frame(size_t i, const std::vector<Eigen::Isometry3d>& T) const;
  LpLayout reduced_;                                    // the projection's LPs
  std::vector<Eigen::Matrix3Xd> local_half_edges_;      // μ' (u_{m+1} - u_m) / 2, m < k/2 (even k only)
  std::vector<int> body_, other_body_;                  // other_body_ -1: the world
  std::vector<std::vector<int>> moving_;                // per contact: the joints that move its point(s)
  std::vector<Eigen::Vector3d> point_in_body_;
  std::vector<Eigen::Isometry3d> other_in_body_;        // other_link's frame in its body's frame
  std::vector<Eigen::Matrix3Xd> local_generators_;      // in world (or other_link) coordinates
  // offset_torques' terms (built once by the constructor): the contacts of one body under one world-fixed
  // normal as a group (their count and the sum of their points in the body), and the contacts on two
  // moving bodies, each on its own.
  struct OffsetGroup {
    int body;
    Eigen::Vector3d normal, sum;
    double count;
  };
  std::vector<OffsetGroup> offset_groups_;
  std::vector<int> offset_moving_;
  ContactOptions options_;
  Eigen::VectorXd tau_min_, tau_max_;
  Eigen::VectorXd phys_tau_min_, phys_tau_max_;  // before scale and margin
};

}  // namespace pathpace
