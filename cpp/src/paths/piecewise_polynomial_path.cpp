#include "pathpace/piecewise_polynomial_path.hpp"

#include <algorithm>
#include <vector>
#include <limits>

#include "base/validate.hpp"

namespace pathpace {

PiecewisePolynomialPath::PiecewisePolynomialPath(Eigen::VectorXd breakpoints, std::vector<Eigen::MatrixXd> coefficients)
    : breakpoints_(std::move(breakpoints)), coefficients_(std::move(coefficients)) {
  if (breakpoints_.size() < 2)
    detail::fail("breakpoints has " + std::to_string(breakpoints_.size()) + " entries, expected at least 2");
  detail::require_finite("breakpoints", breakpoints_);
  detail::require_increasing("breakpoints", breakpoints_);
  const Eigen::Index m = breakpoints_.size() - 1;
  // Both arguments named: either may be the wrong one.
  detail::require_size("coefficients", static_cast<Eigen::Index>(coefficients_.size()), m,
                       "one piece per interval of breakpoints, which has " + std::to_string(m + 1) + " entries");
  const Eigen::Index rows = coefficients_[0].rows(), cols = coefficients_[0].cols();
  if (rows < 1 || cols < 1) detail::fail("coefficients[0] is empty, expected shape (degree + 1, n)");
  for (size_t i = 0; i < coefficients_.size(); ++i) {
    const std::string name = "coefficients[" + std::to_string(i) + "]";
    detail::require_shape(name, coefficients_[i].rows(), coefficients_[i].cols(), rows, cols, "as coefficients[0]");
    detail::require_finite(name, coefficients_[i]);
  }
  dof_ = static_cast<int>(cols);
}

Eigen::Index PiecewisePolynomialPath::piece(double s) const {
  const Eigen::Index m = breakpoints_.size() - 1;
  const double* b = breakpoints_.data();
  const Eigen::Index i = static_cast<Eigen::Index>(std::upper_bound(b, b + m + 1, s) - b) - 1;
  return std::clamp<Eigen::Index>(i, 0, m - 1);
}

void PiecewisePolynomialPath::evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                                       Eigen::Ref<Eigen::VectorXd> ddq) const {
  s = std::clamp(s, s_begin(), s_end());
  const Eigen::Index i = piece(s);
  const Eigen::MatrixXd& c = coefficients_[static_cast<size_t>(i)];
  const double t = s - breakpoints_[i];
  // Horner for p, p', p'' together.
  const Eigen::Index d = c.rows() - 1;
  q = c.row(d).transpose();
  dq.setZero();
  ddq.setZero();
  for (Eigen::Index j = d - 1; j >= 0; --j) {
    ddq = ddq * t + 2.0 * dq;
    dq = dq * t + q;
    q = q * t + c.row(j).transpose();
  }
}

void PiecewisePolynomialPath::evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q,
                                       Eigen::MatrixXd& dq, Eigen::MatrixXd& ddq) const {
  // The grid is sorted in the common case: walk the pieces forward and fall back to bisection. Grid
  // points are taken in runs that share a piece, and each run is evaluated coordinate by coordinate down
  // the (column-major) outputs: the same Horner steps as the one-point evaluate, but with the piece's
  // coefficients fixed over a contiguous loop that the compiler vectorises (this is part of every
  // problem's set-up).
  const Eigen::Index m = s.size(), n = dof_, pieces = breakpoints_.size() - 1;
  q.resize(m, n);
  dq.resize(m, n);
  ddq.resize(m, n);
  const double lo = s_begin(), hi = s_end();
  std::vector<double> t(static_cast<size_t>(m));
  Eigen::Index i = 0;
  for (Eigen::Index r = 0; r < m;) {
    const double x = std::clamp(s[r], lo, hi);
    if (x < breakpoints_[i] || (i + 1 < pieces && x >= breakpoints_[i + 1])) {
      if (i + 1 < pieces && x >= breakpoints_[i + 1] && (i + 2 >= pieces + 1 || x < breakpoints_[i + 2])) ++i;
      else i = piece(x);
    }
    // The run [r, e): the grid points that stay in piece i (x, the first, lies in [b, next) by the choice of i).
    const double b = breakpoints_[i], next = i + 1 < pieces ? breakpoints_[i + 1] : std::numeric_limits<double>::infinity();
    t[static_cast<size_t>(r)] = x - b;
    Eigen::Index e = r + 1;
    for (; e < m; ++e) {
      const double y = std::clamp(s[e], lo, hi);
      if (y < b || y >= next) break;
      t[static_cast<size_t>(e)] = y - b;
    }
    const Eigen::MatrixXd& c = coefficients_[static_cast<size_t>(i)];
    const Eigen::Index d = c.rows() - 1;
    for (Eigen::Index j = 0; j < n; ++j) {
      double* pq = q.col(j).data();
      double* pdq = dq.col(j).data();
      double* pddq = ddq.col(j).data();
      const double* cj = c.col(j).data();
      if (d == 3) {
        // Cubic (every CubicSplinePath): the loop below unrolled, the same operations in the same order.
        const double c0 = cj[0], c1 = cj[1], c2 = cj[2], c3 = cj[3];
        for (Eigen::Index u = r; u < e; ++u) {
          const double tu = t[static_cast<size_t>(u)];
          const double p1 = c3 * tu + c2, dp1 = c3 * tu + p1, p2 = p1 * tu + c1;
          pddq[u] = (2.0 * c3) * tu + 2.0 * dp1;
          pdq[u] = dp1 * tu + p2;
          pq[u] = p2 * tu + c0;
        }
        continue;
      }
      for (Eigen::Index u = r; u < e; ++u) {
        const double tu = t[static_cast<size_t>(u)];
        double p = cj[d], dp = 0.0, ddp = 0.0;
        for (Eigen::Index k = d - 1; k >= 0; --k) {
          ddp = ddp * tu + 2.0 * dp;
          dp = dp * tu + p;
          p = p * tu + cj[k];
        }
        pq[u] = p;
        pdq[u] = dp;
        pddq[u] = ddp;
      }
    }
    r = e;
  }
}

}  // namespace pathpace
