#include "detail/chain_simplex.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detail/tridiagonal.hpp"

namespace pathpace::detail {

ChainSimplex::ChainSimplex(const Chain& chain, Eigen::Index a, Eigen::Index m, const Eigen::VectorXd& lo,
                           const Eigen::VectorXd& hi, Eigen::Index first, Eigen::Index last)
    : lo_(lo), hi_(hi), first_(first), last_(last), n_(static_cast<std::size_t>(last - first + 1)) {
  for (Eigen::Index k = 0; k < m; ++k)
    for (const Line& r : chain.rows(a + k)) rows_.push_back({&r, k});
  in_basis_.assign(rows_.size(), 0);
}

double ChainSimplex::gap(const Eigen::VectorXd& theta, const Eigen::VectorXd& g, int max_pivots) {
  const double inf = std::numeric_limits<double>::infinity();
  y_ = theta;
  if (!start_basis()) return inf;
  if (!match()) return inf;
  double gmax = 0.0;
  for (std::size_t i = 0; i < n_; ++i) gmax = std::max(gmax, std::abs(g[col(i)]));
  pivots_ = 0;
  for (int pivot = 0;; ++pivot) {
    if (!duals(g)) return inf;
    // Bland's rule: the first column whose constraint has a negative multiplier leaves (no cycling; Dantzig's
    // most negative multiplier took more pivots on the arm corpus).
    std::size_t p = n_;
    for (std::size_t i = 0; i < n_; ++i)
      if (lambda_[i] * std::abs(coef(i, i)) < -1e-13 * gmax) {
        p = i;
        break;
      }
    if (p == n_) break;
    if (pivot == max_pivots || !step(p)) return inf;
    ++pivots_;
  }
  // The bound at the start θ, with the row multipliers of the final basis.
  double out = 0.0;
  std::vector<double>& dj = l_;  // reuse: d = g + Aᵀλ on the free columns
  dj.assign(n_, 0.0);
  for (std::size_t i = 0; i < n_; ++i) dj[i] = g[col(i)];
  for (std::size_t i = 0; i < n_; ++i) {
    const int c = match_[i];
    if (c < 0) continue;  // a bound: left to the box
    const double lam = std::max(lambda_[i], 0.0);
    if (lam == 0.0) continue;
    const Row& r = rows_[static_cast<std::size_t>(c)];
    if (free_col(r.k)) dj[local(r.k)] += lam * r.line->a;
    if (free_col(r.k + 1)) dj[local(r.k + 1)] += lam * r.line->b;
    out += lam * (r.line->c - r.line->a * theta[r.k] - r.line->b * theta[r.k + 1]);
  }
  for (std::size_t i = 0; i < n_; ++i) {
    const Eigen::Index j = col(i);
    out += dj[i] * theta[j] - std::min(dj[i] * lo_[j], dj[i] * hi_[j]);
  }
  return std::isfinite(out) ? std::max(out, 0.0) : inf;
}

// Coefficient on free column i of the constraint matched to column `owner` (a bound acts on its own column).
double ChainSimplex::coef(std::size_t owner, std::size_t i) const {
  const int c = match_[owner];
  if (c < 0) return i != owner ? 0.0 : c == kHi ? 1.0 : -1.0;
  const Row& r = rows_[static_cast<std::size_t>(c)];
  const Eigen::Index j = col(i);
  return j == r.k ? r.line->a : j == r.k + 1 ? r.line->b : 0.0;
}

bool ChainSimplex::tight(const Row& r) const {
  const double ax = r.line->a * y_[r.k], by = r.line->b * y_[r.k + 1];
  return slack(r) <= 1e-9 * std::max({1.0, std::abs(r.line->c), std::abs(ax), std::abs(by)});
}

// Per free column: its bound if at one, else a tight row of interval j - 1 (acting on θ_j), else of interval j.
bool ChainSimplex::start_basis() {
  bounds_.assign(n_, 0);
  std::fill(in_basis_.begin(), in_basis_.end(), 0);
  std::size_t r0 = 0;  // first row of interval j - 1
  for (std::size_t i = 0; i < n_; ++i) {
    const Eigen::Index j = col(i);
    while (r0 < rows_.size() && rows_[r0].k < j - 1) ++r0;
    const double tol = 1e-9 * std::max(std::abs(hi_[j]), 1e-300);
    if (y_[j] >= hi_[j] - tol) {
      bounds_[i] = kHi;
      continue;
    }
    if (y_[j] <= lo_[j] + tol) {
      bounds_[i] = kLo;
      continue;
    }
    bool found = false;
    for (std::size_t t = r0; t < rows_.size() && rows_[t].k <= j && !found; ++t) {
      const Row& r = rows_[t];
      const double on_j = r.k == j - 1 ? r.line->b : r.line->a;
      if (in_basis_[t] || on_j == 0.0 || !tight(r)) continue;
      in_basis_[t] = 1;
      found = true;
    }
    if (!found) return false;
  }
  return true;
}

// Earliest deadline first: column j takes its bound if that is in S, else an S-row that must serve it (of
// interval j - 1, or of interval j with no coefficient on column j + 1), else one of interval j.
bool ChainSimplex::match() {
  match_.assign(n_, kHi);
  used_.assign(rows_.size(), 0);
  std::size_t r0 = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    const Eigen::Index j = col(i);
    while (r0 < rows_.size() && rows_[r0].k < j - 1) ++r0;
    int best = -3, best_rank = 3;
    for (std::size_t t = r0; t < rows_.size() && rows_[t].k <= j; ++t) {
      if (!in_basis_[t] || used_[t]) continue;
      const Row& r = rows_[t];
      const double on_j = r.k == j - 1 ? r.line->b : r.line->a;
      if (on_j == 0.0) continue;
      const int rank = r.k == j - 1 ? 0 : (r.line->b == 0.0 || !free_col(j + 1)) ? 1 : 2;
      if (rank < best_rank) {
        best = static_cast<int>(t);
        best_rank = rank;
      }
    }
    if (bounds_[i] != 0) {
      if (best_rank < 2) return false;  // two constraints that can only act on θ_j: singular
      match_[i] = bounds_[i];
      continue;
    }
    if (best < 0) return false;
    match_[i] = best;
    used_[static_cast<std::size_t>(best)] = 1;
    // Rows of interval j - 1 left now can serve no later column.
    for (std::size_t t = r0; t < rows_.size() && rows_[t].k < j; ++t)
      if (in_basis_[t] && !used_[t]) return false;
  }
  for (std::size_t t = 0; t < rows_.size(); ++t)
    if (in_basis_[t] && !used_[t]) return false;
  return true;
}

// Tridiagonal factors of B (transpose = false: constraint i's coefficients on columns i-1, i, i+1) or of Bᵀ.
void ChainSimplex::fill(bool transpose) {
  l_.assign(n_, 0.0);
  d_.assign(n_, 0.0);
  u_.assign(n_, 0.0);
  for (std::size_t i = 0; i < n_; ++i) {
    d_[i] = coef(i, i);
    if (!transpose) {
      if (i > 0) l_[i] = coef(i, i - 1);
      if (i + 1 < n_) u_[i] = coef(i, i + 1);
    } else {
      if (i > 0) l_[i] = coef(i - 1, i);
      if (i + 1 < n_) u_[i] = coef(i + 1, i);
    }
  }
}

bool ChainSimplex::duals(const Eigen::VectorXd& g) {
  fill(true);
  lambda_.resize(n_);
  for (std::size_t i = 0; i < n_; ++i) lambda_[i] = -g[col(i)];
  return solve_tridiagonal(l_, d_, u_, lambda_, u2_);
}

// Constraint p (matched to column p) leaves along d with B d = -e_p; the first constraint to block enters.
bool ChainSimplex::step(std::size_t p) {
  fill(false);
  dir_.assign(n_, 0.0);
  dir_[p] = -1.0;
  if (!solve_tridiagonal(l_, d_, u_, dir_, u2_)) return false;
  double dmax = 0.0;
  for (double v : dir_) dmax = std::max(dmax, std::abs(v));
  double t_best = std::numeric_limits<double>::infinity();
  int enter = -3;
  std::size_t enter_col = 0;
  auto consider = [&](double t, int code, std::size_t i) {
    // Ties (degenerate steps) go to the smallest index: rows first, in order, then bounds by column.
    if (t < t_best * (1 - 1e-12)) {
      t_best = t;
      enter = code;
      enter_col = i;
    }
  };
  for (std::size_t t = 0; t < rows_.size(); ++t) {
    if (in_basis_[t]) continue;
    const Row& r = rows_[t];
    const double dk = free_col(r.k) ? dir_[local(r.k)] : 0.0, dk1 = free_col(r.k + 1) ? dir_[local(r.k + 1)] : 0.0;
    const double ad = r.line->a * dk + r.line->b * dk1;
    if (ad <= 1e-12 * (std::abs(r.line->a) + std::abs(r.line->b)) * dmax) continue;
    consider(std::max(slack(r), 0.0) / ad, static_cast<int>(t), 0);
  }
  for (std::size_t i = 0; i < n_; ++i) {
    const Eigen::Index j = col(i);
    if (dir_[i] > 1e-12 * dmax && match_[i] != kHi) consider(std::max(hi_[j] - y_[j], 0.0) / dir_[i], kHi, i);
    if (dir_[i] < -1e-12 * dmax && match_[i] != kLo) consider(std::max(y_[j] - lo_[j], 0.0) / -dir_[i], kLo, i);
  }
  if (enter == -3 || !std::isfinite(t_best)) return false;
  for (std::size_t i = 0; i < n_; ++i) y_[col(i)] += t_best * dir_[i];
  // S := S - {p} + {enter}.
  if (match_[p] >= 0) in_basis_[static_cast<std::size_t>(match_[p])] = 0;
  else bounds_[p] = 0;
  if (enter >= 0) {
    in_basis_[static_cast<std::size_t>(enter)] = 1;
  } else {
    if (bounds_[enter_col] != 0) return false;
    bounds_[enter_col] = enter;
    // The entering bound is exact: no drift from the step's rounding.
    y_[col(enter_col)] = enter == kHi ? hi_[col(enter_col)] : lo_[col(enter_col)];
  }
  return match();
}

}  // namespace pathpace::detail
