#pragma once
// Sequential linear programming on eq. (26)-(27) (sec. V.C), run only on windows of the grid where the
// relaxation without the positively coupling rows (see Chain) is not already optimal.
//
// Why windows suffice. Let R be the feasible set without the coupling rows (max-closed, greatest element
// θ'), F ⊆ R the full one, so every feasible θ has θ <= θ'. T = Σ_k f_k(θ_k, θ_{k+1}) with every f_k
// decreasing in both arguments. Cover the intervals where θ' violates a coupling row by disjoint windows
// W_i = [a_i, b_i] and let P_i minimise Σ_{k in [a_i, b_i)} f_k subject to all rows of those intervals and
// θ_lo <= θ <= min(θ_hi, θ') on the window's points (its edge points free, except at the path's ends).
// For any feasible y: y <= θ' makes every f_k outside the windows >= f_k(θ'), and y restricted to W_i is
// feasible for P_i, so
//     T(y) >= LB := Σ_{k outside} f_k(θ') + Σ_i opt(P_i),     opt(P_i) >= T_i(z_i) - gap_i
// where gap_i is the Frank-Wolfe gap of the window's iterate z_i (convexity of T). If each z_i meets θ'
// at its edges, z = (θ' outside, z_i inside) is feasible (outside the windows θ' violates no row) and
// attains the bound up to Σ gap_i: the global optimum, certified, without a whole-chain LP. If an edge is
// pressed below θ', the window is widened and solved again. LB is valid in every case; the profile that
// is returned is made exactly feasible by the capped forward pass, and its T - LB is the certified gap.

#include <chrono>
#include <functional>
#include <limits>

#include <Eigen/Core>

#include "solve/reachability.hpp"
#include "pathpace/solver_options.hpp"

namespace pathpace::detail {

using Clock = std::chrono::steady_clock;

struct SlpOutcome {
  enum class Status { Converged, IterationLimit, TimeLimit, LpFailed };
  Status status = Status::Converged;
  Eigen::VectorXd theta;  // feasible profile (repaired by the capped forward pass)
  Eigen::VectorXd caps;   // what the repair was capped by: the windows' iterates between stretches of `upper`
  double T = 0.0;         // its duration, T(theta)
  double lower = 0.0;     // certified lower bound on T*
  int iterations = 0;     // SLP iterations, all windows
  int lp_solves = 0;
  int newton_steps = 0;   // barrier Newton steps, all windows (solve/barrier.hpp)
  int windows = 0;        // windows in the final cover
  Eigen::Index window_points = 0;  // grid points in the final cover
};

/// T(θ) = Σ 2Δs_k / (√θ_k + √θ_{k+1}) (eq. 27); +inf if some interval has θ_k = θ_{k+1} = 0.
double duration(const Eigen::Ref<const Eigen::VectorXd>& ds, const Eigen::Ref<const Eigen::VectorXd>& theta);

/// What the SLP takes of SolverOptions (checked once, by validate() in solve/options.hpp) and the solve's
/// deadline.
struct SlpLimits {
  double tolerance = 1e-7;                 ///< relative gap to certify (SolverOptions::tolerance)
  int max_iterations = 200;                ///< GLPK SLP iterations per window
  double initial_trust_region = 0.5;       ///< relative to max θ of the window's start
  double lp_feasibility_tolerance = 1e-9;  ///< GLPK's tol_bnd
  bool use_barrier = true;                 ///< Method::Auto: the barrier may take a window (Method::Slp: not)
  Clock::time_point deadline = Clock::time_point::max();
};
SlpLimits slp_limits(const SolverOptions& options, Clock::time_point deadline);

/// Where the SLP starts. `upper` bounds every feasible θ componentwise and satisfies every row except on the
/// intervals the first windows must cover: the relaxed greatest element θ' with `relaxed` = true (windows
/// around the intervals where it violates a coupling row), or any bound (e.g. θ_hi) with `relaxed` = false
/// (one window, the whole chain). `greedy` is the full reachability analysis's greedy profile, each window's
/// feasible start, and `repair` that analysis's capped greedy pass (forward_pass on its polygons, or
/// line_forward_pass from the start speed): it makes the result exactly feasible. T_upper is T(upper) when the
/// caller has it (NaN: computed here).
struct SlpStart {
  const Eigen::VectorXd& greedy;
  std::function<Eigen::VectorXd(const Eigen::VectorXd& caps)> repair;
  const Eigen::VectorXd& upper;
  bool relaxed;
  double T_upper = std::numeric_limits<double>::quiet_NaN();
};

/// The optimum of eq. (26)-(27) by SLP on windows (see above). Stops at the deadline with the best feasible
/// profile and its bound.
SlpOutcome windowed_slp(const Chain& chain, const SlpStart& start, const SlpLimits& limits);

}  // namespace pathpace::detail
