#pragma once
// Which solver takes an SLP window next (solve/slp.hpp), and every constant that decides it.
//
// Three solvers minimise eq. (27) over a window's part of eq. (26), each certified by a bound from convexity:
//   - the chain simplex (solve/chain_simplex.hpp): Frank-Wolfe iterations whose LPs it solves on the chain
//     itself, without GLPK, warm from the previous basis. A window whose optimum is a vertex (the usual
//     case of a time-optimal profile, sec. V) is certified in one or two of them;
//   - the log-barrier method (solve/barrier.hpp): O(n) Newton steps on the tridiagonal Hessian, for an
//     optimum inside the window's set, where the SLP's trust region crawls;
//   - GLPK SLP (sec. V.C): trust-region LPs, the fallback that solves every window, slowly on large ones.

namespace pathpace::detail {

/// The constants of the choice, each with why.
struct WindowPolicy {
  /// Windows with this many free points go to the barrier before anything else: one GLPK LP's
  /// factorisations grow faster than the window, the barrier's Newton step is O(n).
  int barrier_first_columns = 2000;
  /// A start whose T is above T(hi) on the window by more than this (relative) is far from the optimum
  /// (many reversals per stretch, an interior optimum): the barrier takes it once the chain simplex has
  /// given up, before GLPK, since SLP from such a start needs many trust-region steps.
  double barrier_first_bracket = 1e-2;
  /// GLPK SLP iterations that did not certify a near start before the barrier gets the window (the
  /// SLP goes on only if the barrier fails).
  int slp_before_barrier = 2;
  int barrier_steps = 300;     ///< the barrier's Newton step budget (then GLPK SLP goes on)
  /// The chain simplex's pivot budget per LP (then the barrier or GLPK): this many, or chain_pivots_per_point
  /// per free point if more. A cold start (the greedy vertex) of a window that every point's row presses
  /// takes about one pivot per point: a guarantee="continuous" round, whose cuts reach most of the path,
  /// needed 92 on a 91-point window and went to GLPK SLP at a fixed 64. Each pivot is one banded solve.
  int chain_pivots = 64;
  double chain_pivots_per_point = 2.0;
  int chain_frank_wolfe = 6;   ///< its Frank-Wolfe iterations (then the barrier or GLPK)
};

enum class WindowSolver { ChainSimplex, Barrier, GlpkSlp, Done };

/// What the choice looks at: the window and what has run on it. A solver that certified the window, or
/// ended it (time limit, LP failure), ends the window before the policy is asked again.
struct WindowProgress {
  int free_points = 0;         ///< the window's unknowns (its points less the fixed ends)
  bool barrier_allowed = true; ///< Method::Auto (Method::Slp: GLPK SLP only)
  bool far_start = false;      ///< far_start() of the start (read only when the barrier is allowed)
  bool chain_tried = false, barrier_tried = false;
  bool slp_started = false;    ///< GLPK's LP set up (then slp_iterations count)
  int slp_iterations = 0;
  int max_iterations = 200;    ///< SolverOptions::max_iterations
};

/// The start's relative bracket T(start) - T(hi) > barrier_first_bracket T(start) (T(hi) <= T* on the
/// window, every feasible θ being <= hi); false if T(hi) is not finite.
bool far_start(const WindowPolicy& policy, double T_start, double T_hi);

/// True if the barrier comes first of all (a large window), so that neither the chain simplex runs nor is
/// the bracket of the start needed.
bool barrier_first(const WindowPolicy& policy, const WindowProgress& progress);

/// The solver that runs next on a window that is not yet certified: the chain simplex first (unless
/// barrier_first); then the barrier if barrier_first or far_start; then GLPK SLP, interrupted once after
/// slp_before_barrier iterations for the barrier; Done when GLPK SLP has spent max_iterations.
WindowSolver next_solver(const WindowPolicy& policy, const WindowProgress& progress);

/// The chain simplex's pivot budget per LP on the window: chain_pivots on a far start that the barrier may
/// take (its optimum is likely interior, where Frank-Wolfe crawls: a long random walk's 999-point window
/// spent six LPs of up to 2n pivots there, then the barrier), else the larger of that and
/// chain_pivots_per_point per free point.
int chain_pivot_budget(const WindowPolicy& policy, const WindowProgress& progress);

/// The iteration count at which GLPK SLP, when it runs, hands back to the policy.
int slp_pause(const WindowPolicy& policy, const WindowProgress& progress);

}  // namespace pathpace::detail
