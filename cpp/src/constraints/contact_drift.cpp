#include "pathpace/contact_drift.hpp"

#include <sstream>

#include "base/validate.hpp"
#include "pathpace/errors.hpp"

namespace pathpace {

std::string ContactDrift::message() const {
  std::ostringstream os;
  os.precision(4);
  if (!constraint.empty()) os << constraint << ": ";
  os << "contact " << contact << " (link '" << link << "') moves by " << drift << " m (farthest at s = " << s
     << "; drift_tolerance " << tolerance << " m): the path does not keep it in place";
  return os.str();
}

std::optional<ContactDrift> check_contact_drift(const ContactConstraint& c, const PathSamples& samples,
                                                double tolerance, DriftPolicy policy) {
  if (!(tolerance >= 0.0)) detail::fail("drift_tolerance = " + detail::fmt(tolerance) + " must be >= 0 (metres)");
  ContactDrift d;
  d.drift = c.max_drift(samples, &d.contact, &d.s);
  if (!(d.drift > tolerance) || d.contact < 0) return std::nullopt;
  d.constraint = c.options().label;
  d.link = c.contacts()[static_cast<size_t>(d.contact)].link;
  d.tolerance = tolerance;
  // Up to 10x the tolerance is rounding or a path fitted to a few mm: timed, and said so; beyond, the
  // forces of the timing assume a contact that slides (Auto errs).
  const bool error = policy == DriftPolicy::Error || (policy == DriftPolicy::Auto && d.drift > 10.0 * tolerance);
  if (error)
    throw InvalidInput(d.message() + "; fix the path, or pass drift='warn' (Python) / DriftPolicy::Warn to time it "
                       "anyway");
  return d;
}

}  // namespace pathpace
