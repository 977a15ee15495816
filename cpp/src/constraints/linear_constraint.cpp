#include "pathpace/constraints/linear_constraint.hpp"

#include <cmath>

#include "base/validate.hpp"

namespace pathpace {

LinearConstraint::LinearConstraint(Eigen::MatrixXd A, Eigen::MatrixXd B, Eigen::MatrixXd C, Eigen::MatrixXd lo,
                                   Eigen::MatrixXd hi, std::string label)
    : A_(std::move(A)), B_(std::move(B)), C_(std::move(C)), lo_(std::move(lo)), hi_(std::move(hi)),
      label_(std::move(label)) {
  const Eigen::Index rows = A_.rows(), cols = A_.cols();
  detail::require_shape("B", B_.rows(), B_.cols(), rows, cols, "same shape as A");
  detail::require_shape("C", C_.rows(), C_.cols(), rows, cols, "same shape as A");
  detail::require_shape("lo", lo_.rows(), lo_.cols(), rows, cols, "same shape as A");
  detail::require_shape("hi", hi_.rows(), hi_.cols(), rows, cols, "same shape as A");
  detail::require_finite("A", A_);
  detail::require_finite("B", B_);
  detail::require_finite("C", C_);
  detail::require_not_nan("lo", lo_);
  detail::require_not_nan("hi", hi_);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index k = 0; k < rows; ++k) {
      if (lo_(k, j) == std::numeric_limits<double>::infinity())
        detail::fail(detail::at("lo", k, j) + " = inf must be < inf");
      if (hi_(k, j) == -std::numeric_limits<double>::infinity())
        detail::fail(detail::at("hi", k, j) + " = -inf must be > -inf");
      if (!(lo_(k, j) <= hi_(k, j)))
        detail::fail(detail::at("lo", k, j) + " = " + detail::fmt(lo_(k, j)) + " must be <= " +
                     detail::at("hi", k, j) + " = " + detail::fmt(hi_(k, j)));
    }
}

ConstraintRows LinearConstraint::evaluate(const PathSamples& samples) const {
  if (A_.rows() != samples.size())
    detail::fail("A has " + std::to_string(A_.rows()) + " rows, expected one per grid point (" +
                 std::to_string(samples.size()) + ")");
  const Eigen::Index r = A_.cols();
  ConstraintRows rows;
  rows.resize(samples.size(), 2 * r);
  for (Eigen::Index j = 0; j < r; ++j) {
    rows.labels[static_cast<size_t>(2 * j)] = label_ + "[" + std::to_string(j) + "] upper";
    rows.labels[static_cast<size_t>(2 * j + 1)] = label_ + "[" + std::to_string(j) + "] lower";
  }
  for (Eigen::Index k = 0; k < samples.size(); ++k)
    for (Eigen::Index j = 0; j < r; ++j) {
      if (std::isfinite(hi_(k, j))) {
        rows.a(k, 2 * j) = A_(k, j);
        rows.b(k, 2 * j) = B_(k, j);
        rows.c(k, 2 * j) = hi_(k, j) - C_(k, j);
      }
      if (std::isfinite(lo_(k, j))) {
        rows.a(k, 2 * j + 1) = -A_(k, j);
        rows.b(k, 2 * j + 1) = -B_(k, j);
        rows.c(k, 2 * j + 1) = C_(k, j) - lo_(k, j);
      }
    }
  return rows;
}

std::shared_ptr<const Constraint> LinearConstraint::at_grid_points(const std::vector<Eigen::Index>& kept) const {
  const auto pick = [&kept](const Eigen::MatrixXd& m) {
    Eigen::MatrixXd out(static_cast<Eigen::Index>(kept.size()), m.cols());
    for (size_t i = 0; i < kept.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = m.row(kept[i]);
    return out;
  };
  return std::make_shared<LinearConstraint>(pick(A_), pick(B_), pick(C_), pick(lo_), pick(hi_), label_);
}

}  // namespace pathpace
