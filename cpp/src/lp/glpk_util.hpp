#pragma once
// GLPK steps shared by the polytope projection and the force-distribution LP (never installed).
// The glpk_ functions call GLPK: run them inside guarded() (glpk_guard.hpp).

#include <vector>

#include <Eigen/Core>
#include <glpk.h>

namespace pathpace::detail {

/// Row (row = true) or column i (1-based) bounded by lo <= . <= hi; ±inf for an absent side, lo == hi
/// an equality.
void glpk_set_bounds(glp_prob* lp, bool row, int i, double lo, double hi);

/// The nonzeros of a dense matrix as GLPK's 1-based triplets (entry 0 unused), for glp_load_matrix
/// (called before the guarded call: it fills containers).
void dense_triplets(const Eigen::MatrixXd& A, std::vector<int>& ia, std::vector<int>& ja, std::vector<double>& ar);
/// glp_load_matrix of such triplets.
void glpk_load_triplets(glp_prob* lp, const std::vector<int>& ia, const std::vector<int>& ja, const std::vector<double>& ar);

/// The statuses of the current basis (GLP_BS, GLP_NL, ...): rows' into stat[0, rows), columns' after them.
void glpk_get_basis(glp_prob* lp, int rows, int cols, signed char* stat);

/// The simplex from the current basis (a warm start); if it stalls, fails or finds no feasible point, again
/// from the slack basis (and once more with textbook pricing if that stalls too); if that still does not
/// end optimal, in exact rational arithmetic, which also confirms an infeasibility (a claim about the
/// robot, so it is checked exactly, starting from the basis the floating-point run ended in). Without
/// exact_confirmation an infeasibility found from the slack basis is returned as is (exact arithmetic
/// costs many simplex solves on a humanoid's LP; the projection's emptiness claims are re-checked exactly
/// by solve()). Returns GLP_OPT, GLP_NOFEAS, or -1 when the solver did not finish.
int glpk_solve_robust(glp_prob* lp, const glp_smcp& parm, bool exact_confirmation = true);

/// The simplex parameters of the projection's LPs (rows x cols): no scaling or presolve, an iteration cap,
/// tight bound and reduced-cost tolerances (projector_lp.cpp says why). False after a GLPK error (parm is
/// then not set).
bool projection_simplex_parameters(int rows, int cols, glp_smcp& parm);

}  // namespace pathpace::detail
