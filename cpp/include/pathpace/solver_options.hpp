#pragma once
/// @file solver_options.hpp
/// Options of TimeScalingProblem::solve.

namespace pathpace {

/// How the optimum of eq. (26)-(27) is found.
enum class Method {
  /// Reachability analysis, then: if no interval row couples θ_k and θ_{k+1} with two positive
  /// coefficients, the feasible set is closed under the componentwise max, and the greedy forward
  /// profile is its greatest element, hence the global optimum (T decreases in every θ_k). Otherwise the
  /// relaxation without those rows brackets the optimum; if the bracket exceeds the tolerance, SLP runs
  /// on windows around the intervals where the relaxation's greatest element breaks a coupling row, the
  /// rest of the grid keeping that element (see docs/method.md: the result is the global optimum).
  /// With jerk limits: the primal-dual interior-point method first, the barrier path where it does not
  /// certify (docs/method.md, "Jerk limits").
  Auto,
  /// Always run SLP over the whole chain from the reachability start (for checking, or if the
  /// shortcuts are not wanted). With jerk limits: the barrier path alone.
  Slp,
};

/// Where the limits hold.
enum class Guarantee {
  /// At the grid points, with the s̈ of both adjacent intervals (eq. 26): the paper's collocation.
  Grid,
  /// At every instant: velocity and acceleration limits by Bernstein bounds of the path's polynomial
  /// pieces over each interval (sufficient by construction; needs a piecewise-polynomial path); every
  /// other constraint (torque, contact, linear) audited at `audit_points` interior points per interval,
  /// the broken rows added there as exact cuts and the problem solved again until the audit passes.
  Continuous,
};

struct SolverOptions {
  Method method = Method::Auto;
  int max_iterations = 200;        ///< SLP iterations per window
  /// Relative optimality tolerance: a result is Optimal when (T - T*) / T* is certified below it, by the
  /// Frank-Wolfe gap of the SLP or by the lattice relaxation's lower bound. The discretisation error of
  /// the grid itself is O(Δs), far above the default.
  double tolerance = 1e-7;
  double initial_trust_region = 0.5;   ///< trust-region half-width, relative to max θ of the start
  double lp_feasibility_tolerance = 1e-9;  ///< GLPK primal feasibility tolerance (tol_bnd)
  /// On an infeasible result, also find the smallest relaxation of each constraint family that makes
  /// it feasible (Result::relaxation; costs a few dozen reachability analyses).
  bool explain = true;
  Guarantee guarantee = Guarantee::Grid;
  int audit_points = 4;            ///< interior points per interval audited (guarantee = continuous)
  /// Relative violation the audit accepts, relative to the row's own terms (max(|c|, |a x| + |b u|)), which
  /// can be larger than the limit itself: 1e-10 keeps violations of the limits below 1e-9 relative.
  double audit_tolerance = 1e-10;
  int max_audit_rounds = 30;       ///< solve-audit-cut rounds before giving up (status IterationLimit)
  /// Wall-clock budget of one solve in seconds (+inf: none). When it runs out during SLP the solve ends
  /// with Status::TimeLimit, the best feasible timing found and its certified gap.
  double time_limit = 60.0;
};

}  // namespace pathpace
