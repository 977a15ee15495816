#pragma once
/// @file feasible_set.hpp
/// The feasible set of (x, u) = (ṡ², s̈) at one grid point: a convex polygon (sec. IV).

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace pathpace {

/// The set {(x, u) : a_i x + b_i u <= c_i, x_min <= x <= x_max} at grid point `index`, reduced to its
/// supporting half-planes (the redundant ones pruned, sec. IV.A).
struct FeasibleSet {
  Eigen::Index index = 0;  ///< grid index k
  double s = 0.0;          ///< s_k
  /// Supporting half-planes, one row [a, b, c] each. Bounds on x alone (b = 0) are folded into
  /// x_min / x_max and not repeated here.
  Eigen::Matrix<double, Eigen::Dynamic, 3> halfplanes;
  std::vector<std::string> labels;  ///< which constraint row each half-plane comes from
  double x_min = 0.0;               ///< lower bound on ṡ² (0 unless a constraint raises it)
  double x_max = std::numeric_limits<double>::infinity();  ///< eq. (16) and any other bound on x alone
  std::string x_max_label;          ///< the constraint row giving x_max ("" if none)
  /// Polygon vertices, counter-clockwise, columns (x, u). An unbounded set (e.g. velocity limits only:
  /// u is free) is shown cut at 1e15 times the problem's typical ṡ² and s̈ (those the solve is scaled by),
  /// with bounded = false.
  Eigen::Matrix<double, Eigen::Dynamic, 2> vertices;
  bool empty = false;
  bool bounded = true;
  /// False where a projected constraint (contacts) is only an inner approximation at this grid point:
  /// its LP solver failed or its LP budget ran out, and the polygon is the hull found so far.
  bool exact = true;

  /// True if (x, u) satisfies every half-plane to the relative tolerance tol.
  bool contains(double x, double u, double tol = 1e-9) const;
};

}  // namespace pathpace
