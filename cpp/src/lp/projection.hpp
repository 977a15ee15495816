#pragma once
// Projection of a polytope {z = (x, u, y) : lo <= A z <= hi, col_lo <= z <= col_hi} onto the (x, u)
// plane by recursive expansion (sec. IV.C; Bretl & Lall), made right by construction:
//  - the polygon is the convex hull of the LP optima found so far (support points of the shadow), so
//    it is always an inner set, whatever the LPs did;
//  - an LP optimum is added only when it lies outside the current hull by more than a tolerance scaled
//    to the polygon's size (never a near-duplicate that would fold a vertex sequence: the hull is
//    recomputed, not spliced);
//  - an edge is final only when an LP along its own outward normal finds nothing beyond it (its
//    certificate), so the shadow lies within the tolerance of the polygon.
// Each LP is eq. (19); GLPK is warm-started from the previous direction's basis.

#include <climits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lp/dense_simplex.hpp"
#include "lp/glpk_guard.hpp"
#include "geometry/polygon2d.hpp"
#include "pathpace/constraints/constraint.hpp"

namespace pathpace::detail {

struct PolytopeLp {
  // Columns 0 and 1 are x = ṡ² and u = s̈; the rest are eliminated (forces, ...).
  Eigen::MatrixXd A;          // (rows, cols), dense is fine at these sizes
  Eigen::VectorXd row_lo, row_hi;  // -inf / +inf for one-sided rows; equal for equalities
  Eigen::VectorXd col_lo, col_hi;
  /// Bounds of x or u at least this large in magnitude are stand-ins (no limit): vertices on them do
  /// not count towards the polygon's size, which scales the tolerance.
  double stand_in = 1e300;
};

/// What stops the shadow at an edge: the constraint of the polytope with the largest dual at the edge's
/// certifying LP. Row r at its lower bound: 2r, at its upper bound: 2r + 1; column j at a bound: -(j + 1).
inline constexpr int kBindingUnknown = INT_MIN;
/// The stand-in bounds are never grown past this: the feasible sets' own box (Polygon2d's 1e15 sides).
inline constexpr double kLargestStandIn = 1e15;
inline bool binding_is_row(int code) { return code >= 0; }
inline int binding_column(int code) { return -code - 1; }

struct Projection {
  enum class Outcome { Polygon, Empty, Failed };
  Outcome outcome = Outcome::Failed;
  /// Polygon only: every edge certified by its own LP. False when an LP failed or the LP budget ran
  /// out: the polygon is then the hull found so far (an inner approximation) and `note` says why.
  bool complete = false;
  std::string note;
  std::vector<Line> halfplanes;  // a x + b u <= c, (a, b) of unit length, counter-clockwise
  std::vector<int> binding;      // per half-plane: the polytope's binding constraint (kBinding... codes)
  std::vector<Vertex> vertices;  // counter-clockwise (the hull of the support points)
  double tolerance = 0.0;        // absolute: the shadow lies within this of every edge (approximation included)
  /// The stand-in bound the polygon was computed with: PolytopeLp::stand_in, or larger when the shadow
  /// lies only beyond it (the stand-in bounds grown past it; edges on them are still not limits).
  double stand_in = 0.0;
  int lp_solves = 0;
  /// lp_solves by cause: the initial triangle, edge LPs that did not certify their edge (a new vertex, or
  /// a failure), edge LPs that certified it, the feasibility LP without the stand-in bounds.
  LpCounts by_cause;
  int approximate_edges = 0;    ///< edges final by `approximation` (no LP; binding unknown)
  /// With a focus (PolytopeProjector::project): `halfplanes` are the outer polygon, the support line of
  /// every LP optimum and every certified edge (a superset of the shadow), and `hull` the hull's edges (an
  /// inner set), with `hull_certified` per edge. Empty without a focus (the halfplanes are the hull's).
  std::vector<Line> hull;
  std::vector<char> hull_certified;
};

/// A focused projection's state at one polytope (PolytopeProjector::project with a focus): its support points,
/// their LPs' directions, what binds there and optimal bases (GLPK's statuses, rows then columns), and the
/// certified edges. A later call on the same polytope with a larger focus goes on from there instead of
/// starting again (the rounds of ContactOptions::project_on_demand).
struct ProjectionState {
  struct Certified {
    int from, to;
    double nx, nu, offset;
    int binding;
  };
  std::vector<Vertex> points, support;
  std::vector<int> binding;
  std::vector<std::vector<signed char>> basis;  // empty where none was kept
  std::vector<Certified> certified;
  bool resumable = false;  // false: start again (none yet, or the stand-in bounds grew)
  bool keep_bases = true;  // false: the bases are not kept (memory), a resumed LP starts from GLPK's
};

/// Projects a sequence of polytopes of one shape (the grid points of one constraint): the GLPK problem
/// is kept from one call to the next and each call starts from the previous call's final basis, which
/// is nearly optimal for a neighbouring grid point (sec. IV.C's warm start, carried across points).
/// `relative_tolerance`: an LP optimum is a new vertex, and an edge is not final, when it lies beyond
/// the edge by more than this times the polygon's size (the larger of its x and u extents, vertices
/// on stand-in bounds left out). `max_lps` bounds the work (the result then says it is incomplete).
class PolytopeProjector {
 public:
  PolytopeProjector() = default;
  PolytopeProjector(const PolytopeProjector&) = delete;
  PolytopeProjector& operator=(const PolytopeProjector&) = delete;
  ~PolytopeProjector();
  /// `approximation` (ContactOptions::projection_tolerance): an edge is also final, without its LP, when
  /// the outer bound beyond it (the apex of the support lines at its ends) lies within this times the
  /// polygon's size of it; the polygon is then an inner set within that of the shadow in every direction.
  ///
  /// `focus` (ContactOptions::project_on_demand): only the hull edges that some focus point lies beyond
  /// are expanded, until every focus point is inside the hull or beyond a certified edge; the result is
  /// then the outer polygon (Projection::hull). With an empty focus: the initial triangle's LPs only.
  /// `state` (with a focus only): where an earlier call on this polytope left off (in), and this one's (out).
  Projection project(const PolytopeLp& lp, double relative_tolerance = 1e-9, int max_lps = 2000,
                     double approximation = 0.0, const std::vector<Vertex>* focus = nullptr,
                     ProjectionState* state = nullptr);

  /// One LP: is the polytope non-empty (1), empty (0, confirmed in exact arithmetic), or did the
  /// solver fail (-1)? With `fix` the point (x, u) = (fix[0], fix[1]) is imposed.
  int feasible(const PolytopeLp& lp, const double* fix = nullptr);

  /// What maximize() tells of a column fixed by its bounds (u in the polygon's slices) at an optimum:
  /// the optimum is c·z + slope (t - t0) for every value t of that column in [from, to] (t0 its value:
  /// the basis stays primal feasible, hence optimal, there), and the optimal value is concave in t, so
  /// that line bounds it from above everywhere. from = to = t0 where the column is basic or GLPK kept no
  /// factorisation; with `label`, `binding` is the constraint with the largest dual other than columns
  /// 0 and 1 (a Projection::binding code).
  struct FixedColumn {
    int column = 1;  // in
    bool label = false;  // in
    double slope = 0.0, from = 0.0, to = 0.0;
    int binding = kBindingUnknown;
  };
  /// One LP: maximise c·z over the polytope (c one per column). 1: optimal, z its point; 0: empty
  /// (confirmed in exact arithmetic); -1: the solver failed; -2: a GLPK error (see glpk_guard.hpp).
  /// Unbounded is a failure. Warm-started like project() (the same problem, from the last basis).
  /// `basis`: at an optimum, its statuses (GLPK's, rows then columns), e.g. for the dense simplex.
  int maximize(const PolytopeLp& lp, const Eigen::VectorXd& c, Eigen::VectorXd& z, FixedColumn* fixed = nullptr,
               std::vector<signed char>* basis = nullptr);

 private:
  // Loads the problem (same shape: the previous basis is kept as the warm start). -1: a GLPK error; else
  // 1 if warm, 0 if cold.
  int load(const PolytopeLp& lp);
  GlpkProblem lp_;
  int rows_ = -1, cols_ = -1;
  std::vector<int> ia_, ja_;  // matrix-loading scratch
  std::vector<double> ar_;
  std::vector<signed char> stat_;  // an LP's final basis, before it is kept
  std::vector<double> z_;          // an LP's point
  Eigen::VectorXd row_norm_;       // the rows' norms, for a FixedColumn's label
  struct Basis {  // an LP's final basis: its direction, then GLPK's row and column statuses
    double angle = 0.0;
    std::vector<signed char> stat;
  };
  std::vector<Basis> previous_, current_;  // the LPs of the previous projection, of this one
  // With a focus: the optimal bases of the last projection's three initial LPs, where the next grid point's
  // dense simplex starts them (a few dual pivots, where a start from the support point 120° away took ~30).
  std::vector<signed char> triangle_[3];
  struct Ranging;
  class Run;
  std::vector<int> tab_ind_;  // glp_eval_tab_row scratch
  std::vector<double> tab_val_;
  std::vector<double> tab_x_, tab_u_;  // the tableau rows of x and u, over every variable (1-based)
  DenseSimplex dense_engine_;
 public:
  /// Solve the LPs after a grid point's first by the dense simplex (dense_simplex.hpp), warm from an
  /// endpoint's optimal basis, each optimum certified (GLPK solves any it gives up on). On by default;
  /// off for tests that compare both.
  bool dense = true;
  /// The dense simplex's limits (tests force its fallbacks through them).
  DenseSimplex::Limits& dense_limits() { return dense_engine_.limits; }
  /// Certify an edge without its LP when an endpoint's optimal basis is also optimal along the edge's
  /// normal (see Ranging in the .cpp). On by default; off for tests that compare both.
  bool ranging = true;
};

/// One polytope, from a cold start.
Projection project_polytope(const PolytopeLp& lp, double relative_tolerance = 1e-9, int max_lps = 2000,
                            double approximation = 0.0, const std::vector<Vertex>* focus = nullptr,
                            ProjectionState* state = nullptr);

}  // namespace pathpace::detail
