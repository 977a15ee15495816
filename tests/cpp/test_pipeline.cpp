// The solve's stages (solve/pipeline.hpp) on their own: a straight line in one joint under a speed and an
// acceleration limit, whose optimum is known in closed form, and the Stops that end a solve early.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "solve/pipeline.hpp"

using namespace pathpace;
using namespace pathpace::detail;

namespace {

// q(s) = s on [0, 1]: p' = 1, p'' = 0.
PathSamples line(int n) {
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(n + 1, 0.0, 1.0);
  ps.q = ps.s;
  ps.dq = Eigen::MatrixXd::Ones(n + 1, 1);
  ps.ddq = Eigen::MatrixXd::Zero(n + 1, 1);
  return ps;
}

// |q̇| <= v (ṡ² <= v²) and |q̈| <= a (|s̈| <= a) at every grid point: rows a x + b u <= c with x = ṡ², u = s̈.
std::vector<ConstraintRows> limits(Eigen::Index points, double v, double a) {
  ConstraintRows r;
  r.resize(points, 3);
  r.labels = {"speed", "accel upper", "accel lower"};
  for (Eigen::Index k = 0; k < points; ++k) {
    r.a(k, 0) = 1.0;
    r.c(k, 0) = v * v;
    r.b(k, 1) = 1.0;
    r.c(k, 1) = a;
    r.b(k, 2) = -1.0;
    r.c(k, 2) = a;
  }
  return {r};
}

SolverOptions defaults() { return SolverOptions(); }

}  // namespace

// No row couples θ_k and θ_{k+1} positively: the chain is a lattice, and the greedy profile from rest to rest
// is its greatest element θ_k = min(v², 2 a s_k, 2 a (1 - s_k)) (eq. 24: θ_{k+1} - θ_k = 2 Δs s̈), proven
// optimal without SLP; assembled, T is Σ 2Δs / (ṡ_k + ṡ_{k+1}) of that profile.
TEST(Pipeline, LatticeIsProvenWithoutSlp) {
  const int n = 40;
  const double v = 0.5, a = 2.0;
  const PathSamples ps = line(n);
  const SetsStage sets = grid_sets_stage(ps, limits(n + 1, v, a), 0.0, 0.0);
  ASSERT_FALSE(sets.stop);
  const ReachStage reach = reachability_stage(ps, sets, nullptr, 0.0, 0.0, defaults());
  ASSERT_FALSE(reach.stop);
  EXPECT_TRUE(reach.chain.lattice);
  EXPECT_TRUE(reach.proven);
  const Certified timing = certify_stage(ps, sets, reach, defaults(), Budget::from(60.0));
  EXPECT_EQ(timing.status, Status::Optimal);
  EXPECT_TRUE(timing.greatest_element);
  EXPECT_EQ(timing.slp_iterations, 0);
  Result res;
  assemble(ps.s, sets.scale, timing.theta, res);
  double T = 0.0;
  for (int k = 0; k < n; ++k) {
    auto sd = [&](int j) { return std::sqrt(std::min({v * v, 2 * a * ps.s[j], 2 * a * (1.0 - ps.s[j])})); };
    T += 2.0 * (ps.s[k + 1] - ps.s[k]) / (sd(k) + sd(k + 1));
    EXPECT_NEAR(res.sdot[k], sd(k), 1e-12) << k;
  }
  EXPECT_NEAR(res.duration, T, 1e-12 * T);
  EXPECT_NEAR(res.times[n], res.duration, 0.0);
}

// A boundary speed above its end point's bound stops at the grid-sets stage, naming the speed row.
TEST(Pipeline, FastBoundarySpeedStopsAtTheGridSets) {
  const PathSamples ps = line(10);
  const SetsStage sets = grid_sets_stage(ps, limits(11, 0.5, 2.0), 0.0, 0.75);
  ASSERT_TRUE(sets.stop);
  EXPECT_EQ(sets.stop->status, Status::Infeasible);
  EXPECT_EQ(sets.stop->k, 10);
  ASSERT_EQ(sets.stop->ids.size(), 1u);
  EXPECT_EQ(sets.sets.label(sets.stop->ids[0]), "speed");
  EXPECT_EQ(sets.stop->why.rfind("sdot_end = 0.75 is faster than the constraints allow at s_end", 0), 0u)
      << sets.stop->why;
}

// A row no (ṡ², s̈) meets at one grid point: an empty polygon there, the stage's Stop.
TEST(Pipeline, EmptyPolygonStopsAtTheGridSets) {
  const PathSamples ps = line(10);
  std::vector<ConstraintRows> rows = limits(11, 0.5, 2.0);
  rows[0].c(4, 0) = -1.0;  // ṡ² <= -1 at s = 0.4
  const SetsStage sets = grid_sets_stage(ps, rows, 0.0, 0.0);
  ASSERT_TRUE(sets.stop);
  EXPECT_EQ(sets.stop->status, Status::Infeasible);
  EXPECT_EQ(sets.stop->k, 4);
  EXPECT_EQ(sets.stop->why, "no (sdot^2, sddot) satisfies the constraints");
}

// Rest to rest with s̈ = 0 allowed only: the speed stays 0 on every interval, which the reachability stage
// reports as a Stop (the path cannot be traversed), not as a timing.
TEST(Pipeline, SpeedForcedToZeroStopsAtReachability) {
  const PathSamples ps = line(10);
  const SetsStage sets = grid_sets_stage(ps, limits(11, 0.5, 0.0), 0.0, 0.0);
  ASSERT_FALSE(sets.stop);
  const ReachStage reach = reachability_stage(ps, sets, nullptr, 0.0, 0.0, defaults());
  ASSERT_TRUE(reach.stop);
  EXPECT_EQ(reach.stop->status, Status::Infeasible);
}
