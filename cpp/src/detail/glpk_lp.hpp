#pragma once
// A thin RAII owner of a GLPK problem for the SLP (never installed: no GLPK type leaves cpp/src).
//
// GLPK aborts the whole process on misuse (glp_error). Inputs are validated before they get here, and
// every call that can reach glp_error runs under an error hook that longjmps back, so a GLPK failure
// becomes a status, not an abort.

#include <vector>

struct glp_prob;

namespace pathpace::detail {

class GlpkLp {
 public:
  enum class Outcome { Optimal, Infeasible, Unbounded, Failed };

  GlpkLp();
  ~GlpkLp();
  GlpkLp(const GlpkLp&) = delete;
  GlpkLp& operator=(const GlpkLp&) = delete;

  /// Minimisation problem with `cols` free columns; rows are added as sparse upper-bounded rows.
  /// The first solve starts from the slack basis (all columns nonbasic at 0), which is primal feasible
  /// whenever every row's bound is >= 0: the SLP writes its LPs in the step d = θ' - θ from a feasible θ
  /// so that this holds and the simplex never needs a phase 1.
  void reset(int cols);
  /// Adds sum_i val[i] * x[idx[i]] <= ub (idx 0-based). Returns the row index.
  int add_row_upper(const std::vector<int>& idx, const std::vector<double>& val, double ub);
  /// Loads the rows added so far into GLPK (call once after the last add_row_upper).
  bool load();

  void set_objective(const std::vector<double>& c);
  /// Row `row` <= ub; ub = +inf frees the row.
  void set_row_upper(int row, double ub);

  /// Simplex from the current basis (the previous solve's, so a warm start). `tol_bnd` is GLPK's
  /// primal feasibility tolerance.
  Outcome solve(double tol_bnd);
  void column_values(std::vector<double>& x) const;
  int simplex_iterations() const { return iterations_; }

 private:
  glp_prob* lp_ = nullptr;
  int cols_ = 0;
  bool basis_ready_ = false;
  std::vector<int> ia_, ja_;
  std::vector<double> ar_, row_ub_;
  int iterations_ = 0;
};

}  // namespace pathpace::detail
