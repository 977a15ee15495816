// SolverOptions checked once, at the door (solve/options.hpp): every field's range, with the house message,
// whatever the guarantee.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "pathpace/errors.hpp"
#include "solve/options.hpp"

using namespace pathpace;

namespace {

std::string message_of(const SolverOptions& o) {
  try {
    detail::validate(o);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Options, DefaultsAndEdgesOfTheRangesPass) {
  EXPECT_EQ(message_of(SolverOptions()), "");
  SolverOptions o;
  o.max_iterations = 0;
  o.audit_points = 1000;
  o.audit_tolerance = 0.0;
  o.max_audit_rounds = 1;
  o.time_limit = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message_of(o), "");
}

// One bad field at a time, under both guarantees: the same message (the audit's fields too, though only
// guarantee = continuous reads them).
TEST(Options, EachFieldOutOfRangeIsNamed) {
  const double nan = std::nan("");
  const std::vector<std::pair<std::function<void(SolverOptions&)>, std::string>> cases = {
      {[](SolverOptions& o) { o.max_iterations = -1; }, "max_iterations = -1 must be >= 0"},
      {[](SolverOptions& o) { o.tolerance = 1.0; }, "tolerance = 1 must be in (0, 1)"},
      {[&](SolverOptions& o) { o.tolerance = nan; }, "tolerance = nan must be in (0, 1)"},
      {[](SolverOptions& o) { o.initial_trust_region = 0.0; }, "initial_trust_region = 0 must be > 0 and finite"},
      {[](SolverOptions& o) { o.initial_trust_region = std::numeric_limits<double>::infinity(); },
       "initial_trust_region = inf must be > 0 and finite"},
      {[](SolverOptions& o) { o.lp_feasibility_tolerance = 1e-3; }, "lp_feasibility_tolerance = 0.001 must be in (0, 1e-3)"},
      {[](SolverOptions& o) { o.time_limit = 0.0; }, "time_limit = 0 must be > 0 (seconds)"},
      {[](SolverOptions& o) { o.audit_points = 0; }, "audit_points = 0 must be in [1, 1000]"},
      {[](SolverOptions& o) { o.audit_points = 1001; }, "audit_points = 1001 must be in [1, 1000]"},
      {[](SolverOptions& o) { o.audit_tolerance = 1.0; }, "audit_tolerance = 1 must be in [0, 1)"},
      {[](SolverOptions& o) { o.max_audit_rounds = 0; }, "max_audit_rounds = 0 must be >= 1"},
  };
  for (const Guarantee g : {Guarantee::Grid, Guarantee::Continuous})
    for (const auto& [bad, expected] : cases) {
      SolverOptions o;
      o.guarantee = g;
      bad(o);
      EXPECT_EQ(message_of(o), expected);
    }
}
