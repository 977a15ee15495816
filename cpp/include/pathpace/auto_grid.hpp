#pragma once
/// @file auto_grid.hpp
/// A grid on s chosen from the path's shape (grid="auto"): fine where the path bends, coarse where it
/// does not, with every breakpoint of a piecewise-polynomial path on it.

#include <Eigen/Core>

#include "pathpace/path.hpp"

namespace pathpace {

// docstrings.txt @@ auto_grid
/// @brief A grid of s fitted to the path's shape (what grid='auto' uses).
///
/// Every interval is halved until p, p' and p'' deviate from their chords at its midpoint by at most
/// `tolerance` times their scale over the path (largest coordinate range, largest |p'_j|, largest |p''_j|);
/// starts from `min_intervals` uniform intervals plus the breakpoints of a piecewise-polynomial path (so
/// no interval straddles a kink of p''). Returns the grid points s_0..s_N (the N used is len - 1).
/// InvalidInput past `max_intervals`, or for a bad argument.
///
/// The constraints of eq. (26) hold at the grid points; between them q̇ = p'(s)ṡ and q̈ = p''(s)ṡ² + p'(s)s̈
/// follow p, p', p'' (eq. 10-11). Deviation from the chord (the linear interpolation between an interval's
/// ends) is what the grid cannot see, so the limits' excursions between grid points and the discretisation
/// error of T shrink with it (both O(Δs²) for smooth pieces). The excursions also depend on the speed
/// profile, so the tolerance bounds the geometry, not the limits' excursions (bench/README.md has them
/// measured). For limits that hold between grid points by construction, see solve's guarantee option.
Eigen::VectorXd auto_grid(const Path& path, double tolerance = 1e-3, int min_intervals = 16,
                          int max_intervals = 1000000);

}  // namespace pathpace
