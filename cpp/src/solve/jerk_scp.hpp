#pragma once
// Jerk-limited timing (TimeScalingProblem::add_jerk_limits): sequential inner linearisation in (θ_k, b_k), θ = ṡ²
// and b = s̈ at each grid point, s̈ linear in s between them (base/jerk_interval.hpp; docs/method.md "Jerk limits").
//
// Every row of the problem's constraints holds at each grid point k with (x, u) = (θ_k, b_k). A jerk limit at
// grid point k, on each side of it (b' of the interval there), reads |p' b' + 3 p'' b + p''' θ| <= J/√θ; J/√θ is
// convex in θ, so its tangent at the iterate's θ̄ lies below it and the linearised row is an inner one: each LP's
// solution is feasible for the true rows, and the iterate itself is feasible for the next linearisation (the
// tangent is exact at θ̄). The objective T = Σ interval times is convex in (θ, b); each round minimises its
// linearisation over the linearised rows within a trust region, then a line search on T itself (the GLPK
// rounds, the fallback), or (jerk_newton, solve/jerk_rows.hpp) a barrier method with banded Newton steps.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/result.hpp"

namespace pathpace::detail {

struct JerkInput {
  const PathSamples* samples = nullptr;
  Eigen::MatrixXd p3_left, p3_right;  ///< p''' at each grid point from the left / right piece
  Eigen::VectorXd jmin, jmax;
  const std::vector<ConstraintRows>* rows = nullptr;
  double sdot_begin = 0, sdot_end = 0;
  bool zero_sddot_begin = false, zero_sddot_end = false;
  Eigen::VectorXd theta_hint;  ///< θ of the second-order optimum (where the first linearisation is taken)
  int max_iterations = 200;
  /// The structured solve tries the primal-dual method first (jerk_newton.cpp), the barrier path where it does
  /// not certify; false: the barrier path alone (SolverOptions::method = Slp, for checking).
  bool primal_dual = true;
  double tolerance = 1e-7;
  double lp_tolerance = 1e-9;
  double time_limit = 60;
};

struct JerkOutput {
  Status status = Status::NumericalError;
  std::string message;
  Eigen::VectorXd theta, b;  ///< at the grid points, exactly consistent (θ_{k+1} = θ_k + Δs_k (b_k + b_{k+1}))
  double duration = 0;
  int iterations = 0, lp_solves = 0;
  int newton_steps = 0;     ///< of the structured solver (jerk_newton)
  bool structured = false;  ///< answered by jerk_newton (else by the GLPK rounds, its fallback)
  /// (T - T_lin*) / T bound: T_lin* the optimum of the convex problem linearised at the final iterate. From the
  /// barrier's multipliers (jerk_newton; T there by 8-point Gauss-Legendre quadrature) or the Frank-Wolfe gap of
  /// the last LP without trust region (GLPK rounds); +inf if that failed.
  double gap = std::numeric_limits<double>::infinity();
  /// Worst violation of a grid row (limits, exact jerk rows, bounds) at the answer, relative to the row's size.
  double grid_violation = 0;
};

JerkOutput solve_jerk(const JerkInput& in);

/// Interval times of a jerk profile (θ, b at the grid points): the rest-end intervals as base/jerk_interval.hpp.
Eigen::VectorXd jerk_interval_times(const Eigen::VectorXd& s, const Eigen::VectorXd& theta, const Eigen::VectorXd& b);

}  // namespace pathpace::detail
