// The choice of solver on an SLP window (solve/window_policy.hpp): the order in which the chain simplex, the
// barrier and GLPK SLP take a window that the previous one did not certify, for each kind of window.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "solve/window_policy.hpp"

using namespace pathpace::detail;

namespace {

// Runs the policy as slp_window does, with no solver ever certifying the window: the solvers in the order
// the policy calls them, GLPK SLP written with the iteration count it stops at.
struct Call {
  WindowSolver solver;
  int until = 0;
  bool operator==(const Call& o) const { return solver == o.solver && until == o.until; }
};

std::vector<Call> sequence(const WindowPolicy& policy, WindowProgress progress) {
  std::vector<Call> calls;
  for (int guard = 0; guard < 20; ++guard) {
    const WindowSolver next = next_solver(policy, progress);
    if (next == WindowSolver::Done) {
      calls.push_back({next, progress.slp_iterations});
      return calls;
    }
    if (next == WindowSolver::ChainSimplex) progress.chain_tried = true;
    if (next == WindowSolver::Barrier) progress.barrier_tried = true;
    if (next == WindowSolver::GlpkSlp) {
      progress.slp_started = true;
      progress.slp_iterations = slp_pause(policy, progress);
    }
    calls.push_back({next, next == WindowSolver::GlpkSlp ? progress.slp_iterations : 0});
  }
  ADD_FAILURE() << "the policy did not end";
  return calls;
}

WindowProgress window(int free_points, bool barrier_allowed, bool far, int max_iterations = 200) {
  WindowProgress p;
  p.free_points = free_points;
  p.barrier_allowed = barrier_allowed;
  p.far_start = far;
  p.max_iterations = max_iterations;
  return p;
}

using S = WindowSolver;

}  // namespace

// A near start on a small window: the chain simplex, two GLPK iterations, the barrier, then GLPK to its limit.
TEST(WindowPolicy, NearStartInterruptsSlpForTheBarrier) {
  const WindowPolicy policy;
  const std::vector<Call> expected = {
      {S::ChainSimplex}, {S::GlpkSlp, policy.slp_before_barrier}, {S::Barrier}, {S::GlpkSlp, 200}, {S::Done, 200}};
  EXPECT_EQ(sequence(policy, window(100, true, false)), expected);
}

// A far start: the barrier right after the chain simplex, before GLPK, which then runs uninterrupted.
TEST(WindowPolicy, FarStartGoesToTheBarrierBeforeGlpk) {
  const std::vector<Call> expected = {{S::ChainSimplex}, {S::Barrier}, {S::GlpkSlp, 200}, {S::Done, 200}};
  EXPECT_EQ(sequence(WindowPolicy(), window(100, true, true)), expected);
}

// A window of barrier_first_columns free points or more: the barrier first of all, no chain simplex, whether
// or not the start is far; one below it is an ordinary window.
TEST(WindowPolicy, LargeWindowStartsWithTheBarrier) {
  const WindowPolicy policy;
  const std::vector<Call> expected = {{S::Barrier}, {S::GlpkSlp, 200}, {S::Done, 200}};
  EXPECT_EQ(sequence(policy, window(policy.barrier_first_columns, true, false)), expected);
  EXPECT_EQ(sequence(policy, window(policy.barrier_first_columns, true, true)), expected);
  EXPECT_TRUE(barrier_first(policy, window(policy.barrier_first_columns, true, false)));
  EXPECT_FALSE(barrier_first(policy, window(policy.barrier_first_columns - 1, true, false)));
}

// Method::Slp: never the barrier, however large or far; the chain simplex still certifies what it can.
TEST(WindowPolicy, WithoutTheBarrierOnlyChainSimplexAndGlpk) {
  const WindowPolicy policy;
  const std::vector<Call> expected = {{S::ChainSimplex}, {S::GlpkSlp, 200}, {S::Done, 200}};
  EXPECT_EQ(sequence(policy, window(100, false, false)), expected);
  EXPECT_EQ(sequence(policy, window(100, false, true)), expected);
  EXPECT_EQ(sequence(policy, window(policy.barrier_first_columns, false, false)), expected);
}

// max_iterations bounds GLPK SLP: no interruption for the barrier at or past the limit, and with 0 the LP is
// still set up (its failure to load is a status) before the window ends.
TEST(WindowPolicy, MaxIterationsBoundsGlpkAndTheInterruption) {
  const WindowPolicy policy;
  const int k = policy.slp_before_barrier;
  EXPECT_EQ(sequence(policy, window(100, true, false, k)),
            (std::vector<Call>{{S::ChainSimplex}, {S::GlpkSlp, k}, {S::Done, k}}));
  EXPECT_EQ(sequence(policy, window(100, true, false, k - 1)),
            (std::vector<Call>{{S::ChainSimplex}, {S::GlpkSlp, k - 1}, {S::Done, k - 1}}));
  EXPECT_EQ(sequence(policy, window(100, true, false, 0)),
            (std::vector<Call>{{S::ChainSimplex}, {S::GlpkSlp, 0}, {S::Done, 0}}));
  EXPECT_EQ(sequence(policy, window(100, true, false, k + 1)),
            (std::vector<Call>{{S::ChainSimplex}, {S::GlpkSlp, k}, {S::Barrier}, {S::GlpkSlp, k + 1}, {S::Done, k + 1}}));
}

// The bracket test: relative to T(start), strictly above barrier_first_bracket; never with an infinite T(hi)
// (a bound of 0 somewhere: no bracket).
TEST(WindowPolicy, FarStartIsTheRelativeBracket) {
  const WindowPolicy policy;
  const double b = policy.barrier_first_bracket;
  EXPECT_TRUE(far_start(policy, 1.0, 1.0 - 2.0 * b));
  EXPECT_FALSE(far_start(policy, 1.0, 1.0 - 0.5 * b));
  EXPECT_FALSE(far_start(policy, 1.0, 1.0));
  EXPECT_FALSE(far_start(policy, 1.0, std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(far_start(policy, 1.0, std::nan("")));
}

// The chain simplex's pivot budget: the fixed floor on small windows, two pivots per free point on large ones
// (a cold start takes about one per point), the floor alone on a far start that the barrier may take.
TEST(WindowPolicy, ChainPivotBudgetGrowsWithTheWindowUnlessTheStartIsFar) {
  const WindowPolicy policy;
  for (bool barrier : {true, false}) {
    EXPECT_EQ(chain_pivot_budget(policy, window(1, barrier, false)), policy.chain_pivots);
    EXPECT_EQ(chain_pivot_budget(policy, window(32, barrier, false)), policy.chain_pivots);
    EXPECT_EQ(chain_pivot_budget(policy, window(91, barrier, false)), 182);
    EXPECT_EQ(chain_pivot_budget(policy, window(1999, barrier, false)), 3998);
  }
  EXPECT_EQ(chain_pivot_budget(policy, window(999, true, true)), policy.chain_pivots);
  EXPECT_EQ(chain_pivot_budget(policy, window(999, false, true)), 1998);  // without the barrier: no one else
}
