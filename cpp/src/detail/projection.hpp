#pragma once
// Projection of a polytope {z = (x, u, y) : lo <= A z <= hi, col_lo <= z <= col_hi} onto the (x, u)
// plane by recursive expansion (sec. IV.C; Bretl & Lall): extremize in three directions, then push each
// edge of the current inner polygon out along its normal with one LP, until no edge moves. Each LP is
// eq. (19); GLPK is warm-started from the previous direction's basis.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "detail/polygon2d.hpp"

struct glp_prob;  // GLPK stays in the .cpp

namespace pathpace::detail {

struct PolytopeLp {
  // Columns 0 and 1 are x = ṡ² and u = s̈; the rest are eliminated (forces, ...).
  Eigen::MatrixXd A;          // (rows, cols), dense is fine at these sizes
  Eigen::VectorXd row_lo, row_hi;  // -inf / +inf for one-sided rows; equal for equalities
  Eigen::VectorXd col_lo, col_hi;
};

struct Projection {
  enum class Outcome { Polygon, Empty, Failed };
  Outcome outcome = Outcome::Failed;
  std::vector<Line> halfplanes;  // a x + b u <= c, (a, b) of unit length, counter-clockwise
  std::vector<Vertex> vertices;  // counter-clockwise
  int lp_solves = 0;
};

/// Projects a sequence of polytopes of one shape (the grid points of one constraint): the GLPK problem
/// is kept from one call to the next and each call starts from the previous call's final basis, which
/// is nearly optimal for a neighbouring grid point (sec. IV.C's warm start, carried across points).
/// `relative_tolerance`: an edge is final when the LP moves it outward by less than this times its
/// support value (at least 1). `max_lps` bounds the work (the result is then an inner approximation).
class PolytopeProjector {
 public:
  PolytopeProjector() = default;
  PolytopeProjector(const PolytopeProjector&) = delete;
  PolytopeProjector& operator=(const PolytopeProjector&) = delete;
  ~PolytopeProjector();
  Projection project(const PolytopeLp& lp, double relative_tolerance = 1e-9, int max_lps = 200);

 private:
  void release();
  ::glp_prob* lp_ = nullptr;
  int rows_ = -1, cols_ = -1;
  std::vector<int> ia_, ja_;  // matrix-loading scratch
  std::vector<double> ar_;
};

/// One polytope, from a cold start.
Projection project_polytope(const PolytopeLp& lp, double relative_tolerance = 1e-9, int max_lps = 200);

}  // namespace pathpace::detail
