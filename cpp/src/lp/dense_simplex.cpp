#include "lp/dense_simplex.hpp"

#include <cmath>
#include <limits>

#include <Eigen/LU>
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

void DenseSimplex::load(const PolytopeLp& lp) {
  lp_ = &lp;
  m_ = static_cast<int>(lp.A.rows());
  n_ = static_cast<int>(lp.A.cols());
  lo_.resize(m_ + n_);
  hi_.resize(m_ + n_);
  lo_ << lp.row_lo, lp.col_lo;
  hi_ << lp.row_hi, lp.col_hi;
  d_.assign(static_cast<size_t>(m_ + n_), 0.0);
  abs_a_ = lp.A.cwiseAbs();
  s_ = State();
}

void DenseSimplex::column(int k, Eigen::VectorXd& a) const {
  if (k < m_) {
    a.setZero(m_);
    a[k] = -1.0;
  } else {
    a = lp_->A.col(k - m_);
  }
}

bool DenseSimplex::factorize() {
  Eigen::MatrixXd B(m_, m_);
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    if (k < m_) {
      B.col(i).setZero();
      B(k, i) = -1.0;
    } else {
      B.col(i) = lp_->A.col(k - m_);
    }
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(B);
  if (!(lu.rcond() > limits.min_rcond)) return false;
  s_.inv = lu.inverse();
  s_.updates = 0;
  return true;
}

// x_B = -B^-1 N x_N from the nonbasic values (exactly at their bounds).
void DenseSimplex::compute_values() {
  const Eigen::MatrixXd& A = lp_->A;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n_);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(m_);
  for (int k = 0; k < m_ + n_; ++k) {
    if (s_.stat[static_cast<size_t>(k)] == GLP_BS) continue;
    if (k < m_) r[k] -= s_.value[k];
    else z[k - m_] = s_.value[k];
  }
  r.noalias() += A * z;
  const Eigen::VectorXd xb = -(s_.inv * r);
  for (int i = 0; i < m_; ++i) s_.value[s_.head[static_cast<size_t>(i)]] = xb[i];
}

bool DenseSimplex::set_basis(const signed char* stat) {
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
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    const double v = s_.value[k];
    if (v < lo_[k] - 10 * bound_tol(lo_[k]) || v > hi_[k] + 10 * bound_tol(hi_[k])) return false;
  }
  return true;
}

int DenseSimplex::maximize(double vx, double vu) {
  if (!lp_ || static_cast<int>(s_.head.size()) != m_) return kNoBasis;
  const Eigen::MatrixXd& A = lp_->A;
  const int total = m_ + n_;
  for (int it = 0; it <= limits.max_pivots; ++it) {
    // Multipliers y = B^-T c_B (only x and u have costs), reduced costs d = c - [A, -I]^T y.
    y_.setZero(m_);
    for (int i = 0; i < m_; ++i) {
      const int k = s_.head[static_cast<size_t>(i)];
      if (k == m_) y_.noalias() += vx * s_.inv.row(i).transpose();
      else if (k == m_ + 1) y_.noalias() += vu * s_.inv.row(i).transpose();
    }
    dstruct_.noalias() = -(A.transpose() * y_);
    dstruct_[0] += vx;
    dstruct_[1] += vu;
    int q = -1;
    double best = 0.0;
    for (int k = 0; k < total; ++k) {
      const signed char st = s_.stat[static_cast<size_t>(k)];
      const double d = k < m_ ? y_[k] : dstruct_[k - m_];
      d_[static_cast<size_t>(k)] = st == GLP_BS ? 0.0 : d;
      if (st == GLP_BS || st == GLP_NS) continue;
      const bool improves = (st == GLP_NL && d > kTolDj) || (st == GLP_NU && d < -kTolDj) ||
                            (st == GLP_NF && std::abs(d) > kTolDj);
      if (improves && std::abs(d) > best) best = std::abs(d), q = k;
    }
    if (q < 0) return certify() ? kOptimal : kCertificate;
    if (it == limits.max_pivots) return kIterationCap;
    const double dir = d_[static_cast<size_t>(q)] > 0 ? 1.0 : -1.0;
    column(q, col_);
    alpha_.noalias() = s_.inv * col_;
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
      continue;
    }
    s_.value[q] += dir * t;
    const int leave = s_.head[static_cast<size_t>(r)];
    const bool to_lo = -alpha_[r] * dir < 0;
    s_.value[leave] = to_lo ? lo_[leave] : hi_[leave];
    s_.stat[static_cast<size_t>(leave)] = lo_[leave] == hi_[leave] ? GLP_NS : to_lo ? GLP_NL : GLP_NU;
    s_.stat[static_cast<size_t>(q)] = GLP_BS;
    s_.head[static_cast<size_t>(r)] = q;
    // B^-1 of the new basis: row r over alpha_r, the other rows minus alpha_i times it.
    pivot_row_.noalias() = s_.inv.row(r) / alpha_[r];
    s_.inv.noalias() -= alpha_ * pivot_row_;
    s_.inv.row(r) = pivot_row_;
    ++pivots;
    if (++s_.updates >= limits.refactor) {
      if (!factorize()) return kSingular;
      compute_values();
    }
  }
  return kIterationCap;
}

// The optimum's certificate, from the problem's own data (not from the updated inverse): the point
// (basic values recomputed, nonbasic ones at their bounds) satisfies every row and bound, and the
// multipliers y leave no nonbasic variable a reduced cost of the improving sign and no basic one a
// reduced cost at all (KKT, to GLPK's tolerances).
bool DenseSimplex::certify() {
  compute_values();
  const Eigen::MatrixXd& A = lp_->A;
  const Eigen::VectorXd z = s_.value.tail(n_);
  // Every row's value from the point, against the row's bounds: the computed value v is within
  // (n + 2) u Σ_j |a_ij z_j| of the exact one (u the unit roundoff), so the row is certified when v less
  // (or plus) that bound still meets its bound within the tolerance. A basic auxiliary takes the value,
  // a nonbasic one keeps its bound (its row then holds to the tolerance).
  rows_.noalias() = A * z;
  err_.noalias() = abs_a_ * z.cwiseAbs();
  const double gamma = (n_ + 2) * std::numeric_limits<double>::epsilon();
  for (int k = 0; k < m_ + n_; ++k) {
    double v = s_.value[k], e = 0.0;
    if (k < m_) {
      v = rows_[k];
      e = gamma * err_[k];
      if (s_.stat[static_cast<size_t>(k)] == GLP_BS) s_.value[k] = v;
    }
    const double lo = lo_[k] - bound_tol(lo_[k]), hi = hi_[k] + bound_tol(hi_[k]);
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

void DenseSimplex::tableau_xu(double* tab_x, double* tab_u) const {
  const int total = m_ + n_;
  for (int k = 0; k <= total; ++k) tab_x[k] = tab_u[k] = 0.0;
  for (int i = 0; i < m_; ++i) {
    const int b = s_.head[static_cast<size_t>(i)];
    if (b != m_ && b != m_ + 1) continue;
    double* out = b == m_ ? tab_x : tab_u;
    // x_B = -B^-1 (N x_N): α_k = -(B^-1 a_k)_i; a_k = -e_k for an auxiliary, A's column for a structural.
    const Eigen::VectorXd w = -(lp_->A.transpose() * s_.inv.row(i).transpose());
    for (int k = 0; k < total; ++k) {
      if (s_.stat[static_cast<size_t>(k)] == GLP_BS) continue;
      out[k + 1] = k < m_ ? s_.inv(i, k) : w[k - m_];
    }
  }
}

}  // namespace pathpace::detail
