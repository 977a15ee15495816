// detail::ChainSimplex (the SLP window's LP by a primal simplex on the chain) against GLPK on random chains.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "solve/chain_simplex.hpp"
#include "lp/glpk_lp.hpp"
#include "solve/reachability.hpp"

using namespace pathpace::detail;

namespace {

// A chain like eq. (26) with acceleration limits of `joints` random joints (|p'_j u + p''_j x| <= 1 at every
// grid point, forward and backward rows) and x_lo = 0 <= θ <= x_hi, rest to rest.
Chain random_chain(std::mt19937& rng, int m, int joints) {
  std::uniform_real_distribution<double> U(-1.0, 1.0), H(0.5, 2.0);
  Chain ch;
  ch.ds = Eigen::VectorXd::Constant(m, 1.0 / m);
  ch.x_lo = Eigen::VectorXd::Zero(m + 1);
  ch.x_hi.resize(m + 1);
  ch.x_lo_id.assign(static_cast<size_t>(m) + 1, -1);
  ch.x_hi_id.assign(static_cast<size_t>(m) + 1, -1);
  for (int k = 0; k <= m; ++k) ch.x_hi[k] = H(rng);
  // Smooth random p', p'' per joint (a few sines), so that the limits bind in ramps as on real paths.
  std::vector<std::array<double, 4>> f(static_cast<size_t>(joints));
  for (auto& c : f) c = {U(rng), 3 + 3 * H(rng), U(rng), 3 * U(rng)};
  auto p1 = [&](int j, double s) { return f[j][0] * std::sin(f[j][1] * s + f[j][2]) + 0.3 * f[j][3]; };
  auto p2 = [&](int j, double s) { return f[j][0] * f[j][1] * std::cos(f[j][1] * s + f[j][2]); };
  ch.row_offset.push_back(0);
  for (int k = 0; k < m; ++k) {
    const double h = m / 2.0;  // 1 / (2 Δs)
    for (int j = 0; j < joints; ++j)
      for (double sgn : {1.0, -1.0}) {
        const double a0 = sgn * p2(j, double(k) / m), b0 = sgn * p1(j, double(k) / m);
        const double a1 = sgn * p2(j, double(k + 1) / m), b1 = sgn * p1(j, double(k + 1) / m);
        ch.row_data.push_back({a0 - b0 * h, b0 * h, 1.0, j});   // forward row at s_k
        ch.row_data.push_back({-b1 * h, a1 + b1 * h, 1.0, j});  // backward row at s_k+1
      }
    ch.coupled_offset.push_back(ch.row_data.size());
    ch.row_offset.push_back(ch.row_data.size());
  }
  return ch;
}

// A window of the sizes the corpus's windows have (30-150 intervals, 2-4 joints), its reachability analysis
// from rest to rest (the greedy profile reach.theta is a vertex of the window's LP) and the LP's column bounds:
// the chain's, with both ends fixed at the greedy profile's values (as slp_window fixes them). The caller
// asserts that the analysis is feasible.
struct GreedyWindow {
  Chain ch;
  Reachability reach;
  Eigen::VectorXd lo, hi;
  int m() const { return static_cast<int>(ch.intervals()); }
};

GreedyWindow greedy_window(std::mt19937& rng) {
  const int m = 30 + static_cast<int>(rng() % 121), joints = 2 + static_cast<int>(rng() % 3);
  GreedyWindow w{random_chain(rng, m, joints), {}, {}, {}};
  w.reach = reachability(w.ch, 0.0, 0.0);
  w.lo = w.ch.x_lo;
  w.hi = w.ch.x_hi;
  if (w.reach.outcome == Reachability::Outcome::Feasible) {
    w.lo[0] = w.hi[0] = w.reach.theta[0];
    w.lo[m] = w.hi[m] = w.reach.theta[m];
  }
  return w;
}

// min g·y over the chain's rows and lo <= y <= hi with y_0, y_m fixed at theta's values, by GLPK.
double glpk_optimum(const Chain& ch, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, const Eigen::VectorXd& theta,
                    const Eigen::VectorXd& g) {
  const Eigen::Index m = ch.intervals();
  GlpkLp lp;
  lp.reset(static_cast<int>(m - 1));
  for (Eigen::Index k = 0; k < m; ++k)
    for (const Line& r : ch.rows(k)) {
      std::vector<int> idx;
      std::vector<double> val;
      double ub = r.c;
      if (k >= 1) { idx.push_back(static_cast<int>(k - 1)); val.push_back(r.a); } else { ub -= r.a * theta[0]; }
      if (k + 1 <= m - 1) { idx.push_back(static_cast<int>(k)); val.push_back(r.b); } else { ub -= r.b * theta[m]; }
      lp.add_row_upper(idx, val, ub);
    }
  EXPECT_TRUE(lp.load());
  std::vector<double> cost(static_cast<size_t>(m - 1));
  for (Eigen::Index j = 1; j < m; ++j) {
    lp.set_col_bounds(static_cast<int>(j - 1), lo[j], hi[j]);
    cost[static_cast<size_t>(j - 1)] = g[j];
  }
  lp.set_objective(cost);
  EXPECT_EQ(lp.solve(1e-12), GlpkLp::Outcome::Optimal);
  std::vector<double> x;
  lp.column_values(x);
  double v = g[0] * theta[0] + g[m] * theta[m];
  for (Eigen::Index j = 1; j < m; ++j) v += g[j] * x[static_cast<size_t>(j - 1)];
  return v;
}

// ∇T (eq. 27) at θ: -(1/√θ_j) Σ_{k ∋ j} Δs_k / (√θ_k + √θ_k+1)²; the fixed ends do not enter.
Eigen::VectorXd grad_T(const Chain& ch, const Eigen::VectorXd& theta) {
  const Eigen::Index m = ch.intervals();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(m + 1);
  for (Eigen::Index k = 0; k < m; ++k) {
    const double w = std::sqrt(theta[k]) + std::sqrt(theta[k + 1]), t = ch.ds[k] / (w * w);
    g[k] -= t;
    g[k + 1] -= t;
  }
  for (Eigen::Index j = 1; j < m; ++j) g[j] /= std::sqrt(theta[j]);
  g[0] = g[m] = 0.0;
  return g;
}

// The simplex's bound at `at` for objective g is GLPK's (valid to 1e-10, tight to 1e-9), and the vertex it
// ends on is GLPK's optimum and meets every row.
void expect_certified(const Chain& ch, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, const ChainSimplex& cs,
                      const Eigen::VectorXd& at, const Eigen::VectorXd& g, double gap, int trial) {
  const double opt = glpk_optimum(ch, lo, hi, at, g);
  const double gat = g.dot(at), scale = std::abs(gat) + 1.0;
  EXPECT_GE(gap, gat - opt - 1e-10 * scale) << "trial " << trial << ": the bound is not valid";
  EXPECT_LE(gap, gat - opt + 1e-9 * scale) << "trial " << trial << ": the bound is loose";
  EXPECT_NEAR(g.dot(cs.vertex()), opt, 1e-9 * scale) << "trial " << trial;
  for (Eigen::Index k = 0; k < ch.intervals(); ++k)
    for (const Line& r : ch.rows(k))
      EXPECT_LE(row_violation(r, cs.vertex()[k], cs.vertex()[k + 1]), 1e-9) << "trial " << trial;
}

}  // namespace

// 200 seeded random chains (30-150 intervals, 2-4 joints): from the greedy profile of the reachability
// analysis (a vertex), the chain simplex reaches GLPK's optimum of the window LP for a random decreasing
// objective and for ∇T, and its bound on g·θ - min g·y is valid (not below the true gap) and tight (1e-9); so
// is the bound for a second objective from the first's optimal basis (warm start). The matching the pivots
// kept up incrementally is the one computed from scratch.
TEST(ChainSimplex, MatchesGlpkFromTheGreedyVertex) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> G(-1.0, -0.05);
  int solved = 0, trials = 0, pivots = 0, warm = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const GreedyWindow w = greedy_window(rng);
    ASSERT_EQ(w.reach.outcome, Reachability::Outcome::Feasible) << "trial " << trial;
    const Chain& ch = w.ch;
    const Eigen::VectorXd &theta = w.reach.theta, &lo = w.lo, &hi = w.hi;
    const int m = w.m();
    Eigen::VectorXd g(m + 1);
    if (trial % 2 == 0) {
      for (int j = 0; j <= m; ++j) g[j] = G(rng);
    } else {
      g = grad_T(ch, theta);
    }
    ++trials;
    ChainSimplex cs(ch, 0, m, lo, hi, 1, m - 1);
    const double gap = cs.gap(theta, g, 1000);
    if (!std::isfinite(gap)) continue;
    ++solved;
    pivots += cs.pivots();
    expect_certified(ch, lo, hi, cs, theta, g, gap, trial);
    // The pivots keep the matching up incrementally (walked again only from the columns the pivot's two
    // constraints act on): it is the one matched from scratch, and the multipliers solve Bᵀλ = -g.
    EXPECT_TRUE(cs.fresh_state(g)) << "trial " << trial;
    // A second objective from the vertex's basis (warm, as the Frank-Wolfe iterations of slp.cpp use it).
    const Eigen::VectorXd v = cs.vertex();
    Eigen::VectorXd g2(m + 1);
    for (int j = 0; j <= m; ++j) g2[j] = G(rng);
    const double gap2 = cs.gap(v, g2, 1000, true);
    if (!std::isfinite(gap2)) continue;
    ++warm;
    EXPECT_TRUE(cs.fresh_state(g2)) << "trial " << trial;
    const double opt2 = glpk_optimum(ch, lo, hi, v, g2), gv = g2.dot(v), scale2 = std::abs(gv) + 1.0;
    EXPECT_GE(gap2, gv - opt2 - 1e-10 * scale2) << "trial " << trial << ": the warm bound is not valid";
    EXPECT_LE(gap2, gv - opt2 + 1e-9 * scale2) << "trial " << trial << ": the warm bound is loose";
  }
  EXPECT_GE(warm, solved * 95 / 100);
  EXPECT_GE(solved, trials * 95 / 100);  // gives up (singular basis, pivot budget) on at most 5 %
  EXPECT_GT(pivots, trials);             // the chains are degenerate enough to need pivots
}

// The Frank-Wolfe iterations of slp.cpp after a step that stops short of the LP's vertex (an interior optimum):
// the next check runs warm from the previous optimal basis, which stands on that vertex, not on the iterate.
// On 200 seeded random chains, v the optimum for a random decreasing objective from θ_g, with the iterate
// θ_α = θ_g + α (v - θ_g) (α in (0.05, 0.95), feasible by convexity, at no vertex) and g = ∇T(θ_α): the
// bound on g·θ_α - min g·y is valid and tight (1e-9 against GLPK), and the simplex ends at GLPK's optimum,
// feasible.
TEST(ChainSimplex, WarmFromTheLastVertexBoundsTheGapAtAnIterateShortOfIt) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> A(0.05, 0.95), G(-1.0, -0.05);
  int trials = 0, solved = 0, moved = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const GreedyWindow w = greedy_window(rng);
    ASSERT_EQ(w.reach.outcome, Reachability::Outcome::Feasible) << "trial " << trial;
    const Chain& ch = w.ch;
    const Eigen::VectorXd &theta = w.reach.theta, &lo = w.lo, &hi = w.hi;
    const int m = w.m();
    ChainSimplex cs(ch, 0, m, lo, hi, 1, m - 1);
    Eigen::VectorXd g0(m + 1);
    for (int j = 0; j <= m; ++j) g0[j] = G(rng);
    if (!std::isfinite(cs.gap(theta, g0, 1000))) continue;
    ++trials;
    const Eigen::VectorXd v = cs.vertex();
    const Eigen::VectorXd it = theta + A(rng) * (v - theta);
    if ((it - v).cwiseAbs().maxCoeff() > 1e-9) ++moved;  // the iterate is not the vertex the simplex stands on
    const Eigen::VectorXd g = grad_T(ch, it);
    const double gap = cs.gap(it, g, 1000, true);
    if (!std::isfinite(gap)) continue;
    ++solved;
    expect_certified(ch, lo, hi, cs, it, g, gap, trial);
    EXPECT_TRUE(cs.fresh_state(g)) << "trial " << trial;
  }
  EXPECT_GE(trials, 190);
  // Most iterates are off the vertex (on the others the first objective was already optimal at θ_g).
  EXPECT_GE(moved, trials / 2);
  EXPECT_GE(solved, trials * 95 / 100);
}

// forward_pass with caps reuses the analysis's own greedy profile where it runs along it
// (Reachability::theta_is_greedy): the same profile, to the bit, as slicing every interval. Caps at, above and
// below the greedy profile on 200 seeded random chains.
TEST(ForwardPass, ReusingTheGreedyProfileChangesNothing) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> F(0.8, 1.2);
  int reused = 0;
  for (int trial = 0; trial < 200; ++trial) {
    GreedyWindow w = greedy_window(rng);
    Reachability& reach = w.reach;
    ASSERT_EQ(reach.outcome, Reachability::Outcome::Feasible) << "trial " << trial;
    ASSERT_TRUE(reach.theta_is_greedy);
    const int m = w.m();
    // The greedy profile itself on a stretch, above it (no cap) and below it (a cap that binds) elsewhere.
    Eigen::VectorXd caps = reach.theta;
    for (int k = 0; k <= m; ++k)
      if ((k / 10) % 3 == 1) caps[k] *= F(rng);
    const Eigen::VectorXd fast = forward_pass(reach, 0.0, &caps);
    reach.theta_is_greedy = false;
    const Eigen::VectorXd slow = forward_pass(reach, 0.0, &caps);
    ASSERT_EQ(fast.size(), slow.size());
    for (int k = 0; k <= m; ++k) EXPECT_EQ(fast[k], slow[k]) << "trial " << trial << " k " << k;
    reused += (fast.array() == reach.theta.array()).count() > m / 4;
  }
  EXPECT_GT(reused, 150);  // the reuse is exercised: long stretches run along the greedy profile
}
