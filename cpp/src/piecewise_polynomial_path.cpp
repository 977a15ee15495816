#include "pathpace/piecewise_polynomial_path.hpp"

#include <algorithm>

#include "detail/validate.hpp"

namespace pathpace {

PiecewisePolynomialPath::PiecewisePolynomialPath(Eigen::VectorXd breakpoints, std::vector<Eigen::MatrixXd> coefficients)
    : breakpoints_(std::move(breakpoints)), coefficients_(std::move(coefficients)) {
  if (breakpoints_.size() < 2)
    detail::fail("breakpoints has " + std::to_string(breakpoints_.size()) + " entries, expected at least 2");
  detail::require_finite("breakpoints", breakpoints_);
  detail::require_increasing("breakpoints", breakpoints_);
  const Eigen::Index m = breakpoints_.size() - 1;
  detail::require_size("coefficients", static_cast<Eigen::Index>(coefficients_.size()), m, "one piece per interval");
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

}  // namespace pathpace
