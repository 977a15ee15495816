#include "pathpace/cubic_spline_path.hpp"

#include <cmath>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include "base/validate.hpp"

namespace pathpace {

namespace {

void check_waypoints(const Eigen::MatrixXd& w) {
  if (w.rows() < 2) detail::fail("waypoints has " + std::to_string(w.rows()) + " rows, expected at least 2");
  if (w.cols() < 1) detail::fail("waypoints has 0 columns, expected at least 1 coordinate");
  detail::require_finite("waypoints", w);
}

// scipy's "clamped" without slopes means p' = 0 at both ends; explicit slopes pass through.
Eigen::VectorXd end_slope(SplineBoundary boundary, const Eigen::VectorXd& d, const Eigen::MatrixXd& w) {
  if (boundary == SplineBoundary::Clamped && d.size() == 0) return Eigen::VectorXd::Zero(w.cols());
  return d;
}

Eigen::VectorXd place_knots(const Eigen::MatrixXd& w, KnotSpacing spacing, double a, double b) {
  if (!std::isfinite(a)) detail::fail("s_begin = " + detail::fmt(a) + " must be finite");
  if (!std::isfinite(b)) detail::fail("s_end = " + detail::fmt(b) + " must be finite");
  if (!(a < b)) detail::fail("s_begin = " + detail::fmt(a) + " must be < s_end = " + detail::fmt(b));
  const Eigen::Index K = w.rows();
  if (spacing == KnotSpacing::Uniform) return Eigen::VectorXd::LinSpaced(K, a, b);
  Eigen::VectorXd cum(K);
  cum[0] = 0.0;
  for (Eigen::Index i = 1; i < K; ++i) {
    const double d = (w.row(i) - w.row(i - 1)).norm();
    if (!(d > 0.0))
      detail::fail("waypoints[" + std::to_string(i) + "] equals waypoints[" + std::to_string(i - 1) +
                   "]: chord-length knots need distinct consecutive waypoints");
    cum[i] = cum[i - 1] + d;
  }
  Eigen::VectorXd knots = (a + (b - a) * cum.array() / cum[K - 1]).matrix();
  knots[K - 1] = b;
  return knots;
}

}  // namespace

CubicSplinePath::CubicSplinePath(const Eigen::MatrixXd& waypoints, KnotSpacing spacing, SplineBoundary boundary,
                                 double s_begin, double s_end, const Eigen::VectorXd& d0, const Eigen::VectorXd& d1)
    : PiecewisePolynomialPath((check_waypoints(waypoints),
                               build(waypoints, place_knots(waypoints, spacing, s_begin, s_end), boundary,
                                     end_slope(boundary, d0, waypoints), end_slope(boundary, d1, waypoints)))),
      waypoints_(waypoints),
      boundary_(boundary),
      start_derivative_(end_slope(boundary, d0, waypoints)),
      end_derivative_(end_slope(boundary, d1, waypoints)) {}

CubicSplinePath::CubicSplinePath(const Eigen::MatrixXd& waypoints, const Eigen::VectorXd& knots,
                                 SplineBoundary boundary, const Eigen::VectorXd& d0, const Eigen::VectorXd& d1)
    : PiecewisePolynomialPath((check_waypoints(waypoints), build(waypoints, knots, boundary, end_slope(boundary, d0, waypoints),
                                                         end_slope(boundary, d1, waypoints)))),
      waypoints_(waypoints),
      boundary_(boundary),
      start_derivative_(end_slope(boundary, d0, waypoints)),
      end_derivative_(end_slope(boundary, d1, waypoints)) {}

PiecewisePolynomialPath CubicSplinePath::build(const Eigen::MatrixXd& y, const Eigen::VectorXd& t,
                                               SplineBoundary boundary, const Eigen::VectorXd& d0,
                                               const Eigen::VectorXd& d1) {
  const Eigen::Index K = y.rows(), n = y.cols();
  detail::require_size("knots", t.size(), K, "one per waypoint");
  detail::require_finite("knots", t);
  detail::require_increasing("knots", t);
  if (boundary == SplineBoundary::Clamped) {
    detail::require_size("start_derivative", d0.size(), n, "one per coordinate");
    detail::require_size("end_derivative", d1.size(), n, "one per coordinate");
    detail::require_finite("start_derivative", d0);
    detail::require_finite("end_derivative", d1);
  } else if (d0.size() != 0 || d1.size() != 0) {
    detail::fail("start_derivative and end_derivative are only used with the clamped boundary");
  }
  const Eigen::VectorXd h = t.tail(K - 1) - t.head(K - 1);
  // Unknowns: second derivatives M_i at the knots. Interior rows are the C2 conditions
  // h_{i-1} M_{i-1} + 2(h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (Δ_i - Δ_{i-1}), Δ_i = (y_{i+1} - y_i)/h_i.
  Eigen::MatrixXd delta(K - 1, n);
  for (Eigen::Index i = 0; i + 1 < K; ++i) delta.row(i) = (y.row(i + 1) - y.row(i)) / h[i];
  std::vector<Eigen::Triplet<double>> tr;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(K, n);
  for (Eigen::Index i = 1; i + 1 < K; ++i) {
    tr.emplace_back(i, i - 1, h[i - 1]);
    tr.emplace_back(i, i, 2.0 * (h[i - 1] + h[i]));
    tr.emplace_back(i, i + 1, h[i]);
    rhs.row(i) = 6.0 * (delta.row(i) - delta.row(i - 1));
  }
  const Eigen::Index L = K - 1;
  switch (boundary) {
    case SplineBoundary::Natural:
      tr.emplace_back(0, 0, 1.0);
      tr.emplace_back(L, L, 1.0);
      break;
    case SplineBoundary::Clamped:
      tr.emplace_back(0, 0, 2.0 * h[0]);
      tr.emplace_back(0, 1, h[0]);
      rhs.row(0) = 6.0 * (delta.row(0) - d0.transpose());
      tr.emplace_back(L, L - 1, h[L - 1]);
      tr.emplace_back(L, L, 2.0 * h[L - 1]);
      rhs.row(L) = 6.0 * (d1.transpose() - delta.row(L - 1));
      break;
    case SplineBoundary::NotAKnot:
      if (K == 2) {  // a straight line, as scipy does
        tr.emplace_back(0, 0, 1.0);
        tr.emplace_back(L, L, 1.0);
      } else if (K == 3) {  // the single parabola through three points: M constant
        tr.emplace_back(0, 0, 1.0);
        tr.emplace_back(0, 1, -1.0);
        tr.emplace_back(L, L - 1, 1.0);
        tr.emplace_back(L, L, -1.0);
      } else {  // p''' continuous at knots 1 and K-2
        tr.emplace_back(0, 0, h[1]);
        tr.emplace_back(0, 1, -(h[0] + h[1]));
        tr.emplace_back(0, 2, h[0]);
        tr.emplace_back(L, L - 2, h[L - 1]);
        tr.emplace_back(L, L - 1, -(h[L - 2] + h[L - 1]));
        tr.emplace_back(L, L, h[L - 2]);
      }
      break;
  }
  Eigen::SparseMatrix<double> A(K, K);
  A.setFromTriplets(tr.begin(), tr.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) throw Error("cubic spline system is singular (knots too close together?)");
  const Eigen::MatrixXd M = lu.solve(rhs);

  std::vector<Eigen::MatrixXd> coefficients(static_cast<size_t>(K - 1), Eigen::MatrixXd(4, n));
  for (Eigen::Index i = 0; i + 1 < K; ++i) {
    Eigen::MatrixXd& c = coefficients[static_cast<size_t>(i)];
    c.row(0) = y.row(i);
    c.row(1) = delta.row(i) - h[i] * (2.0 * M.row(i) + M.row(i + 1)) / 6.0;
    c.row(2) = 0.5 * M.row(i);
    c.row(3) = (M.row(i + 1) - M.row(i)) / (6.0 * h[i]);
    // Knots so close (or waypoints so far apart) that a derivative overflows: name the cause, not the
    // coefficient it produced.
    if (!c.allFinite())
      detail::fail("knots[" + std::to_string(i + 1) + "] - knots[" + std::to_string(i) + "] = " + detail::fmt(h[i]) +
                   " is too small for these waypoints: the spline's derivatives overflow (widen [s_begin, s_end] "
                   "or the knots)");
  }
  return PiecewisePolynomialPath(t, std::move(coefficients));
}

}  // namespace pathpace
