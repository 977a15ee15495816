// PolytopeProjector's one call of project() (sec. IV.C's recursive expansion): the state its stages share,
// written in projection.cpp (the triangle, the LPs, the polygon) and projection_edges.cpp (the edges'
// certificates). Private to lp/.
#pragma once

#include "lp/projection.hpp"

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <glpk.h>

namespace pathpace::detail {

// An optimal basis of eq. (19) stays optimal for every direction v in which its reduced costs keep their
// signs; they are linear in v: d_j(v) = v_x A_j + v_u B_j over the nonbasic variables j (A_j = [j = x] +
// α_xj, B_j = [j = u] + α_uj, α the tableau rows of x and u, x_B = Σ α x_N). If an edge's outward normal
// keeps the basis of one of its endpoints dual feasible (GLPK's own optimality test, with a stricter
// tolerance), that endpoint is an optimum along the normal: the edge's LP, started from that basis,
// would stop there without a pivot and certify the edge. The test replaces that LP (one LP per vertex
// instead of one per vertex and one per edge), and the same reduced costs give binding()'s duals.
struct PolytopeProjector::Ranging {
  std::vector<int> var;            // GLPK variable: 1..rows (auxiliary), rows + 1.. (structural)
  std::vector<signed char> stat;   // GLP_NL, GLP_NU, GLP_NF, GLP_NS
  std::vector<double> A, B;
};

// GLPK's side of Run::binding, inside a guarded call at an optimum of `in`: the inequality row (its dual
// per unit of its normalised row, row_norm) or the bound of a column from `first_column` on with the
// largest dual, as a Projection::binding code (kBindingUnknown: none). Equalities are structure, not
// limits one could relax. maximize() leaves out the slices' fixed x and u columns (first_column 2).
int glpk_binding(glp_prob* lp, const PolytopeLp& in, const double* row_norm, int first_column);

// One call of project(): the data its stages share. The stages: the initial triangle of directions (with
// the stand-in bounds grown and the triangle started again when they hide the whole shadow), the
// expansion of uncertified hull edges until each is certified, and the polygon's half-planes.
class PolytopeProjector::Run {
 public:
  Run(PolytopeProjector& self, const PolytopeLp& in, double relative_tolerance, int max_lps, double approximation,
      const std::vector<Vertex>* focus, ProjectionState* state)
      : self_(self), in_(in), relative_tolerance_(relative_tolerance), max_lps_(max_lps), approximation_(approximation),
        focus_(focus), state_(focus ? state : nullptr) {}
  Projection project();

 private:
  // What a stage tells project(): go on, go back (grow the stand-in bounds and start the triangle again;
  // the hull grew and its edges change), or stop (out_ is the result).
  enum class Step { Ok, Again, Stop };
  struct Pending {  // an uncertified direction: the outward normal of hull edge (from, to), its support value
    int from, to;
    double nx, nu, offset;
  };
  bool start();
  bool load_glpk();
  Step triangle();
  Step grow_stand_in();
  Step expand();
  Step certify_pending();
  void polygon();
  void outer_polygon();
  void focus_directions();
  void resume();
  void keep_state();
  void certify(const Pending& d, int code);
  int extremize(double vx, double vu, Vertex& p, int start_point);
  bool extremize_dense(double vx, double vu, Vertex& p, int start_point, double angle);
  const Basis* warm_basis(double angle) const;
  struct LpPoint {
    int st = -1;
    bool ranged = false;
    double px = 0.0, pu = 0.0;
  };
  void solve_lp(double vx, double vu, const signed char* start, const signed char* fallback, bool range, LpPoint& r);
  void range_basis(bool computed);
  void add_point(const Vertex& p, const Vertex& direction);
  bool binding(int& code);
  bool range_certifies(const Ranging& rg, double nx, double nu, int& code) const;
  bool within_approximation(const Pending& d) const;
  void directions();
  void hull_changed();
  double size_of() const;
  bool is_stand_in(double b) const { return std::abs(b) >= stand_in_; }
  bool capped(double b) const { return std::isfinite(b) && is_stand_in(b); }  // a bound the LPs see
  bool real(const Vertex& p, bool along_x) const;
  Step glpk_error();

  PolytopeProjector& self_;
  const PolytopeLp& in_;
  const double relative_tolerance_;
  const int max_lps_;
  const double approximation_;
  const std::vector<Vertex>* const focus_;  // null: every edge; else only edges some of these points lie beyond
  ProjectionState* const state_;            // with a focus: where to go on from, and where to leave off
  Projection out_;
  glp_smcp parm_, dual_;
  glp_prob* lp_ = nullptr;
  int rows_ = 0, cols_ = 0, total_ = 0;
  // eq. (19): max v·(x, u) over the polytope. The LP's columns 1 and 2 are x / sx and u / su: scaled only
  // when the shadow lies far beyond the stand-in bounds (grow_stand_in), so that GLPK's unscaled simplex
  // sees values of order one.
  double sx_ = 1.0, su_ = 1.0;
  bool same_shape_ = false;         // previous_ holds bases of this shape to warm-start from
  bool record_ = false;             // this size keeps its bases for the next grid point (kRestoreColumns)
  std::vector<char> nonempty_col_;  // per column: a nonzero in this grid point's matrix
  Ranging last_range_;              // the ranging of the last LP's optimal basis (empty if not computed)
  // The dense simplex (dense_simplex.hpp): on for this grid point while the LP is the caller's own
  // (unscaled, the stand-in bounds not grown); the optimal basis of each support point's LP (empty head:
  // none) and of the last LP; whether the dense simplex solved the last LP (binding() reads it).
  bool dense_on_ = false;
  std::vector<DenseSimplex::State> states_;
  DenseSimplex::State last_state_;
  bool last_dense_ = false;
  const signed char* warm_ = nullptr;  // a basis for the next dense LP to start from (see PolytopeProjector::triangle_)
  std::vector<Vertex> points_;      // every support point found
  std::vector<Ranging> ranges_;     // and its LP's ranging
  std::vector<Vertex> support_;     // and the (unit) direction of that LP
  // The stand-in bounds on x and u (those at least in.stand_in in magnitude): the shadow is that of the
  // polytope without them, which they must not cut. Grown when they hide all of it.
  double xlo_ = 0.0, xhi_ = 0.0, ulo_ = 0.0, uhi_ = 0.0, stand_in_ = 0.0;
  // Certified directions, keyed by the hull edge (from, to) that produced them; (i, i) is the end
  // direction beyond point i of a hull that is a segment. The value: what binds there (see binding()).
  std::map<std::pair<int, int>, int> certified_;
  std::vector<std::pair<Pending, int>> certified_lines_;  // with a focus: each certified direction, its binding
  std::vector<int> support_binding_;                       // with a focus: what binds at each support point
  std::vector<std::vector<signed char>> basis_;            // with a focus: each support point's optimal basis
  Eigen::VectorXd row_norm_;
  std::vector<int> hull_;
  std::vector<Pending> pending_;
  double tol_ = 0.0, approx_ = 0.0;
};

}  // namespace pathpace::detail
