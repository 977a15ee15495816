// glpk_solve_robust: every branch of its cascade (warm run, slack-basis retry, textbook retry, exact
// simplex from the last basis or from the slack basis) ends in the LP's true status and optimum.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glpk.h>

#include "lp/glpk_guard.hpp"
#include "lp/glpk_util.hpp"

using namespace pathpace::detail;

namespace {

// max x1 + x2 + ... + xn over 0 <= x_j <= 1, Σ_j x_j <= n - 1/2 (optimum n - 1/2: n pivots from the slack
// basis), and, when `infeasible`, also Σ_j x_j >= n (empty). Every column is nonzero in every row, so the
// dual and primal simplex need several pivots: an iteration limit of 1 stalls every floating-point run.
struct SmallLp {
  GlpkProblem problem;
  std::vector<int> ia, ja;
  std::vector<double> ar;

  explicit SmallLp(int n, bool infeasible) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Ones(infeasible ? 2 : 1, n);
    dense_triplets(A, ia, ja, ar);
    EXPECT_TRUE(problem.create());
    glp_prob* lp = problem.get();
    EXPECT_TRUE(guarded([&] {
      glp_set_obj_dir(lp, GLP_MAX);
      glp_add_rows(lp, static_cast<int>(A.rows()));
      glp_add_cols(lp, n);
      glpk_set_bounds(lp, true, 1, -INFINITY, n - 0.5);
      if (infeasible) glpk_set_bounds(lp, true, 2, n, INFINITY);
      for (int j = 1; j <= n; ++j) {
        glpk_set_bounds(lp, false, j, 0.0, 1.0);
        glp_set_obj_coef(lp, j, 1.0);
      }
      glpk_load_triplets(lp, ia, ja, ar);
    }));
  }

  // The return code of one plain glp_simplex from the slack basis with that limit (the precondition:
  // GLP_EITLIM means the cascade's floating-point runs stall).
  int plain(int it_lim) {
    glp_prob* lp = problem.get();
    glp_smcp parm;
    EXPECT_TRUE(projection_simplex_parameters(glp_get_num_rows(lp), glp_get_num_cols(lp), parm));
    parm.it_lim = it_lim;
    int ret = -2;
    EXPECT_TRUE(guarded([&] {
      glp_std_basis(lp);
      ret = glp_simplex(lp, &parm);
    }));
    return ret;
  }

  // The status glpk_solve_robust returns with the iteration limit `it_lim`, and the objective if optimal.
  int solve(int it_lim, bool exact_confirmation, double& objective) {
    glp_prob* lp = problem.get();
    glp_smcp parm;
    EXPECT_TRUE(projection_simplex_parameters(glp_get_num_rows(lp), glp_get_num_cols(lp), parm));
    parm.it_lim = it_lim;
    int st = -2;
    EXPECT_TRUE(guarded([&] {
      glp_std_basis(lp);
      st = glpk_solve_robust(lp, parm, exact_confirmation);
      objective = glp_get_obj_val(lp);
    }));
    return st;
  }
};

}  // namespace

TEST(GlpkSolveRobust, FeasibleLpIsOptimalWhetherOrNotTheSimplexStalls) {
  for (int it_lim : {1000, 1}) {
    for (bool exact : {false, true}) {
      SmallLp lp(8, false);
      EXPECT_EQ(lp.plain(it_lim), it_lim == 1 ? GLP_EITLIM : 0);
      double obj = 0.0;
      EXPECT_EQ(lp.solve(it_lim, exact, obj), GLP_OPT) << "it_lim " << it_lim;
      EXPECT_NEAR(obj, 7.5, 1e-12) << "it_lim " << it_lim;
    }
  }
}

TEST(GlpkSolveRobust, EmptyLpIsInfeasibleWhetherOrNotTheSimplexStalls) {
  // it_lim 1000: the floating-point runs find it (exact confirmation from their basis, or none); 1: every
  // floating-point run stalls, so the exact simplex decides, from the stalled run's basis.
  for (int it_lim : {1000, 1}) {
    for (bool exact : {false, true}) {
      SmallLp lp(8, true);
      EXPECT_EQ(lp.plain(it_lim), it_lim == 1 ? GLP_EITLIM : 0);
      double obj = 0.0;
      EXPECT_EQ(lp.solve(it_lim, exact, obj), GLP_NOFEAS) << "it_lim " << it_lim << " exact " << exact;
    }
  }
}
