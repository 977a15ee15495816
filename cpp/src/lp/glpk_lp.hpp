#pragma once
// A thin RAII owner of a GLPK problem for the SLP (never installed: no GLPK type leaves cpp/src).
//
// GLPK aborts the whole process on misuse (glp_error). Inputs are validated before they get here, and
// every GLPK call runs in guarded() (glpk_guard.hpp), so a GLPK failure becomes a status, not an abort.
// The class keeps its own copy of the problem (matrix, bounds, objective) and applies the changes in
// solve(), in one guarded call: so that a GLPK error elsewhere in the thread, which frees this problem
// too, costs only the basis (the next solve() rebuilds the problem from the copy, from the slack basis).

#include <vector>

#include "lp/glpk_guard.hpp"

namespace pathpace::detail {

class GlpkLp {
 public:
  enum class Outcome { Optimal, Infeasible, Unbounded, TimeLimit, Failed };

  GlpkLp();
  ~GlpkLp();
  GlpkLp(const GlpkLp&) = delete;
  GlpkLp& operator=(const GlpkLp&) = delete;

  /// Minimisation problem with `cols` columns (free until set_col_bounds); rows are added as sparse
  /// upper-bounded rows. The first solve starts from the slack basis (columns nonbasic at a bound), made
  /// feasible by the primal simplex's phase 1 if need be; later solves start from the previous basis.
  void reset(int cols);
  /// Adds sum_i val[i] * x[idx[i]] <= ub (idx 0-based). Returns the row index.
  int add_row_upper(const std::vector<int>& idx, const std::vector<double>& val, double ub);
  /// Loads the rows added so far into GLPK (call once after the last add_row_upper).
  bool load();
  /// After load(): one more row, basic (so the current basis stays a basis; the next solve starts from it).
  void append_row_upper(const std::vector<int>& idx, const std::vector<double>& val, double ub);

  void set_objective(const std::vector<double>& c);
  /// lo <= x[col] <= hi (lo == hi fixes it). Bounds on columns cost the simplex nothing, where the same
  /// bounds as rows would add two rows per column to every basis factorisation.
  void set_col_bounds(int col, double lo, double hi);

  enum class Stat { Basic, AtLower, AtUpper };
  /// Installs a basis (row and column statuses; a nonbasic variable sits at the named bound, a fixed
  /// one at its value). The next solve starts from it; if it is singular, from the slack basis.
  void set_basis(const std::vector<Stat>& rows, const std::vector<Stat>& cols);

  /// Simplex from the current basis (the previous solve's, so a warm start: a change of bounds or
  /// objective keeps the basis valid). `tol_bnd` is GLPK's primal feasibility tolerance; `time_limit_ms`
  /// (< 0: none) ends it with Outcome::TimeLimit.
  Outcome solve(double tol_bnd, int time_limit_ms = -1);
  /// The last successful solve's column values.
  void column_values(std::vector<double>& x) const;
  /// A lower bound on the LP's optimum that does not trust the solver's optimality tolerances: with the
  /// row multipliers λ = max(0, -dual) of the last solve, min over the column bounds of
  /// c·x + λ·(A x - ub) (Lagrangian weak duality: valid for any λ >= 0). -inf if a column whose reduced
  /// cost pulls it that way is unbounded.
  double lagrangian_bound(const std::vector<double>& cost) const;

 private:
  bool rebuild();           // the GLPK problem from the copy (after load(), or after a GLPK error freed it)
  void prepare_changes();   // the pending changes as plain arrays for solve()'s guarded call
  GlpkProblem lp_;
  int cols_ = 0;
  bool loaded_ = false;
  bool basis_ready_ = false;
  // The copy: 1-based triplets in row order (row r's entries from row_begin_[r]), row upper bounds
  // (+inf: free), column bounds, objective.
  std::vector<int> ia_, ja_, row_begin_;
  std::vector<double> ar_, row_ub_, col_lo_, col_hi_, obj_;
  // Changes since the last solve: rows [glpk_rows_, rows) not yet in GLPK (appended basic), whether the
  // column bounds / objective changed, a basis to install.
  int glpk_rows_ = 0;
  bool cols_dirty_ = false, obj_dirty_ = false, basis_pending_ = false;
  std::vector<Stat> basis_rows_, basis_cols_;
  // Scratch and results of solve() (plain arrays for the guarded call).
  std::vector<int> col_type_, row_code_, col_code_;
  std::vector<double> x_, row_dual_, activity_;
};

}  // namespace pathpace::detail
