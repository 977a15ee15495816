#pragma once
/// @file contact_forces.hpp
/// A distribution of contact forces that realises a motion (the force-distribution LP), with its margin.

#include <limits>

#include <Eigen/Core>

namespace pathpace {

/// The contact forces at one state (q, q̇, q̈), chosen as the most robust distribution: the one that
/// maximises the margin
///   δ = min( min_ie λ_ie , min_i (n_i·f_i - min_normal_force) )   [N]
/// over the cone weights λ (f_i = Σ_e λ_ie g_ie, n_i·g_ie = 1), subject to the torque limits (equalities
/// for unactuated joints). δ >= 0 means the motion is realisable with the constraint's friction cones,
/// margins and minimum normal force; δ < 0 means it needs forces that do not exist (pulling, or outside
/// a cone) — by δ newtons of cone weight.
struct ContactForces {
  /// False when no forces at all, of any sign, meet the torque limits and the unactuated equalities.
  bool feasible = false;
  double margin = -std::numeric_limits<double>::infinity();  ///< δ (N); -inf when not feasible
  /// (contacts, 3): the world-frame force on each contact's `link` (NaN when not feasible).
  Eigen::Matrix<double, Eigen::Dynamic, 3> forces;
  /// Joint torques that go with these forces: τ = RNEA(q, q̇, q̈) - Σ J_iᵀ f_i (NaN when not feasible).
  Eigen::VectorXd torques;
};

}  // namespace pathpace
