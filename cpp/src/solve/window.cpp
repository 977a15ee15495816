// The chain simplex and barrier solvers of one SLP window, and the rows they share (solve/window.hpp).
#include "solve/window.hpp"

#include <algorithm>
#include <cmath>

#include "solve/chain_simplex.hpp"

namespace pathpace::detail {

// ∂T/∂θ_j = -(1/√θ_j) Σ_{k ∋ j} Δs_k / (√θ_k + √θ_{k+1})² (eq. 27). A zero θ_j would give -inf: a floor
// keeps the LP finite while still pulling θ_j up as hard as the trust region allows.
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

namespace {

// Directional derivative of T along d at θ + α d (T is convex along the segment).
double slope(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta, const Eigen::VectorXd& d, double alpha,
             double floor, Eigen::VectorXd& tmp, Eigen::VectorXd& g) {
  tmp = theta + alpha * d;
  gradient(ds, tmp, floor, g);
  return g.dot(d);
}

}  // namespace

// Bisection on the sign of the slope (T convex along the segment): 60 halvings reach the last bit of α.
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

// The first LP is the Frank-Wolfe check at the start, and usually all that the window needs (with the step to
// its vertex). Each next check starts from the previous LP's optimal basis, whether the step went all the way
// to its vertex (the optimum of a time-optimal problem is usually a vertex) or stopped short of it (an
// interior optimum): the window's set and bounds do not change, so that basis is still primal feasible, and
// the bound is computed at the new iterate whatever vertex the simplex stands on. An interior optimum on a
// face of low dimension (a coupling row traded between its two points) is then typically certified by the
// second check, with a few pivots.
bool chain_simplex_window(const WindowData& w, const WindowPolicy& policy, const WindowProgress& progress,
                          Eigen::VectorXd& theta, WindowResult& out) {
  const Eigen::Index m = w.m;
  const Eigen::VectorXd& ds = w.ds;
  const double floor = w.floor, rel_target = w.rel_target;
  Eigen::VectorXd g, d(m + 1), tmp, gtmp;
  ChainSimplex cs(w.chain, w.a, m, w.lo, w.hi, w.first, w.last);
  gradient(ds, theta, floor, g);
  bool warm = false;
  for (int fw = 0; fw < policy.chain_frank_wolfe; ++fw) {
    const double gap = cs.gap(theta, g, chain_pivot_budget(policy, progress), warm);
    if (!std::isfinite(gap)) break;
    ++out.lp_solves;  // an LP, solved without GLPK
    out.lower = std::max(out.lower, out.T - gap);
    out.gap = out.T - out.lower;
    if (out.gap <= rel_target * out.T) return true;
    // The Frank-Wolfe step to the LP's vertex with an exact line search; the bound above certifies it if the
    // step realises all but the target of the decrease the LP promised.
    d = cs.vertex() - theta;
    // A step of nearly the whole way goes to the vertex itself (T there is above the segment's minimum by a
    // second-order amount), whose tight rows then hold exactly.
    const double alpha = line_search(ds, theta, d, floor, tmp, gtmp);
    const bool to_vertex = alpha >= 0.999;
    Eigen::VectorXd next = to_vertex ? cs.vertex() : Eigen::VectorXd(theta + alpha * d);
    for (Eigen::Index j = 0; j <= m; ++j) next[j] = std::clamp(next[j], w.lo[j], w.hi[j]);
    const double T_next = duration(ds, next);
    if (!(T_next < out.T)) break;
    theta = next;
    out.theta = next;
    out.T = T_next;
    out.gap = T_next - out.lower;
    gradient(ds, theta, floor, g);
    if (out.gap <= rel_target * out.T) return true;
    warm = true;
  }
  return false;
}

// Only the rows that support interval k's polygon within the column bounds' box can bind in any of the
// window's LPs (every trust region lies inside that box): typically two or three of the ~5 per interval.
std::vector<WindowRow> window_rows(const WindowData& w) {
  Polygon2d poly;
  std::vector<Line> local, kept;
  std::vector<WindowRow> wrows;
  for (Eigen::Index k = 0; k < w.m; ++k) {
    const View<Line> all = w.chain.rows(w.a + k);
    kept.assign(all.begin(), all.end());
    if (k >= w.first && k + 1 <= w.last && all.n > 2) {
      // Rows on one variable only (α or β exactly 0) are kept as they are: the polygon would fold them into
      // its box and report the box's side, not the row.
      local.clear();
      kept.clear();
      for (size_t i = 0; i < all.n; ++i) {
        if (all[i].a == 0.0 || all[i].b == 0.0) kept.push_back(all[i]);
        else local.push_back({all[i].a, all[i].b, all[i].c, static_cast<int>(i)});
      }
      interval_polygon(poly, w.lo[k], w.hi[k], w.lo[k + 1], w.hi[k + 1], {local.data(), local.size()});
      if (poly.empty()) {
        kept.assign(all.begin(), all.end());
      } else {
        for (const Line& e : poly.edges())
          if (e.id >= 0) kept.push_back(all[static_cast<size_t>(e.id)]);
      }
    }
    for (const Line& r : kept) wrows.push_back({k, r.a, r.b, r.c});
  }
  return wrows;
}

// Newton's method on a log barrier (solve/barrier.hpp: O(n) per step, certified by the same kind of bound) from
// the current iterate, for an optimum that is not at a vertex of the window's set (a long stretch of many short
// path pieces), where trust-region SLP crawls.
bool barrier_attempt(const WindowData& w, const std::vector<WindowRow>& rows, const WindowPolicy& policy,
                     const Eigen::VectorXd& theta, WindowResult& out) {
  const BarrierResult br = barrier_window(w.ds, rows, w.lo, w.hi, theta, w.rel_target * out.T, policy.barrier_steps,
                                          w.limits.deadline);
  out.newton_steps = br.newton_steps;
  if (!(br.ok && br.T <= out.T)) return false;
  out.theta = br.theta;
  out.T = br.T;
  out.lower = std::max(out.lower, br.lower);
  out.gap = out.T - out.lower;
  out.status = SlpOutcome::Status::Converged;
  return true;
}

}  // namespace pathpace::detail
