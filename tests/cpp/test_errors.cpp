#include <gtest/gtest.h>

#include "detail/validate.hpp"
#include "pathpace/errors.hpp"

using pathpace::InvalidInput;

TEST(Validate, FiniteNamesArgumentIndexAndValue) {
  Eigen::VectorXd v(3);
  v << 1.0, std::nan(""), 2.0;
  try {
    pathpace::detail::require_finite("vmax", v);
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "vmax[1] = nan must be finite");
  }
}

TEST(Validate, IncreasingNamesBothEntries) {
  Eigen::VectorXd v(3);
  v << 0.0, 0.5, 0.5;
  try {
    pathpace::detail::require_increasing("grid", v);
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "grid[2] = 0.5 must be > grid[1] = 0.5 (strictly increasing)");
  }
}
