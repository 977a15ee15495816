// The analyses by lines (solve/line_reachability.hpp) against the polygons' (solve/reachability.hpp) on the
// same chains: seeded random arm-like paths under velocity and acceleration limits, on uniform and on
// non-uniform grids whose intervals span three decades; and each case in which they must give way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "solve/line_reachability.hpp"
#include "solve/pipeline.hpp"
#include "solve/slp.hpp"

using namespace pathpace;
using namespace pathpace::detail;

namespace {

// A path of `joints` smooth random joints (a few sines, so that p' changes sign and the acceleration rows
// couple θ_k and θ_{k+1} positively near the reversals) sampled on n intervals, uniform or with Δs spread over
// three decades; |q̇_j| <= v_j, |q̈_j| <= a_j as rows a x + b u <= c.
struct ArmCase {
  PathSamples samples;
  std::vector<ConstraintRows> rows;
};

ArmCase arm_case(std::mt19937& rng, int n, int joints, bool uniform) {
  std::uniform_real_distribution<double> U(-1.0, 1.0), H(0.5, 2.0), E(-3.0, 0.0);
  ArmCase c;
  PathSamples& ps = c.samples;
  ps.s.resize(n + 1);
  ps.s[0] = 0.0;
  for (int k = 0; k < n; ++k) ps.s[k + 1] = ps.s[k] + (uniform ? 1.0 : std::pow(10.0, E(rng)));
  ps.s /= ps.s[n];
  ps.s[n] = 1.0;
  ps.q.resize(n + 1, joints);
  ps.dq.resize(n + 1, joints);
  ps.ddq.resize(n + 1, joints);
  ConstraintRows r;
  r.resize(n + 1, 3 * joints);
  for (int j = 0; j < joints; ++j) {
    const double amp = U(rng), w = 3 + 6 * H(rng), ph = U(rng), off = 0.3 * U(rng);
    const double v = H(rng), a = 4 * H(rng);
    r.labels.push_back("velocity " + std::to_string(j));
    r.labels.push_back("acceleration+ " + std::to_string(j));
    r.labels.push_back("acceleration- " + std::to_string(j));
    for (int k = 0; k <= n; ++k) {
      const double s = ps.s[k];
      ps.q(k, j) = -amp / w * std::cos(w * s + ph) + off * s;
      const double d1 = amp * std::sin(w * s + ph) + off, d2 = amp * w * std::cos(w * s + ph);
      ps.dq(k, j) = d1;
      ps.ddq(k, j) = d2;
      r.a(k, 3 * j) = d1 * d1;
      r.c(k, 3 * j) = v * v;
      for (int sgn : {0, 1}) {
        const double m = sgn ? -1.0 : 1.0;
        r.a(k, 3 * j + 1 + sgn) = m * d2;
        r.b(k, 3 * j + 1 + sgn) = m * d1;
        r.c(k, 3 * j + 1 + sgn) = a;
      }
    }
  }
  c.rows = {r};
  return c;
}

double rel_diff(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

// A chain of one joint by hand: x_lo = 0, x_hi = 1 at every point, rows `rows` on every interval.
Chain hand_chain(int n, const std::vector<Line>& rows) {
  Chain ch;
  ch.ds = Eigen::VectorXd::Constant(n, 1.0 / n);
  ch.x_lo = Eigen::VectorXd::Zero(n + 1);
  ch.x_hi = Eigen::VectorXd::Ones(n + 1);
  ch.x_lo_id.assign(static_cast<size_t>(n) + 1, -1);
  ch.x_hi_id.assign(static_cast<size_t>(n) + 1, -1);
  ch.row_offset.push_back(0);
  for (int k = 0; k < n; ++k) {
    for (const Line& l : rows) ch.row_data.push_back(l);
    ch.coupled_offset.push_back(ch.row_data.size());
    ch.row_offset.push_back(ch.row_data.size());
  }
  return ch;
}

}  // namespace

// On 120 seeded chains (2-7 joints, 20-400 intervals, half of them non-uniform): where the lines take the
// case, K's tops and both greedy profiles are the polygons' to rounding (1e-12 relative to the largest θ), and
// the capped pass (the SLP's repair) is theirs under caps above, at and below the greedy profile. The common
// case is the usual one: the lines take (nearly) every chain.
TEST(LineReachability, SameAnalysesAsThePolygons) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> F(0.7, 1.1);
  int taken = 0, coupled = 0, compared = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const int joints = 2 + static_cast<int>(rng() % 6), n = 20 + static_cast<int>(rng() % 381);
    const ArmCase c = arm_case(rng, n, joints, trial % 2 == 0);
    const SetsStage sets = grid_sets_stage(c.samples, c.rows, 0.0, 0.0);
    ASSERT_FALSE(sets.stop) << "trial " << trial;
    const Chain ch = build_chain(c.samples.s, sets.sets, nullptr, sets.scale);
    coupled += !ch.lattice;
    Reachability relaxed, full;
    ASSERT_TRUE(reachability_pair(ch, 0.0, 0.0, relaxed, full)) << "trial " << trial;
    LineAnalysis lr, lf;
    if (!line_analysis(ch, true, 0.0, 0.0, lr) || !line_analysis(ch, false, 0.0, 0.0, lf)) continue;
    ++taken;
    EXPECT_LE(rel_diff(lr.k_hi, relaxed.k_hi), 1e-12) << "trial " << trial;
    EXPECT_LE(rel_diff(lf.k_hi, full.k_hi), 1e-12) << "trial " << trial;
    EXPECT_LE(rel_diff(lr.theta, relaxed.theta), 1e-12) << "trial " << trial;
    EXPECT_LE(rel_diff(lf.theta, full.theta), 1e-12) << "trial " << trial;
    Eigen::VectorXd caps = full.theta;
    for (int k = 0; k <= n; ++k)
      if ((k / 7) % 3 == 1) caps[k] *= F(rng);
    const Eigen::VectorXd by_lines = line_forward_pass(ch, lf, 0.0, caps);
    const Eigen::VectorXd by_polygons = forward_pass(full, 0.0, &caps);
    EXPECT_LE(rel_diff(by_lines, by_polygons), 1e-10) << "trial " << trial;
    EXPECT_EQ(by_lines[0], 0.0);
    EXPECT_EQ(by_lines[n], 0.0);
    ++compared;
  }
  EXPECT_GE(taken, 114);
  EXPECT_GE(coupled, 60);  // the coupling rows (the full analysis differs from the relaxed one) are exercised
  EXPECT_EQ(compared, taken);
}

// The stage takes the lines where they apply, and its answer is then the polygons' (Method::Slp runs neither
// the lines nor the bracket: whole-chain SLP on the polygons' analysis), to the tolerance.
TEST(LineReachability, StageAnswerIsThePolygonPipelines) {
  std::mt19937 rng(7);
  int by_lines = 0, trials = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 50 + static_cast<int>(rng() % 200);
    const ArmCase c = arm_case(rng, n, 2 + static_cast<int>(rng() % 5), trial % 2 == 0);
    const SetsStage sets = grid_sets_stage(c.samples, c.rows, 0.0, 0.0);
    ASSERT_FALSE(sets.stop);
    SolverOptions auto_opts, slp_opts;
    slp_opts.method = Method::Slp;
    const ReachStage a = reachability_stage(c.samples, sets, nullptr, 0.0, 0.0, auto_opts);
    const ReachStage b = reachability_stage(c.samples, sets, nullptr, 0.0, 0.0, slp_opts);
    ASSERT_FALSE(a.stop);
    ASSERT_FALSE(b.stop);
    by_lines += a.lines != nullptr || a.reach.theta.size() == 0;
    const Certified ta = certify_stage(c.samples, sets, a, auto_opts, Budget::from(60.0));
    const Certified tb = certify_stage(c.samples, sets, b, slp_opts, Budget::from(60.0));
    ASSERT_EQ(ta.status, Status::Optimal) << ta.message;
    ASSERT_EQ(tb.status, Status::Optimal) << tb.message;
    const double Ta = duration(a.chain.ds, ta.theta), Tb = duration(b.chain.ds, tb.theta);
    EXPECT_NEAR(Ta, Tb, 2e-7 * Tb) << "trial " << trial;  // each within the tolerance (1e-7) of T*
    // The library's contract: 1e-12 where the lines' repair made it (3.2e-13 at most here), 1e-9 where the
    // polygons repaired again (by_slp), which another CPU's rounding may pick.
    EXPECT_LE(grid_violation(a.chain, sets.sets, ta.theta, nullptr), 1e-9) << "trial " << trial;
    ++trials;
  }
  EXPECT_GE(by_lines, trials - 2);
}

// Where the common case does not hold, line_analysis says so (and the polygons decide).
TEST(LineReachability, GivesWayOutsideTheCommonCase) {
  const Line up{0.0, 1.0, 0.5, 0}, down{0.0, -1.0, 0.5, 1};  // |θ_{k+1}| <= 0.5, as a speed bound after each step
  LineAnalysis a;
  // The common case itself: from rest to rest under y <= 0.5.
  const Chain plain = hand_chain(8, {up, down});
  ASSERT_TRUE(line_analysis(plain, false, 0.0, 0.0, a));
  EXPECT_EQ(a.k_hi[0], 1.0);
  EXPECT_EQ(a.theta[1], 0.5);
  EXPECT_EQ(a.theta[8], 0.0);
  // A row bounding θ_k from below above x_lo (-θ_k <= -0.25): K_k's bottom is not x_lo.
  EXPECT_FALSE(line_analysis(hand_chain(8, {up, {-1.0, 0.0, -0.25, 2}}), false, 0.25, 0.25, a));
  // A row that no θ_k meets (0 θ_k + 0 θ_{k+1} <= -1).
  EXPECT_FALSE(line_analysis(hand_chain(8, {up, {0.0, 0.0, -1.0, 3}}), false, 0.0, 0.0, a));
  // The end speed outside [x_lo, x_hi] at s_N, or unreachable in one step (θ_N = 0.9 > 0.5).
  EXPECT_FALSE(line_analysis(plain, false, 0.0, 2.0, a));
  EXPECT_FALSE(line_analysis(plain, false, 0.0, 0.9, a));
  // A start speed above K_0's top (1).
  EXPECT_FALSE(line_analysis(plain, false, 1.5, 0.0, a));
  // Nothing bounds the speed inside the path (x_hi at the cap, no row on θ_k): the polygons report it.
  Chain open = hand_chain(8, {});
  open.x_hi.setConstant(open.cap);
  EXPECT_FALSE(line_analysis(open, false, 0.0, 0.0, a));
  // θ_{k+1} <= θ_k - 2 with θ_{k+1} >= 0 leaves no θ_k in [0, 1]: K_k is empty (the polygons name the rows).
  EXPECT_FALSE(line_analysis(hand_chain(8, {{-1.0, 1.0, -2.0, 4}, down}), false, 0.0, 0.0, a));
}

// On a fine grid whose intervals span three decades (N = 10^5) a line's value is exact to eps θ, which is
// eps θ / (2Δs) in s̈: the proven profile breaks a grid row by ~1e-10 before the exact-feasibility step
// scales it to 1e-12, at a cost in T that the gap carries. Its T is then inside the polygons' bracket.
TEST(LineReachability, FineGridProofIsMadeExact) {
  std::mt19937 rng(11);
  const ArmCase c = arm_case(rng, 100000, 6, false);
  const SetsStage sets = grid_sets_stage(c.samples, c.rows, 0.0, 0.0);
  ASSERT_FALSE(sets.stop);
  SolverOptions options;
  const ReachStage reach = reachability_stage(c.samples, sets, nullptr, 0.0, 0.0, options);
  ASSERT_FALSE(reach.stop);
  ASSERT_EQ(reach.reach.theta.size(), 0);  // the lines stood in for the polygons
  ASSERT_TRUE(reach.proven);
  EXPECT_LE(grid_violation(reach.chain, sets.sets, reach.theta, nullptr), 1e-12);
  // The step had work to do: the bracket proved the full profile (θ' breaks a coupling row), which the lines
  // leave breaking a row by more than rounding (1.0e-10 here, 100x the 1e-12 it is made to meet).
  LineAnalysis lr, lf;
  ASSERT_TRUE(line_analysis(reach.chain, true, 0.0, 0.0, lr));
  ASSERT_TRUE(line_analysis(reach.chain, false, 0.0, 0.0, lf, &lr));
  EXPECT_GT(coupled_violation(reach.chain, lr.theta), 1e-12);
  EXPECT_GT(grid_violation(reach.chain, sets.sets, lf.theta, nullptr), 1e-12);
  Reachability relaxed, full;
  ASSERT_TRUE(reachability_pair(reach.chain, 0.0, 0.0, relaxed, full));
  const double T = duration(reach.chain.ds, reach.theta), lower = duration(reach.chain.ds, relaxed.theta);
  EXPECT_GE(T, lower * (1 - 1e-12));
  EXPECT_LE(T, lower * (1 + reach.gap + 1e-12));
  EXPECT_LE(reach.gap, options.tolerance);
}
