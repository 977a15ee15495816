#include "paths/third_derivatives.hpp"

#include "base/validate.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace::detail {

void third_derivatives(const Path& path, const Eigen::VectorXd& s, Eigen::MatrixXd& left, Eigen::MatrixXd& right) {
  const PiecewisePolynomialPath* poly = path.polynomial();
  if (!poly)
    fail("jerk limits need the path's third derivative p''', which only a path of polynomial pieces "
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

}  // namespace pathpace::detail
