#pragma once
// The analytic centre of a polytope {y : A y = b, G y <= h}: the unique maximiser of Σ_r log(h_r - G_r y)
// on the affine set (the feasible set must be bounded). Used for a force distribution with room
// (ContactConstraint::force_distribution, ForceDistribution::Centre).
//
// Why it is continuous: Σ log s is strictly concave on a bounded polytope with an interior, so the centre
// is unique, and its optimality conditions Zᵀ Gᵀ (1/s) = 0 have a nonsingular Jacobian (Zᵀ Gᵀ S⁻² G Z,
// Z a basis of A's null space), so by the implicit function theorem the centre is a smooth function of
// (A, b, G, h) wherever A keeps its rank and the interior is not empty. A vertex of an LP jumps between
// vertices when the objective's direction turns past an edge; the centre does not.

#include <Eigen/Core>

namespace pathpace::detail {

class PolytopeProjector;

struct CentreResult {
  // Failed: Newton did not converge (the caller keeps its vertex); SolverError: the phase-I LP's solver
  // failed or did not finish (the caller reports it, as for its own LP).
  enum class Status { Centre, EmptyInterior, Infeasible, Failed, SolverError };
  Status status = Status::Failed;
  double depth = 0.0;   // the phase-I LP's max-min slack when it ran (rows of unit norm), else -1
  int newton_steps = 0;
  bool phase_one = false;  // the warm start was not strictly feasible: an LP found the start
};

/// Damped Newton with equality constraints (in A's null space), started from `y` projected onto A y = b
/// when that is strictly feasible, else from the max-min-slack point of an LP (on `lp`, kept warm). Rows of
/// G should have unit norm (slacks in y's units). `empty_tol`: a max-min slack at most this means the
/// interior is empty (EmptyInterior; y is then that LP's point). On Centre, y is the centre.
CentreResult analytic_centre(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& G,
                             const Eigen::VectorXd& h, double empty_tol, PolytopeProjector& lp, Eigen::VectorXd& y);

}  // namespace pathpace::detail
