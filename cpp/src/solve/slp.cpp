#include "solve/slp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "solve/window.hpp"

namespace pathpace::detail {

double duration(const Eigen::Ref<const Eigen::VectorXd>& ds, const Eigen::Ref<const Eigen::VectorXd>& theta) {
  // Array expressions (no branch per interval): the square roots and divisions vectorise; called on the whole
  // chain several times per solve.
  const Eigen::Index n = ds.size();
  const Eigen::ArrayXd r = theta.array().max(0.0).sqrt();
  const auto w = r.head(n) + r.tail(n);  // an expression: one temporary per call, not two
  if ((w == 0.0).any()) return std::numeric_limits<double>::infinity();
  return (2.0 * ds.array() / w).sum();
}

namespace {

// What every window of one windowed_slp shares: the bound above θ, the feasible start, the target.
struct WindowShared {
  const Chain& chain;
  const Eigen::VectorXd& hi_all;
  const Eigen::VectorXd& start;
  double rel_target;  // the gap to reach, relative to the window's T
  const SlpLimits& limits;
};

// One window: its points [a, b], and whether θ_a (θ_b) is fixed at the start (the path's ends).
struct WindowSpan {
  Eigen::Index a, b;
  bool fix_a, fix_b;
};

// The window's problem (lo <= θ <= min(hi, upper) on its points, the ends fixed at the path's ends), and its
// start in theta and out: the feasible start clamped to the bounds, which only rounding can move.
WindowData make_window(const WindowShared& shared, const WindowSpan& span, Eigen::VectorXd& theta,
                       WindowResult& out) {
  const Eigen::Index a = span.a, m = span.b - span.a;  // intervals
  WindowData w{shared.chain, a, m, shared.chain.ds.segment(a, m), shared.chain.x_lo.segment(a, m + 1),
               shared.hi_all.segment(a, m + 1), 0, 0, 0, 0.0, 0.0, shared.rel_target, shared.limits};
  theta = shared.start.segment(a, m + 1);
  for (Eigen::Index j = 0; j <= m; ++j) {
    w.hi[j] = std::max(w.hi[j], w.lo[j]);
    theta[j] = std::clamp(theta[j], w.lo[j], w.hi[j]);  // rounding only: the start is feasible
  }
  if (span.fix_a) w.lo[0] = w.hi[0] = theta[0] = shared.start[a];
  if (span.fix_b) w.lo[m] = w.hi[m] = theta[m] = shared.start[span.b];
  out.theta = theta;
  out.T = duration(w.ds, theta);
  // Columns: the points that are not fixed.
  w.first = span.fix_a ? 1 : 0;
  w.last = span.fix_b ? m - 1 : m;
  w.cols = static_cast<int>(w.last - w.first + 1);
  w.theta_max = std::max(theta.maxCoeff(), 1e-300);
  w.floor = 1e-24 * w.theta_max * w.theta_max + 1e-300;
  return w;
}

// Minimises Σ_{k in [a, b)} f_k (eq. 27) over θ_a..θ_b subject to the rows of those intervals (eq. 26) and
// lo <= θ <= hi, with the solvers that WindowPolicy chooses in turn, until one certifies the gap
// rel_target T or the window ends (time limit, LP failure, max_iterations of GLPK SLP).
WindowResult slp_window(const WindowShared& shared, const WindowSpan& span, GlpkLp& lp) {
  WindowResult out;
  Eigen::VectorXd theta;
  const WindowData w = make_window(shared, span, theta, out);
  if (w.cols <= 0) {
    out.gap = 0.0;
    out.lower = out.T;
    return out;
  }
  if (Clock::now() >= shared.limits.deadline) {
    out.status = SlpOutcome::Status::TimeLimit;
    return out;
  }
  const WindowPolicy policy;
  WindowProgress progress;
  progress.free_points = w.cols;
  progress.barrier_allowed = shared.limits.use_barrier;
  progress.max_iterations = shared.limits.max_iterations;
  // Every feasible θ <= hi on the window, so T(hi) bounds its optimum from below: the bracket of the start.
  if (progress.barrier_allowed && !barrier_first(policy, progress))
    progress.far_start = far_start(policy, out.T, duration(w.ds, w.hi));
  std::vector<WindowRow> rows;
  bool have_rows = false;
  std::optional<GlpkSlp> slp;
  for (;;) {
    const WindowSolver next = next_solver(policy, progress);
    if (next == WindowSolver::ChainSimplex) {
      progress.chain_tried = true;
      if (chain_simplex_window(w, policy, progress, theta, out)) return out;
      continue;
    }
    if (next == WindowSolver::Done) {
      out.status = SlpOutcome::Status::IterationLimit;
      return out;
    }
    if (!have_rows) {
      rows = window_rows(w);
      have_rows = true;
    }
    if (next == WindowSolver::Barrier) {
      progress.barrier_tried = true;
      if (barrier_attempt(w, rows, policy, theta, out)) return out;
      continue;
    }
    if (!slp) {
      slp.emplace(w, rows, theta, lp);
      progress.slp_started = true;
      if (!slp->loaded()) {
        out.status = SlpOutcome::Status::LpFailed;
        return out;
      }
    }
    if (slp->iterate(slp_pause(policy, progress), theta, out)) return out;
    progress.slp_iterations = out.iterations;
  }
}

struct Window {
  Eigen::Index a, b;
  bool solved = false;
  WindowResult result;
  double t_upper = 0.0;  // T(upper) on the window (set with the cover, again when it is widened or merged)
};

// Sorts by start and merges windows that overlap or touch (a shared point would need one value from two
// problems); a merged window is solved again.
void merge(std::vector<Window>& ws) {
  std::sort(ws.begin(), ws.end(), [](const Window& x, const Window& y) { return x.a < y.a; });
  std::vector<Window> out;
  for (Window& w : ws) {
    if (!out.empty() && w.a <= out.back().b) {
      out.back().b = std::max(out.back().b, w.b);
      out.back().solved = false;
      continue;
    }
    out.push_back(std::move(w));
  }
  ws = std::move(out);
}

// The least ε >= 0 such that (1 - ε) z meets every row α θ_k + β θ_{k+1} <= c with c > 0 that z breaks
// (scaling θ scales the left side), doubled, plus 1e-12: a margin for the slices' rounding. NaN if z breaks a
// row with c <= 0, which no scaling mends.
double shrink_to_rows(const Chain& chain, const Eigen::VectorXd& z) {
  double eps = 0.0;
  for (Eigen::Index k = 0; k < chain.intervals(); ++k)
    for (const Line& r : chain.rows(k)) {
      const double lhs = r.a * z[k] + r.b * z[k + 1];
      if (!(lhs > r.c)) continue;
      if (!(r.c > 0.0)) return std::numeric_limits<double>::quiet_NaN();
      eps = std::max(eps, 1.0 - r.c / lhs);
    }
  return 2.0 * eps + 1e-12;
}

}  // namespace

SlpLimits slp_limits(const SolverOptions& options, Clock::time_point deadline) {
  SlpLimits limits;
  limits.tolerance = options.tolerance;
  limits.max_iterations = options.max_iterations;
  limits.initial_trust_region = options.initial_trust_region;
  limits.lp_feasibility_tolerance = options.lp_feasibility_tolerance;
  limits.use_barrier = options.method == Method::Auto;
  limits.deadline = deadline;
  return limits;
}

SlpOutcome windowed_slp(const Chain& chain, const SlpStart& start, const SlpLimits& limits) {
  const Eigen::VectorXd& upper = start.upper;
  double T_upper = start.T_upper;
  SlpOutcome out;
  const Eigen::Index n = chain.intervals();
  std::vector<Window> ws;
  const Eigen::Index margin = 2 + n / 500;
  if (start.relaxed) {
    // Where the greedy feasible profile θ_g meets θ' the optimum does too, in the common case (it never
    // departs from θ' except to slow down for a coupling row, and θ_g already does so, with the deceleration
    // ramps before and after): the stretches where θ_g < θ', widened by a margin, are the first windows.
    // Each contains the intervals it must (where θ' breaks a coupling row, θ_g, which is feasible, differs
    // from it at one end at least).
    const Eigen::VectorXd& g = start.greedy;
    auto below = [&](Eigen::Index j) { return g[j] < upper[j] - 1e-12 * std::max(upper[j], 1e-300); };
    for (Eigen::Index j = 0; j <= n; ++j) {
      if (!below(j)) continue;
      Eigen::Index e = j;
      while (e < n && below(e + 1)) ++e;
      ws.push_back({std::max<Eigen::Index>(0, j - margin), std::min(n, e + margin), false, {}});
      j = e;
    }
    for (Eigen::Index k = 0; k < n; ++k) {
      bool violated = false;
      for (const Line& r : chain.coupled_rows(k))
        if (row_violation(r, upper[k], upper[k + 1]) > 1e-12) {
          violated = true;
          break;
        }
      if (violated) ws.push_back({std::max<Eigen::Index>(0, k - margin), std::min(n, k + 1 + margin), false, {}});
    }
  } else {
    ws.push_back({0, n, false, {}});
  }
  merge(ws);

  if (std::isnan(T_upper)) T_upper = duration(chain.ds, upper);
  auto window_upper = [&](const Window& w) {
    return duration(chain.ds.segment(w.a, w.b - w.a), upper.segment(w.a, w.b - w.a + 1));
  };
  // The windows share half the tolerance on T (the rest is for the repair), each in proportion to its T:
  // relative to its own T, a window may be off by 0.5 tol T / Σ_windows T_i.
  double t_windows = 0.0;
  for (Window& w : ws) t_windows += (w.t_upper = window_upper(w));
  const double rel_target = 0.5 * limits.tolerance * std::max(1.0, T_upper / std::max(t_windows, 1e-300));
  GlpkLp lp;
  Eigen::VectorXd z;
  for (;;) {
    for (Window& w : ws) {
      if (w.solved) continue;
      w.result = slp_window({chain, upper, start.greedy, rel_target, limits}, {w.a, w.b, w.a == 0, w.b == n}, lp);
      out.newton_steps += w.result.newton_steps;
      w.solved = true;
      out.iterations += w.result.iterations;
      out.lp_solves += w.result.lp_solves;
      if (w.result.status != SlpOutcome::Status::Converged && out.status == SlpOutcome::Status::Converged)
        out.status = w.result.status;
    }
    // Assemble, repair, bound.
    z = upper;
    double lower = T_upper, T_z = T_upper;
    for (const Window& w : ws) {
      z.segment(w.a, w.b - w.a + 1) = w.result.theta;
      // Every feasible y <= upper, so the window's part of T(y) is >= its part of T(upper) as well.
      lower += std::max(w.t_upper, w.result.lower) - w.t_upper;
      T_z += w.result.T - w.t_upper;  // T(z), from the windows' parts
    }
    out.theta = start.repair(z);
    out.caps = z;
    out.lower = lower;
    out.T = duration(chain.ds, out.theta);
    // The repair can lose far more than z's infeasibility (GLPK's tolerance): where the rows bound θ_{k+1}
    // from below with a slope above 1 (a braking ramp), once it has raised θ_k by a rounding-size amount it
    // must raise θ_{k+1} by about twice that, and so on until θ meets the greedy profile, far above T(z). z
    // scaled down by its largest relative excess meets those rows with room, and its repair follows it.
    if (out.T - T_z > 0.1 * limits.tolerance * T_z) {
      const double eps = shrink_to_rows(chain, z);
      if (!std::isnan(eps) && eps < 1e-6) {
        const Eigen::VectorXd shrunk = z * (1.0 - eps);
        Eigen::VectorXd alt = start.repair(shrunk);
        const double T_alt = duration(chain.ds, alt);
        if (T_alt < out.T) {
          out.theta = std::move(alt);
          out.caps = shrunk;
          out.T = T_alt;
        }
      }
    }
    if (out.T - lower <= limits.tolerance * lower || out.status != SlpOutcome::Status::Converged) break;
    // Widen the windows whose optimum presses an edge below θ': there the seam with θ' is not feasible.
    bool widened = false;
    for (Window& w : ws) {
      const Eigen::Index width = std::max(w.b - w.a, margin);
      const auto pressed = [&](Eigen::Index j, double v) { return v < upper[j] - 1e-10 * std::max(upper[j], 1e-300); };
      const bool left = w.a > 0 && pressed(w.a, w.result.theta[0]);
      const bool right = w.b < n && pressed(w.b, w.result.theta[w.b - w.a]);
      if (left) w.a = std::max<Eigen::Index>(0, w.a - width);
      if (right) w.b = std::min(n, w.b + width);
      if (left || right) w.solved = false;
      widened = widened || !w.solved;
    }
    if (!widened) break;
    merge(ws);
    for (Window& w : ws)
      if (!w.solved) w.t_upper = window_upper(w);  // widened or merged: its part of T(upper) anew
  }
  out.windows = static_cast<int>(ws.size());
  for (const Window& w : ws) out.window_points += w.b - w.a + 1;
  return out;
}

}  // namespace pathpace::detail
