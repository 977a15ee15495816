#pragma once
/// @file contact_phase.hpp
/// One phase of a path with changing contacts: a stretch [s_begin, s_end] and the contacts that hold on it.

#include <optional>
#include <vector>

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

}  // namespace pathpace
