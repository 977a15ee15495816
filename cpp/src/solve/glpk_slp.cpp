// GLPK SLP on one window (solve/window.hpp): the paper's sec. V.C, with a trust region and a Frank-Wolfe
// certificate.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "solve/window.hpp"

namespace pathpace::detail {

namespace {

int remaining_ms(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::clamp<long long>(left, 0, 1000000000LL));
}

}  // namespace

GlpkSlp::GlpkSlp(const WindowData& w, const std::vector<WindowRow>& rows, const Eigen::VectorXd& theta, GlpkLp& lp)
    : w_(w), lp_(lp), d_(w.m + 1) {
  lp_.reset(w.cols);
  // The LP is posed in y_j = θ_j / σ_j with σ_j the start's θ_j (floored), and each row divided by its size
  // at the start: ṡ² spans orders of magnitude along a path and GLPK's tolerances are absolute in the problem
  // it is given, so in θ itself a row with c ~ 1e-5 could be broken by 1e-9, 1e-4 of itself, which the
  // repair would then pay for in T.
  sigma_ = theta.cwiseMax(1e-6 * w.theta_max);
  add_rows(rows, theta);
  loaded_ = lp_.load();
  if (!loaded_) return;
  cost_.resize(static_cast<size_t>(w.cols));
  rho_ = w.limits.initial_trust_region * w.theta_max;
}

void GlpkSlp::add_rows(const std::vector<WindowRow>& rows, const Eigen::VectorXd& theta) {
  const Eigen::Index first = w_.first, last = w_.last;
  for (const WindowRow& r : rows) {
    const Eigen::Index k = r.k;
    idx_.clear();
    val_.clear();
    double rhs = r.c;
    double size = 0.0;
    if (k >= first && k <= last) {
      if (r.alpha != 0.0) { idx_.push_back(static_cast<int>(k - first)); val_.push_back(r.alpha * sigma_[k]); }
    } else {
      rhs -= r.alpha * theta[k];
    }
    if (k + 1 >= first && k + 1 <= last) {
      if (r.beta != 0.0) { idx_.push_back(static_cast<int>(k + 1 - first)); val_.push_back(r.beta * sigma_[k + 1]); }
    } else {
      rhs -= r.beta * theta[k + 1];
    }
    if (idx_.empty()) continue;  // both ends fixed: nothing to decide
    for (double v : val_) size += std::abs(v);
    size = std::max(size, std::abs(rhs));
    for (double& v : val_) v /= size;
    LpRow row{k, r.alpha, r.beta, r.c, k >= first && k <= last && r.alpha != 0.0,
              k + 1 >= first && k + 1 <= last && r.beta != 0.0, static_cast<int>(idx_.size()), {idx_[0], 0},
              {val_[0], 0.0}, rhs / size};
    if (idx_.size() > 1) {
      row.col[1] = idx_[1];
      row.val[1] = val_[1];
    }
    // Rows are added lazily: first those nearly tight at the start (slack within 1 % of the row's size),
    // which the start basis and most LP vertices need; the others only once an LP solution breaks them
    // (see solve_lp). The LP is then a relaxation until the last round, which still gives valid bounds,
    // and its basis factorisations have a quarter of the rows.
    const double ax = r.alpha * theta[k], by = r.beta * theta[k + 1];
    const double slack = (r.c - ax - by) / std::max({std::abs(r.c), std::abs(ax) + std::abs(by), 1e-300});
    if (slack <= 1e-2) {
      lp_.add_row_upper(idx_, val_, row.rhs);
      lp_rows_.push_back(row);
    } else {
      waiting_.push_back(row);
    }
  }
}

// A tight unused row of interval k acting on column j becomes non-basic (at its upper bound).
bool GlpkSlp::take_row(Eigen::Index k, Eigen::Index j, const std::vector<char>& tight,
                       const std::vector<size_t>& row_begin, std::vector<GlpkLp::Stat>& rs) const {
  if (k < 0 || k >= w_.m) return false;
  for (size_t i = row_begin[static_cast<size_t>(k)]; i < row_begin[static_cast<size_t>(k) + 1]; ++i) {
    const LpRow& r = lp_rows_[i];
    if (!tight[i] || rs[i] != GlpkLp::Stat::Basic || !(j == r.k ? r.on_k : r.on_k1)) continue;
    rs[i] = GlpkLp::Stat::AtUpper;
    return true;
  }
  return false;
}

// The start basis: the greedy profile is a vertex of the window's set (each θ_j is the top of a slice of a
// polygon, so a row of interval j-1 or j, or a bound, is tight there), so a basis with one tight constraint
// per column is primal feasible and the first LP needs no phase 1 and, at a nearly optimal start, few pivots
// (instead of a climb from the slack basis over every column). Columns are matched left to right to a tight
// bound, else a tight unused row of interval j-1, else of interval j; if some column finds none, or the basis
// is singular, GLPK starts from the slack basis instead.
void GlpkSlp::start_basis(const Eigen::VectorXd& theta) {
  const Eigen::Index m = w_.m;
  std::vector<GlpkLp::Stat> rs(lp_rows_.size(), GlpkLp::Stat::Basic), cs(static_cast<size_t>(w_.cols), GlpkLp::Stat::Basic);
  std::vector<char> tight(lp_rows_.size(), 0);
  std::vector<size_t> row_begin(static_cast<size_t>(m) + 1, lp_rows_.size());
  for (size_t i = lp_rows_.size(); i-- > 0;) row_begin[static_cast<size_t>(lp_rows_[i].k)] = i;
  for (Eigen::Index k = m - 1; k >= 0; --k)
    row_begin[static_cast<size_t>(k)] = std::min(row_begin[static_cast<size_t>(k)], row_begin[static_cast<size_t>(k) + 1]);
  for (size_t i = 0; i < lp_rows_.size(); ++i) {
    const LpRow& r = lp_rows_[i];
    const double ax = r.alpha * theta[r.k], by = r.beta * theta[r.k + 1];
    tight[i] = r.c - ax - by <= 1e-9 * std::max({1.0, std::abs(r.c), std::abs(ax), std::abs(by)});
  }
  for (Eigen::Index j = w_.first; j <= w_.last; ++j) {
    const double tol = 1e-9 * std::max(std::abs(w_.hi[j]), 1e-300);
    GlpkLp::Stat& c = cs[static_cast<size_t>(j - w_.first)];
    if (theta[j] >= w_.hi[j] - tol) c = GlpkLp::Stat::AtUpper;
    else if (theta[j] <= w_.lo[j] + tol) c = GlpkLp::Stat::AtLower;
    else if (!take_row(j - 1, j, tight, row_begin, rs) && !take_row(j, j, tight, row_begin, rs)) return;
  }
  lp_.set_basis(rs, cs);
}

// Minimises g·θ over the window's LP, within `radius` of θ (inf: the whole set); d = θ_lp - θ.
SlpOutcome::Status GlpkSlp::solve_lp(double radius, const Eigen::VectorXd& theta, WindowResult& out) {
  for (Eigen::Index j = w_.first; j <= w_.last; ++j) {
    const double l = std::max(w_.lo[j], theta[j] - radius), h = std::min(w_.hi[j], theta[j] + radius);
    lp_.set_col_bounds(static_cast<int>(j - w_.first), std::min(l, h) / sigma_[j], h / sigma_[j]);
  }
  if (first_lp_) start_basis(theta);
  first_lp_ = false;
  const SlpOutcome::Status st = solve_and_add_broken_rows(out);
  if (st != SlpOutcome::Status::Converged) return st;
  d_.setZero();
  for (Eigen::Index j = w_.first; j <= w_.last; ++j) d_[j] = sigma_[j] * x_[static_cast<size_t>(j - w_.first)] - theta[j];
  return SlpOutcome::Status::Converged;
}

// Solves the LP; rows still waiting that its solution breaks join it, and it is solved again from its basis,
// until none does.
SlpOutcome::Status GlpkSlp::solve_and_add_broken_rows(WindowResult& out) {
  const double tol_bnd = w_.limits.lp_feasibility_tolerance;
  const int ms = remaining_ms(w_.limits.deadline);
  if (ms <= 0) return SlpOutcome::Status::TimeLimit;
  ++out.lp_solves;
  GlpkLp::Outcome o = lp_.solve(tol_bnd, ms);
  for (;;) {
    if (o == GlpkLp::Outcome::TimeLimit) return SlpOutcome::Status::TimeLimit;
    if (o != GlpkLp::Outcome::Optimal) return SlpOutcome::Status::LpFailed;
    lp_.column_values(x_);
    size_t kept_waiting = 0;
    bool added = false;
    for (const LpRow& r : waiting_) {
      double act = 0.0;
      for (int t = 0; t < r.n; ++t) act += r.val[t] * x_[static_cast<size_t>(r.col[t])];
      if (act > r.rhs + 10.0 * tol_bnd * (1.0 + std::abs(r.rhs))) {
        idx_.assign(r.col, r.col + r.n);
        val_.assign(r.val, r.val + r.n);
        lp_.append_row_upper(idx_, val_, r.rhs);
        lp_rows_.push_back(r);
        added = true;
      } else {
        waiting_[kept_waiting++] = r;
      }
    }
    waiting_.resize(kept_waiting);
    if (!added) return SlpOutcome::Status::Converged;
    ++out.lp_solves;
    o = lp_.solve(tol_bnd, std::max(remaining_ms(w_.limits.deadline), 1));
  }
}

bool GlpkSlp::iterate(int until, Eigen::VectorXd& theta, WindowResult& out) {
  for (; out.iterations < until; ++out.iterations)
    if (one_iteration(theta, out)) return true;
  return false;
}

// One SLP iteration: an LP within the trust region (or, after a full Frank-Wolfe step or when the trust region
// promises nothing more, over the whole window, whose bound certifies the iterate), then the exact line search
// along its step; true if the window ended (certified, or out.status set).
bool GlpkSlp::one_iteration(Eigen::VectorXd& theta, WindowResult& out) {
  const Eigen::Index first = w_.first, last = w_.last, m = w_.m;
  const double rel_target = w_.rel_target, theta_max = w_.theta_max;
  if (Clock::now() >= w_.limits.deadline) {
    out.status = SlpOutcome::Status::TimeLimit;
    return true;
  }
  gradient(w_.ds, theta, w_.floor, g_);
  for (Eigen::Index j = first; j <= last; ++j) cost_[static_cast<size_t>(j - first)] = g_[j] * sigma_[j];
  lp_.set_objective(cost_);
  SlpOutcome::Status st = solve_lp(global_ ? std::numeric_limits<double>::infinity() : rho_, theta, out);
  if (st != SlpOutcome::Status::Converged) {
    out.status = st;
    return true;
  }
  double predicted = -g_.dot(d_);
  if (!global_ && (predicted <= rel_target * out.T || rho_ <= 1e-13 * theta_max)) {
    // The trust-region step promises nothing more: check optimality over the whole window.
    st = solve_lp(std::numeric_limits<double>::infinity(), theta, out);
    if (st != SlpOutcome::Status::Converged) {
      out.status = st;
      return true;
    }
    predicted = -g_.dot(d_);
    global_ = true;
  }
  if (global_) {
    // Frank-Wolfe: T(θ) - min T <= ∇T(θ)·θ - min ∇T(θ)·θ' over the window's set, the minimum bounded
    // from below by weak duality (not by GLPK's word that its vertex is optimal).
    double g_theta = 0.0;
    for (Eigen::Index j = first; j <= last; ++j) g_theta += g_[j] * theta[j];
    out.gap = std::max({g_theta - lp_.lagrangian_bound(cost_), predicted, 0.0});
    out.lower = std::max(out.lower, out.T - out.gap);
    if (out.gap <= rel_target * out.T) {
      out.status = SlpOutcome::Status::Converged;
      return true;
    }
  }
  // Exact line search on the convex 1-D restriction: bisection on the sign of the slope.
  const double alpha = line_search(w_.ds, theta, d_, w_.floor, tmp_, gtmp_);
  Eigen::VectorXd next = theta + alpha * d_;
  for (Eigen::Index j = 0; j <= m; ++j) next[j] = std::clamp(next[j], w_.lo[j], w_.hi[j]);
  const double T_next = duration(w_.ds, next);
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
      return true;
    }
  }
  const double step = (alpha * d_).cwiseAbs().maxCoeff();
  // A full Frank-Wolfe step lands on a vertex of the window's set, where the optimum of a time-optimal
  // problem usually is: check it with another Frank-Wolfe LP first; otherwise continue with a trust region.
  const bool full_fw_step = global_ && alpha >= 0.999;
  if (global_) rho_ = std::max(step, 1e-6 * theta_max);
  else if (alpha >= 0.999) rho_ *= 2.0;
  else rho_ = std::max(0.5 * step, 0.25 * rho_);
  global_ = full_fw_step;
  return false;
}

}  // namespace pathpace::detail
