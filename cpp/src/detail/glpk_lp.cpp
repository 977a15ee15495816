#include "detail/glpk_lp.hpp"

#include "detail/glpk_guard.hpp"
#include "detail/glpk_util.hpp"

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <limits>
#include <cstdlib>

#include <vector>

#include <glpk.h>

namespace pathpace::detail {

extern "C" void pathpace_glpk_error_hook(void* info) {
  // Called by glp_error before GLPK would abort: jump back to the guarded call instead.
  std::longjmp(static_cast<GlpkHookState*>(info)->env, 1);
}

namespace {

// Runs GLPK calls under the error hook. `f` must only call GLPK and touch plain data: a longjmp out of
// it skips destructors. On a GLPK error the environment is freed (GLPK requires it), which also frees
// `lp`; the caller then drops its pointer.
template <typename F>
bool guarded(F&& f) {
  GlpkHookState state;
  glp_error_hook(pathpace_glpk_error_hook, &state);
  if (setjmp(state.env)) {
    glp_error_hook(nullptr, nullptr);
    glp_free_env();
    return false;
  }
  f();
  glp_error_hook(nullptr, nullptr);
  return true;
}

// Every upper-bounded row holds at the column values, to tol (1 + |ub|), computed from the matrix itself.
bool rows_hold(glp_prob* lp, double tol) {
  const int m = glp_get_num_rows(lp), n = glp_get_num_cols(lp);
  std::vector<double> act(static_cast<size_t>(m) + 1, 0.0), val(static_cast<size_t>(m) + 1);
  std::vector<int> ind(static_cast<size_t>(m) + 1);
  for (int j = 1; j <= n; ++j) {
    const double x = glp_get_col_prim(lp, j);
    const int len = glp_get_mat_col(lp, j, ind.data(), val.data());
    for (int t = 1; t <= len; ++t) act[static_cast<size_t>(ind[t])] += val[t] * x;
  }
  for (int i = 1; i <= m; ++i)
    if (glp_get_row_type(lp, i) == GLP_UP) {
      const double ub = glp_get_row_ub(lp, i);
      if (act[static_cast<size_t>(i)] > ub + tol * (1.0 + std::abs(ub))) return false;
    }
  return true;
}

}  // namespace

GlpkLp::GlpkLp() = default;

GlpkLp::~GlpkLp() {
  if (lp_) glp_delete_prob(lp_);
}

void GlpkLp::reset(int cols) {
  if (lp_) glp_delete_prob(lp_);
  lp_ = nullptr;
  cols_ = cols;
  basis_ready_ = false;
  ia_.assign(1, 0);  // GLPK arrays are 1-based
  ja_.assign(1, 0);
  ar_.assign(1, 0.0);
  row_ub_.clear();
  iterations_ = 0;
}

int GlpkLp::add_row_upper(const std::vector<int>& idx, const std::vector<double>& val, double ub) {
  const int row = static_cast<int>(row_ub_.size()) + 1;
  for (size_t i = 0; i < idx.size(); ++i) {
    ia_.push_back(row);
    ja_.push_back(idx[i] + 1);
    ar_.push_back(val[i]);
  }
  row_ub_.push_back(ub);
  return row - 1;
}

bool GlpkLp::load() {
  glp_term_out(GLP_OFF);  // never print
  glp_prob* lp = nullptr;
  const int rows = static_cast<int>(row_ub_.size());
  const bool ok = guarded([&] {
    lp = glp_create_prob();
    glp_set_obj_dir(lp, GLP_MIN);
    if (rows > 0) glp_add_rows(lp, rows);
    glp_add_cols(lp, cols_);
    for (int i = 0; i < rows; ++i) glp_set_row_bnds(lp, i + 1, GLP_UP, 0.0, row_ub_[static_cast<size_t>(i)]);
    for (int j = 0; j < cols_; ++j) glp_set_col_bnds(lp, j + 1, GLP_FR, 0.0, 0.0);
    glp_load_matrix(lp, static_cast<int>(ar_.size()) - 1, ia_.data(), ja_.data(), ar_.data());
    // No glp_scale_prob: the caller poses the LP in normalised columns and rows (see slp.cpp), and GLPK's
    // equilibration on top of that was seen to end a warm-started solve OPTIMAL with a row broken by 1 %.
  });
  lp_ = ok ? lp : nullptr;
  return ok;
}

void GlpkLp::append_row_upper(const std::vector<int>& idx, const std::vector<double>& val, double ub) {
  const int row = add_row_upper(idx, val, ub) + 1;
  std::vector<int> ind(idx.size() + 1);
  std::vector<double> v(val.size() + 1);
  for (size_t i = 0; i < idx.size(); ++i) {
    ind[i + 1] = idx[i] + 1;
    v[i + 1] = val[i];
  }
  glp_add_rows(lp_, 1);
  glp_set_mat_row(lp_, row, static_cast<int>(idx.size()), ind.data(), v.data());
  glp_set_row_bnds(lp_, row, GLP_UP, 0.0, ub);
  glp_set_row_stat(lp_, row, GLP_BS);
}

void GlpkLp::set_objective(const std::vector<double>& c) {
  for (int j = 0; j < cols_; ++j) glp_set_obj_coef(lp_, j + 1, c[static_cast<size_t>(j)]);
}

void GlpkLp::set_row_upper(int row, double ub) {
  glpk_set_bounds(lp_, true, row + 1, -std::numeric_limits<double>::infinity(), ub);
}

void GlpkLp::set_col_bounds(int col, double lo, double hi) { glpk_set_bounds(lp_, false, col + 1, lo, hi); }

void GlpkLp::set_basis(const std::vector<Stat>& rows, const std::vector<Stat>& cols) {
  auto code = [](Stat st, int type) {
    if (st == Stat::Basic) return GLP_BS;
    if (type == GLP_FX) return GLP_NS;
    if (type == GLP_FR) return GLP_NF;
    if (type == GLP_UP) return GLP_NU;
    if (type == GLP_LO) return GLP_NL;
    return st == Stat::AtUpper ? GLP_NU : GLP_NL;
  };
  for (size_t i = 0; i < rows.size(); ++i)
    glp_set_row_stat(lp_, static_cast<int>(i) + 1, code(rows[i], glp_get_row_type(lp_, static_cast<int>(i) + 1)));
  for (size_t j = 0; j < cols.size(); ++j)
    glp_set_col_stat(lp_, static_cast<int>(j) + 1, code(cols[j], glp_get_col_type(lp_, static_cast<int>(j) + 1)));
  basis_ready_ = true;
}

GlpkLp::Outcome GlpkLp::solve(double tol_bnd, int time_limit_ms) {
  if (!lp_) return Outcome::Failed;
  glp_term_out(GLP_OFF);
  int ret = 0, status = 0, iters_before = 0, iters_after = 0;
  glp_prob* lp = lp_;
  bool first = !basis_ready_;
  const bool ok = guarded([&] {
    if (first) glp_std_basis(lp);
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    // Primal simplex: between two SLP iterations both the objective (the gradient) and the column bounds
    // (the trust region) change, so the previous basis is neither primal nor dual feasible in general, and
    // a phase 1 from a nearby basis is short. (The dual simplex from an advanced basis was seen to declare
    // such LPs infeasible when rows of very different scales meet GLPK's scaling.)
    parm.meth = GLP_PRIMAL;
    parm.presolve = GLP_OFF;  // presolve would discard the warm-start basis
    parm.tol_bnd = tol_bnd;
    // The SLP certifies 1e-7 relative gaps with a bound computed from these duals (lagrangian_bound):
    // GLPK's default dual tolerance (1e-7) would leave them loose by about as much.
    parm.tol_dj = 1e-10;
    parm.it_lim = 100 * (glp_get_num_rows(lp) + glp_get_num_cols(lp)) + 1000;  // never a hang
    if (time_limit_ms >= 0) parm.tm_lim = std::max(time_limit_ms, 1);
    iters_before = glp_get_it_cnt(lp);
    ret = glp_simplex(lp, &parm);
    if (ret != GLP_ETMLIM && (ret != 0 || glp_get_status(lp) != GLP_OPT)) {
      // The warm basis led astray (singular, or numerically lost): restart from the slack basis.
      glp_std_basis(lp);
      ret = glp_simplex(lp, &parm);
    }
    if (ret == 0 && glp_get_status(lp) == GLP_OPT && !rows_hold(lp, 10.0 * tol_bnd)) {
      // Never trust an OPTIMAL whose point breaks a row: once more from the slack basis.
      glp_std_basis(lp);
      ret = glp_simplex(lp, &parm);
      if (ret == 0 && glp_get_status(lp) == GLP_OPT && !rows_hold(lp, 10.0 * tol_bnd)) ret = -1;
    }
    iters_after = glp_get_it_cnt(lp);
    status = glp_get_status(lp);
  });
  if (!ok) {
    lp_ = nullptr;  // freed with the environment
    return Outcome::Failed;
  }
  basis_ready_ = true;
  iterations_ += iters_after - iters_before;
  if (ret == GLP_ETMLIM) return Outcome::TimeLimit;
  if (ret != 0) return Outcome::Failed;
  if (status == GLP_OPT) return Outcome::Optimal;
  if (status == GLP_NOFEAS) return Outcome::Infeasible;
  if (status == GLP_UNBND) return Outcome::Unbounded;
  return Outcome::Failed;
}

double GlpkLp::lagrangian_bound(const std::vector<double>& cost) const {
  const int rows = static_cast<int>(row_ub_.size());
  std::vector<double> lambda(static_cast<size_t>(rows) + 1), reduced(cost.begin(), cost.end());
  double bound = 0.0;
  for (int i = 1; i <= rows; ++i) {
    // A row freed by set_row_upper(+inf) has dual 0; the others are <= ub with a dual <= 0.
    const double l = glp_get_row_type(lp_, i) == GLP_FR ? 0.0 : std::max(0.0, -glp_get_row_dual(lp_, i));
    lambda[static_cast<size_t>(i)] = l;
    if (l > 0.0) bound -= l * glp_get_row_ub(lp_, i);
  }
  for (size_t e = 1; e < ar_.size(); ++e)
    reduced[static_cast<size_t>(ja_[e] - 1)] += lambda[static_cast<size_t>(ia_[e])] * ar_[e];
  for (int j = 0; j < cols_; ++j) {
    const double r = reduced[static_cast<size_t>(j)];
    const int type = glp_get_col_type(lp_, j + 1);
    const double lo = (type == GLP_FR || type == GLP_UP) ? -std::numeric_limits<double>::infinity() : glp_get_col_lb(lp_, j + 1);
    const double hi = (type == GLP_FR || type == GLP_LO) ? std::numeric_limits<double>::infinity() : glp_get_col_ub(lp_, j + 1);
    if (r > 0.0) bound += r * lo;
    else if (r < 0.0) bound += r * hi;
  }
  return std::isnan(bound) ? -std::numeric_limits<double>::infinity() : bound;
}

void GlpkLp::column_values(std::vector<double>& x) const {
  x.resize(static_cast<size_t>(cols_));
  for (int j = 0; j < cols_; ++j) x[static_cast<size_t>(j)] = glp_get_col_prim(lp_, j + 1);
}

}  // namespace pathpace::detail
