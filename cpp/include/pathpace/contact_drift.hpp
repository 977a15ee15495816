#pragma once
/// @file contact_drift.hpp
/// Whether a path keeps its contacts in place: the contact model (eq. 17-18) assumes c(p(s)) is fixed
/// wherever a contact holds; a path that slides a contact is timed with forces it could not have.

#include <limits>
#include <optional>
#include <string>

#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/path_samples.hpp"

namespace pathpace {

/// What to do when a contact point moves by more than the drift tolerance along the path.
enum class DriftPolicy {
  Auto,   ///< Warn up to 10x the tolerance (rounding, a path fitted to a few mm), Error beyond
  Warn,   ///< time it anyway; Result::contact_drift and Result::message say the contacts moved
  Error,  ///< throw InvalidInput naming the contact, s and the drift
};

/// The worst-moving contact of one contact constraint along a path.
struct ContactDrift {
  std::string constraint;  ///< the constraint's label ("phases[1]"), "" for a contact set of the whole path
  int contact = -1;        ///< index into ContactConstraint::contacts()
  std::string link;        ///< that contact's link
  double s = std::numeric_limits<double>::quiet_NaN();  ///< where it is farthest from where it started
  double drift = 0.0;      ///< m: how far (in the world, or relative to other_link)
  double tolerance = 0.0;  ///< m: the tolerance it exceeds
  /// "phases[0]: contact 0 (link 'foot') moves by 0.05 m (at s = 0.7; drift_tolerance 1e-06 m)".
  std::string message() const;
};

/// The contact of `c` that moves most over `samples` (where c is active), if it moves by more than
/// `tolerance` (m, >= 0); nothing otherwise. Under DriftPolicy::Error, or Auto with a drift beyond
/// 10 x tolerance, throws InvalidInput instead, naming the contact, s and the drift.
std::optional<ContactDrift> check_contact_drift(const ContactConstraint& c, const PathSamples& samples,
                                                double tolerance, DriftPolicy policy = DriftPolicy::Auto);

}  // namespace pathpace
