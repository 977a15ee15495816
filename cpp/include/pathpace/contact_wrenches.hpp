#pragma once
/// @file contact_wrenches.hpp
/// Per-link totals of a contact-force distribution: the wrench on each link and its centre of pressure.

#include <string>
#include <vector>

#include <Eigen/Core>

namespace pathpace {

// docstrings.txt @@ ContactWrenches
/// @brief Per-link totals of a contact-force distribution (`Trajectory.contact_wrenches`).
///
/// At each sample, for every link that carries contacts (on either side of a contact: `link`, or
/// `other_link` of a robot–robot contact, which receives the opposite force), in first-appearance order
/// over the contacts (and phases): the force Σ_i F_i (world frame, N); its moment Σ_i (p_i - o) × F_i about
/// the link's origin o (world axes, N·m: what a sole's force/torque sensor at o would read, in world
/// axes); the normal force Σ_i n_i·F_i with n_i the contact's normal into the link (N); the centre of
/// pressure Σ_i (n_i·F_i) p_i / Σ_i n_i·F_i (world frame, m: the point of the contact plane where the
/// normal forces' resultant acts, the zero-moment point of a flat sole; NaN where the link's contacts do
/// not share one normal or push with no normal force). A link whose phase does not hold it at a sample has
/// zero force and NaN centre of pressure there; a sample whose distribution is infeasible is NaN
/// throughout.
struct ContactWrenches {
  // docstrings.txt @@ ContactWrenches.links
  /// Every link on either side of a contact, in first appearance over the contacts (and phases).
  std::vector<std::string> links;
  /// (samples, 3 · links): link l at columns 3l, 3l+1, 3l+2.
  Eigen::MatrixXd force, moment, center_of_pressure;
  // docstrings.txt @@ ContactWrenches.normal_force
  /// (samples, links): Sum of the normal forces into each link, N.
  Eigen::MatrixXd normal_force;
  // docstrings.txt @@ ContactWrenches.margin
  /// (samples,): N: the force-distribution LP's margin at the state of each sample, as ContactForces.margin of
  /// `contact_forces(t)` (the same evaluation whose forces are summed here); -inf where not feasible.
  Eigen::VectorXd margin;
  // docstrings.txt @@ ContactWrenches.feasible
  /// As ContactForces.feasible: False where no forces of any sign meet the torque limits (the totals are
  /// NaN there).
  Eigen::Matrix<bool, Eigen::Dynamic, 1> feasible;
  // docstrings.txt @@ ContactWrenches.phase
  /// As ContactForces.phase: the contact phase whose contacts served each sample (the later one at a
  /// switch); -1 without phases.
  Eigen::VectorXi phase;
};

}  // namespace pathpace
