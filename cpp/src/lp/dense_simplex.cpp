#include "lp/dense_simplex.hpp"

#include <cmath>

#include <Eigen/LU>
#include <glpk.h>

#include "lp/projection.hpp"

namespace pathpace::detail {

namespace {
// GLPK's own optimality tolerances for these LPs (projection.cpp's simplex_parameters), and its pivot
// tolerance: a smaller pivot is a failure here (GLPK then solves the LP).
constexpr double kTolDj = 1e-10, kTolPivot = 1e-9, kTie = 1e-12;
// The certificate's: GLPK's optimum passes it, a drifted inverse does not.
constexpr double kCertBnd = 2e-10, kCertDj = 1e-10;
// Pivots per LP (an LP from an endpoint's basis takes a few; more means cycling or a far start) and
// rank-one updates before the inverse is computed again from B.
constexpr int kMaxPivots = 200, kRefactor = 25;
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
  if (!(lu.rcond() > 1e-10)) return false;  // ill-conditioned: GLPK's LU (and its tolerances) instead
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
    if (v < lo_[k] - kCertBnd * (1 + std::abs(lo_[k])) || v > hi_[k] + kCertBnd * (1 + std::abs(hi_[k]))) return false;
  }
  return true;
}

int DenseSimplex::maximize(double vx, double vu) {
  if (!lp_ || static_cast<int>(s_.head.size()) != m_) return 0;
  const Eigen::MatrixXd& A = lp_->A;
  const int total = m_ + n_;
  for (int it = 0; it <= kMaxPivots; ++it) {
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
    if (q < 0) return certify(vx, vu) ? 1 : 0;
    if (it == kMaxPivots) return 0;
    const double dir = d_[static_cast<size_t>(q)] > 0 ? 1.0 : -1.0;
    column(q, col_);
    alpha_.noalias() = s_.inv * col_;
    // Ratio test: x_B changes by -alpha dir t. The smallest ratio exactly (no Harris tolerance: a basic
    // variable left beyond its bound by it was seen to put a vertex 2e-6 of the polygon's size outside
    // the shadow, through a torque row with small x and u coefficients); among near-ties (1e-12) the
    // largest pivot.
    double tmax = INFINITY;
    for (int i = 0; i < m_; ++i) {
      const double delta = -alpha_[i] * dir;
      if (std::abs(alpha_[i]) < kTolPivot) continue;
      const int k = s_.head[static_cast<size_t>(i)];
      const double v = s_.value[k];
      if (delta < 0 && std::isfinite(lo_[k])) tmax = std::min(tmax, std::max(v - lo_[k], 0.0) / -delta);
      if (delta > 0 && std::isfinite(hi_[k])) tmax = std::min(tmax, std::max(hi_[k] - v, 0.0) / delta);
    }
    int r = -1;
    double t = INFINITY, big = 0.0;
    for (int i = 0; i < m_; ++i) {
      const double delta = -alpha_[i] * dir;
      if (std::abs(alpha_[i]) < kTolPivot) continue;
      const int k = s_.head[static_cast<size_t>(i)];
      const double v = s_.value[k];
      double ti = INFINITY;
      if (delta < 0 && std::isfinite(lo_[k])) ti = (v - lo_[k]) / -delta;
      if (delta > 0 && std::isfinite(hi_[k])) ti = (hi_[k] - v) / delta;
      if (ti <= tmax + kTie * (1 + tmax) && std::abs(alpha_[i]) > big) big = std::abs(alpha_[i]), r = i, t = std::max(ti, 0.0);
    }
    const double range = hi_[q] - lo_[q];  // the entering variable's own bound (a flip)
    const bool flip = std::isfinite(range) && range <= t;
    if (flip) t = range;
    if (!std::isfinite(t)) return 0;  // unbounded along (vx, vu): not a projection LP's answer
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
    const Eigen::RowVectorXd pivot_row = s_.inv.row(r) / alpha_[r];
    s_.inv.noalias() -= alpha_ * pivot_row;
    s_.inv.row(r) = pivot_row;
    ++pivots;
    if (++s_.updates >= kRefactor) {
      if (!factorize()) return 0;
      compute_values();
    }
  }
  return 0;
}

// B^-T e_pos (the multipliers of the cost e on the basic variable at position pos), with one step of
// iterative refinement against the basis's own columns: after rank-one updates of an ill-conditioned
// basis (32-edge cones: nearly parallel generators) the inverse alone was seen to leave errors that
// moved a polygon by 2e-6 of its size.
void DenseSimplex::refined_row(int pos, Eigen::VectorXd& y) const {
  y = s_.inv.row(pos).transpose();
  Eigen::VectorXd res(m_);
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    const double bty = k < m_ ? -y[k] : lp_->A.col(k - m_).dot(y);
    res[i] = (i == pos ? 1.0 : 0.0) - bty;
  }
  y.noalias() += s_.inv.transpose() * res;
}

// The optimum's certificate, from the problem's own data (not from the updated inverse): the point
// (basic values recomputed and refined, nonbasic ones at their bounds) satisfies every row and bound,
// and the multipliers y leave no nonbasic variable a reduced cost of the improving sign and no basic one
// a reduced cost at all (KKT, to GLPK's tolerances).
bool DenseSimplex::certify(double vx, double vu) {
  compute_values();
  const Eigen::MatrixXd& A = lp_->A;
  // One refinement step of x_B: the residual of A z - aux = 0 over every variable.
  {
    const Eigen::VectorXd res = A * s_.value.tail(n_) - s_.value.head(m_);
    const Eigen::VectorXd dx = s_.inv * res;
    for (int i = 0; i < m_; ++i) s_.value[s_.head[static_cast<size_t>(i)]] += dx[i];
  }
  const Eigen::VectorXd z = s_.value.tail(n_);
  const Eigen::VectorXd rows = A * z;
  for (int k = 0; k < m_ + n_; ++k) {
    const double v = k < m_ ? rows[k] : z[k - m_];
    if (v < lo_[k] - kCertBnd * (1 + std::abs(lo_[k])) || v > hi_[k] + kCertBnd * (1 + std::abs(hi_[k]))) return false;
    if (k < m_) s_.value[k] = v;
  }
  yx_.setZero(m_);
  yu_.setZero(m_);
  for (int i = 0; i < m_; ++i) {
    const int k = s_.head[static_cast<size_t>(i)];
    if (k == m_) refined_row(i, yx_);
    else if (k == m_ + 1) refined_row(i, yu_);
  }
  y_ = vx * yx_ + vu * yu_;
  dstruct_.noalias() = -(A.transpose() * y_);
  dstruct_[0] += vx;
  dstruct_[1] += vu;
  for (int k = 0; k < m_ + n_; ++k) {
    const double d = k < m_ ? y_[k] : dstruct_[k - m_];
    const signed char st = s_.stat[static_cast<size_t>(k)];
    const bool bad = (st == GLP_BS && std::abs(d) > kCertDj) || (st == GLP_NL && d > kCertDj) ||
                     (st == GLP_NU && d < -kCertDj) || (st == GLP_NF && std::abs(d) > kCertDj);
    if (bad) return false;
    d_[static_cast<size_t>(k)] = st == GLP_BS ? 0.0 : d;
  }
  return true;
}

void DenseSimplex::tableau_xu(double* tab_x, double* tab_u) const {
  const int total = m_ + n_;
  for (int k = 0; k <= total; ++k) tab_x[k] = tab_u[k] = 0.0;
  // From the refined multipliers of the last certificate: x_B = -B^-1 (N x_N), so α_k = -(B^-1 a_k)_i =
  // -y·a_k with y = B^-T e_i; a_k = -e_k for an auxiliary, A's column for a structural.
  for (int c = 0; c < 2; ++c) {
    bool basic = false;
    for (int i = 0; i < m_; ++i) basic = basic || s_.head[static_cast<size_t>(i)] == m_ + c;
    if (!basic) continue;
    const Eigen::VectorXd& y = c == 0 ? yx_ : yu_;
    double* out = c == 0 ? tab_x : tab_u;
    const Eigen::VectorXd w = -(lp_->A.transpose() * y);
    for (int k = 0; k < total; ++k) {
      if (s_.stat[static_cast<size_t>(k)] == GLP_BS) continue;
      out[k + 1] = k < m_ ? y[k] : w[k - m_];
    }
  }
}

}  // namespace pathpace::detail
