// The log-barrier window solver (solve/barrier.hpp) on problems whose optimum is known, and its certificate.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include "solve/barrier.hpp"
#include "test_util.hpp"

using namespace pathpace::detail;
using pathpace::test::duration_of;

namespace {

const auto kNoDeadline = std::chrono::steady_clock::time_point::max();

}  // namespace

// Box only: T decreases in every θ, so the optimum is θ = hi; the barrier's answer is strictly inside, within
// the target of T(hi), and its bound brackets T(hi).
TEST(Barrier, BoxOnlyConvergesToTheUpperBounds) {
  const int m = 50;
  Eigen::VectorXd ds = Eigen::VectorXd::Constant(m, 0.02), lo = Eigen::VectorXd::Zero(m + 1), hi(m + 1);
  for (int j = 0; j <= m; ++j) hi[j] = 1.0 + 0.5 * std::sin(0.3 * j);
  lo[0] = hi[0] = 0.25;  // a fixed end
  const double Tstar = duration_of(ds, hi);
  const double target = 1e-9 * Tstar;
  const BarrierResult r = barrier_window(ds, {}, lo, hi, 0.5 * hi, target, 300, kNoDeadline);
  ASSERT_TRUE(r.ok);
  EXPECT_LE(r.lower, Tstar * (1 + 1e-15));
  EXPECT_GE(r.T, Tstar);
  EXPECT_LE(r.T - r.lower, target);
  EXPECT_EQ(r.theta[0], 0.25);
  for (int j = 1; j <= m; ++j) EXPECT_LT(r.theta[j], hi[j]);
}

// Two free points between fixed ends θ_0 = θ_3 = 1, equal Δs, one coupling row θ_1 + θ_2 <= 2 (α, β > 0: the
// kind that breaks max-closure). T is symmetric and convex, so θ_1 = θ_2 = 1 and T* = 3 Δs; any asymmetric
// split is worse.
TEST(Barrier, CouplingRowOptimumBySymmetry) {
  Eigen::VectorXd ds = Eigen::VectorXd::Constant(3, 0.1);
  Eigen::VectorXd lo = Eigen::VectorXd::Zero(4), hi = Eigen::VectorXd::Constant(4, 5.0);
  lo[0] = hi[0] = 1.0;
  lo[3] = hi[3] = 1.0;
  const std::vector<WindowRow> rows = {{1, 1.0, 1.0, 2.0}};
  Eigen::VectorXd start(4);
  start << 1.0, 1.5, 0.5, 1.0;  // feasible, on the row, asymmetric
  const BarrierResult r = barrier_window(ds, rows, lo, hi, start, 1e-10, 300, kNoDeadline);
  ASSERT_TRUE(r.ok) << r.newton_steps << " " << r.T << " " << r.lower;
  EXPECT_GE(r.T, 0.3 - 1e-15);
  EXPECT_LE(r.T - 0.3, 1e-10);  // the target
  EXPECT_LE(r.lower, 0.3 + 1e-15);
  EXPECT_NEAR(r.theta[1], 1.0, 1e-5);
  EXPECT_NEAR(r.theta[2], 1.0, 1e-5);
  EXPECT_LT(r.theta[1] + r.theta[2], 2.0);
}

// Random chains with acceleration-like rows |θ_{k+1} - θ_k| <= 2 a Δs and speed caps: the certificate holds
// against the best of many random feasible profiles (each must be >= lower), and the answer is feasible.
TEST(Barrier, RandomChainsCertificateIsALowerBound) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const int m = 20 + static_cast<int>(60 * U(gen));
    Eigen::VectorXd ds = Eigen::VectorXd::Constant(m, 1.0 / m), lo = Eigen::VectorXd::Zero(m + 1), hi(m + 1);
    for (int j = 0; j <= m; ++j) hi[j] = 0.2 + 2.0 * U(gen);
    lo[0] = hi[0] = 0.0;
    lo[m] = hi[m] = 0.0;
    std::vector<WindowRow> rows;
    const double a = 0.5 + U(gen);
    for (int k = 0; k < m; ++k) {
      rows.push_back({k, -1.0, 1.0, 2 * a * ds[k]});
      rows.push_back({k, 1.0, -1.0, 2 * a * ds[k]});
      rows.push_back({k, 0.3, 0.3, 0.5 + U(gen)});  // positively coupled
    }
    // A feasible start: a ramp up and down at the acceleration rows' slope, capped below every θ bound.
    Eigen::VectorXd start = Eigen::VectorXd::Zero(m + 1);
    const double cap = std::min(hi.segment(1, m - 1).minCoeff(), 0.4);
    for (int j = 1; j < m; ++j) start[j] = std::min(2 * a * ds[0] * std::min(j, m - j), cap);
    const double T0 = duration_of(ds, start);
    const BarrierResult r = barrier_window(ds, rows, lo, hi, start, 1e-9 * T0, 400, kNoDeadline);
    ASSERT_TRUE(r.ok) << trial << " steps " << r.newton_steps << " T " << r.T << " lower " << r.lower;
    EXPECT_LE(r.lower, r.T);
    EXPECT_LE(r.T - r.lower, 1e-9 * T0) << trial;  // the certificate is as tight as asked
    EXPECT_LE(r.T, T0 * (1 + 1e-12)) << trial;
    for (const WindowRow& w : rows) EXPECT_LE(w.alpha * r.theta[w.k] + w.beta * r.theta[w.k + 1], w.c) << trial;
    for (int j = 0; j <= m; ++j) EXPECT_LE(r.theta[j], hi[j]);
    // Random feasible profiles (convex combinations of the answer and the start, scaled down) are no better
    // than the bound.
    for (int s = 0; s < 50; ++s) {
      const double l = U(gen), shrink = 0.9 + 0.1 * U(gen);
      const Eigen::VectorXd y = shrink * (l * r.theta + (1 - l) * start);
      EXPECT_GE(duration_of(ds, y), r.lower) << trial;
    }
  }
}

// No strictly feasible start (a row tight at the start and at lo): the solver declines, so that the caller
// falls back to the SLP.
TEST(Barrier, DeclinesWithoutAStrictlyFeasibleStart) {
  Eigen::VectorXd ds = Eigen::VectorXd::Constant(2, 0.5), lo = Eigen::VectorXd::Zero(3), hi = Eigen::VectorXd::Ones(3);
  lo[0] = hi[0] = 0.0;
  const std::vector<WindowRow> rows = {{0, 0.0, 1.0, 0.0}};  // θ_1 <= 0
  const BarrierResult r = barrier_window(ds, rows, lo, hi, Eigen::VectorXd::Zero(3), 1e-9, 100, kNoDeadline);
  EXPECT_FALSE(r.ok);
}
