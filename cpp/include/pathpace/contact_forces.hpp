#pragma once
/// @file contact_forces.hpp
/// A distribution of contact forces that realises a motion (the force-distribution LP), with its margin.

#include <limits>

#include <Eigen/Core>

namespace pathpace {

/// @brief Which of the forces that realise a motion `force_distribution` / `Trajectory.contact_forces` give.
///
/// Centre ("centre", the default): the analytic centre of the physical force set at each state, the forces
/// that maximise Σ log slack over every friction facet of μ (no friction_margin), every torque limit before
/// torque_scale and torque_margin, under the dynamics' equalities (the unactuated joints). It is unique and
/// continuous in t wherever the motion (q, q̇, q̈) is, so a controller can feed it forward. Where that set has
/// no interior (a sample on a zero-margin plan's boundary, where some physical row must bind) there is no
/// centre: the LP's vertex is given instead (`centred` False). Vertex ("vertex"): the force-distribution
/// LP's optimum, a vertex that can jump between neighbouring samples.
enum class ForceDistribution { Centre, Vertex };

// docstrings.txt @@ ContactForces
/// @brief Contact forces that realise a motion at samples, with the force-distribution LP's margin.
///
/// `forces` and `torques` are those of the distribution asked for (ForceDistribution: by default the
/// analytic centre of the physical force set, continuous in t). `margin` and `feasible` are the LP's
/// whichever distribution is asked for. At each state (q, q̇, q̈) the LP finds the most robust distribution: the one
/// that maximises the margin
///   δ = min( min_ie λ_ie , min_i (n_i·f_i - min_normal_force) , min_l (Σ_{i on l} n_i·f_i - min_link_normal_force) )
/// in N, over the cone weights λ (f_i = Σ_e λ_ie g_ie, n_i·g_ie = 1), subject to the torque limits (after
/// torque_scale and torque_margin; equalities for unactuated joints). The per-link term (l over the links
/// that carry contacts) counts only when min_link_normal_force > 0. The rows are those of the projection
/// (the same polytope at this state), so δ >= 0 means the motion is realisable with every margin the
/// solve used: friction cones of μ (1 - friction_margin), both minimum normal forces, the torque limits;
/// δ < 0 means it needs forces that do not exist (pulling, outside a cone, below a minimum) — by δ
/// newtons.
///
/// One state per ContactForces (the Python class holds arrays over the samples).
struct ContactForces {
  /// False when no forces at all, of any sign, meet the torque limits and the unactuated equalities.
  bool feasible = false;
  double margin = -std::numeric_limits<double>::infinity();  ///< δ (N); -inf when not feasible
  /// (contacts, 3): the world-frame force on each contact's `link` (NaN when not feasible).
  Eigen::Matrix<double, Eigen::Dynamic, 3> forces;
  /// Joint torques that go with these forces: τ = RNEA(q, q̇, q̈) - Σ J_iᵀ f_i (NaN when not feasible).
  Eigen::VectorXd torques;
  // docstrings.txt @@ ContactForces.centred
  /// True where forces is the analytic centre; False for the LP's vertex (asked for, or where the
  /// physical force set has no interior).
  bool centred = false;
  // docstrings.txt @@ ContactForces.slack
  /// (samples,): N: the smallest slack of forces in the physical rows (friction facets of μ, torque limits before
  /// scale and margin), each row's distance in force space to its boundary; NaN when not feasible.
  double slack = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace pathpace
