#pragma once
// A window of eq. (26)-(27) solved by a primal log-barrier method with Newton steps on the chain.
//
// Why. Every row of eq. (26) couples at most two neighbouring unknowns θ_k, θ_{k+1}, and T of eq. (27) is a
// sum of terms in (θ_k, θ_{k+1}): the Hessian of T plus any barrier of those rows is tridiagonal, so a Newton
// step costs O(n) (one tridiagonal solve), with no basis factorisation. The SLP of sec. V.C takes many
// trust-region steps where the optimum is not at a vertex (long stretches of interior optimum, e.g. a path
// of many short spline pieces); the barrier method converges there in a few dozen Newton steps. Its answer
// is certified the same way as the SLP's: T is convex, so for any y in the window's set and any
// multipliers λ >= 0 of its rows,
//     T(y) >= T(θ) + ∇T(θ)·(y - θ) >= T(θ) - ∇T(θ)·θ - λ·c + Σ_j min_{lo_j <= y_j <= hi_j} (∇T(θ) + Aᵀλ)_j y_j,
// a bound computed here from the barrier's own multipliers λ_r = 1 / (t s_r), in O(rows).

#include <chrono>
#include <vector>

#include <Eigen/Core>

namespace pathpace::detail {

/// α θ_k + β θ_{k+1} <= c on the window's local interval k (0 <= k < m).
struct WindowRow {
  Eigen::Index k;
  double alpha, beta, c;
};

struct BarrierResult {
  bool ok = false;        // converged to the target gap; otherwise nothing below is meaningful
  Eigen::VectorXd theta;  // strictly feasible for every row and bound (θ_0..θ_m)
  double T = 0.0;         // Σ_k f_k at theta
  double lower = 0.0;     // certified lower bound on the window's optimum
  int newton_steps = 0;
};

/// Minimises Σ_{k<m} 2Δs_k / (√θ_k + √θ_{k+1}) over θ_0..θ_m subject to `rows` and lo <= θ <= hi, where
/// the points with lo_j == hi_j are fixed at that value. `start` must satisfy every row (the greedy
/// profile); the barrier starts from a strictly feasible point between it and lo. Gives up (ok = false)
/// if no strictly feasible start is found, after `max_steps` Newton steps, at `deadline`, or if the
/// certified gap does not reach `abs_target`.
BarrierResult barrier_window(const Eigen::VectorXd& ds, const std::vector<WindowRow>& rows, const Eigen::VectorXd& lo,
                             const Eigen::VectorXd& hi, const Eigen::VectorXd& start, double abs_target, int max_steps,
                             std::chrono::steady_clock::time_point deadline);

}  // namespace pathpace::detail
