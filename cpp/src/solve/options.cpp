#include "solve/options.hpp"

#include <cmath>
#include <string>

#include "base/validate.hpp"

namespace pathpace::detail {

void validate(const SolverOptions& options) {
  if (options.max_iterations < 0)
    fail("max_iterations = " + std::to_string(options.max_iterations) + " must be >= 0");
  if (!(options.tolerance > 0.0 && options.tolerance < 1.0))
    fail("tolerance = " + fmt(options.tolerance) + " must be in (0, 1)");
  if (!(options.initial_trust_region > 0.0) || !std::isfinite(options.initial_trust_region))
    fail("initial_trust_region = " + fmt(options.initial_trust_region) + " must be > 0 and finite");
  if (!(options.lp_feasibility_tolerance > 0.0 && options.lp_feasibility_tolerance < 1e-3))
    fail("lp_feasibility_tolerance = " + fmt(options.lp_feasibility_tolerance) + " must be in (0, 1e-3)");
  if (!(options.time_limit > 0.0)) fail("time_limit = " + fmt(options.time_limit) + " must be > 0 (seconds)");
  // The audit's fields are read only with guarantee = continuous, but a bad value is a bad value: checked
  // whatever the guarantee, so that switching the guarantee never turns a call into an error.
  if (options.audit_points < 1 || options.audit_points > 1000)
    fail("audit_points = " + std::to_string(options.audit_points) + " must be in [1, 1000]");
  if (!(options.audit_tolerance >= 0.0 && options.audit_tolerance < 1.0))
    fail("audit_tolerance = " + fmt(options.audit_tolerance) + " must be in [0, 1)");
  if (options.max_audit_rounds < 1)
    fail("max_audit_rounds = " + std::to_string(options.max_audit_rounds) + " must be >= 1");
}

}  // namespace pathpace::detail
