#pragma once
/// @file auto_grid.hpp
/// A grid on s chosen from the path's shape (grid="auto"): fine where the path bends, coarse where it
/// does not, with every breakpoint of a piecewise-polynomial path on it.

#include <Eigen/Core>

#include "pathpace/path.hpp"

namespace pathpace {

/// The constraints of eq. (26) hold at the grid points; between them q̇ = p'(s)ṡ and
/// q̈ = p''(s)ṡ² + p'(s)s̈ follow p, p', p'' (eq. 10-11). The grid is refined until, on every interval,
/// p, p' and p'' deviate from their chords (the linear interpolation between the interval's ends) at
/// the interval's midpoint by at most `tolerance` times their scale over the whole path (per order: the
/// largest range of a coordinate of p, the largest |p'_j|, the largest |p''_j|). Deviation from the chord
/// is what the grid cannot see, so the limits' excursions between grid points and the discretisation
/// error of T shrink with it (both O(Δs²) for smooth pieces). The excursions also depend on the speed
/// profile, so the tolerance bounds the geometry, not the limits' excursions (bench/README.md has them
/// measured). For limits that hold between grid points by construction, see solve's guarantee option.
///
/// Starts from `min_intervals` uniform intervals plus the breakpoints of a PiecewisePolynomialPath (so
/// no interval straddles a kink of p''), and halves every interval that fails, until none fails.
/// Throws InvalidInput if more than `max_intervals` would be needed, or for a bad argument.
Eigen::VectorXd auto_grid(const Path& path, double tolerance = 1e-3, int min_intervals = 16,
                          int max_intervals = 1000000);

}  // namespace pathpace
