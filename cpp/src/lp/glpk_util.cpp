#include "lp/glpk_util.hpp"

#include <cmath>

namespace pathpace::detail {

void glpk_set_bounds(glp_prob* lp, bool row, int i, double lo, double hi) {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  const int type = has_lo && has_hi ? (lo == hi ? GLP_FX : GLP_DB) : has_lo ? GLP_LO : has_hi ? GLP_UP : GLP_FR;
  (row ? glp_set_row_bnds : glp_set_col_bnds)(lp, i, type, has_lo ? lo : 0.0, has_hi ? hi : 0.0);
}

void dense_triplets(const Eigen::MatrixXd& A, std::vector<int>& ia, std::vector<int>& ja, std::vector<double>& ar) {
  ia.assign(1, 0);  // GLPK's arrays are 1-based
  ja.assign(1, 0);
  ar.assign(1, 0.0);
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index j = 0; j < A.cols(); ++j)
      if (A(i, j) != 0.0) {
        ia.push_back(static_cast<int>(i) + 1);
        ja.push_back(static_cast<int>(j) + 1);
        ar.push_back(A(i, j));
      }
}

void glpk_load_triplets(glp_prob* lp, const std::vector<int>& ia, const std::vector<int>& ja, const std::vector<double>& ar) {
  glp_load_matrix(lp, static_cast<int>(ar.size()) - 1, ia.data(), ja.data(), ar.data());
}

void glpk_get_basis(glp_prob* lp, int rows, int cols, signed char* stat) {
  for (int i = 0; i < rows; ++i) stat[i] = static_cast<signed char>(glp_get_row_stat(lp, i + 1));
  for (int j = 0; j < cols; ++j) stat[rows + j] = static_cast<signed char>(glp_get_col_stat(lp, j + 1));
}

namespace {

// One simplex run: GLP_OPT, GLP_NOFEAS, or 0 when it did not finish (an iteration limit, a singular
// basis, a status neither optimal nor infeasible).
int simplex_run(glp_prob* lp, const glp_smcp& parm) {
  const int ret = glp_simplex(lp, &parm);
  const int st = glp_get_status(lp);
  return ret == 0 && (st == GLP_OPT || st == GLP_NOFEAS) ? st : 0;
}

// The exact simplex from the current basis (the last floating-point run's: usually a few rational pivots
// from the answer), else from the slack basis (many: hundreds of ms on a humanoid's LP).
int exact_run(glp_prob* lp, const glp_smcp& parm) {
  if (glp_exact(lp, &parm) != 0) {
    glp_std_basis(lp);
    if (glp_exact(lp, &parm) != 0) return -1;
  }
  const int st = glp_get_status(lp);
  return st == GLP_OPT || st == GLP_NOFEAS ? st : -1;
}

}  // namespace

int glpk_solve_robust(glp_prob* lp, const glp_smcp& parm, bool exact_confirmation) {
  const int first = simplex_run(lp, parm);
  if (first == GLP_OPT) return GLP_OPT;
  // Again from the slack basis, after an infeasibility too: a floating-point optimum from either basis
  // is accepted. A plan point on a torque boundary gives a force LP that is empty by rounding only (the
  // exact simplex says so), and the force distribution needs the floating-point optimum there. The dual
  // simplex when the primal one stalled (a degenerate cycle was seen to use the whole iteration limit on
  // a humanoid carrying a box).
  glp_smcp retry = parm;
  if (first == 0) retry.meth = GLP_DUALP;
  glp_std_basis(lp);
  int st = simplex_run(lp, retry);
  if (st == 0) {
    // Both stalled (phase 1 of a 37 x 154 contact LP at a relaxed torque scale, seen to take the whole
    // limit from both bases): the textbook pricing and ratio test from the slack basis once more, which
    // takes another pivot sequence, before the exact simplex.
    retry.pricing = GLP_PT_STD;
    retry.r_test = GLP_RT_STD;
    glp_std_basis(lp);
    st = simplex_run(lp, retry);
  }
  if (st == GLP_OPT) return GLP_OPT;
  // Two simplex runs from different bases agree (the warm one and the slack basis), or the slack basis's
  // runs alone after a stall: enough for a projection, whose infeasibility claims solve() re-checks
  // exactly before reporting them.
  if (st == GLP_NOFEAS && !exact_confirmation) return GLP_NOFEAS;
  return exact_run(lp, parm);
}

}  // namespace pathpace::detail
