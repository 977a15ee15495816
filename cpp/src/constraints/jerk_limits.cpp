#include "pathpace/constraints/jerk_limits.hpp"

#include <algorithm>
#include <cmath>

#include "base/validate.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace {

JerkLimits::JerkLimits(Eigen::VectorXd jmin, Eigen::VectorXd jmax, std::vector<std::string> joint_names)
    : jmin_(std::move(jmin)), jmax_(std::move(jmax)), joint_names_(std::move(joint_names)) {
  detail::require_size("jmin", jmin_.size(), jmax_.size(), "one entry per joint, as jmax");
  if (jmax_.size() == 0) detail::fail("jmax has 0 entries, expected one per joint");
  if (!joint_names_.empty())
    detail::require_size("joint_names", static_cast<Eigen::Index>(joint_names_.size()), jmax_.size(), "one per joint, as jmax");
  detail::require_not_nan("jmin", jmin_);
  detail::require_not_nan("jmax", jmax_);
  for (Eigen::Index j = 0; j < jmax_.size(); ++j) {
    const std::string which = joint_names_.empty() ? "" : " (" + joint_names_[static_cast<size_t>(j)] + ")";
    // A jerk bound of 0 on one side would forbid every start from rest: the limits must straddle 0.
    if (!(jmax_[j] > 0.0)) detail::fail(detail::at("jmax", j) + which + " = " + detail::fmt(jmax_[j]) + " must be > 0");
    if (!(jmin_[j] < 0.0)) detail::fail(detail::at("jmin", j) + which + " = " + detail::fmt(jmin_[j]) + " must be < 0");
  }
}

void JerkLimits::third_derivatives(const Path& path, const Eigen::VectorXd& s, Eigen::MatrixXd& left,
                                   Eigen::MatrixXd& right) {
  const PiecewisePolynomialPath* poly = path.polynomial();
  if (!poly)
    detail::fail("jerk limits need the path's third derivative p''', which only a path of polynomial pieces "
                 "(CubicSplinePath, PiecewisePolynomialPath, SampledPath, pathpace.as_path of a scipy spline) "
                 "gives; sample a callback path into a SampledPath");
  const Eigen::VectorXd& br = poly->breakpoints();
  const auto& co = poly->coefficients();
  const Eigen::Index n = poly->dof();
  left.setZero(s.size(), n);
  right.setZero(s.size(), n);
  auto third = [&](Eigen::Index i, double x) {
    const Eigen::MatrixXd& c = co[static_cast<size_t>(i)];
    const double h = x - br[i];
    Eigen::RowVectorXd out = Eigen::RowVectorXd::Zero(n);
    for (Eigen::Index d = c.rows() - 1; d >= 3; --d)  // Horner on Σ d(d-1)(d-2) c_d h^(d-3)
      out = out * h + static_cast<double>(d * (d - 1) * (d - 2)) * c.row(d);
    return out;
  };
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    const Eigen::Index i = poly->piece(s[k]);
    right.row(k) = third(i, s[k]);
    // At a breakpoint the piece to the left gives the left limit.
    const Eigen::Index il = (i > 0 && s[k] <= br[i]) ? i - 1 : i;
    if (il == i) left.row(k) = right.row(k);
    else left.row(k) = third(il, s[k]);
  }
}

}  // namespace pathpace
