// detail::solve_tridiagonal against Eigen's dense LU, on matrices that need pivoting.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include <Eigen/Dense>

#include "lp/tridiagonal.hpp"

using pathpace::detail::solve_tridiagonal;

// 400 seeded random systems of size 1-40 whose diagonal is often zero or tiny next to the off-diagonals (the
// chain LP's bases are like that: a row matched to a column by its small coefficient), and where a row with a
// regular diagonal has one of its off-diagonal entries zero half the time (a chain basis's rows act on one
// neighbour only: the steps that skip the elimination): the solution matches a dense partial-pivoting LU of the same matrix to 1e-10 relative,
// and its residual is at rounding level.
TEST(Tridiagonal, MatchesDenseLuWithPivoting) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int compared = 0, sparse_rows = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 40;
    std::vector<double> l(n), d(n), u(n), r(n), u2;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd b(n);
    for (int j = 0; j < n; ++j) {
      const int kind = static_cast<int>(rng() % 3);
      d[j] = kind == 0 ? 0.0 : kind == 1 ? 1e-9 * U(rng) : U(rng);
      // A zero off-diagonal entry only beside a diagonal that can stand alone (else most draws are singular).
      const bool sparse = kind == 2 && rng() % 2 == 0;
      l[j] = j > 0 && !(sparse && rng() % 2 == 0) ? U(rng) : 0.0;
      u[j] = j + 1 < n && !(sparse && l[j] != 0.0) ? U(rng) : 0.0;
      r[j] = b[j] = U(rng);
      A(j, j) = d[j];
      if (j > 0) A(j, j - 1) = l[j];
      if (j + 1 < n) A(j, j + 1) = u[j];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    const bool ok = solve_tridiagonal(l, d, u, r, u2);
    if (!lu.isInvertible()) continue;
    const double cond = A.norm() * A.inverse().norm();
    if (cond > 1e8) continue;  // too ill-conditioned to compare at 1e-10
    ASSERT_TRUE(ok) << "trial " << trial;
    ++compared;
    for (int j = 0; j + 1 < n; ++j) sparse_rows += A(j + 1, j) == 0.0 || A(j, j + 1) == 0.0;  // (u is overwritten)
    const Eigen::VectorXd x = lu.solve(b);
    const Eigen::VectorXd ours = Eigen::Map<const Eigen::VectorXd>(r.data(), n);
    EXPECT_LE((ours - x).norm(), 1e-10 * std::max(1.0, x.norm())) << "trial " << trial;
    EXPECT_LE((A * ours - b).norm(), 1e-12 * cond * std::max(1.0, b.norm())) << "trial " << trial;
  }
  EXPECT_GT(compared, 250);      // the skips (singular or ill-conditioned draws) are a minority
  EXPECT_GT(sparse_rows, 500);   // the steps with nothing to eliminate are exercised (681 rows)
}

TEST(Tridiagonal, SingularIsReported) {
  // Row 1 is zero.
  std::vector<double> l = {0, 0, 1}, d = {1, 0, 2}, u = {1, 0, 0}, r = {1, 1, 1}, u2;
  EXPECT_FALSE(solve_tridiagonal(l, d, u, r, u2));
  // Columns 0 and 1 equal in rows 0, 1 (and zero in row 2).
  l = {0, 2, 0};
  d = {1, 2, 3};
  u = {1, 1, 0};
  r = {1, 1, 1};
  EXPECT_FALSE(solve_tridiagonal(l, d, u, r, u2));
  // Empty and 1x1.
  std::vector<double> e;
  EXPECT_TRUE(solve_tridiagonal(e, e, e, e, u2));
  l = {0};
  d = {4};
  u = {0};
  r = {2};
  ASSERT_TRUE(solve_tridiagonal(l, d, u, r, u2));
  EXPECT_EQ(r[0], 0.5);
  // A zero first pivot: [[0, 1], [2, 1]] x = [1, 4] has x = [1.5, 1], reachable only by swapping the rows.
  l = {0, 2};
  d = {0, 1};
  u = {1, 0};
  r = {1, 4};
  ASSERT_TRUE(solve_tridiagonal(l, d, u, r, u2));
  EXPECT_EQ(r[0], 1.5);
  EXPECT_EQ(r[1], 1.0);
}
