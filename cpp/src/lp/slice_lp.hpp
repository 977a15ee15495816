// The LPs of a constraint's slices (ContactConstraint::slice, guarantee = "continuous"): at a sample, u
// fixed, the largest and the smallest x over the projection polytope (eq. 19), with u's sensitivity there
// (PolytopeProjector::FixedColumn). Private to lp/ and the constraints that slice.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lp/dense_simplex.hpp"
#include "lp/projection.hpp"

namespace pathpace::detail {

/// One sequence of samples along a path. A sample's LP differs from the previous one's by the path's
/// motion between them, so each end's optimal basis there is nearly optimal: the dense simplex restarts
/// from it (dual simplex pivots where the new sample's point has left the polytope, then the primal
/// simplex) and certifies the optimum from the LP's own data, as in the projection; GLPK solves what it
/// gives up, and finds every empty slice (confirmed in exact arithmetic).
class SliceLp {
 public:
  /// The next sample's LP, its bounds final (kept by reference until the next load).
  void load(const PolytopeLp& lp);
  /// Maximise sign x (+1: the slice's top, -1: its bottom). 1: optimal, x the optimum's x (not times
  /// sign) and `fixed` (if given) u's column; 0: the slice is empty; -1: the solver failed. The dense
  /// simplex starts from `start` if given (a basis of this LP's shape), else from this end's last optimum;
  /// where the dense simplex gives up from that start (one neither primal nor dual feasible, for which it
  /// has no phase, most often), the bottom starts again from the top's optimum of this same LP (a vertex of
  /// its polytope: primal feasible), and the top from its last optimum, before GLPK.
  int extreme(double sign, double& x, PolytopeProjector::FixedColumn* fixed,
              const std::vector<signed char>* start = nullptr);
  /// This end's last optimal basis (0 the top, 1 the bottom; empty: none).
  const std::vector<signed char>& basis(int end) const { return basis_[end]; }
  int dense = 0, glpk = 0;  ///< LPs each engine answered (statistics)

 private:
  const PolytopeLp* lp_ = nullptr;
  DenseSimplex dense_;
  PolytopeProjector glpk_[2];                // per end: each warm-starts from its own last optimum
  std::vector<signed char> basis_[2];       // per end: the last optimal basis (empty: none yet)
  Eigen::VectorXd objective_, z_, row_norm_;
  bool norms_ = false;                      // row_norm_ is of the loaded LP
  bool top_here_ = false;                   // basis_[0] is the loaded LP's top optimum
};

}  // namespace pathpace::detail
