// detail::gather_rows: the rows a contact phase takes of the grid samples (ContactConstraint::evaluate) and of
// a trajectory's samples (Trajectory::contact_forces).
#include <gtest/gtest.h>

#include <vector>

#include "base/gather_rows.hpp"

using pathpace::detail::gather_rows;

TEST(GatherRows, TakesTheRowsInTheGivenOrder) {
  Eigen::MatrixXd m(4, 3);
  m << 0, 1, 2, 10, 11, 12, 20, 21, 22, 30, 31, 32;
  const Eigen::MatrixXd g = gather_rows(m, {3, 1, 1});
  Eigen::MatrixXd want(3, 3);
  want << 30, 31, 32, 10, 11, 12, 10, 11, 12;
  EXPECT_EQ(g, want);
  const Eigen::VectorXd s = Eigen::VectorXd::LinSpaced(5, 0.0, 4.0);
  EXPECT_EQ(gather_rows(s, {0, 4}), Eigen::Vector2d(0.0, 4.0));
  const Eigen::MatrixXd none = gather_rows(m, {});
  EXPECT_EQ(none.rows(), 0);
  EXPECT_EQ(none.cols(), 3);
}
