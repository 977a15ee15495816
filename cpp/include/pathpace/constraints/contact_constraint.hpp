#pragma once
/// @file contact_constraint.hpp
/// Torque limits with frictional contact forces (eq. 17-18): the feasible (ṡ², s̈) polygon at each grid
/// point is the projection of the polytope in (ṡ², s̈, contact forces) (sec. IV.B-C).

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/contact.hpp"
#include "pathpace/contact_forces.hpp"
#include "pathpace/robot_model.hpp"

namespace pathpace {

struct ContactOptions {
  int cone_edges = 8;              ///< polyhedral friction cone with k edges, inscribed in the true cone
  double friction_margin = 0.0;    ///< μ is used as μ (1 - friction_margin) (sec. V.D)
  double min_normal_force = 0.0;   ///< N: every contact pushes at least this hard (sec. V.D)
  double torque_scale = 1.0;       ///< multiplies the torque limits (sec. V.D)
  double torque_margin = 0.0;      ///< N·m subtracted from each side
  /// Stand-in bounds on ṡ² and |s̈| for the projection LPs: polygon edges on them are not limits and are
  /// dropped (a direction in which nothing else bounds the set).
  double cap = 1e6;
};

/// At grid point k: τ = a x + b u + c - Σ_i J_iᵀ f_i (J_i the contact point's Jacobian on `link`, minus
/// the same world point's Jacobian on `other_link` for a robot–robot contact) with τ_L <= τ <= τ_U (τ_L = τ_U = 0 for an
/// unactuated floating base), f_i = Σ_e λ_ie g_ie with λ >= 0 (the cone's generators g_ie = n_i +
/// μ (cos φ_e t1 + sin φ_e t2), so that n·f_i = Σ_e λ_ie), and Σ_e λ_ie >= min_normal_force. The
/// polygon's edges become this constraint's half-planes (a varying number per point; inactive padding).
/// The torque limits are part of this constraint: do not add TorqueLimits to the same problem.
class ContactConstraint : public Constraint {
 public:
  ContactConstraint(std::shared_ptr<const RobotModel> robot, std::vector<Contact> contacts,
                    const ContactOptions& options = {}, Eigen::VectorXd tau_min = Eigen::VectorXd(),
                    Eigen::VectorXd tau_max = Eigen::VectorXd());

  std::string name() const override { return "contact"; }
  ConstraintRows evaluate(const PathSamples& samples) const override;

  /// The largest distance a contact point moves along the path's samples (0 for a path that keeps
  /// every contact in place): in the world for a world contact, relative to `other_link` for a
  /// robot–robot contact. `contact` receives the index of the worst one.
  double max_drift(const PathSamples& samples, int* contact = nullptr) const;

  /// The force-distribution LP at each row of (q, q̇, q̈) (each (samples, nq)): the most robust contact
  /// forces and their margin (see ContactForces). This is how a timing is audited between grid points.
  std::vector<ContactForces> force_distribution(const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd,
                                                const Eigen::MatrixXd& qdd) const;

  const std::shared_ptr<const RobotModel>& robot() const { return robot_; }
  const Eigen::VectorXd& tau_min() const { return tau_min_; }  ///< after scale and margin
  const Eigen::VectorXd& tau_max() const { return tau_max_; }

  const std::vector<Contact>& contacts() const { return contacts_; }
  const ContactOptions& options() const { return options_; }

 private:
  std::shared_ptr<const RobotModel> robot_;
  std::vector<Contact> contacts_;
  // Fills J (3·m x nq: the stacked J_i) and the cone generators in world coordinates (3 x m·k) at q.
  void contact_jacobians(const Eigen::Ref<const Eigen::VectorXd>& q, std::vector<Eigen::Isometry3d>& T,
                         Eigen::MatrixXd& J, Eigen::Matrix3Xd& gen) const;
  std::vector<int> body_, other_body_;                  // other_body_ -1: the world
  std::vector<Eigen::Vector3d> point_in_body_;
  std::vector<Eigen::Isometry3d> other_in_body_;        // other_link's frame in its body's frame
  std::vector<Eigen::Matrix3Xd> local_generators_;      // in world (or other_link) coordinates
  ContactOptions options_;
  Eigen::VectorXd tau_min_, tau_max_;
};

}  // namespace pathpace
