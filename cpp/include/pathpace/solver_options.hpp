#pragma once
/// @file solver_options.hpp
/// Options of TimeScalingProblem::solve.

namespace pathpace {

/// How the optimum of eq. (26)-(27) is found.
enum class Method {
  /// Reachability analysis, then: if no interval row couples θ_k and θ_{k+1} with two positive
  /// coefficients, the feasible set is closed under the componentwise max, and the greedy forward
  /// profile is its greatest element, hence the global optimum (T decreases in every θ_k); otherwise SLP.
  Auto,
  /// Always run SLP from the reachability start (for checking, or if the shortcut is not wanted).
  Slp,
};

struct SolverOptions {
  Method method = Method::Auto;
  int max_iterations = 200;        ///< SLP iterations
  double objective_tolerance = 1e-12;  ///< stop when the relative decrease of T and the LP's predicted one are below it
  double initial_trust_region = 0.5;   ///< trust-region half-width, relative to max θ of the start
  double lp_feasibility_tolerance = 1e-9;  ///< GLPK primal feasibility tolerance (tol_bnd)
};

}  // namespace pathpace
