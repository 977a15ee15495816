#pragma once
/// @file feasible_set.hpp
/// The feasible set of (x, u) = (ṡ², s̈) at one grid point: a convex polygon (sec. IV).

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace pathpace {

// docstrings.txt @@ FeasibleSet
/// @brief The pruned feasible polygon of (x, u) = (ṡ², s̈) at one grid point.
///
/// The set {(x, u) : a_i x + b_i u <= c_i, x_min <= x <= x_max} at grid point `index`, reduced to its
/// supporting half-planes (the redundant ones pruned, sec. IV.A).
struct FeasibleSet {
  Eigen::Index index = 0;  ///< grid index k
  double s = 0.0;          ///< s_k
  // docstrings.txt @@ FeasibleSet.halfplanes
  /// (r, 3): Supporting half-planes, rows [a, b, c] of a·x + b·u <= c. Bounds on x alone (b = 0) are folded into
  /// x_min / x_max and not repeated here.
  Eigen::Matrix<double, Eigen::Dynamic, 3> halfplanes;
  // docstrings.txt @@ FeasibleSet.labels
  /// The constraint row behind each half-plane.
  std::vector<std::string> labels;
  // docstrings.txt @@ FeasibleSet.x_min
  /// Lower bound on ṡ² (1/s²): 0 unless a constraint raises it.
  double x_min = 0.0;
  // docstrings.txt @@ FeasibleSet.x_max
  /// Upper bound on ṡ² (1/s²): eq. (16) and any other bound on x alone.
  double x_max = std::numeric_limits<double>::infinity();
  // docstrings.txt @@ FeasibleSet.x_max_label
  /// The constraint row giving x_max ('' if none).
  std::string x_max_label;
  // docstrings.txt @@ FeasibleSet.vertices
  /// (v, 2): Counter-clockwise vertices (x, u). An unbounded set (e.g. velocity limits only: u is free) is shown
  /// cut at 1e15 times the problem's typical ṡ² and s̈ (those the solve is scaled by), with bounded =
  /// False.
  Eigen::Matrix<double, Eigen::Dynamic, 2> vertices;
  bool empty = false;
  bool bounded = true;
  // docstrings.txt @@ FeasibleSet.exact
  /// False where a projected constraint (contacts) is only an inner approximation at this grid point:
  /// its LP solver failed or its LP budget ran out, and the polygon is the hull found so far.
  bool exact = true;

  // docstrings.txt @@ FeasibleSet.contains
  /// @brief Whether (x, u) = (ṡ², s̈) satisfies every half-plane to within tol, relative to the row's own terms
  /// (max(1, |a x|, |b u|, |c|); the bounds on x relative to max(1, |x|)). Non-finite points are outside.
  bool contains(double x, double u, double tol = 1e-9) const;
};

}  // namespace pathpace
