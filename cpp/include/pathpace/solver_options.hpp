#pragma once
/// @file solver_options.hpp
/// Options of TimeScalingProblem::solve.

namespace pathpace {

/// How the optimum of eq. (26)-(27) is found.
enum class Method {
  /// Reachability analysis, then: if no interval row couples θ_k and θ_{k+1} with two positive
  /// coefficients, the feasible set is closed under the componentwise max, and the greedy forward
  /// profile is its greatest element, hence the global optimum (T decreases in every θ_k). Otherwise the
  /// relaxation without those rows brackets the optimum; SLP runs only if the bracket exceeds the
  /// tolerance.
  Auto,
  /// Always run SLP from the reachability start (for checking, or if the shortcut is not wanted).
  Slp,
};

struct SolverOptions {
  Method method = Method::Auto;
  int max_iterations = 200;        ///< SLP iterations
  /// Relative optimality tolerance: a result is Optimal when (T - T*) / T* is certified below it, by the
  /// Frank-Wolfe gap of the SLP or by the lattice relaxation's lower bound. The discretisation error of
  /// the grid itself is O(Δs), far above the default.
  double tolerance = 1e-7;
  double initial_trust_region = 0.5;   ///< trust-region half-width, relative to max θ of the start
  double lp_feasibility_tolerance = 1e-9;  ///< GLPK primal feasibility tolerance (tol_bnd)
  /// On an infeasible result, also find the smallest relaxation of each constraint family that makes
  /// it feasible (Result::relaxation; costs a few dozen reachability analyses).
  bool explain = true;
};

}  // namespace pathpace
