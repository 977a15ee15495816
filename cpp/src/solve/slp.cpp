#include "solve/slp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "solve/barrier.hpp"
#include "solve/chain_simplex.hpp"
#include "lp/glpk_lp.hpp"

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

// ∂T/∂θ_j = -(1/√θ_j) Σ_{k ∋ j} Δs_k / (√θ_k + √θ_{k+1})². A zero θ_j would give -inf: a floor keeps
// the LP finite while still pulling θ_j up as hard as the trust region allows.
void gradient(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta, double floor, Eigen::VectorXd& g) {
  const Eigen::Index n = ds.size();
  g.setZero(n + 1);
  Eigen::VectorXd w = theta.cwiseMax(0.0).cwiseSqrt();
  for (Eigen::Index k = 0; k < n; ++k) {
    const double s = w[k] + w[k + 1];
    const double term = ds[k] / std::max(s * s, floor);
    g[k] -= term;
    g[k + 1] -= term;
  }
  for (Eigen::Index j = 0; j <= n; ++j) g[j] /= std::max(w[j], std::sqrt(floor));
}

// Directional derivative of T along d at θ + α d (T is convex along the segment).
double slope(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta, const Eigen::VectorXd& d, double alpha,
             double floor, Eigen::VectorXd& tmp, Eigen::VectorXd& g) {
  tmp = theta + alpha * d;
  gradient(ds, tmp, floor, g);
  return g.dot(d);
}

// The exact minimiser of T on the segment θ + α d, α in [0, 1] (T is convex along it): bisection on the sign
// of the slope.
double line_search(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta, const Eigen::VectorXd& d, double floor,
                   Eigen::VectorXd& tmp, Eigen::VectorXd& g) {
  if (slope(ds, theta, d, 1.0, floor, tmp, g) <= 0.0) return 1.0;
  double l = 0.0, h = 1.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (l + h);
    (slope(ds, theta, d, mid, floor, tmp, g) > 0.0 ? h : l) = mid;
  }
  return l;
}

}  // namespace

namespace {

// When the barrier method takes over a window (see slp_window), after the chain simplex's Frank-Wolfe
// iterations (which certify nearly every window of the arm corpus, at N = 100 also those whose bracket is
// large, in fewer µs than ~25 Newton steps) have given up: at once if the greedy profile is far from the
// relaxation's bound on the window (relative bracket above kBarrierFirstBracket: many reversals per stretch, an
// interior optimum, where the SLP from the greedy start needs many trust-region steps); otherwise after
// kSlpBeforeBarrier GLPK SLP iterations that did not certify it. Measured: at N = 10000, windows of ~800
// points: one GLPK LP ~1 ms, the barrier ~3 ms; on the 400-waypoint random walk the greedy profile is 6 % above
// the optimum and the barrier certifies a 1001-point window in ~8 ms where SLP took 1.4 s. On windows of
// kBarrierFirstColumns free points or more the barrier comes first of all, before the chain simplex too
// (the walk at N = 100000: windows of ~5000 points, one GLPK LP each ~75 ms, the barrier ~30 ms).
constexpr int kSlpBeforeBarrier = 2;
constexpr double kBarrierFirstBracket = 1e-2;
constexpr int kBarrierFirstColumns = 2000;
constexpr int kBarrierSteps = 300;  // its Newton step budget (then the SLP goes on)
constexpr int kChainPivots = 64;    // ChainSimplex's pivot budget per LP (then the barrier or GLPK)
constexpr int kChainFrankWolfe = 6; // its Frank-Wolfe iterations (then the barrier or GLPK)

struct WindowResult {
  SlpOutcome::Status status = SlpOutcome::Status::Converged;
  Eigen::VectorXd theta;  // θ_a .. θ_b
  double T = 0.0;         // Σ_{k in [a, b)} f_k at theta
  double gap = std::numeric_limits<double>::infinity();  // Frank-Wolfe gap of theta (absolute), if computed
  // Best lower bound on the window's optimum: max over the Frank-Wolfe checks of T(θ) - gap(θ).
  double lower = -std::numeric_limits<double>::infinity();
  int iterations = 0, lp_solves = 0, newton_steps = 0;
};

int remaining_ms(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::clamp<long long>(left, 0, 1000000000LL));
}

// The paper's SLP (sec. V.C) on window [a, b]: minimise Σ_{k in [a, b)} f_k over θ_a..θ_b subject to the rows
// of those intervals and lo <= θ <= hi, θ_a (θ_b) fixed at the start value if fix_a (fix_b). The LP is in θ
// itself, so its rows never change; the trust region and the bounds are column bounds; each LP starts from
// the previous one's basis. The first LP has no trust region: it is the Frank-Wolfe check, and at a start
// that is already optimal (the common case: the greedy profile) it certifies it at once. `target` is the
// absolute gap to reach.
WindowResult slp_window(const Chain& chain, Eigen::Index a, Eigen::Index b, const Eigen::VectorXd& hi_all,
                        const Eigen::VectorXd& start, bool fix_a, bool fix_b, double rel_target,
                        const SolverOptions& options, Clock::time_point deadline, GlpkLp& lp, bool use_barrier) {
  WindowResult out;
  const Eigen::Index m = b - a;  // intervals
  const Eigen::VectorXd ds = chain.ds.segment(a, m);
  Eigen::VectorXd theta = start.segment(a, m + 1);
  Eigen::VectorXd lo = chain.x_lo.segment(a, m + 1), hi = hi_all.segment(a, m + 1);
  for (Eigen::Index j = 0; j <= m; ++j) {
    hi[j] = std::max(hi[j], lo[j]);
    theta[j] = std::clamp(theta[j], lo[j], hi[j]);  // rounding only: the start is feasible
  }
  if (fix_a) lo[0] = hi[0] = theta[0] = start[a];
  if (fix_b) lo[m] = hi[m] = theta[m] = start[b];
  out.theta = theta;
  out.T = duration(ds, theta);
  // Columns: the points that are not fixed.
  const Eigen::Index first = fix_a ? 1 : 0, last = fix_b ? m - 1 : m;
  const int cols = static_cast<int>(last - first + 1);
  if (cols <= 0) {
    out.gap = 0.0;
    out.lower = out.T;
    return out;
  }
  const double theta_max = std::max(theta.maxCoeff(), 1e-300);
  const double floor = 1e-24 * theta_max * theta_max + 1e-300;
  Eigen::VectorXd g, d(m + 1), tmp, gtmp;
  if (Clock::now() >= deadline) {
    out.status = SlpOutcome::Status::TimeLimit;
    return out;
  }
  // Every feasible θ <= hi on the window, so T(hi) bounds its optimum from below: the bracket of the start
  // (read only to choose the barrier).
  const bool barrier_first = use_barrier && cols >= kBarrierFirstColumns;
  bool far_start = barrier_first;  // implies use_barrier
  if (use_barrier && !far_start) {
    const double T_hi = duration(ds, hi);
    far_start = std::isfinite(T_hi) && out.T - T_hi > kBarrierFirstBracket * out.T;
  }
  if (!barrier_first) {
    // The first LP below is the Frank-Wolfe check at the start, and usually all that the window needs (with the
    // step to its vertex): the chain simplex does both without GLPK when it can (see ChainSimplex). Each next
    // check starts from the previous LP's optimal basis, whether the step went all the way to its vertex (the
    // optimum of a time-optimal problem is usually a vertex) or stopped short of it (an interior optimum): the
    // window's set and bounds do not change, so that basis is still primal feasible, and the bound is computed
    // at the new iterate whatever vertex the simplex stands on. An interior optimum on a face of low
    // dimension (a coupling row traded between its two points) is typically certified by the second check
    // (xArm7 seed 3 (b), N = 1000: a 122-point window, step 0.48, then a check from the same basis with 2
    // pivots, where GLPK's cold LP took ~1 ms); kChainFrankWolfe iterations, then GLPK (or the barrier).
    ChainSimplex cs(chain, a, m, lo, hi, first, last);
    gradient(ds, theta, floor, g);
    bool warm = false;
    for (int fw = 0; fw < kChainFrankWolfe; ++fw) {
      const double gap = cs.gap(theta, g, kChainPivots, warm);
      if (!std::isfinite(gap)) break;
      ++out.lp_solves;  // an LP, solved without GLPK
      out.lower = std::max(out.lower, out.T - gap);
      out.gap = out.T - out.lower;
      if (out.gap <= rel_target * out.T) return out;
      // The Frank-Wolfe step to the LP's vertex with an exact line search; the bound above certifies it if the
      // step realises all but the target of the decrease the LP promised.
      d = cs.vertex() - theta;
      // A step of nearly the whole way goes to the vertex itself (T there is above the segment's minimum by a
      // second-order amount), whose tight rows then hold exactly.
      const double alpha = line_search(ds, theta, d, floor, tmp, gtmp);
      const bool to_vertex = alpha >= 0.999;
      Eigen::VectorXd next = to_vertex ? cs.vertex() : Eigen::VectorXd(theta + alpha * d);
      for (Eigen::Index j = 0; j <= m; ++j) next[j] = std::clamp(next[j], lo[j], hi[j]);
      const double T_next = duration(ds, next);
      if (!(T_next < out.T)) break;
      theta = next;
      out.theta = next;
      out.T = T_next;
      out.gap = T_next - out.lower;
      gradient(ds, theta, floor, g);
      if (out.gap <= rel_target * out.T) return out;
      warm = true;
    }
  }
  // Only the rows that support interval k's polygon within the column bounds' box can bind in any of the
  // window's LPs (every trust region lies inside that box): typically two or three of the ~5 per interval.
  Polygon2d poly;
  std::vector<Line> local, kept;
  std::vector<WindowRow> wrows;
  for (Eigen::Index k = 0; k < m; ++k) {
    const View<Line> all = chain.rows(a + k);
    kept.assign(all.begin(), all.end());
    if (k >= first && k + 1 <= last && all.n > 2) {
      // Rows on one variable only (α or β exactly 0) are kept as they are: the polygon would fold them into
      // its box and report the box's side, not the row.
      local.clear();
      kept.clear();
      for (size_t i = 0; i < all.n; ++i) {
        if (all[i].a == 0.0 || all[i].b == 0.0) kept.push_back(all[i]);
        else local.push_back({all[i].a, all[i].b, all[i].c, static_cast<int>(i)});
      }
      interval_polygon(poly, lo[k], hi[k], lo[k + 1], hi[k + 1], {local.data(), local.size()});
      if (poly.empty()) {
        kept.assign(all.begin(), all.end());
      } else {
        for (const Line& e : poly.edges())
          if (e.id >= 0) kept.push_back(all[static_cast<size_t>(e.id)]);
      }
    }
    for (const Line& r : kept) wrows.push_back({k, r.a, r.b, r.c});
  }

  // Newton's method on a log barrier (solve/barrier.hpp: O(n) per step, certified by the same kind of bound)
  // from the current iterate, where the optimum is not at a vertex of the window's set (typically a long
  // stretch where the optimum is interior: many short path pieces) and trust-region SLP crawls; true if it
  // certified the window. First (before GLPK is set up) on a far start, else after kSlpBeforeBarrier SLP
  // iterations; the SLP goes on only if it fails.
  auto barrier = [&]() {
    const BarrierResult br = barrier_window(ds, wrows, lo, hi, theta, rel_target * out.T, kBarrierSteps, deadline);
    out.newton_steps = br.newton_steps;
    if (!(br.ok && br.T <= out.T)) return false;
    out.theta = br.theta;
    out.T = br.T;
    out.lower = std::max(out.lower, br.lower);
    out.gap = out.T - out.lower;
    out.status = SlpOutcome::Status::Converged;
    return true;
  };
  if (far_start && barrier()) return out;

  lp.reset(cols);
  // The LP is posed in y_j = θ_j / σ_j with σ_j the start's θ_j (floored), and each row divided by its size
  // at the start: ṡ² spans orders of magnitude along a path (1e-5 near a slow point, 1 elsewhere) and
  // GLPK's tolerances are absolute in the problem it is given, so in θ itself a row with c ~ 1e-5 could be
  // broken by 1e-9, 1e-4 of itself, which the repair would then pay for in T.
  Eigen::VectorXd sigma = theta.cwiseMax(1e-6 * theta_max);
  struct LpRow {
    Eigen::Index k;  // interval (local)
    double alpha, beta, c;
    bool on_k, on_k1;  // coefficient on a column at point k / k+1
    int n;             // LP coefficients (1 or 2), normalised
    int col[2];
    double val[2], rhs;
  };
  std::vector<LpRow> lp_rows;   // the rows in the LP, in its order
  std::vector<LpRow> waiting;   // the rows not (yet) in it
  std::vector<int> idx;
  std::vector<double> val;
  for (const WindowRow& r : wrows) {
    const Eigen::Index k = r.k;
    idx.clear();
    val.clear();
    double rhs = r.c;
    double size = 0.0;
    if (k >= first && k <= last) {
      if (r.alpha != 0.0) { idx.push_back(static_cast<int>(k - first)); val.push_back(r.alpha * sigma[k]); }
    } else {
      rhs -= r.alpha * theta[k];
    }
    if (k + 1 >= first && k + 1 <= last) {
      if (r.beta != 0.0) { idx.push_back(static_cast<int>(k + 1 - first)); val.push_back(r.beta * sigma[k + 1]); }
    } else {
      rhs -= r.beta * theta[k + 1];
    }
    if (idx.empty()) continue;  // both ends fixed: nothing to decide
    for (double v : val) size += std::abs(v);
    size = std::max(size, std::abs(rhs));
    for (double& v : val) v /= size;
    LpRow row{k, r.alpha, r.beta, r.c, k >= first && k <= last && r.alpha != 0.0,
              k + 1 >= first && k + 1 <= last && r.beta != 0.0, static_cast<int>(idx.size()), {idx[0], 0},
              {val[0], 0.0}, rhs / size};
    if (idx.size() > 1) {
      row.col[1] = idx[1];
      row.val[1] = val[1];
    }
    // Rows are added lazily: first those nearly tight at the start (slack within 1 % of the row's size),
    // which the start basis and most LP vertices need; the others only once an LP solution breaks them
    // (see solve_lp). The LP is then a relaxation until the last round, which still gives valid bounds,
    // and its basis factorisations have a quarter of the rows.
    const double ax = r.alpha * theta[k], by = r.beta * theta[k + 1];
    const double slack = (r.c - ax - by) / std::max({std::abs(r.c), std::abs(ax) + std::abs(by), 1e-300});
    if (slack <= 1e-2) {
      lp.add_row_upper(idx, val, row.rhs);
      lp_rows.push_back(row);
    } else {
      waiting.push_back(row);
    }
  }
  if (!lp.load()) {
    out.status = SlpOutcome::Status::LpFailed;
    return out;
  }

  std::vector<double> cost(static_cast<size_t>(cols)), x;
  double rho = options.initial_trust_region * theta_max;
  bool global = true;  // next LP without trust region (Frank-Wolfe)

  // The start basis: the greedy profile is a vertex of the window's set (each θ_j is the top of a slice of
  // a polygon, so a row of interval j-1 or j, or a bound, is tight there), so a basis with one tight
  // constraint per column is primal feasible and the first LP needs no phase 1 and, at a nearly optimal
  // start, few pivots (instead of a climb from the slack basis over every column). Columns are matched
  // left to right to a tight bound, else a tight unused row of interval j-1, else of interval j; if some
  // column finds none, or the basis is singular, GLPK starts from the slack basis instead.
  auto start_basis = [&]() {
    std::vector<GlpkLp::Stat> rs(lp_rows.size(), GlpkLp::Stat::Basic), cs(static_cast<size_t>(cols), GlpkLp::Stat::Basic);
    std::vector<char> tight(lp_rows.size(), 0);
    std::vector<size_t> row_begin(static_cast<size_t>(m) + 1, lp_rows.size());
    for (size_t i = lp_rows.size(); i-- > 0;) row_begin[static_cast<size_t>(lp_rows[i].k)] = i;
    for (Eigen::Index k = m - 1; k >= 0; --k)
      row_begin[static_cast<size_t>(k)] = std::min(row_begin[static_cast<size_t>(k)], row_begin[static_cast<size_t>(k) + 1]);
    for (size_t i = 0; i < lp_rows.size(); ++i) {
      const LpRow& r = lp_rows[i];
      const double ax = r.alpha * theta[r.k], by = r.beta * theta[r.k + 1];
      tight[i] = r.c - ax - by <= 1e-9 * std::max({1.0, std::abs(r.c), std::abs(ax), std::abs(by)});
    }
    auto take = [&](Eigen::Index k, Eigen::Index j) {  // a tight unused row of interval k acting on column j
      if (k < 0 || k >= m) return false;
      for (size_t i = row_begin[static_cast<size_t>(k)]; i < row_begin[static_cast<size_t>(k) + 1]; ++i) {
        const LpRow& r = lp_rows[i];
        if (!tight[i] || rs[i] != GlpkLp::Stat::Basic || !(j == r.k ? r.on_k : r.on_k1)) continue;
        rs[i] = GlpkLp::Stat::AtUpper;
        return true;
      }
      return false;
    };
    for (Eigen::Index j = first; j <= last; ++j) {
      const double tol = 1e-9 * std::max(std::abs(hi[j]), 1e-300);
      GlpkLp::Stat& c = cs[static_cast<size_t>(j - first)];
      if (theta[j] >= hi[j] - tol) c = GlpkLp::Stat::AtUpper;
      else if (theta[j] <= lo[j] + tol) c = GlpkLp::Stat::AtLower;
      else if (!take(j - 1, j) && !take(j, j)) return;
    }
    lp.set_basis(rs, cs);
  };
  bool first_lp = true;

  // Minimises g·θ over the window's LP, within `radius` of θ (inf: the whole set); d = θ_lp - θ.
  auto solve_lp = [&](double radius) -> SlpOutcome::Status {
    for (Eigen::Index j = first; j <= last; ++j) {
      const double l = std::max(lo[j], theta[j] - radius), h = std::min(hi[j], theta[j] + radius);
      lp.set_col_bounds(static_cast<int>(j - first), std::min(l, h) / sigma[j], h / sigma[j]);
    }
    if (first_lp) start_basis();
    first_lp = false;
    const int ms = remaining_ms(deadline);
    if (ms <= 0) return SlpOutcome::Status::TimeLimit;
    ++out.lp_solves;
    GlpkLp::Outcome o = lp.solve(options.lp_feasibility_tolerance, ms);
    for (;;) {
      if (o == GlpkLp::Outcome::TimeLimit) return SlpOutcome::Status::TimeLimit;
      if (o != GlpkLp::Outcome::Optimal) return SlpOutcome::Status::LpFailed;
      lp.column_values(x);
      // Rows still waiting that the solution breaks join the LP, which is solved again from its basis.
      size_t kept_waiting = 0;
      bool added = false;
      for (const LpRow& r : waiting) {
        double act = 0.0;
        for (int t = 0; t < r.n; ++t) act += r.val[t] * x[static_cast<size_t>(r.col[t])];
        if (act > r.rhs + 10.0 * options.lp_feasibility_tolerance * (1.0 + std::abs(r.rhs))) {
          idx.assign(r.col, r.col + r.n);
          val.assign(r.val, r.val + r.n);
          lp.append_row_upper(idx, val, r.rhs);
          lp_rows.push_back(r);
          added = true;
        } else {
          waiting[kept_waiting++] = r;
        }
      }
      waiting.resize(kept_waiting);
      if (!added) break;
      ++out.lp_solves;
      o = lp.solve(options.lp_feasibility_tolerance, std::max(remaining_ms(deadline), 1));
    }
    d.setZero();
    for (Eigen::Index j = first; j <= last; ++j) d[j] = sigma[j] * x[static_cast<size_t>(j - first)] - theta[j];
    return SlpOutcome::Status::Converged;
  };

  for (out.iterations = 0; out.iterations < options.max_iterations; ++out.iterations) {
    // The SLP has not certified the window in a few LPs: see barrier above.
    if (use_barrier && !far_start && out.iterations == kSlpBeforeBarrier && barrier()) return out;
    if (Clock::now() >= deadline) {
      out.status = SlpOutcome::Status::TimeLimit;
      return out;
    }
    gradient(ds, theta, floor, g);
    for (Eigen::Index j = first; j <= last; ++j) cost[static_cast<size_t>(j - first)] = g[j] * sigma[j];
    lp.set_objective(cost);
    SlpOutcome::Status st = solve_lp(global ? std::numeric_limits<double>::infinity() : rho);
    if (st != SlpOutcome::Status::Converged) {
      out.status = st;
      return out;
    }
    double predicted = -g.dot(d);
    if (!global && (predicted <= rel_target * out.T || rho <= 1e-13 * theta_max)) {
      // The trust-region step promises nothing more: check optimality over the whole window.
      st = solve_lp(std::numeric_limits<double>::infinity());
      if (st != SlpOutcome::Status::Converged) {
        out.status = st;
        return out;
      }
      predicted = -g.dot(d);
      global = true;
    }
    if (global) {
      // Frank-Wolfe: T(θ) - min T <= ∇T(θ)·θ - min ∇T(θ)·θ' over the window's set, the minimum bounded
      // from below by weak duality (not by GLPK's word that its vertex is optimal).
      double g_theta = 0.0;
      for (Eigen::Index j = first; j <= last; ++j) g_theta += g[j] * theta[j];
      out.gap = std::max({g_theta - lp.lagrangian_bound(cost), predicted, 0.0});
      out.lower = std::max(out.lower, out.T - out.gap);
      if (out.gap <= rel_target * out.T) {
        out.status = SlpOutcome::Status::Converged;
        return out;
      }
    }
    // Exact line search on the convex 1-D restriction: bisection on the sign of the slope.
    const double alpha = line_search(ds, theta, d, floor, tmp, gtmp);
    Eigen::VectorXd next = theta + alpha * d;
    for (Eigen::Index j = 0; j <= m; ++j) next[j] = std::clamp(next[j], lo[j], hi[j]);
    const double T_next = duration(ds, next);
    if (T_next < out.T) {
      theta = next;
      out.theta = theta;
      out.T = T_next;
      // The bound of an earlier check still holds: if the step has brought T within the target of it, the
      // new iterate is certified without another LP (a small Frank-Wolfe step realises nearly all of the
      // decrease the LP predicted, so this is the common end).
      out.gap = out.T - out.lower;
      if (out.gap <= rel_target * out.T) {
        out.status = SlpOutcome::Status::Converged;
        ++out.iterations;
        return out;
      }
    }
    const double step = (alpha * d).cwiseAbs().maxCoeff();
    // A full Frank-Wolfe step lands on a vertex of the window's set, where the optimum of a time-optimal
    // problem usually is: check it with another Frank-Wolfe LP first; otherwise continue with a trust region.
    const bool full_fw_step = global && alpha >= 0.999;
    if (global) rho = std::max(step, 1e-6 * theta_max);
    else if (alpha >= 0.999) rho *= 2.0;
    else rho = std::max(0.5 * step, 0.25 * rho);
    global = full_fw_step;
  }
  out.status = SlpOutcome::Status::IterationLimit;
  return out;
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

SlpOutcome windowed_slp(const Chain& chain, const Reachability& full, const Eigen::VectorXd& upper, bool relaxed,
                        double theta_begin, const SolverOptions& options, Clock::time_point deadline,
                        double T_upper) {
  SlpOutcome out;
  const Eigen::Index n = chain.intervals();
  std::vector<Window> ws;
  const Eigen::Index margin = 2 + n / 500;
  if (relaxed) {
    // Where the greedy feasible profile θ_g meets θ' the optimum does too, in the common case (it never
    // departs from θ' except to slow down for a coupling row, and θ_g already does so, with the deceleration
    // ramps before and after): the stretches where θ_g < θ', widened by a margin, are the first windows.
    // Each contains the intervals it must (where θ' breaks a coupling row, θ_g, which is feasible, differs
    // from it at one end at least).
    const Eigen::VectorXd& g = full.theta;
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
  const double rel_target = 0.5 * options.tolerance * std::max(1.0, T_upper / std::max(t_windows, 1e-300));
  GlpkLp lp;
  const bool use_barrier = options.method == Method::Auto;
  Eigen::VectorXd z;
  for (;;) {
    for (Window& w : ws) {
      if (w.solved) continue;
      w.result = slp_window(chain, w.a, w.b, upper, full.theta, w.a == 0, w.b == n, rel_target, options, deadline, lp,
                            use_barrier);
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
    out.theta = forward_pass(full, theta_begin, &z);  // θ_0 = theta_begin
    out.lower = lower;
    out.T = duration(chain.ds, out.theta);
    // The repair can lose far more than z's infeasibility (GLPK's tolerance): where the rows bound θ_{k+1}
    // from below with a slope above 1 (a braking ramp), once it has raised θ_k by a rounding-size amount it
    // must raise θ_{k+1} by about twice that, and so on until θ meets the greedy profile (the pure SLP on
    // xArm7, seed 3 (b), N = 1000: the tail went back to the greedy one, T 1.5e-5 above z's). z scaled down
    // by its largest relative excess meets those rows with room, and its repair follows it.
    if (out.T - T_z > 0.1 * options.tolerance * T_z) {
      const double eps = shrink_to_rows(chain, z);
      if (!std::isnan(eps) && eps < 1e-6) {
        const Eigen::VectorXd shrunk = z * (1.0 - eps);
        Eigen::VectorXd alt = forward_pass(full, theta_begin, &shrunk);
        const double T_alt = duration(chain.ds, alt);
        if (T_alt < out.T) {
          out.theta = std::move(alt);
          out.T = T_alt;
        }
      }
    }
    if (out.T - lower <= options.tolerance * lower || out.status != SlpOutcome::Status::Converged) break;
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
    ++out.widenings;
    merge(ws);
    for (Window& w : ws)
      if (!w.solved) w.t_upper = window_upper(w);  // widened or merged: its part of T(upper) anew
  }
  out.windows = static_cast<int>(ws.size());
  for (const Window& w : ws) out.window_points += w.b - w.a + 1;
  return out;
}

}  // namespace pathpace::detail
