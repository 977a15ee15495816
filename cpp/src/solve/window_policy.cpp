#include "solve/window_policy.hpp"

#include <algorithm>
#include <cmath>

namespace pathpace::detail {

bool far_start(const WindowPolicy& policy, double T_start, double T_hi) {
  return std::isfinite(T_hi) && T_start - T_hi > policy.barrier_first_bracket * T_start;
}

int chain_pivot_budget(const WindowPolicy& policy, const WindowProgress& progress) {
  if (progress.barrier_allowed && progress.far_start) return policy.chain_pivots;
  return std::max(policy.chain_pivots, static_cast<int>(std::ceil(policy.chain_pivots_per_point * progress.free_points)));
}

bool barrier_first(const WindowPolicy& policy, const WindowProgress& progress) {
  return progress.barrier_allowed && progress.free_points >= policy.barrier_first_columns;
}

namespace {

// The barrier takes over GLPK SLP that has run slp_before_barrier iterations on a near start (a far start
// had the barrier before GLPK).
bool barrier_interrupts(const WindowPolicy& policy, const WindowProgress& progress) {
  return progress.barrier_allowed && !progress.far_start && !progress.barrier_tried &&
         progress.slp_iterations < policy.slp_before_barrier;
}

}  // namespace

WindowSolver next_solver(const WindowPolicy& policy, const WindowProgress& progress) {
  const bool first = barrier_first(policy, progress);
  if (!progress.chain_tried && !first) return WindowSolver::ChainSimplex;
  const bool far = first || (progress.barrier_allowed && progress.far_start);
  if (far && !progress.barrier_tried) return WindowSolver::Barrier;
  if (!progress.slp_started) return WindowSolver::GlpkSlp;
  if (progress.barrier_allowed && !far && !progress.barrier_tried &&
      progress.slp_iterations == policy.slp_before_barrier && progress.slp_iterations < progress.max_iterations)
    return WindowSolver::Barrier;
  return progress.slp_iterations < progress.max_iterations ? WindowSolver::GlpkSlp : WindowSolver::Done;
}

int slp_pause(const WindowPolicy& policy, const WindowProgress& progress) {
  return barrier_interrupts(policy, progress) ? std::min(policy.slp_before_barrier, progress.max_iterations)
                                              : progress.max_iterations;
}

}  // namespace pathpace::detail
