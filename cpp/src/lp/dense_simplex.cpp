#include "lp/dense_simplex.hpp"

#include <cmath>
#include <limits>

#include <glpk.h>

#include "lp/projection.hpp"

namespace pathpace::detail {

namespace {
// GLPK's feasibility and optimality tolerances for these LPs (projection_simplex_parameters: tol_bnd =
// tol_dj = 1e-10) in GLPK's own form: a bound b is met within tol + 1e-3 tol |b| (spx's tol_bnd1). The
// certificate holds the optimum to exactly that, so it claims no more than GLPK would; the ratio test
// keeps half of it in hand. (The first version of this engine certified 1e-9 (1 + |b|): on rows whose
// bound is a gravity wrench of ~400 N that is 4e-7, 3000 times GLPK's, which put a Talos support point
// 2e-6 of the polygon's size outside the shadow.) A pivot below Limits::tol_pivot is a failure (GLPK then
// solves).
constexpr double kTolBnd = 1e-10, kTolDj = 1e-10;
inline double bound_tol(double b) { return kTolBnd + 1e-3 * kTolBnd * std::abs(b); }
// Limits: pivots per LP (an LP from an endpoint's basis takes a few; more means cycling or a far start)
// and rank-one updates before the inverse is computed again from B.
}  // namespace

void DenseSimplex::load(const PolytopeLp& lp, bool transpose) {
  lp_ = &lp;
  m_ = static_cast<int>(lp.A.rows());
  n_ = static_cast<int>(lp.A.cols());
  lo_.resize(m_ + n_);
  hi_.resize(m_ + n_);
  lo_ << lp.row_lo, lp.col_lo;
  hi_ << lp.row_hi, lp.col_hi;
  d_.assign(static_cast<size_t>(m_ + n_), 0.0);
  // Each row's largest |a_ij|, column by column (contiguous), and A^T written in its own storage order
  // (A read with a stride, A^T written contiguously: a loop over A's columns that scattered its stores
  // was most of this function). transposed_times and certify() read A's rows as A^T's contiguous columns.
  row_max_.setZero(m_);
  for (int j = 0; j < n_; ++j) row_max_ = row_max_.cwiseMax(lp.A.col(j).cwiseAbs());
  transposed_ = transpose;
  if (transpose) at_.noalias() = lp.A.transpose();
  // No basis; the storage stays (a slice LP loads at every sample, and set_basis sizes it again).
  s_.head.clear();
  s_.stat.clear();
  s_.updates = 0;
}

// alpha_ = B^-1 a_k. An auxiliary's a_k is -e_k: minus column k of B^-1. A structural's is A's column,
// and B^-1's column i is -e_(its position) wherever auxiliary i is basic (see replace()), so only the
// columns of the rows whose auxiliary is nonbasic (a basis's binding rows, few) are multiplied.
void DenseSimplex::solve_column(int k) {
  if (k < m_) {
    alpha_ = -s_.inv.col(k);
    return;
  }
  const auto a = lp_->A.col(k - m_);
  alpha_.setZero(m_);
  for (int i = 0; i < m_; ++i)
    if (a[i] != 0.0 && s_.stat[static_cast<size_t>(i)] != GLP_BS) alpha_.noalias() += a[i] * s_.inv.col(i);
  for (int i = 0; i < m_; ++i) {
    const int b = s_.head[static_cast<size_t>(i)];
    if (b < m_) alpha_[i] -= a[b];
  }
}

// B's columns are -e_k for a basic auxiliary k and A's column j for a basic structural j. With R the rows
// whose auxiliary is nonbasic and S the basic structurals (as many: s), B w = r reads A[R,S] w_S = r_R on
// R and w_k = A[k,S] w_S - r_k on each other row k, so B^-1 follows from the s x s matrix A[R,S]^-1 alone:
// s^3 instead of m^3, and a projection LP's basis is mostly the slacks of torque rows that do not bind.
bool DenseSimplex::factorize() {
  const Eigen::MatrixXd& A = lp_->A;
  std::vector<int>& spos = f_spos_;  // scratch kept between calls: a slice LP factorises at every sample
  std::vector<int>& scol = f_scol_;
  std::vector<int>& rows = f_rows_;
  std::vector<int>& apos = f_apos_;  // the positions of the basic auxiliaries, and (f_arow_) their rows
  std::vector<int>& arow = f_arow_;
  spos.clear(), scol.clear(), rows.clear(), apos.clear(), arow.clear();
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    if (k < m_) apos.push_back(i), arow.push_back(k);
    else spos.push_back(i), scol.push_back(k - m_);
  }
  for (int r = 0; r < m_; ++r)
    if (s_.stat[static_cast<size_t>(r)] != GLP_BS) rows.push_back(r);
  const int s = static_cast<int>(scol.size()), na = static_cast<int>(apos.size());
  if (static_cast<int>(rows.size()) != s) return false;  // an auxiliary twice: not a basis
  s_.inv.setZero(m_, m_);
  for (int t = 0; t < na; ++t) s_.inv(apos[static_cast<size_t>(t)], arow[static_cast<size_t>(t)]) = -1.0;
  if (s > 0) {
    // The scratch is m x m, used in blocks: s changes from one basis to the next, and matrices resized to
    // each s would be allocated again at every factorisation.
    if (f_c_.rows() < m_) {
      for (Eigen::MatrixXd* M : {&f_c_, &f_m_, &f_ak_, &f_w_}) M->resize(m_, m_);
      f_col_.resize(m_);
    }
    auto C = f_c_.topLeftCorner(s, s);
    auto M = f_m_.topLeftCorner(s, s);
    for (int b = 0; b < s; ++b)
      for (int a = 0; a < s; ++a) C(a, b) = A(rows[static_cast<size_t>(a)], scol[static_cast<size_t>(b)]);
    if (!invert_small(C, M)) return false;  // A[R,S]^-1
    for (int b = 0; b < s; ++b)
      for (int a = 0; a < s; ++a) s_.inv(spos[static_cast<size_t>(b)], rows[static_cast<size_t>(a)]) = M(b, a);
    // Each basic auxiliary's row: A[k,S] A[R,S]^-1, all of them in one product.
    auto Ak = f_ak_.topLeftCorner(na, s);
    auto W = f_w_.topLeftCorner(na, s);
    for (int b = 0; b < s; ++b)
      for (int t = 0; t < na; ++t) Ak(t, b) = A(arow[static_cast<size_t>(t)], scol[static_cast<size_t>(b)]);
    W.noalias() = Ak * M;
    for (int a = 0; a < s; ++a)
      for (int t = 0; t < na; ++t) s_.inv(apos[static_cast<size_t>(t)], rows[static_cast<size_t>(a)]) = W(t, a);
  }
  s_.updates = 0;
  return true;
}

// X = C^-1 by Gauss-Jordan elimination with partial pivoting, in place: s^3 multiply-adds in column
// sweeps, where an LU and its inverse take 2 s^3 (and a condition estimate more solves); the condition is
// then exact, ||C||_1 ||C^-1||_1, from the explicit inverse. false if C is (nearly) singular, 1 / that
// condition not above limits.min_rcond. A pivot's small size is caught by the condition; the optimum's
// certificate (certify) is what the answer rests on either way.
bool DenseSimplex::invert_small(Eigen::Ref<const Eigen::MatrixXd> C, Eigen::Ref<Eigen::MatrixXd> X) {
  const Eigen::Index s = C.rows();
  X = C;
  const double norm_c = C.cwiseAbs().colwise().sum().maxCoeff();
  f_piv_.resize(static_cast<size_t>(s));
  auto col = f_col_.head(s);
  for (Eigen::Index k = 0; k < s; ++k) {
    Eigen::Index p = k;
    X.col(k).tail(s - k).cwiseAbs().maxCoeff(&p);
    p += k;
    if (!(std::abs(X(p, k)) > 0.0)) return false;
    f_piv_[static_cast<size_t>(k)] = static_cast<int>(p);
    if (p != k) X.row(p).swap(X.row(k));
    const double inv_pivot = 1.0 / X(k, k);
    col = X.col(k);
    col[k] = 0.0;
    X.col(k).setZero();
    X(k, k) = 1.0;
    X.row(k) *= inv_pivot;
    for (Eigen::Index j = 0; j < s; ++j) {
      const double xkj = X(k, j);
      if (xkj != 0.0) X.col(j).noalias() -= xkj * col;
    }
  }
  for (Eigen::Index k = s - 1; k >= 0; --k) {
    const Eigen::Index p = f_piv_[static_cast<size_t>(k)];
    if (p != k) X.col(p).swap(X.col(k));
  }
  const double norm_x = X.cwiseAbs().colwise().sum().maxCoeff();
  return std::isfinite(norm_x) && 1.0 / (norm_c * norm_x) > limits.min_rcond;
}

// x_B = -B^-1 N x_N from the nonbasic values (exactly at their bounds). N x_N column by column over the
// nonbasic structurals off zero only: most sit at a zero bound (a polytope LP's cone weights), so a
// product with all of A would multiply mostly zeros.
void DenseSimplex::compute_values() {
  const Eigen::MatrixXd& A = lp_->A;
  Eigen::VectorXd& r = cv_r_;
  r.setZero(m_);
  for (int k = 0; k < m_; ++k)
    if (s_.stat[static_cast<size_t>(k)] != GLP_BS) r[k] -= s_.value[k];
  for (int j = 0; j < n_; ++j) {
    const double v = s_.value[m_ + j];
    if (s_.stat[static_cast<size_t>(m_ + j)] != GLP_BS && v != 0.0) r.noalias() += v * A.col(j);
  }
  cv_xb_.noalias() = s_.inv * r;
  for (int i = 0; i < m_; ++i) s_.value[s_.head[static_cast<size_t>(i)]] = -cv_xb_[i];
}

bool DenseSimplex::set_basis(const signed char* stat, bool primal_feasible) {
  if (!lp_) return false;
  s_.stat.assign(stat, stat + m_ + n_);
  s_.head.clear();
  s_.value.setZero(m_ + n_);
  for (int k = 0; k < m_ + n_; ++k) {
    const signed char st = stat[k];
    const double lo = lo_[k], hi = hi_[k];
    switch (st) {
      case GLP_BS: s_.head.push_back(k); break;
      case GLP_NL: s_.value[k] = lo; break;
      case GLP_NU: s_.value[k] = hi; break;
      case GLP_NS: s_.value[k] = lo; break;
      case GLP_NF: s_.value[k] = 0.0; break;
      default: return false;
    }
    if (st != GLP_BS && st != GLP_NF && !std::isfinite(s_.value[k])) return false;
  }
  if (static_cast<int>(s_.head.size()) != m_ || !factorize()) return false;
  compute_values();
  if (!primal_feasible) return true;
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    const double v = s_.value[k];
    if (v < lo_[k] - 10 * bound_tol(lo_[k]) || v > hi_[k] + 10 * bound_tol(hi_[k])) return false;
  }
  return true;
}

// out = A^T v over v's nonzeros only: y and the rows of B^-1 are exactly zero on the rows whose slack is
// basic (factorize() leaves them so and a pivot keeps them so: 0 - α 0), most rows of a projection LP.
// Without A^T (see load()), one product with A's columns, over all of v.
void DenseSimplex::transposed_times(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
  if (!transposed_) {
    out.noalias() = lp_->A.transpose() * v;
    return;
  }
  out.setZero(n_);
  for (int i = 0; i < m_; ++i)
    if (v[i] != 0.0) out.noalias() += v[i] * at_.col(i);
}

void DenseSimplex::price(double vx, double vu) {
  // Multipliers y = B^-T c_B (only x and u have costs), reduced costs d = c - [A, -I]^T y.
  y_.setZero(m_);
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    if (k == m_) y_.noalias() += vx * s_.inv.row(i).transpose();
    else if (k == m_ + 1) y_.noalias() += vu * s_.inv.row(i).transpose();
  }
  transposed_times(y_, dstruct_);
  dstruct_ = -dstruct_;
  dstruct_[0] += vx;
  dstruct_[1] += vu;
  for (int k = 0; k < m_ + n_; ++k)
    d_[static_cast<size_t>(k)] = s_.stat[static_cast<size_t>(k)] == GLP_BS ? 0.0 : k < m_ ? y_[k] : dstruct_[k - m_];
}

// Basis position r leaves for variable q (alpha_ = B^-1 a_q, the values already moved), `leave_at_lo`
// its bound; B^-1 of the new basis by a rank-one update: row r over alpha_r, the other rows minus alpha_i
// times it. False if the refactorisation that follows every Limits::refactor updates finds B singular.
bool DenseSimplex::replace(int r, int q, bool leave_at_lo) {
  const int leave = s_.head[static_cast<size_t>(r)];
  s_.value[leave] = leave_at_lo ? lo_[leave] : hi_[leave];
  s_.stat[static_cast<size_t>(leave)] = lo_[leave] == hi_[leave] ? GLP_NS : leave_at_lo ? GLP_NL : GLP_NU;
  s_.stat[static_cast<size_t>(q)] = GLP_BS;
  s_.head[static_cast<size_t>(r)] = q;
  // B^-1 <- E B^-1 over the columns where row r is nonzero only: the column of a basic auxiliary k at
  // position i is exactly -e_i (B^-1 (-e_k) = e_i), zero in row r unless k is the one leaving. An entering
  // auxiliary's column becomes exactly -e_r too, with or without FMA: alpha is minus that column, so the
  // pivot row's entry there is v / -v = -1 and the column less -1 times alpha is 0 but in row r.
  pivot_row_.noalias() = s_.inv.row(r) / alpha_[r];
  for (int k = 0; k < m_; ++k)
    if (pivot_row_[k] != 0.0) s_.inv.col(k).noalias() -= pivot_row_[k] * alpha_;
  s_.inv.row(r) = pivot_row_;
  ++pivots;
  if (++s_.updates >= limits.refactor) {
    if (!factorize()) return false;
    compute_values();
  }
  return true;
}

int DenseSimplex::worst_infeasible(double& target) const {
  int r = -1;
  double worst = 0.0;
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    const double v = s_.value[k];
    const double below = lo_[k] - bound_tol(lo_[k]) - v, above = v - hi_[k] - bound_tol(hi_[k]);
    if (below > worst) worst = below, r = i, target = lo_[k];
    if (above > worst) worst = above, r = i, target = hi_[k];
  }
  return r;
}

// The dual simplex (bounded variables, Harris's two-pass ratio test on the reduced costs): the basic
// variable furthest outside its bounds leaves at that bound, and the nonbasic variable that moves it back
// at the least cost in the objective enters, so the reduced costs keep their signs; repeated until every
// basic variable is within GLPK's tolerance of its bounds. A slice LP's previous optimum stays dual
// feasible when the path moves a little (only its point leaves the polytope), so this is a few pivots;
// maximize() then goes on with the primal simplex and the certificate.
int DenseSimplex::dual_phase(double vx, double vu) {
  for (int it = 0;; ++it) {
    double target = 0.0;
    const int r = worst_infeasible(target);
    if (r < 0) return kOptimal;
    if (it == limits.max_pivots) return kIterationCap;
    // The reduced costs from y, at the start and after a refactorisation; a pivot updates them (below).
    if (it == 0 || s_.updates == 0) price(vx, vu);
    if (it == 0)
      for (int k = 0; k < m_ + n_; ++k) {
        const double d = d_[static_cast<size_t>(k)];
        const signed char st = s_.stat[static_cast<size_t>(k)];
        if ((st == GLP_NL && d > kTolDj) || (st == GLP_NU && d < -kTolDj) || (st == GLP_NF && std::abs(d) > kTolDj))
          return kNotDualFeasible;
      }
    // Row r of the tableau: x_B[r] moves by -w_j per unit of nonbasic x_j, w_j = (B^-1 a_j)_r.
    rho_ = s_.inv.row(r).transpose();
    transposed_times(rho_, wstruct_);
    const int leave = s_.head[static_cast<size_t>(r)];
    const double up = target > s_.value[leave] ? 1.0 : -1.0;  // the direction x_B[r] must move
    auto w_of = [&](int k) { return k < m_ ? -rho_[k] : wstruct_[k - m_]; };
    // x_j may move by sign(j) > 0 in its own direction: NL up, NU down, NF either.
    auto eligible = [&](int k, double& w) {
      const signed char st = s_.stat[static_cast<size_t>(k)];
      if (st == GLP_BS || st == GLP_NS) return false;
      w = w_of(k);
      const double gain = -w * up;  // x_B[r]'s move per unit increase of x_j, in the direction it must go
      return std::abs(w) >= limits.tol_pivot && (st == GLP_NF || (st == GLP_NL && gain > 0) || (st == GLP_NU && gain < 0));
    };
    double tmax = INFINITY;
    for (int k = 0; k < m_ + n_; ++k) {
      double w = 0.0;
      if (eligible(k, w)) tmax = std::min(tmax, (std::abs(d_[static_cast<size_t>(k)]) + 0.5 * kTolDj) / std::abs(w));
    }
    int q = -1;
    double big = 0.0;
    for (int k = 0; k < m_ + n_; ++k) {
      double w = 0.0;
      if (eligible(k, w) && std::abs(d_[static_cast<size_t>(k)]) / std::abs(w) <= tmax && std::abs(w) > big)
        big = std::abs(w), q = k;
    }
    if (q < 0) return kDualRay;
    // d_j -= δ w_j with δ = d_q / w_q (y moves by δ times row r of B^-1): d_q becomes 0, and the leaving
    // variable (w = 1, d = 0 while basic) takes -δ.
    const double delta = d_[static_cast<size_t>(q)] / w_of(q);
    for (int k = 0; k < m_ + n_; ++k)
      if (s_.stat[static_cast<size_t>(k)] != GLP_BS) d_[static_cast<size_t>(k)] -= delta * w_of(k);
    d_[static_cast<size_t>(q)] = 0.0;
    d_[static_cast<size_t>(leave)] = -delta;
    solve_column(q);
    const double step = (target - s_.value[leave]) / -alpha_[r];  // x_q's move that puts x_B[r] on its bound
    for (int i = 0; i < m_; ++i) s_.value[s_.head[static_cast<size_t>(i)]] -= alpha_[i] * step;
    s_.value[q] += step;
    if (!replace(r, q, target == lo_[leave])) return kSingular;
  }
}

int DenseSimplex::maximize(double vx, double vu) {
  if (!lp_ || static_cast<int>(s_.head.size()) != m_) return kNoBasis;
  const int dual = dual_phase(vx, vu);
  if (dual != kOptimal) return dual;
  const int total = m_ + n_;
  bool priced = false;  // y and d are of the current basis (a bound flip keeps both)
  for (int it = 0; it <= limits.max_pivots; ++it) {
    if (!priced) price(vx, vu);
    priced = false;
    int q = -1;
    double best = 0.0;
    for (int k = 0; k < total; ++k) {
      const signed char st = s_.stat[static_cast<size_t>(k)];
      const double d = d_[static_cast<size_t>(k)];
      if (st == GLP_BS || st == GLP_NS) continue;
      const bool improves = (st == GLP_NL && d > kTolDj) || (st == GLP_NU && d < -kTolDj) ||
                            (st == GLP_NF && std::abs(d) > kTolDj);
      if (improves && std::abs(d) > best) best = std::abs(d), q = k;
    }
    if (q < 0) return certify() ? kOptimal : kCertificate;
    if (it == limits.max_pivots) return kIterationCap;
    const double dir = d_[static_cast<size_t>(q)] > 0 ? 1.0 : -1.0;
    solve_column(q);
    // Ratio test (Harris's two passes): x_B changes by -alpha dir t.
    double tmax = INFINITY;
    bool small = false;  // a bounding row passed over for its tiny pivot
    for (int i = 0; i < m_; ++i) {
      const double delta = -alpha_[i] * dir;
      const int k = s_.head[static_cast<size_t>(i)];
      if (std::abs(alpha_[i]) < limits.tol_pivot) {
        small = small || (delta < 0 && std::isfinite(lo_[k])) || (delta > 0 && std::isfinite(hi_[k]));
        continue;
      }
      const double v = s_.value[k];
      if (delta < 0 && std::isfinite(lo_[k])) tmax = std::min(tmax, (v - lo_[k] + 0.5 * bound_tol(lo_[k])) / -delta);
      if (delta > 0 && std::isfinite(hi_[k])) tmax = std::min(tmax, (hi_[k] - v + 0.5 * bound_tol(hi_[k])) / delta);
    }
    int r = -1;
    double t = INFINITY, big = 0.0;
    for (int i = 0; i < m_; ++i) {
      const double delta = -alpha_[i] * dir;
      if (std::abs(alpha_[i]) < limits.tol_pivot) continue;
      const int k = s_.head[static_cast<size_t>(i)];
      const double v = s_.value[k];
      double ti = INFINITY;
      if (delta < 0 && std::isfinite(lo_[k])) ti = (v - lo_[k]) / -delta;
      if (delta > 0 && std::isfinite(hi_[k])) ti = (hi_[k] - v) / delta;
      if (ti <= tmax && std::abs(alpha_[i]) > big) big = std::abs(alpha_[i]), r = i, t = std::max(ti, 0.0);
    }
    const double range = hi_[q] - lo_[q];  // the entering variable's own bound (a flip)
    const bool flip = std::isfinite(range) && range <= t;
    if (flip) t = range;
    if (!std::isfinite(t)) return small ? kSmallPivot : kUnbounded;
    for (int i = 0; i < m_; ++i) s_.value[s_.head[static_cast<size_t>(i)]] -= alpha_[i] * dir * t;
    if (flip) {
      s_.stat[static_cast<size_t>(q)] = dir > 0 ? GLP_NU : GLP_NL;
      s_.value[q] = dir > 0 ? hi_[q] : lo_[q];
      ++pivots;
      priced = true;
      continue;
    }
    s_.value[q] += dir * t;
    if (!replace(r, q, -alpha_[r] * dir < 0)) return kSingular;
  }
  return kIterationCap;
}

void DenseSimplex::bound_range(int k, double& from, double& to) {
  from = to = s_.value[k];
  if (s_.stat[static_cast<size_t>(k)] == GLP_BS) return;
  solve_column(k);
  // x_k = t0 + t moves x_B by -alpha t; each basic variable's bounds limit t (a coefficient at rounding
  // level moves its variable by less than the bound tolerance over any range the audit reuses).
  double lo = -INFINITY, hi = INFINITY;
  for (int i = 0; i < m_; ++i) {
    const double a = alpha_[i];
    if (std::abs(a) < 1e-12) continue;
    const int b = s_.head[static_cast<size_t>(i)];
    const double v = s_.value[b];
    const double down = (v - lo_[b]) / a, up = (v - hi_[b]) / a;  // t at which x_b reaches lo, hi
    const double t_lo = std::min(down, up), t_hi = std::max(down, up);
    lo = std::max(lo, std::min(t_lo, 0.0));
    hi = std::min(hi, std::max(t_hi, 0.0));
  }
  from += lo;
  to += hi;
}

// The optimum's certificate, from the problem's own data (not from the updated inverse): the point
// (basic values recomputed, nonbasic ones at their bounds) satisfies every row and bound, and the
// multipliers y leave no nonbasic variable a reduced cost of the improving sign and no basic one a
// reduced cost at all (KKT, to GLPK's tolerances).
bool DenseSimplex::certify() {
  compute_values();
  const Eigen::MatrixXd& A = lp_->A;
  Eigen::VectorXd& z = cv_z_;
  z = s_.value.tail(n_);
  // Every row's value from the point, against the row's bounds: the computed value v is within
  // (n + 2) u Σ_j |a_ij z_j| of the exact one (u the unit roundoff), so the row is certified when v less
  // (or plus) that bound still meets its bound within the tolerance. A basic auxiliary takes the value,
  // a nonbasic one keeps its bound (its row then holds to the tolerance).
  rows_.noalias() = A * z;
  Eigen::VectorXd& abs_z = cv_r_;
  abs_z = z.cwiseAbs();
  const double gamma = (n_ + 2) * std::numeric_limits<double>::epsilon();
  // Σ_j |a_kj z_j| <= max_j |a_kj| ||z||_1 (rounded up by the factor 1 + 1e-12, far above the rounding of
  // these two products): a row well inside its bounds is decided without its exact sum.
  const double z1 = abs_z.sum() * (1.0 + 1e-12);
  for (int k = 0; k < m_ + n_; ++k) {
    double v = s_.value[k], e = 0.0;
    const double lo = lo_[k] - bound_tol(lo_[k]), hi = hi_[k] + bound_tol(hi_[k]);
    if (k < m_) {
      v = rows_[k];
      if (s_.stat[static_cast<size_t>(k)] == GLP_BS) s_.value[k] = v;
      e = gamma * row_max_[k] * z1;
      if (!(v - e >= lo && v + e <= hi))
        e = gamma * (transposed_ ? at_.col(k).cwiseAbs().dot(abs_z) : A.row(k).cwiseAbs().dot(abs_z.transpose()));
    }
    if (v - e >= lo && v + e <= hi) continue;
    // Undecided in double: the row again in extended precision, whose error bound is 2048 times smaller.
    // An equality row of the gravity wrench, summed from much larger terms with cancellation, has a
    // double bound above the tolerance itself, which no point can meet.
    if (k >= m_ || !row_within(k, z, lo, hi)) return false;
  }
  // The multipliers y and reduced costs d of the last pricing (the same basis and inverse): no basic
  // variable keeps a reduced cost (B^T y = c_B: the inverse is still accurate), no nonbasic one has one
  // of the improving sign.
  for (int k = 0; k < m_ + n_; ++k) {
    const double d = k < m_ ? y_[k] : dstruct_[k - m_];
    const signed char st = s_.stat[static_cast<size_t>(k)];
    const bool bad = (st == GLP_BS && std::abs(d) > 10 * kTolDj) || (st == GLP_NL && d > kTolDj) ||
                     (st == GLP_NU && d < -kTolDj) || (st == GLP_NF && std::abs(d) > kTolDj);
    if (bad) return false;
    d_[static_cast<size_t>(k)] = st == GLP_BS ? 0.0 : d;
  }
  return true;
}

bool DenseSimplex::row_within(int k, const Eigen::VectorXd& z, double lo, double hi) const {
  // Each product and sum in long double (x87's 64-bit mantissa on x86-64, never contracted into an FMA),
  // so the computed value is within (n + 1) u Σ_j |a_kj z_j| of the exact one for any summation order,
  // u = epsilon / 2 of long double; epsilon itself (twice u) and the factor (n + 2) leave room for the
  // rounding of the sum of magnitudes. Where long double is double the bound is the double one, and the
  // row fails as before: the check stays rigorous on every platform, only less often conclusive.
  const Eigen::MatrixXd& A = lp_->A;
  long double v = 0.0L, mag = 0.0L;
  for (int j = 0; j < n_; ++j) {
    const long double t = static_cast<long double>(A(k, j)) * static_cast<long double>(z[j]);
    v += t;
    mag += t < 0 ? -t : t;
  }
  const long double e = (n_ + 2) * std::numeric_limits<long double>::epsilon() * mag;
  return v - e >= static_cast<long double>(lo) && v + e <= static_cast<long double>(hi);
}

void DenseSimplex::tableau_xu(double* tab_x, double* tab_u) {
  const int total = m_ + n_;
  for (int k = 0; k <= total; ++k) tab_x[k] = tab_u[k] = 0.0;
  for (int i = 0; i < m_; ++i) {
    const int b = s_.head[static_cast<size_t>(i)];
    if (b != m_ && b != m_ + 1) continue;
    double* out = b == m_ ? tab_x : tab_u;
    // x_B = -B^-1 (N x_N): α_k = -(B^-1 a_k)_i; a_k = -e_k for an auxiliary, A's column for a structural.
    rho_ = s_.inv.row(i).transpose();
    transposed_times(rho_, wstruct_);
    for (int k = 0; k < total; ++k) {
      if (s_.stat[static_cast<size_t>(k)] == GLP_BS) continue;
      out[k + 1] = k < m_ ? s_.inv(i, k) : -wstruct_[k - m_];
    }
  }
}

}  // namespace pathpace::detail
