#pragma once
// A small dense bounded primal simplex for the projection's support LPs (eq. 19) at one grid point:
// the constraints stay, only the direction (v_x, v_u) of the objective changes. GLPK copies the problem
// and factorises its basis on every call; here the explicit inverse of the basis is kept with each
// support point, so that the LP of an edge starts from an endpoint's optimal basis (primal feasible,
// nearly optimal) and costs a few rank-one updates. Every optimum is certified from the problem's own
// data (primal feasibility of the point, each row with a bound on its rounding; dual feasibility of the
// multipliers), to GLPK's own tolerances; anything else is a failure and the caller falls back to GLPK.
//
// Variables in GLPK's numbering, 0-based: k < m the auxiliary of row k (its value A_k z), k >= m the
// column k - m; the constraint A z - aux = 0. Statuses are GLPK's (GLP_BS, GLP_NL, GLP_NU, GLP_NF,
// GLP_NS), so that a basis passes between the two solvers.

#include <vector>

#include <Eigen/Core>

namespace pathpace::detail {

struct PolytopeLp;

class DenseSimplex {
 public:
  /// A basis and what the simplex keeps with it.
  struct State {
    std::vector<int> head;            // basic variable of each basis position
    std::vector<signed char> stat;    // per variable
    Eigen::MatrixXd inv;              // B^-1
    Eigen::VectorXd value;            // per variable (basic: computed, nonbasic: at its bound)
    int updates = 0;                  // rank-one updates since inv was computed from B
  };

  /// The problem (kept by reference until the next load: the caller keeps it alive). `transpose`: keep
  /// A^T for the pricing's products, worth its writing where one load takes many pivots (a projection's
  /// LPs at one grid point), not for the one or two LPs of a slice (SliceLp loads without it).
  void load(const PolytopeLp& lp, bool transpose = true);
  /// The basis `stat` (GLPK's statuses, rows then columns): false if it is not a basis, singular, or,
  /// with `primal_feasible`, not primal feasible. A basis whose point lies outside the polytope (the
  /// previous sample's optimum in a slice LP) is brought back by maximize(), by dual simplex pivots.
  bool set_basis(const signed char* stat, bool primal_feasible = true);
  /// What maximize() found: an optimum it certified, or why it gave up (the caller then uses GLPK).
  enum Outcome : int {
    kOptimal = 1,
    kNoBasis = 0,         ///< no problem loaded or no basis set
    kIterationCap = -1,   ///< kMaxPivots pivots without an optimum (cycling, or a far start)
    kSmallPivot = -2,     ///< every row that bounds the step has |alpha| below the pivot tolerance
    kUnbounded = -3,      ///< no row nor bound stops the step: a ray (not a projection LP's answer)
    kSingular = -4,       ///< the basis refactorised after kRefactor updates is (nearly) singular
    kCertificate = -5,    ///< the optimum fails its certificate from the LP's own data
    kNotDualFeasible = -6,  ///< a start outside the polytope whose reduced costs are not dual feasible
    kDualRay = -7,        ///< a basic variable outside its bounds that no nonbasic one can move back
  };
  /// Maximise v_x x + v_u u from the current basis: an Outcome. A basis outside the polytope is first
  /// made primal feasible by the dual simplex, if its reduced costs along (v_x, v_u) are dual feasible.
  int maximize(double vx, double vu);
  /// The values of nonbasic variable k (0-based, as in reduced_cost) for which the current basis stays
  /// primal feasible, hence optimal (glp_analyze_bound's range): [from, to] around its value, ±infinity
  /// where no basic variable limits it. Basic k: its value twice.
  void bound_range(int k, double& from, double& to);

  const State& state() const { return s_; }
  void restore(const State& s) { s_ = s; }
  double x() const { return s_.value[m_]; }
  double u() const { return s_.value[m_ + 1]; }
  /// The reduced cost of variable k at the last optimum (GLPK's row / column dual).
  double reduced_cost(int k) const { return d_[static_cast<size_t>(k)]; }
  /// GLPK's tableau rows of x and u (x_B = Σ α x_N), 1-based over every variable, zero where x (u) is
  /// nonbasic or the variable is basic.
  void tableau_xu(double* tab_x, double* tab_u);
  int pivots = 0;  ///< since load (statistics)
  /// The engine's limits (tests force each Outcome through them): pivots per LP, rank-one updates before
  /// B^-1 is computed again from B, the smallest pivot, the smallest reciprocal condition of B.
  struct Limits {
    int max_pivots = 200, refactor = 40;
    double tol_pivot = 1e-9, min_rcond = 1e-12;
  } limits;

 private:
  bool factorize();
  void compute_values();
  void price(double vx, double vu);
  bool replace(int r, int q, bool leave_at_lo);  // the basis change of a pivot  // y_, dstruct_, d_ for the objective v_x x + v_u u
  int dual_phase(double vx, double vu);  // kOptimal once the basis is primal feasible, else an Outcome
  int worst_infeasible(double& target) const;  // the basis position furthest outside its bounds, or -1
  void solve_column(int k);  // alpha_ = B^-1 a_k, a_k the constraint column of variable k
  bool certify();
  // Row k's value A_k z, in extended precision with its rounding bound, within [lo, hi] (certify's second
  // look at a row that the double evaluation leaves undecided).
  bool row_within(int k, const Eigen::VectorXd& z, double lo, double hi) const;
  const PolytopeLp* lp_ = nullptr;
  int m_ = 0, n_ = 0;
  Eigen::VectorXd lo_, hi_;  // per variable
  State s_;
  std::vector<double> d_;
  void transposed_times(const Eigen::VectorXd& v, Eigen::VectorXd& out) const;
  Eigen::VectorXd y_, alpha_, dstruct_, rows_, wstruct_, rho_;
  Eigen::RowVectorXd pivot_row_;  // scratch of a pivot's inverse update (no allocation per pivot)
  // factorize()'s and compute_values()'s scratch (no allocation per call once sized).
  std::vector<int> f_spos_, f_scol_, f_rows_, f_apos_, f_arow_;
  Eigen::MatrixXd f_c_, f_m_, f_ak_, f_w_;
  bool invert_small(Eigen::Ref<const Eigen::MatrixXd> C, Eigen::Ref<Eigen::MatrixXd> X);  // factorize()'s A[R,S]^-1
  std::vector<int> f_piv_;
  Eigen::VectorXd f_col_;
  Eigen::VectorXd cv_z_, cv_r_, cv_xb_;
  Eigen::MatrixXd at_;      // A^T: its column i is A's row i, contiguous (if transposed_)
  bool transposed_ = true;
  Eigen::VectorXd row_max_;  // max_j |a_ij| per row
};

}  // namespace pathpace::detail
