#include "lp/glpk_lp.hpp"

#include "lp/glpk_util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glpk.h>

namespace pathpace::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

int bound_type(double lo, double hi) {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  return has_lo && has_hi ? (lo == hi ? GLP_FX : GLP_DB) : has_lo ? GLP_LO : has_hi ? GLP_UP : GLP_FR;
}

// GLPK's status code for a basis status of a variable of this bound type.
int status_code(GlpkLp::Stat st, int type) {
  if (st == GlpkLp::Stat::Basic) return GLP_BS;
  if (type == GLP_FX) return GLP_NS;
  if (type == GLP_FR) return GLP_NF;
  if (type == GLP_UP) return GLP_NU;
  if (type == GLP_LO) return GLP_NL;
  return st == GlpkLp::Stat::AtUpper ? GLP_NU : GLP_NL;
}

// Every upper-bounded row holds at x, to tol (1 + |ub|), its activity computed from the copy of the matrix
// (plain arrays: this runs inside the guarded call).
bool rows_hold(const int* ia, const int* ja, const double* ar, int entries, const double* ub, int rows, const double* x,
               double* act, double tol) {
  for (int i = 0; i < rows; ++i) act[i] = 0.0;
  for (int e = 1; e <= entries; ++e) act[ia[e] - 1] += ar[e] * x[ja[e] - 1];
  for (int i = 0; i < rows; ++i)
    if (std::isfinite(ub[i]) && act[i] > ub[i] + tol * (1.0 + std::abs(ub[i]))) return false;
  return true;
}

}  // namespace

GlpkLp::GlpkLp() = default;
GlpkLp::~GlpkLp() = default;  // GlpkProblem deletes the problem, unless a GLPK error freed it

void GlpkLp::reset(int cols) {
  lp_.reset();
  cols_ = cols;
  loaded_ = basis_ready_ = false;
  ia_.assign(1, 0);  // GLPK arrays are 1-based
  ja_.assign(1, 0);
  ar_.assign(1, 0.0);
  row_begin_.clear();
  row_ub_.clear();
  col_lo_.assign(static_cast<size_t>(cols), -kInf);
  col_hi_.assign(static_cast<size_t>(cols), kInf);
  obj_.assign(static_cast<size_t>(cols), 0.0);
  glpk_rows_ = 0;
  cols_dirty_ = obj_dirty_ = basis_pending_ = false;
}

int GlpkLp::add_row_upper(const std::vector<int>& idx, const std::vector<double>& val, double ub) {
  const int row = static_cast<int>(row_ub_.size()) + 1;
  row_begin_.push_back(static_cast<int>(ia_.size()));
  for (size_t i = 0; i < idx.size(); ++i) {
    ia_.push_back(row);
    ja_.push_back(idx[i] + 1);
    ar_.push_back(val[i]);
  }
  row_ub_.push_back(ub);
  return row - 1;
}

bool GlpkLp::load() {
  loaded_ = true;
  return rebuild();
}

bool GlpkLp::rebuild() {
  basis_ready_ = false;
  if (!lp_.create()) return false;
  glp_prob* lp = lp_.get();
  const int rows = static_cast<int>(row_ub_.size()), cols = cols_;
  const double *ub = row_ub_.data(), *lo_c = col_lo_.data(), *hi_c = col_hi_.data(), *obj = obj_.data();
  const int entries = static_cast<int>(ar_.size()) - 1;
  const int* ia = ia_.data();
  const int* ja = ja_.data();
  const double* ar = ar_.data();
  const bool ok = guarded([&] {
    glp_set_obj_dir(lp, GLP_MIN);
    if (rows > 0) glp_add_rows(lp, rows);
    if (cols > 0) glp_add_cols(lp, cols);
    for (int i = 0; i < rows; ++i) glpk_set_bounds(lp, true, i + 1, -kInf, ub[i]);
    for (int j = 0; j < cols; ++j) {
      glpk_set_bounds(lp, false, j + 1, lo_c[j], hi_c[j]);
      glp_set_obj_coef(lp, j + 1, obj[j]);
    }
    glp_load_matrix(lp, entries, ia, ja, ar);
    // No glp_scale_prob: the caller poses the LP in normalised columns and rows (see slp.cpp), and GLPK's
    // equilibration on top of that was seen to end a warm-started solve OPTIMAL with a row broken by 1 %.
  });
  glpk_rows_ = rows;
  cols_dirty_ = obj_dirty_ = false;
  return ok;
}

void GlpkLp::append_row_upper(const std::vector<int>& idx, const std::vector<double>& val, double ub) {
  add_row_upper(idx, val, ub);  // rows from glpk_rows_ on enter GLPK, basic, at the next solve
}

void GlpkLp::set_objective(const std::vector<double>& c) {
  std::copy(c.begin(), c.begin() + cols_, obj_.begin());
  obj_dirty_ = true;
}

void GlpkLp::set_col_bounds(int col, double lo, double hi) {
  col_lo_[static_cast<size_t>(col)] = lo;
  col_hi_[static_cast<size_t>(col)] = hi;
  cols_dirty_ = true;
}

void GlpkLp::set_basis(const std::vector<Stat>& rows, const std::vector<Stat>& cols) {
  basis_rows_ = rows;
  basis_cols_ = cols;
  basis_pending_ = true;
  basis_ready_ = true;
}

void GlpkLp::prepare_changes() {
  const size_t rows = row_ub_.size();
  x_.resize(static_cast<size_t>(cols_));
  row_dual_.resize(rows);
  activity_.resize(rows);
  row_code_.clear();
  col_code_.clear();
  if (!basis_pending_) return;
  // The codes for the bound types the solve will see (bounds are applied before the basis).
  for (size_t i = 0; i < basis_rows_.size(); ++i)
    row_code_.push_back(status_code(basis_rows_[i], std::isfinite(row_ub_[i]) ? GLP_UP : GLP_FR));
  for (size_t j = 0; j < basis_cols_.size(); ++j) col_code_.push_back(status_code(basis_cols_[j], bound_type(col_lo_[j], col_hi_[j])));
}

GlpkLp::Outcome GlpkLp::solve(double tol_bnd, int time_limit_ms) {
  if (!loaded_) return Outcome::Failed;
  if (!lp_.get() && !rebuild()) return Outcome::Failed;  // a GLPK error freed it: again from the copy
  prepare_changes();
  glp_prob* lp = lp_.get();
  const int rows = static_cast<int>(row_ub_.size()), cols = cols_, first_new = glpk_rows_;
  const int entries = static_cast<int>(ar_.size()) - 1;
  const int basis_rows = static_cast<int>(row_code_.size()), basis_cols = static_cast<int>(col_code_.size());
  const int *ia = ia_.data(), *ja = ja_.data(), *row_begin = row_begin_.data();
  const int *row_code = row_code_.data(), *col_code = col_code_.data();
  const double *ar = ar_.data(), *ub = row_ub_.data(), *lo_c = col_lo_.data(), *hi_c = col_hi_.data(), *obj = obj_.data();
  double *x = x_.data(), *dual = row_dual_.data(), *act = activity_.data();
  const bool set_cols = cols_dirty_, set_obj = obj_dirty_, set_stats = basis_pending_, first = !basis_ready_;
  int ret = 0, status = 0;
  const bool ok = guarded([&] {
    // The changes since the last solve, in the order the caller made them in the SLP: new rows (basic, so
    // that the current basis stays a basis), column bounds, objective, then a basis.
    if (rows > first_new) glp_add_rows(lp, rows - first_new);
    for (int r = first_new; r < rows; ++r) {
      const int begin = row_begin[r], end = r + 1 < rows ? row_begin[r + 1] : entries + 1;
      glp_set_mat_row(lp, r + 1, end - begin, ja + begin - 1, ar + begin - 1);  // GLPK reads [1, len]
      glpk_set_bounds(lp, true, r + 1, -kInf, ub[r]);
      glp_set_row_stat(lp, r + 1, GLP_BS);
    }
    if (set_cols)
      for (int j = 0; j < cols; ++j) glpk_set_bounds(lp, false, j + 1, lo_c[j], hi_c[j]);
    if (set_obj)
      for (int j = 0; j < cols; ++j) glp_set_obj_coef(lp, j + 1, obj[j]);
    if (set_stats) {
      for (int i = 0; i < basis_rows; ++i) glp_set_row_stat(lp, i + 1, row_code[i]);
      for (int j = 0; j < basis_cols; ++j) glp_set_col_stat(lp, j + 1, col_code[j]);
    } else if (first) {
      glp_std_basis(lp);
    }
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
    parm.it_lim = 100 * (rows + cols) + 1000;  // never a hang
    if (time_limit_ms >= 0) parm.tm_lim = std::max(time_limit_ms, 1);
    auto optimal_point_holds = [&] {  // never trust an OPTIMAL whose point breaks a row
      for (int j = 0; j < cols; ++j) x[j] = glp_get_col_prim(lp, j + 1);
      return rows_hold(ia, ja, ar, entries, ub, rows, x, act, 10.0 * tol_bnd);
    };
    ret = glp_simplex(lp, &parm);
    if (ret != GLP_ETMLIM && (ret != 0 || glp_get_status(lp) != GLP_OPT)) {
      // The warm basis led astray (singular, or numerically lost): restart from the slack basis.
      glp_std_basis(lp);
      ret = glp_simplex(lp, &parm);
    }
    if (ret == 0 && glp_get_status(lp) == GLP_OPT && !optimal_point_holds()) {
      glp_std_basis(lp);  // once more from the slack basis
      ret = glp_simplex(lp, &parm);
      if (ret == 0 && glp_get_status(lp) == GLP_OPT && !optimal_point_holds()) ret = -1;
    }
    status = glp_get_status(lp);
    for (int j = 0; j < cols; ++j) x[j] = glp_get_col_prim(lp, j + 1);
    for (int i = 0; i < rows; ++i) dual[i] = glp_get_row_dual(lp, i + 1);
  });
  basis_pending_ = false;
  if (!ok) {  // the problem went with the environment; the next solve rebuilds it
    basis_ready_ = false;
    return Outcome::Failed;
  }
  glpk_rows_ = rows;
  cols_dirty_ = obj_dirty_ = false;
  basis_ready_ = true;
  if (ret == GLP_ETMLIM) return Outcome::TimeLimit;
  if (ret != 0) return Outcome::Failed;
  if (status == GLP_OPT) return Outcome::Optimal;
  if (status == GLP_NOFEAS) return Outcome::Infeasible;
  if (status == GLP_UNBND) return Outcome::Unbounded;
  return Outcome::Failed;
}

double GlpkLp::lagrangian_bound(const std::vector<double>& cost) const {
  // From the copy of the problem and the last solve's duals (rows appended since have none yet: 0).
  const size_t rows = row_ub_.size();
  std::vector<double> lambda(rows + 1, 0.0), reduced(cost.begin(), cost.end());
  double bound = 0.0;
  for (size_t i = 0; i < rows && i < row_dual_.size(); ++i) {
    // A row with ub = +inf is free (dual 0); the others are <= ub with a dual <= 0.
    const double l = std::isfinite(row_ub_[i]) ? std::max(0.0, -row_dual_[i]) : 0.0;
    lambda[i + 1] = l;
    if (l > 0.0) bound -= l * row_ub_[i];
  }
  for (size_t e = 1; e < ar_.size(); ++e)
    reduced[static_cast<size_t>(ja_[e] - 1)] += lambda[static_cast<size_t>(ia_[e])] * ar_[e];
  for (int j = 0; j < cols_; ++j) {
    const double r = reduced[static_cast<size_t>(j)];
    if (r > 0.0) bound += r * col_lo_[static_cast<size_t>(j)];
    else if (r < 0.0) bound += r * col_hi_[static_cast<size_t>(j)];
  }
  return std::isnan(bound) ? -std::numeric_limits<double>::infinity() : bound;
}

void GlpkLp::column_values(std::vector<double>& x) const { x = x_; }

}  // namespace pathpace::detail
