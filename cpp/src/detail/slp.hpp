#pragma once
// Sequential linear programming on eq. (26)-(27) with a trust region, warm-started GLPK simplex and an
// exact line search along each LP step. Convergence is certified by the Frank-Wolfe gap: for convex T,
// T(θ) - T* <= ∇T(θ)·(θ - θ_lp) where θ_lp minimises the linearisation over the whole feasible set.

#include <Eigen/Core>

#include "detail/reachability.hpp"
#include "pathpace/solver_options.hpp"

namespace pathpace::detail {

struct SlpOutcome {
  enum class Status { Converged, IterationLimit, LpFailed };
  Status status = Status::Converged;
  Eigen::VectorXd theta;
  int iterations = 0;
  int lp_solves = 0;
  double gap = 0.0;  // last Frank-Wolfe gap over T (bound on (T - T*) / T)
};

/// T(θ) = Σ 2Δs_k / (√θ_k + √θ_{k+1}) (eq. 27); +inf if some interval has θ_k = θ_{k+1} = 0.
double duration(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta);

/// Starts from the feasible θ (θ_0 and θ_N are kept fixed).
SlpOutcome slp(const Chain& chain, const Eigen::VectorXd& theta_start, const SolverOptions& options);

}  // namespace pathpace::detail
