#include <gtest/gtest.h>

#include "base/validate.hpp"
#include "pathpace/errors.hpp"
#include "test_util.hpp"

using pathpace::test::error_of;

TEST(Validate, FiniteNamesArgumentIndexAndValue) {
  Eigen::VectorXd v(3);
  v << 1.0, std::nan(""), 2.0;
  EXPECT_EQ(error_of([&] { pathpace::detail::require_finite("vmax", v); }), "vmax[1] = nan must be finite");
}

TEST(Validate, IncreasingNamesBothEntries) {
  Eigen::VectorXd v(3);
  v << 0.0, 0.5, 0.5;
  EXPECT_EQ(error_of([&] { pathpace::detail::require_increasing("grid", v); }),
            "grid[2] = 0.5 must be > grid[1] = 0.5 (strictly increasing)");
}
