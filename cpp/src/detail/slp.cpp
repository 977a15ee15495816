#include "detail/slp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "detail/glpk_lp.hpp"

namespace pathpace::detail {

double duration(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta) {
  double T = 0.0;
  for (Eigen::Index k = 0; k < ds.size(); ++k) {
    const double w = std::sqrt(std::max(theta[k], 0.0)) + std::sqrt(std::max(theta[k + 1], 0.0));
    if (w == 0.0) return std::numeric_limits<double>::infinity();
    T += 2.0 * ds[k] / w;
  }
  return T;
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

}  // namespace

SlpOutcome slp(const Chain& chain, const Eigen::VectorXd& theta_start, const SolverOptions& options) {
  SlpOutcome out;
  out.theta = theta_start;
  const Eigen::Index n = chain.ds.size();
  const int cols = static_cast<int>(n) - 1;  // θ_1 .. θ_{N-1}; the ends are fixed
  if (cols <= 0) return out;

  const double scale = std::max(theta_start.maxCoeff(), 1e-300);
  const double floor = 1e-24 * scale * scale + 1e-300;

  // The LP is written in the step d = θ' - θ (columns free): each row α θ'_k + β θ'_{k+1} <= c becomes
  // α d_k + β d_{k+1} <= c - α θ_k - β θ_{k+1} >= 0, and the trust region and the bounds on θ are rows
  // d_j <= ub_j, -d_j <= lb_j with ub_j, lb_j >= 0. So d = 0 is always feasible and the slack basis is a
  // primal-feasible start (the "first basis built from the feasible start").
  struct LpRow {
    Eigen::Index k;
    double alpha, beta, c;
  };
  std::vector<LpRow> rows;
  GlpkLp lp;
  lp.reset(cols);
  std::vector<int> idx;
  std::vector<double> val;
  for (Eigen::Index k = 0; k < n; ++k) {
    for (const Line& r : chain.rows(k)) {
      idx.clear();
      val.clear();
      if (k > 0 && r.a != 0.0) { idx.push_back(static_cast<int>(k) - 1); val.push_back(r.a); }
      if (k + 1 < n && r.b != 0.0) { idx.push_back(static_cast<int>(k)); val.push_back(r.b); }
      if (idx.empty()) continue;  // both ends fixed: nothing to decide
      lp.add_row_upper(idx, val, 0.0);
      rows.push_back({k, r.a, r.b, r.c});
    }
  }
  const int first_box_row = static_cast<int>(rows.size());
  for (int j = 0; j < cols; ++j) {
    lp.add_row_upper({j}, {1.0}, 0.0);
    lp.add_row_upper({j}, {-1.0}, 0.0);
  }
  if (!lp.load()) {
    out.status = SlpOutcome::Status::LpFailed;
    return out;
  }

  Eigen::VectorXd theta = theta_start, g, d(n + 1), tmp, gtmp;
  std::vector<double> cost(static_cast<size_t>(cols)), x;
  double T = duration(chain.ds, theta);
  double rho = options.initial_trust_region * scale;

  // Minimises g·d over the step LP around θ with trust-region radius `radius` (inf: the whole set).
  auto solve_lp = [&](double radius, Eigen::VectorXd& step) -> bool {
    for (size_t i = 0; i < rows.size(); ++i) {
      const LpRow& r = rows[i];
      const double slack = r.c - r.alpha * theta[r.k] - r.beta * theta[r.k + 1];
      // θ is feasible up to rounding; a -1e-17 slack must not make d = 0 infeasible.
      lp.set_row_upper(static_cast<int>(i), std::max(slack, 0.0));
    }
    for (int j = 0; j < cols; ++j) {
      const Eigen::Index k = j + 1;
      const double up = std::min(radius, chain.x_hi[k] - theta[k]);
      const double down = std::min(radius, theta[k] - chain.x_lo[k]);
      lp.set_row_upper(first_box_row + 2 * j, std::max(up, 0.0));
      lp.set_row_upper(first_box_row + 2 * j + 1, std::max(down, 0.0));
    }
    ++out.lp_solves;
    if (lp.solve(options.lp_feasibility_tolerance) != GlpkLp::Outcome::Optimal) return false;
    lp.column_values(x);
    step.setZero(n + 1);
    for (int j = 0; j < cols; ++j) step[j + 1] = x[static_cast<size_t>(j)];
    return true;
  };

  for (out.iterations = 0; out.iterations < options.max_iterations; ++out.iterations) {
    gradient(chain.ds, theta, floor, g);
    for (int j = 0; j < cols; ++j) cost[static_cast<size_t>(j)] = g[j + 1];
    lp.set_objective(cost);

    if (!solve_lp(rho, d)) {
      out.status = SlpOutcome::Status::LpFailed;
      break;
    }
    double predicted = -g.dot(d);
    bool frank_wolfe = false;
    if (predicted <= options.tolerance * T || rho <= 1e-13 * scale) {
      // The trust-region step promises nothing more: check optimality over the whole feasible set.
      if (!solve_lp(std::numeric_limits<double>::infinity(), d)) {
        out.status = SlpOutcome::Status::LpFailed;
        break;
      }
      out.gap = -g.dot(d) / T;
      if (out.gap <= options.tolerance) {
        out.status = SlpOutcome::Status::Converged;
        out.theta = theta;
        return out;
      }
      frank_wolfe = true;
    }
    // Exact line search on the convex 1-D restriction: bisection on the sign of the slope.
    double alpha = 1.0;
    if (slope(chain.ds, theta, d, 1.0, floor, tmp, gtmp) > 0.0) {
      double lo = 0.0, hi = 1.0;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (slope(chain.ds, theta, d, mid, floor, tmp, gtmp) > 0.0 ? hi : lo) = mid;
      }
      alpha = lo;
    }
    Eigen::VectorXd next = theta + alpha * d;
    const double T_next = duration(chain.ds, next);
    if (T_next < T) {
      theta = next;
      T = T_next;
    }
    const double step = (alpha * d).cwiseAbs().maxCoeff();
    if (frank_wolfe) rho = std::max(step, 1e-6 * scale);
    else if (alpha >= 0.999) rho *= 2.0;
    else rho = std::max(0.5 * step, 0.25 * rho);
  }
  out.theta = theta;
  if (out.status == SlpOutcome::Status::Converged) out.status = SlpOutcome::Status::IterationLimit;
  return out;
}

}  // namespace pathpace::detail
