// The slices' LPs (lp/slice_lp.hpp) and the dense simplex's dual phase they rely on: started from the
// previous sample's optimal basis, whose point the next sample's LP no longer contains.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glpk.h>

#include "lp/dense_simplex.hpp"
#include "lp/projection.hpp"
#include "lp/slice_lp.hpp"
#include "test_fixtures.hpp"

using namespace pathpace::detail;
using pathpace::test::one_row_lp;

namespace {

// A projection polytope of eq. (19)'s shape that moves with a parameter t: columns x in [0, 1000], u
// fixed at u(t), p "forces" f >= 0; `eq` equality rows (a wrench balance) and `in` inequality rows (torque
// limits), A(t) = A0 + t D. A point z0 (f > 0) is kept feasible at every t: the equalities' right side is
// A(t) z0, each inequality's bound is A(t) z0 plus a seeded margin.
struct MovingPolytope {
  Eigen::MatrixXd A0, D;
  Eigen::VectorXd z0, margin;
  int eq = 0;
  MovingPolytope(unsigned seed, int eq_rows, int in_rows, int p) : eq(eq_rows) {
    std::mt19937 gen(seed);
    std::normal_distribution<double> n01(0.0, 1.0);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int m = eq_rows + in_rows, n = 2 + p;
    A0 = Eigen::MatrixXd::NullaryExpr(m, n, [&] { return n01(gen); });
    D = Eigen::MatrixXd::NullaryExpr(m, n, [&] { return n01(gen); });
    z0 = Eigen::VectorXd::NullaryExpr(n, [&] { return 0.2 + unit(gen); });
    z0[0] = 10.0 * unit(gen);
    margin = Eigen::VectorXd::NullaryExpr(in_rows, [&] { return 0.1 + 2.0 * unit(gen); });
  }
  PolytopeLp at(double t, double u) const {
    PolytopeLp lp;
    lp.A = A0 + t * D;
    Eigen::VectorXd z = z0;
    z[1] = u;
    const Eigen::VectorXd v = lp.A * z;
    const Eigen::Index m = lp.A.rows(), n = lp.A.cols();
    lp.row_lo.resize(m);
    lp.row_hi.resize(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      lp.row_hi[i] = i < eq ? v[i] : v[i] + margin[i - eq];
      lp.row_lo[i] = i < eq ? v[i] : -INFINITY;
    }
    lp.col_lo = Eigen::VectorXd::Zero(n);
    lp.col_hi = Eigen::VectorXd::Constant(n, INFINITY);
    lp.col_hi[0] = 1000.0;
    lp.col_lo[1] = lp.col_hi[1] = u;
    return lp;
  }
};

}  // namespace

TEST(SliceLp, EverySampleAgreesWithGlpkAndTheDenseSimplexAnswersMost) {
  // 8 seeded polytopes, 60 samples each along t, both ends of every slice against a fresh GLPK solve (the
  // oracle: no warm start), to 1e-9 of the polytope's x range. The dense simplex must answer most of them
  // from the previous sample's basis, and some only after dual simplex pivots (the start outside the
  // polytope: set_basis asks feasibility and refuses it).
  int dense = 0, glpk = 0, outside = 0, compared = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const MovingPolytope mp(seed, 6, 10, 24);
    SliceLp slices;
    std::vector<signed char> last[2];
    for (int k = 0; k < 60; ++k) {
      const double t = 0.004 * k, u = 0.3 * std::sin(0.1 * k);
      const PolytopeLp lp = mp.at(t, u);
      slices.load(lp);
      for (double sign : {1.0, -1.0}) {
        PolytopeProjector::FixedColumn fixed;
        double x = NAN;
        const int st = slices.extreme(sign, x, &fixed);
        PolytopeProjector oracle;
        Eigen::VectorXd c = Eigen::VectorXd::Zero(lp.A.cols()), z;
        c[0] = sign;
        std::vector<signed char> basis;
        ASSERT_EQ(oracle.maximize(lp, c, z, nullptr, &basis), 1) << "seed " << seed << " k " << k;
        ASSERT_EQ(st, 1) << "seed " << seed << " k " << k << " sign " << sign;
        EXPECT_NEAR(x, z[0], 1e-9 * 1000.0) << "seed " << seed << " k " << k << " sign " << sign;
        EXPECT_LE(fixed.from, u);
        EXPECT_GE(fixed.to, u);
        ++compared;
        std::vector<signed char>& prev = last[sign > 0 ? 0 : 1];
        if (!prev.empty()) {
          DenseSimplex probe;
          probe.load(lp);
          if (!probe.set_basis(prev.data())) ++outside;
        }
        prev = basis;
      }
    }
    dense += slices.dense;
    glpk += slices.glpk;
  }
  EXPECT_EQ(compared, 8 * 60 * 2);
  EXPECT_EQ(dense + glpk, compared);
  EXPECT_GT(dense, 9 * glpk) << "dense " << dense << ", GLPK " << glpk;
  EXPECT_GT(outside, 20);
}

TEST(SliceLp, TheFixedColumnsSlopeAndRangeAreTheEdgeOfTheSlicesTop) {
  // max x subject to x + u <= 1.5, x >= 0, u fixed: the top is 1.5 - u (slope -1) for every u <= 1.5
  // (below -inf no basic variable stops it; at 1.5 x reaches its bound 0). The first sample is GLPK's,
  // the second the dense simplex's from its basis: both tell the same edge.
  PolytopeLp lp = one_row_lp(1, 1, -INFINITY, 1.5, Eigen::Vector2d(0, 0.5), Eigen::Vector2d(INFINITY, 0.5));
  SliceLp slices;
  for (int engine = 0; engine < 2; ++engine) {
    slices.load(lp);
    PolytopeProjector::FixedColumn fixed;
    fixed.label = true;
    double x = NAN;
    ASSERT_EQ(slices.extreme(1.0, x, &fixed), 1);
    EXPECT_EQ(slices.glpk, 1);
    EXPECT_EQ(slices.dense, engine);
    EXPECT_NEAR(x, 1.0, 1e-15);
    EXPECT_NEAR(fixed.slope, -1.0, 1e-15);
    EXPECT_LT(fixed.from, -1e300);
    EXPECT_NEAR(fixed.to, 1.5, 1e-15);
    EXPECT_EQ(fixed.binding, 1) << "engine " << engine;  // row 0's upper side: 2 i + 1
  }
  // An empty slice (u beyond 1.5: x would be negative) is GLPK's answer.
  lp.col_lo[1] = lp.col_hi[1] = 2.0;
  slices.load(lp);
  double x = NAN;
  EXPECT_EQ(slices.extreme(1.0, x, nullptr), 0);
  EXPECT_EQ(slices.glpk, 2);
}

TEST(SliceLp, ABottomWhoseStartTheDenseSimplexCannotRepairStartsFromTheTopsOptimumNotGlpk) {
  // max / min x subject to x <= 0.8 (row 0), x in [0, 1], u fixed at 0.5. The top starts from a basis with x
  // basic (primal feasible: x = 0.8). The bottom's start has row 0's auxiliary basic and x at its upper
  // bound 1: the row's value 1 is outside its bound, and along -x the reduced cost of x at its upper bound
  // improves, so it is not dual feasible either (DenseSimplex::kNotDualFeasible). The bottom then starts
  // from the top's optimum of the same LP (a vertex: primal feasible) and reaches x = 0 by the primal
  // simplex; GLPK answers nothing.
  const PolytopeLp lp = one_row_lp(1, 0, -INFINITY, 0.8, Eigen::Vector2d(0, 0.5), Eigen::Vector2d(1, 0.5));
  const std::vector<signed char> top_start = {GLP_NU, GLP_BS, GLP_NS}, bottom_start = {GLP_BS, GLP_NU, GLP_NS};
  DenseSimplex probe;
  probe.load(lp);
  ASSERT_TRUE(probe.set_basis(bottom_start.data(), false));
  ASSERT_EQ(probe.maximize(-1.0, 0.0), DenseSimplex::kNotDualFeasible);
  SliceLp slices;
  slices.load(lp);
  double top = NAN, bottom = NAN;
  ASSERT_EQ(slices.extreme(1.0, top, nullptr, &top_start), 1);
  ASSERT_EQ(slices.extreme(-1.0, bottom, nullptr, &bottom_start), 1);
  EXPECT_NEAR(top, 0.8, 1e-15);
  EXPECT_NEAR(bottom, 0.0, 1e-15);
  EXPECT_EQ(slices.dense, 2);
  EXPECT_EQ(slices.glpk, 0);
}

TEST(DenseSimplex, ADualPhaseGivesUpOnAStartThatIsNotDualFeasibleAndOnAnEmptyRow) {
  // x in [0, 1], u in [0, 1]; row 0: x >= 2 (nothing meets it). The basis {row 0's auxiliary} puts the
  // row's value 0 below its bound. Along -x its reduced costs are dual feasible: x enters up to 2 (above
  // its own bound 1), then x leaves at 1 and no nonbasic variable can raise the row again: a dual ray.
  // Along +x, x at its lower bound has an improving reduced cost: not dual feasible.
  PolytopeLp lp = one_row_lp(1, 0, 2.0, INFINITY, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  const signed char start[] = {GLP_BS, GLP_NL, GLP_NL};
  DenseSimplex ds;
  ds.load(lp);
  EXPECT_FALSE(ds.set_basis(start));  // primal infeasible: refused unless asked not to check
  ASSERT_TRUE(ds.set_basis(start, false));
  EXPECT_EQ(ds.maximize(-1.0, 0.0), DenseSimplex::kDualRay);
  ASSERT_TRUE(ds.set_basis(start, false));
  EXPECT_EQ(ds.maximize(1.0, 0.0), DenseSimplex::kNotDualFeasible);
  // Row 0 relaxed to x >= 0.5: the same start repairs in one dual pivot and ends at the optimum of -x.
  lp.row_lo[0] = 0.5;
  ds.load(lp);
  ASSERT_TRUE(ds.set_basis(start, false));
  const int before = ds.pivots;
  ASSERT_EQ(ds.maximize(-1.0, 0.0), DenseSimplex::kOptimal);
  EXPECT_NEAR(ds.x(), 0.5, 1e-15);
  EXPECT_EQ(ds.pivots - before, 1);
}

// The explicit inverse's structure that pricing and the pivots rely on (DenseSimplex::solve_column, replace):
// after primal and dual pivots, the column of B^-1 of every basic auxiliary is exactly -e at its position (not
// to rounding: the pivots skip the columns where the pivot row is zero), and B^-1 is the inverse of B.
TEST(DenseSimplex, ABasicAuxiliarysColumnOfTheInverseStaysExactlyAUnitVector) {
  int pivots = 0, checked = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const MovingPolytope mp(seed, 6, 10, 24);
    const PolytopeLp lp0 = mp.at(0.0, 0.1);
    PolytopeProjector oracle;
    Eigen::VectorXd c = Eigen::VectorXd::Zero(lp0.A.cols()), z;
    c[0] = 1.0;
    std::vector<signed char> basis;
    ASSERT_EQ(oracle.maximize(lp0, c, z, nullptr, &basis), 1);
    DenseSimplex ds;
    std::vector<PolytopeLp> lps;
    for (int k = 0; k < 8; ++k) lps.push_back(mp.at(0.01 * k, 0.1 + 0.05 * std::sin(k)));
    for (const PolytopeLp& lp : lps) {
      ds.load(lp);
      if (!ds.set_basis(basis.data(), false)) continue;
      for (double sign : {-1.0, 1.0, -1.0}) {
        if (ds.maximize(sign, 0.0) != DenseSimplex::kOptimal) break;
        const DenseSimplex::State& s = ds.state();
        const int m = static_cast<int>(lp.A.rows());
        Eigen::MatrixXd B(m, m);
        for (int i = 0; i < m; ++i) {
          const int k = s.head[static_cast<size_t>(i)];
          if (k < m) {
            B.col(i) = -Eigen::VectorXd::Unit(m, k);
            for (int r = 0; r < m; ++r) ASSERT_EQ(s.inv(r, k), r == i ? -1.0 : 0.0) << "seed " << seed << " aux " << k;
          } else {
            B.col(i) = lp.A.col(k - m);
          }
        }
        EXPECT_LE((s.inv * B - Eigen::MatrixXd::Identity(m, m)).cwiseAbs().maxCoeff(), 1e-9) << "seed " << seed;
        basis = s.stat;
        ++checked;
      }
    }
    pivots += ds.pivots;
  }
  EXPECT_GT(checked, 60);
  EXPECT_GT(pivots, 100);
}
