// The band LDLᵀ of the structured jerk solve (lp/band_ldlt.hpp) against Eigen's dense factorisation of the same
// matrices: seeded quasi-definite band matrices (a positive and a negative diagonal block interleaved, as the
// KKT systems have them) of every size around the band's width, so that the substitutions' first and last
// rows (fewer than four neighbours) and their steady-state loops are both exercised.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Dense>

#include "lp/band_ldlt.hpp"

using namespace pathpace::detail;

namespace {

// A random band matrix with |i - j| <= 4 whose every third diagonal entry is negative: (θ, b, ν) rows.
void random_band(std::mt19937& rng, Eigen::Index m, BandLdlt& band, Eigen::MatrixXd& dense) {
  std::uniform_real_distribution<double> U(-1.0, 1.0), P(2.0, 4.0);
  dense.setZero(m, m);
  band.clear();
  for (Eigen::Index i = 0; i < m; ++i) {
    const double d = (i % 3 == 2 ? -1.0 : 1.0) * P(rng) * 4;
    dense(i, i) = d;
    band.add(i, i, d);
    for (Eigen::Index j = std::max<Eigen::Index>(0, i - BandLdlt::kBand); j < i; ++j) {
      const double v = U(rng);
      dense(i, j) = dense(j, i) = v;
      band.add(j, i, v);  // either order
    }
  }
}

}  // namespace

TEST(BandLdlt, SolvesAndMultipliesAsTheDenseMatrixAtEverySize) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (Eigen::Index m : {1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 40, 301}) {
    for (int rep = 0; rep < 5; ++rep) {
      BandLdlt band(m);
      Eigen::MatrixXd dense;
      random_band(rng, m, band, dense);
      for (Eigen::Index i = 0; i < m; ++i)
        for (Eigen::Index j = 0; j < m; ++j) ASSERT_EQ(band.at(i, j), dense(i, j)) << m << " " << i << " " << j;
      Eigen::VectorXd x(m), y;
      for (Eigen::Index i = 0; i < m; ++i) x[i] = U(rng);
      band.multiply(x, y);
      EXPECT_LE((y - dense * x).lpNorm<Eigen::Infinity>(), 1e-13 * (1 + x.lpNorm<Eigen::Infinity>())) << m;
      // Regularised as the KKT systems are: + reg on the diagonal.
      Eigen::VectorXd reg(m);
      for (Eigen::Index i = 0; i < m; ++i) reg[i] = i % 3 == 2 ? -1e-3 : 1e-3;
      ASSERT_TRUE(band.factor(reg)) << m;
      const Eigen::MatrixXd regularised = dense + Eigen::MatrixXd(reg.asDiagonal());
      Eigen::VectorXd sol = x;
      band.solve(sol);
      const Eigen::VectorXd want = regularised.fullPivLu().solve(x);
      EXPECT_LE((sol - want).lpNorm<Eigen::Infinity>(), 1e-11 * (1 + want.lpNorm<Eigen::Infinity>())) << m;
      EXPECT_LE((regularised * sol - x).lpNorm<Eigen::Infinity>(), 1e-12) << m;
    }
  }
}

TEST(BandLdlt, ScaledIsTheSymmetricScalingAndAZeroPivotIsReported) {
  std::mt19937 rng(7);
  const Eigen::Index m = 11;
  BandLdlt band(m), scaled(m);
  Eigen::MatrixXd dense;
  random_band(rng, m, band, dense);
  Eigen::VectorXd s(m);
  for (Eigen::Index i = 0; i < m; ++i) s[i] = 0.5 + i;
  scaled.scaled(band, s);
  const Eigen::MatrixXd want = s.asDiagonal() * dense * s.asDiagonal();
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j)
      EXPECT_NEAR(scaled.at(i, j), want(i, j), 1e-13 * std::abs(want(i, j))) << i << " " << j;
  BandLdlt zero(6);  // all zero: the first pivot is 0
  EXPECT_FALSE(zero.factor(Eigen::VectorXd::Zero(6)));
  BandLdlt nan(6);
  nan.add(0, 0, std::nan(""));
  EXPECT_FALSE(nan.factor(Eigen::VectorXd::Zero(6)));
}
