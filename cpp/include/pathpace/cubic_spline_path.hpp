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

// docstrings.txt @@ CubicSplinePath
/// @brief A C² cubic spline through waypoints, as scipy.interpolate.CubicSpline.
///
/// A piecewise polynomial path whose pieces are computed from the waypoints.
class CubicSplinePath : public PiecewisePolynomialPath {
 public:
  // docstrings.txt @@ CubicSplinePath.__init__
  /// @param waypoints (K, n): K >= 2 waypoints in rad (or m), one per row.
  /// @param spacing How the knots are placed on [s_begin, s_end] (KnotSpacing).
  /// @param boundary scipy's bc_type: p''' continuous at the second and second-last knots; p'' = 0 at the ends; or
  ///   given end slopes p' (zero when no derivative is given, scipy's "clamped").
  /// @param s_begin,s_end Domain for 'uniform' and 'chord' knots.
  /// @param start_derivative,end_derivative (n,): p'(s_begin), p'(s_end) for `boundary='clamped'`.
  CubicSplinePath(const Eigen::MatrixXd& waypoints, KnotSpacing spacing = KnotSpacing::Uniform,
                  SplineBoundary boundary = SplineBoundary::NotAKnot, double s_begin = 0.0, double s_end = 1.0,
                  const Eigen::VectorXd& start_derivative = Eigen::VectorXd(),
                  const Eigen::VectorXd& end_derivative = Eigen::VectorXd());
  // docstrings.txt @@ CubicSplinePath.__init__
  /// @param waypoints (K, n): K >= 2 waypoints in rad (or m), one per row.
  /// @param knots K strictly increasing knots; the domain is [knots[0], knots[K-1]].
  /// @param boundary scipy's bc_type: p''' continuous at the second and second-last knots; p'' = 0 at the ends; or
  ///   given end slopes p' (zero when no derivative is given, scipy's "clamped").
  /// @param start_derivative,end_derivative (n,): p'(s_begin), p'(s_end) for `boundary='clamped'`.
  CubicSplinePath(const Eigen::MatrixXd& waypoints, const Eigen::VectorXd& knots,
                  SplineBoundary boundary = SplineBoundary::NotAKnot,
                  const Eigen::VectorXd& start_derivative = Eigen::VectorXd(),
                  const Eigen::VectorXd& end_derivative = Eigen::VectorXd());

  const Eigen::VectorXd& knots() const { return breakpoints(); }
  const Eigen::MatrixXd& waypoints() const { return waypoints_; }
  // docstrings.txt @@ CubicSplinePath.boundary
  /// The end conditions, scipy's bc_type: 'not-a-knot', 'natural' or 'clamped'.
  SplineBoundary boundary() const { return boundary_; }
  // docstrings.txt @@ CubicSplinePath.start_derivative
  /// (n,): p'(s_begin) of a clamped spline; None (in C++ empty) for the other boundaries.
  const Eigen::VectorXd& start_derivative() const { return start_derivative_; }
  // docstrings.txt @@ CubicSplinePath.end_derivative
  /// (n,): p'(s_end) of a clamped spline; None (in C++ empty) for the other boundaries.
  const Eigen::VectorXd& end_derivative() const { return end_derivative_; }

 private:
  static PiecewisePolynomialPath build(const Eigen::MatrixXd& waypoints, const Eigen::VectorXd& knots,
                                       SplineBoundary boundary, const Eigen::VectorXd& d0, const Eigen::VectorXd& d1);
  Eigen::MatrixXd waypoints_;
  SplineBoundary boundary_ = SplineBoundary::NotAKnot;
  Eigen::VectorXd start_derivative_, end_derivative_;
};

}  // namespace pathpace
