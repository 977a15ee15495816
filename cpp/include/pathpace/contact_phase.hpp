#pragma once
/// @file contact_phase.hpp
/// One phase of a path with changing contacts: a stretch [s_begin, s_end] and the contacts that hold on it,
/// and which phase holds at a given s.

#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "pathpace/contact.hpp"
#include "pathpace/constraints/contact_constraint.hpp"

namespace pathpace {

/// The contacts that hold for s in [s_begin, s_end] (both ends: at a switch both adjacent stances hold).
/// `options`, if set, replaces the margins given to TimeScalingProblem::add_contact_phases for this phase
/// (its cone_edges, friction_margin, min_normal_force, ...; the torque limits are the call's).
struct ContactPhase {
  double s_begin = 0.0;
  double s_end = 0.0;
  std::vector<Contact> contacts;
  std::optional<ContactOptions> options;
};

// docstrings.txt @@ contact_phase_of_s
/// @brief The index of the phase that holds at each s.
///
/// The last phase whose [active_begin, active_end], widened by 1e-12 max(1, |s|) as its rows are, holds
/// s: at a switch both adjacent phases hold, and the later one has the contacts that hold after it. An s
/// that no phase holds (a rounding beyond the path's ends, or a gap between phases) gets the phase
/// nearest to it, the later one on a tie. This is Trajectory.contact_phase's rule, and what
/// `pathpace.sim` uses to tell which of a plan's contacts hold at a time.
///
/// @param phases In order of s (active_begin non-decreasing), at least one: Trajectory.contact_phases, or
///   ContactConstraint(..., active_begin=, active_end=) per phase.
/// @param s (m,): Path parameters, finite.
/// @return (m,): Indices into phases.
/// @throws InvalidInput for no phases, a null phase, phases out of order of s, or an s that is not finite.
Eigen::VectorXi contact_phase_of_s(const std::vector<std::shared_ptr<const ContactConstraint>>& phases,
                                   const Eigen::Ref<const Eigen::VectorXd>& s);

}  // namespace pathpace
