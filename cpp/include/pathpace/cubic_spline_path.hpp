#pragma once
/// @file cubic_spline_path.hpp
/// A C2 cubic spline through waypoints.

#include <Eigen/Core>

#include "pathpace/path.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace {

/// How the knots s_i of the waypoints are placed on [s_begin, s_end].
enum class KnotSpacing {
  Uniform,      ///< equally spaced
  ChordLength,  ///< proportional to the cumulative Euclidean distance between waypoints
};

/// End conditions; they match scipy.interpolate.CubicSpline's bc_type of the same names.
enum class SplineBoundary {
  NotAKnot,  ///< p''' continuous at the second and second-last knots (2 waypoints: a line; 3: a parabola)
  Natural,   ///< p'' = 0 at both ends
  Clamped,   ///< p' given at both ends; zero slopes when no derivative is given (scipy's "clamped")
};

/// A cubic spline is a piecewise polynomial path whose pieces are computed from the waypoints.
class CubicSplinePath : public PiecewisePolynomialPath {
 public:
  /// waypoints (K, n), K >= 2, knots placed by `spacing` on [s_begin, s_end].
  CubicSplinePath(const Eigen::MatrixXd& waypoints, KnotSpacing spacing = KnotSpacing::Uniform,
                  SplineBoundary boundary = SplineBoundary::NotAKnot, double s_begin = 0.0, double s_end = 1.0,
                  const Eigen::VectorXd& start_derivative = Eigen::VectorXd(),
                  const Eigen::VectorXd& end_derivative = Eigen::VectorXd());
  /// Explicit knots (K, strictly increasing); the domain is [knots[0], knots[K-1]].
  CubicSplinePath(const Eigen::MatrixXd& waypoints, const Eigen::VectorXd& knots,
                  SplineBoundary boundary = SplineBoundary::NotAKnot,
                  const Eigen::VectorXd& start_derivative = Eigen::VectorXd(),
                  const Eigen::VectorXd& end_derivative = Eigen::VectorXd());

  const Eigen::VectorXd& knots() const { return breakpoints(); }
  const Eigen::MatrixXd& waypoints() const { return waypoints_; }
  SplineBoundary boundary() const { return boundary_; }
  /// p'(s_begin) and p'(s_end) of a clamped spline (empty for the other boundaries).
  const Eigen::VectorXd& start_derivative() const { return start_derivative_; }
  const Eigen::VectorXd& end_derivative() const { return end_derivative_; }

 private:
  static PiecewisePolynomialPath build(const Eigen::MatrixXd& waypoints, const Eigen::VectorXd& knots,
                                       SplineBoundary boundary, const Eigen::VectorXd& d0, const Eigen::VectorXd& d1);
  Eigen::MatrixXd waypoints_;
  SplineBoundary boundary_ = SplineBoundary::NotAKnot;
  Eigen::VectorXd start_derivative_, end_derivative_;
};

}  // namespace pathpace
