#include "pathpace/sampled_path.hpp"

#include "base/validate.hpp"

namespace pathpace {

SampledPath::SampledPath(const Eigen::VectorXd& s, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                         const Eigen::MatrixXd& ddq)
    : PiecewisePolynomialPath(build(s, q, dq, ddq)) {}

PiecewisePolynomialPath SampledPath::build(const Eigen::VectorXd& s, const Eigen::MatrixXd& q,
                                           const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq) {
  if (s.size() < 2) detail::fail("s has " + std::to_string(s.size()) + " entries, expected at least 2");
  detail::require_finite("s", s);
  detail::require_increasing("s", s);
  const Eigen::Index m = s.size(), n = q.cols();
  if (n < 1) detail::fail("q has 0 columns, expected at least 1 coordinate");
  detail::require_shape("q", q.rows(), q.cols(), m, n, "one row per sample");
  detail::require_shape("dq", dq.rows(), dq.cols(), m, n, "as q");
  detail::require_shape("ddq", ddq.rows(), ddq.cols(), m, n, "as q");
  detail::require_finite("q", q);
  detail::require_finite("dq", dq);
  detail::require_finite("ddq", ddq);
  std::vector<Eigen::MatrixXd> coefficients(static_cast<size_t>(m - 1), Eigen::MatrixXd(6, n));
  for (Eigen::Index i = 0; i + 1 < m; ++i) {
    // Quintic in τ = s - s_i on [0, h] matching (q, q', q'') at both ends.
    const double h = s[i + 1] - s[i], h2 = h * h, h3 = h2 * h, h4 = h3 * h, h5 = h4 * h;
    const Eigen::RowVectorXd p0 = q.row(i), v0 = dq.row(i), a0 = ddq.row(i);
    const Eigen::RowVectorXd p1 = q.row(i + 1), v1 = dq.row(i + 1), a1 = ddq.row(i + 1);
    Eigen::MatrixXd& c = coefficients[static_cast<size_t>(i)];
    c.row(0) = p0;
    c.row(1) = v0;
    c.row(2) = 0.5 * a0;
    c.row(3) = (20 * (p1 - p0) - (8 * v1 + 12 * v0) * h - (3 * a0 - a1) * h2) / (2 * h3);
    c.row(4) = (30 * (p0 - p1) + (14 * v1 + 16 * v0) * h + (3 * a0 - 2 * a1) * h2) / (2 * h4);
    c.row(5) = (12 * (p1 - p0) - 6 * (v1 + v0) * h - (a0 - a1) * h2) / (2 * h5);
  }
  return PiecewisePolynomialPath(s, std::move(coefficients));
}

}  // namespace pathpace
