#include "lp/band_ldlt.hpp"

#include <cmath>

namespace pathpace::detail {

void BandLdlt::scaled(const BandLdlt& K, const Eigen::VectorXd& scale) {
  for (Eigen::Index i = 0; i < m_; ++i)
    for (Eigen::Index e = 0; e <= std::min<Eigen::Index>(i, kBand); ++e)
      a_[idx(i, i - e)] = scale[i] * K.a_[idx(i, i - e)] * scale[i - e];
}

bool BandLdlt::factor(const Eigen::VectorXd& reg) {
  f_ = a_;
  for (Eigen::Index i = 0; i < m_; ++i) {
    double* fi = f_.data() + i * kW;
    fi[0] += reg[i];
    const Eigen::Index top = std::min<Eigen::Index>(i, kBand);
    // L(i, j) for j = i - top .. i - 1, each from the row's earlier entries: L(i, j) D(j) = A(i, j) - Σ_k
    // L(i, k) D(k) L(j, k) over the columns k < j both rows reach.
    for (Eigen::Index d = top; d >= 1; --d) {
      const double* fj = f_.data() + (i - d) * kW;
      double v = fi[d];
      for (Eigen::Index e = d + 1; e <= top; ++e) v -= fi[e] * f_[static_cast<size_t>((i - e) * kW)] * fj[e - d];
      fi[d] = v * inv_d_[static_cast<size_t>(i - d)];
    }
    double dd = fi[0];
    for (Eigen::Index e = 1; e <= top; ++e) dd -= fi[e] * fi[e] * f_[static_cast<size_t>((i - e) * kW)];
    if (!(std::abs(dd) > 0) || !std::isfinite(dd)) return false;
    fi[0] = dd;
    inv_d_[static_cast<size_t>(i)] = 1.0 / dd;
  }
  return true;
}

// The substitutions carry the last four values in registers, and the term of the value just computed is
// subtracted last: a row waits on the previous row for one product and one subtraction.
void BandLdlt::solve(Eigen::VectorXd& x) const {
  const double* f = f_.data();
  const Eigen::Index head = std::min<Eigen::Index>(m_, kBand);
  for (Eigen::Index i = 0; i < head; ++i)
    for (Eigen::Index e = 1; e <= i; ++e) x[i] -= f[i * kW + e] * x[i - e];
  if (m_ > kBand) {
    double x1 = x[3], x2 = x[2], x3 = x[1], x4 = x[0];
    for (Eigen::Index i = kBand; i < m_; ++i) {
      const double* fi = f + i * kW;
      const double v = (x[i] - (fi[2] * x2 + (fi[3] * x3 + fi[4] * x4))) - fi[1] * x1;
      x[i] = v, x4 = x3, x3 = x2, x2 = x1, x1 = v;
    }
  }
  for (Eigen::Index i = 0; i < m_; ++i) x[i] *= inv_d_[static_cast<size_t>(i)];
  const Eigen::Index tail = std::max<Eigen::Index>(0, m_ - kBand);
  for (Eigen::Index i = m_ - 1; i >= tail; --i)
    for (Eigen::Index e = 1; i + e < m_; ++e) x[i] -= f[(i + e) * kW + e] * x[i + e];
  if (m_ > kBand) {
    double x1 = x[tail], x2 = x[tail + 1], x3 = x[tail + 2], x4 = x[tail + 3];
    for (Eigen::Index i = tail - 1; i >= 0; --i) {
      const double v = (x[i] - (f[(i + 2) * kW + 2] * x2 + (f[(i + 3) * kW + 3] * x3 + f[(i + 4) * kW + 4] * x4))) -
                       f[(i + 1) * kW + 1] * x1;
      x[i] = v, x4 = x3, x3 = x2, x2 = x1, x1 = v;
    }
  }
}

void BandLdlt::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.resize(m_);
  const double* a = a_.data();
  for (Eigen::Index i = 0; i < m_; ++i) {
    double v = a[i * kW] * x[i];
    for (Eigen::Index e = 1; e <= std::min<Eigen::Index>(i, kBand); ++e) v += a[i * kW + e] * x[i - e];
    for (Eigen::Index e = 1; e <= std::min<Eigen::Index>(m_ - 1 - i, kBand); ++e) v += a[(i + e) * kW + e] * x[i + e];
    y[i] = v;
  }
}

}  // namespace pathpace::detail
