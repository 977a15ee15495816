// PolytopeProjector's single LPs on the projection's polytope (eq. 19): loading it into GLPK, a feasibility
// LP, and one maximisation along a direction. projection.cpp runs them in the recursive expansion (sec. IV.C).
#include "lp/projection.hpp"
#include "lp/projection_run.hpp"

#include "lp/glpk_util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glpk.h>

namespace pathpace::detail {

PolytopeProjector::~PolytopeProjector() = default;

int PolytopeProjector::load(const PolytopeLp& in) {
  const int rows = static_cast<int>(in.A.rows()), cols = static_cast<int>(in.A.cols());
  // A problem freed by a GLPK error (get() == nullptr) is created again, cold.
  const bool warm = lp_.get() != nullptr && rows == rows_ && cols == cols_;
  if (!warm) {
    rows_ = cols_ = -1;
    if (!lp_.create()) return -1;
  }
  dense_triplets(in.A, ia_, ja_, ar_);
  glp_prob* lp = lp_.get();
  const bool ok = guarded([&] {
    if (!warm) {
      glp_set_obj_dir(lp, GLP_MAX);
      if (rows > 0) glp_add_rows(lp, rows);
      if (cols > 0) glp_add_cols(lp, cols);
    }
    for (int i = 0; i < rows; ++i) glpk_set_bounds(lp, true, i + 1, in.row_lo[i], in.row_hi[i]);
    for (int j = 0; j < cols; ++j) glpk_set_bounds(lp, false, j + 1, in.col_lo[j], in.col_hi[j]);
    glpk_load_triplets(lp, ia_, ja_, ar_);
    // A new problem starts from an advanced basis; a reloaded one keeps the previous point's statuses.
    if (!warm) glp_adv_basis(lp, 0);
  });
  if (!ok) return -1;
  rows_ = rows;
  cols_ = cols;
  return warm ? 1 : 0;
}

bool projection_simplex_parameters(int rows, int cols, glp_smcp& parm) {
  if (!guarded([&] { glp_init_smcp(&parm); })) return false;  // it only fills the struct, but it is GLPK
  parm.msg_lev = GLP_MSG_OFF;
  // No scaling, no presolve: GLPK's automatic scaling was seen to make the primal simplex declare small,
  // plainly feasible projection LPs infeasible (rows of torque balance next to stand-in bounds of 1e6).
  parm.presolve = GLP_OFF;
  // Never a hang: a cycling simplex ends as a failure, and is retried (glpk_solve_robust). A warm
  // solve takes a few dozen pivots, a cold one at most a few times rows + cols.
  parm.it_lim = 10 * (rows + cols) + 100;
  // GLPK's default bound tolerance (1e-7, relative to each bound) lets an optimum lie outside the
  // polytope by more than the 1e-9 of the polygon's size that the projection certifies, and hides
  // vertices of short edges; these small dense LPs solve as reliably at 1e-10.
  parm.tol_bnd = 1e-10;
  parm.tol_dj = 1e-10;
  return true;
}

int PolytopeProjector::feasible(const PolytopeLp& in, const double* fix) {
  glp_smcp parm;
  if (!projection_simplex_parameters(static_cast<int>(in.A.rows()), static_cast<int>(in.A.cols()), parm) || load(in) < 0) return -1;
  glp_prob* lp = lp_.get();
  int st = -1;
  const bool ok = guarded([&] {
    if (fix) {
      glpk_set_bounds(lp, false, 1, fix[0], fix[0]);
      glpk_set_bounds(lp, false, 2, fix[1], fix[1]);
    }
    glp_set_obj_coef(lp, 1, 0.0);
    glp_set_obj_coef(lp, 2, 0.0);
    st = glpk_solve_robust(lp, parm);
    if (fix) {  // the next projection reloads the bounds anyway; restore them for a warm feasible() too
      glpk_set_bounds(lp, false, 1, in.col_lo[0], in.col_hi[0]);
      glpk_set_bounds(lp, false, 2, in.col_lo[1], in.col_hi[1]);
    }
  });
  if (!ok) return -1;
  return st == GLP_OPT ? 1 : st == GLP_NOFEAS ? 0 : -1;
}

namespace {

// FixedColumn's ranging (projection.hpp), inside maximize()'s guarded call. The column is nonbasic at
// its fixed value; glp_analyze_bound moves that value until a basic variable reaches a bound (the basis
// then stops being primal feasible; its dual feasibility does not depend on bounds), and the objective
// moves along by the column's reduced cost in between (LP sensitivity to a bound). `row_norm`: in.A's
// row norms, for the label (computed outside the guarded call).
void fixed_column(glp_prob* lp, const PolytopeLp& in, const double* row_norm, PolytopeProjector::FixedColumn& f) {
  const int rows = static_cast<int>(in.A.rows()), j = f.column + 1;
  const double t0 = glp_get_col_prim(lp, j);
  // The reduced cost bounds the optimum at every value by weak duality (the dual solution stays feasible
  // whatever the column's bound), also where the range is not known.
  f.slope = glp_get_col_dual(lp, j);
  f.from = f.to = t0;
  if (glp_bf_exists(lp) && glp_get_col_stat(lp, j) != GLP_BS) {
    double v1 = 0.0, v2 = 0.0;
    int var1 = 0, var2 = 0;
    glp_analyze_bound(lp, rows + j, &v1, &var1, &v2, &var2);
    f.from = std::min(v1, t0);  // -DBL_MAX / +DBL_MAX: no basic variable limits the range that way
    f.to = std::max(v2, t0);
  }
  // What stops the optimum, the fixed columns 0 and 1 (x, u) left out.
  f.binding = f.label ? glpk_binding(lp, in, row_norm, 2) : kBindingUnknown;
}

}  // namespace

int PolytopeProjector::maximize(const PolytopeLp& in, const Eigen::VectorXd& c, Eigen::VectorXd& z, FixedColumn* fixed,
                                std::vector<signed char>* basis) {
  glp_smcp parm;
  if (!projection_simplex_parameters(static_cast<int>(in.A.rows()), static_cast<int>(in.A.cols()), parm) || load(in) < 0)
    return -2;
  glp_prob* lp = lp_.get();
  const int rows = rows_, cols = cols_;
  z_.resize(static_cast<size_t>(cols));
  if (fixed && fixed->label) row_norm_ = in.A.rowwise().norm();
  if (basis) basis->resize(static_cast<size_t>(rows + cols));
  const double* norm = row_norm_.data();
  double* zp = z_.data();
  const double* cp = c.data();
  int st = -1;
  const bool ok = guarded([&] {
    for (int j = 0; j < cols; ++j) glp_set_obj_coef(lp, j + 1, cp[j]);
    st = glpk_solve_robust(lp, parm);
    if (st == GLP_OPT) {
      for (int j = 0; j < cols; ++j) zp[j] = glp_get_col_prim(lp, j + 1);
      if (fixed) fixed_column(lp, in, norm, *fixed);
      if (basis) glpk_get_basis(lp, rows, cols, basis->data());
    }
    for (int j = 0; j < cols; ++j) glp_set_obj_coef(lp, j + 1, 0.0);  // project() sets only x's and u's
  });
  if (!ok) return -2;
  if (st != GLP_OPT) return st == GLP_NOFEAS ? 0 : -1;
  z = Eigen::Map<const Eigen::VectorXd>(z_.data(), cols);
  return 1;
}

}  // namespace pathpace::detail
