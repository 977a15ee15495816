#include "solve/chain_simplex.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "lp/tridiagonal.hpp"

namespace pathpace::detail {

ChainSimplex::ChainSimplex(const Chain& chain, Eigen::Index a, Eigen::Index m, const Eigen::VectorXd& lo,
                           const Eigen::VectorXd& hi, Eigen::Index first, Eigen::Index last)
    : lo_(lo), hi_(hi), first_(first), last_(last), n_(static_cast<std::size_t>(last - first + 1)) {
  row_begin_.resize(static_cast<std::size_t>(m) + 1);
  // The window's rows are contiguous in the chain: sized once, not grown by push_back.
  rows_.reserve(chain.row_offset[static_cast<std::size_t>(a + m)] - chain.row_offset[static_cast<std::size_t>(a)]);
  for (Eigen::Index k = 0; k < m; ++k) {
    row_begin_[static_cast<std::size_t>(k)] = rows_.size();
    for (const Line& r : chain.rows(a + k)) rows_.push_back({&r, k});
  }
  row_begin_[static_cast<std::size_t>(m)] = rows_.size();
  in_basis_.assign(rows_.size(), 0);
}

double ChainSimplex::gap(const Eigen::VectorXd& theta, const Eigen::VectorXd& g, int max_pivots, bool warm) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!warm || !has_basis_) {
    y_ = theta;
    has_basis_ = start_basis() && match();
    if (!has_basis_) return inf;
    own_.resize(n_);
    left_.resize(n_);
    right_.resize(n_);
    coefs(0, n_ - 1);
  }
  has_basis_ = false;  // until this call ends at an optimal basis
  lambda_.resize(n_);  // every entry written by the first duals() (the whole range)
  double gmax = 0.0;
  for (std::size_t i = 0; i < n_; ++i) gmax = std::max(gmax, std::abs(g[col(i)]));
  std::size_t cl = 0, cr = n_ - 1;  // the columns whose multipliers must be solved again
  for (pivots_ = 0;; ++pivots_) {
    if (!duals(g, cl, cr)) return inf;
    // Bland's rule: the first column whose constraint has a negative multiplier leaves (no cycling; Dantzig's
    // most negative multiplier took more pivots on the arm corpus).
    std::size_t p = n_;
    for (std::size_t i = 0; i < n_; ++i)
      if (lambda_[i] * std::abs(own_[i]) < -1e-13 * gmax) {
        p = i;
        break;
      }
    if (p == n_) {
      has_basis_ = true;
      break;
    }
    if (pivots_ == max_pivots || !step(p, cl, cr)) return inf;
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

// The start basis at the vertex y_: per free point one constraint that holds there, a bound or a tight row of
// interval j - 1 or j acting on θ_j, each row used once, with the least total slack (a bound that holds only to
// the tolerance, θ_j 1e-10 below θ'_j say, loses to a row that holds exactly: taking it made every multiplier
// along a deceleration ramp wrong, one degenerate pivot per point to mend, 64 pivots on a 250-point window and
// then GLPK). Rows are shared only between neighbours (a row of interval j can serve point j or j + 1), so a
// dynamic programme over the points whose state is "point j - 1 took row r of interval j - 1" finds it exactly;
// ties go to bounds, then to earlier rows.
bool ChainSimplex::start_basis() {
  bounds_.assign(n_, 0);
  std::fill(in_basis_.begin(), in_basis_.end(), 0);
  // The options of point i are opt_[opt_begin_[i] .. opt_begin_[i + 1]) (one buffer for the window).
  opt_.clear();
  opt_begin_.resize(n_);  // every entry written below
  // Each row's relative slack at y_ (reachability's row_violation, negated), once: a row is an option of both
  // its points.
  viol_.resize(rows_.size());
  for (std::size_t t = 0; t < rows_.size(); ++t) viol_[t] = row_violation(*rows_[t].line, y_[rows_[t].k], y_[rows_[t].k + 1]);
  opt_.reserve(4 * n_);  // a point has ~2 options; the window's ChainSimplex is new
  for (std::size_t i = 0; i < n_; ++i) {
    const Eigen::Index j = col(i);
    std::size_t t0, t1, t2;
    point_rows(j, t0, t1, t2);
    const double scale = std::max(std::abs(hi_[j]), 1e-300);
    const double hi_gap = std::max(hi_[j] - y_[j], 0.0) / scale, lo_gap = std::max(y_[j] - lo_[j], 0.0) / scale;
    const std::size_t o0 = opt_.size();
    opt_begin_[i] = o0;
    if (hi_gap <= 1e-9) opt_.push_back({kHi, hi_gap, 0.0, -1});
    else if (lo_gap <= 1e-9) opt_.push_back({kLo, lo_gap, 0.0, -1});
    for (std::size_t t = t0; t < t2; ++t) {
      const double on_j = t < t1 ? rows_[t].line->b : rows_[t].line->a;
      if (on_j == 0.0) continue;
      const double v = viol_[t];
      if (v < -1e-9) continue;  // not tight: a relative slack of more than 1e-9
      const double rel = std::max(-v, 0.0);
      opt_.push_back({static_cast<int>(t), rel + 1e-15 * static_cast<double>(opt_.size() - o0 + 1), 0.0, -1});
    }
    if (opt_.size() == o0) return false;
    for (std::size_t x = o0; x < opt_.size(); ++x) {
      Option& o = opt_[x];
      if (i == 0) {
        o.total = o.cost;
        continue;
      }
      o.total = std::numeric_limits<double>::infinity();
      for (std::size_t q = opt_begin_[i - 1]; q < o0; ++q) {
        if (o.code >= 0 && opt_[q].code == o.code) continue;  // the row is point i - 1's already
        if (opt_[q].total + o.cost < o.total) {
          o.total = opt_[q].total + o.cost;
          o.prev = static_cast<int>(q);
        }
      }
    }
  }
  int at = -1;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t q = opt_begin_[n_ - 1]; q < opt_.size(); ++q)
    if (opt_[q].total < best) {
      best = opt_[q].total;
      at = static_cast<int>(q);
    }
  for (std::size_t i = n_; i-- > 0;) {
    if (at < 0) return false;
    const Option& x = opt_[static_cast<std::size_t>(at)];
    if (x.code < 0) {
      bounds_[i] = x.code;
    } else {
      in_basis_[static_cast<std::size_t>(x.code)] = 1;
    }
    at = x.prev;
  }
  return true;
}

// Earliest deadline first: column j takes its bound if that is in S, else an S-row that must serve it (of
// interval j - 1, or of interval j with no coefficient on column j + 1), else one of interval j. O(n).
bool ChainSimplex::match() {
  match_.assign(n_, kHi);
  std::size_t cl = n_, cr = 0;
  return edf(0, n_, match_, cl, cr);
}

// The matching from column i0 on, columns before it keeping theirs (mt[i0 - 1] is the one input from them).
// Column j's choice depends only on the S-rows of intervals j - 1 and j, its bound, and which row column j - 1
// took (the only column before j that can take a row of interval j - 1). So after a pivot that changed S in
// the columns [i0, i_stop] only, the walk can stop at the first column i >= i_stop whose choice is the one mt
// holds: every later column sees what it saw before. [cl, cr] is widened to the columns whose entry changed.
// False if S cannot be matched (singular).
bool ChainSimplex::edf(std::size_t i0, std::size_t i_stop, std::vector<int>& mt, std::size_t& cl,
                       std::size_t& cr) const {
  for (std::size_t i = i0; i < n_; ++i) {
    const Eigen::Index j = col(i);
    const int prev = i > 0 ? mt[i - 1] : kHi;
    std::size_t t0, t1, t2;
    point_rows(j, t0, t1, t2);
    int best = -1, best_rank = 3;
    for (std::size_t t = t0; t < t2; ++t) {
      if (!in_basis_[t] || static_cast<int>(t) == prev) continue;
      const Row& r = rows_[t];
      const bool of_left = t < t1;
      const double on_j = of_left ? r.line->b : r.line->a;
      if (on_j == 0.0) continue;
      const int rank = of_left ? 0 : (r.line->b == 0.0 || !free_col(j + 1)) ? 1 : 2;
      if (rank < best_rank) {
        best = static_cast<int>(t);
        best_rank = rank;
      }
    }
    int c = best;
    if (bounds_[i] != 0) {
      if (best_rank < 2) return false;  // two constraints that can only act on θ_j: singular
      c = bounds_[i];
    } else if (best < 0) {
      return false;
    }
    // Every S-row of interval j - 1 is taken by now (by column j - 1 or j; no later column can take it).
    for (std::size_t t = t0; t < t1; ++t)
      if (in_basis_[t] && static_cast<int>(t) != prev && static_cast<int>(t) != c) return false;
    if (mt[i] != c) {
      mt[i] = c;
      cl = std::min(cl, i);
      cr = std::max(cr, i);
    } else if (i >= i_stop && i + 1 < n_) {
      return true;
    }
  }
  // The last column's interval: its S-rows can serve only that column.
  std::size_t t0, t1, t2;
  point_rows(col(n_ - 1), t0, t1, t2);
  for (std::size_t t = t1; t < t2; ++t)
    if (in_basis_[t] && static_cast<int>(t) != mt[n_ - 1]) return false;
  return true;
}

bool ChainSimplex::fresh_state(const Eigen::VectorXd& g) const {
  std::vector<int> full(n_, kHi);
  std::size_t cl = n_, cr = 0;
  if (!edf(0, n_, full, cl, cr) || full != match_) return false;
  for (std::size_t i = 0; i < n_; ++i)
    if (own_[i] != coef(i, i) || left_[i] != (i > 0 ? coef(i, i - 1) : 0.0) ||
        right_[i] != (i + 1 < n_ ? coef(i, i + 1) : 0.0))
      return false;
  // λ solves Bᵀλ = -g (to rounding), by B's entries from coef().
  for (std::size_t i = 0; i < n_; ++i) {
    double sum = g[col(i)], scale = std::abs(g[col(i)]);
    for (std::size_t o = i > 0 ? i - 1 : 0; o <= std::min(i + 1, n_ - 1); ++o) {
      sum += coef(o, i) * lambda_[o];
      scale += std::abs(coef(o, i) * lambda_[o]);
    }
    if (!(std::abs(sum) <= 1e-12 * scale)) return false;
  }
  return true;
}

// B's row i (the constraint matched to column i: its coefficients on columns i-1, i, i+1) for i in [i0, i1].
void ChainSimplex::coefs(std::size_t i0, std::size_t i1) {
  for (std::size_t i = i0; i <= i1; ++i) {
    own_[i] = coef(i, i);
    left_[i] = i > 0 ? coef(i, i - 1) : 0.0;
    right_[i] = i + 1 < n_ ? coef(i, i + 1) : 0.0;
  }
}

// The columns [bl, br] of column i's block: B (and Bᵀ) couple columns i and i + 1 only if the constraint matched
// to one acts on the other; between blocks the systems are independent.
void ChainSimplex::block(std::size_t i, std::size_t& bl, std::size_t& br) const {
  bl = br = i;
  while (bl > 0 && (right_[bl - 1] != 0.0 || left_[bl] != 0.0)) --bl;
  while (br + 1 < n_ && (right_[br] != 0.0 || left_[br + 1] != 0.0)) ++br;
}

// Tridiagonal factors of B's rows [i0, i1] (transpose = false: constraint i's coefficients on columns i-1, i,
// i+1) or of Bᵀ's, into l_, d_, u_ (from index 0).
void ChainSimplex::fill(bool transpose, std::size_t i0, std::size_t i1) {
  const std::size_t len = i1 - i0 + 1;
  l_.assign(len, 0.0);
  d_.assign(len, 0.0);
  u_.assign(len, 0.0);
  for (std::size_t i = i0; i <= i1; ++i) {
    const std::size_t t = i - i0;
    d_[t] = own_[i];
    if (i > i0) l_[t] = transpose ? right_[i - 1] : left_[i];
    if (i < i1) u_[t] = transpose ? left_[i + 1] : right_[i];
  }
}

// λ on the blocks that hold columns cl - 1 .. cr + 1 (the equations that the last pivot changed): Bᵀλ = -g there.
bool ChainSimplex::duals(const Eigen::VectorXd& g, std::size_t cl, std::size_t cr) {
  std::size_t bl, br, tmp;
  block(cl > 0 ? cl - 1 : 0, bl, tmp);
  block(std::min(cr + 1, n_ - 1), tmp, br);
  fill(true, bl, br);
  rhs_.resize(br - bl + 1);
  for (std::size_t i = bl; i <= br; ++i) rhs_[i - bl] = -g[col(i)];
  if (!solve_tridiagonal(l_, d_, u_, rhs_, u2_)) return false;
  std::copy(rhs_.begin(), rhs_.end(), lambda_.begin() + static_cast<long>(bl));
  return true;
}

// Constraint p (matched to column p) leaves along d with B d = -e_p (nonzero on p's block only); the first
// constraint to block enters. On return [cl, cr] holds the columns whose matching changed.
bool ChainSimplex::step(std::size_t p, std::size_t& cl, std::size_t& cr) {
  std::size_t bl, br;
  block(p, bl, br);
  fill(false, bl, br);
  rhs_.assign(br - bl + 1, 0.0);
  rhs_[p - bl] = -1.0;
  if (!solve_tridiagonal(l_, d_, u_, rhs_, u2_)) return false;
  // d on p's block only: d_i = rhs_[i - bl] for i in [bl, br] (nothing below changes rhs_).
  const double* d = rhs_.data();
  double dmax = 0.0;
  for (double v : rhs_) dmax = std::max(dmax, std::abs(v));
  const double inf = std::numeric_limits<double>::infinity();
  double t_best = inf;
  int enter = -3;
  std::size_t enter_col = 0;
  double t_cut = inf;  // t_best * (1 - 1e-12): a constraint enters only if its step is below that
  auto consider = [&](double t, int code, std::size_t i) {
    // Ties (degenerate steps) go to the smallest index: rows first, in order, then bounds by column.
    if (t < t_cut) {
      t_best = t;
      t_cut = t * (1 - 1e-12);
      enter = code;
      enter_col = i;
    }
  };
  // The rows that act on the block's columns: intervals col(bl) - 1 .. col(br), interval by interval (its two
  // columns' d and y loaded once for its ~6 rows).
  const Eigen::Index jl = col(bl), jr = col(br);
  auto dget = [&](Eigen::Index j) { return j >= jl && j <= jr ? d[local(j) - bl] : 0.0; };
  const Eigen::Index k0 = std::max<Eigen::Index>(jl - 1, 0);
  const Eigen::Index k1 = std::min<Eigen::Index>(jr, static_cast<Eigen::Index>(row_begin_.size()) - 2);
  for (Eigen::Index k = k0; k <= k1; ++k) {
    const double dk = dget(k), dk1 = dget(k + 1), yk = y_[k], yk1 = y_[k + 1];
    const std::size_t t1 = row_begin_[static_cast<std::size_t>(k) + 1];
    for (std::size_t t = row_begin_[static_cast<std::size_t>(k)]; t < t1; ++t) {
      if (in_basis_[t]) continue;
      const Line& r = *rows_[t].line;
      const double ad = r.a * dk + r.b * dk1;
      if (ad <= 1e-12 * (std::abs(r.a) + std::abs(r.b)) * dmax) continue;
      const double slack = std::max(r.c - r.a * yk - r.b * yk1, 0.0);
      // Most rows cannot beat t_cut: those are told without the division (the dearest part of the loop).
      // slack > ad t_cut (1 + 1e-14), rounding included, means slack / ad >= t_cut after rounding too (while
      // ad t_cut is a normal number; t_cut = 0 admits nothing, slack >= 0); the division decides the others.
      const double cut = ad * t_cut * (1 + 1e-14);
      if (t_cut == 0.0 || (cut > 1e-290 && slack > cut)) continue;
      consider(slack / ad, static_cast<int>(t), 0);
    }
  }
  for (std::size_t i = bl; i <= br; ++i) {
    const Eigen::Index j = col(i);
    const double di = d[i - bl];
    if (di > 1e-12 * dmax && match_[i] != kHi) consider(std::max(hi_[j] - y_[j], 0.0) / di, kHi, i);
    if (di < -1e-12 * dmax && match_[i] != kLo) consider(std::max(y_[j] - lo_[j], 0.0) / -di, kLo, i);
  }
  if (!std::isfinite(t_best)) return false;  // no constraint blocks: an unbounded ray
  for (std::size_t i = bl; i <= br; ++i) y_[col(i)] += t_best * d[i - bl];
  // S := S - {p} + {enter}; the matching changes only from the first column these act on (see edf).
  const auto span = [&](int code, std::size_t i) {
    if (code < 0) return std::make_pair(i, i);
    const Eigen::Index k = rows_[static_cast<std::size_t>(code)].k;  // acts on columns k and k + 1
    return std::make_pair(local(std::max(k, first_)), local(std::min(k + 1, last_)));
  };
  const auto out = span(match_[p], p), in = span(enter, enter_col);
  if (match_[p] >= 0) {
    in_basis_[static_cast<std::size_t>(match_[p])] = 0;
  } else {
    bounds_[p] = 0;
  }
  if (enter >= 0) {
    in_basis_[static_cast<std::size_t>(enter)] = 1;
  } else {
    if (bounds_[enter_col] != 0) return false;
    bounds_[enter_col] = enter;
    // The entering bound is exact: no drift from the step's rounding.
    y_[col(enter_col)] = enter == kHi ? hi_[col(enter_col)] : lo_[col(enter_col)];
  }
  cl = n_;
  cr = 0;
  if (!edf(std::min(out.first, in.first), std::max(out.second, in.second), match_, cl, cr)) return false;
  if (cl > cr) {
    cl = cr = p;
  } else {
    coefs(cl, cr);  // B's other rows are unchanged
  }
  return true;
}

}  // namespace pathpace::detail
