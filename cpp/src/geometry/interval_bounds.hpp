#pragma once
// Bounds of the joint velocities and accelerations over a whole grid interval (sec. V.D's "interval
// analysis", done exactly for polynomial paths with Bernstein coefficients), for guarantee="continuous".
//
// On interval k, s̈ = u is constant and θ(s) = ṡ² is linear: θ(s) = θ_k + 2u(s - s_k), with
// u = (θ_{k+1} - θ_k) / (2Δs_k). With σ = s - s_k, eq. (11) gives
//   q̈_j(σ) = A_j(σ) θ_k + B_j(σ) θ_{k+1},
//   A_j = p''_j - (2σ p''_j + p'_j) / (2Δs_k),   B_j = (2σ p''_j + p'_j) / (2Δs_k),
// polynomials in σ on each piece of the path inside the interval. Written in the Bernstein basis of a
// piece (non-negative functions summing to one), q̈_j is a convex combination of the linear forms
// A_ji θ_k + B_ji θ_{k+1}, so "every such form <= a_U" implies q̈_j(σ) <= a_U at every σ. The first and last
// forms of the interval are q̈_j at s_k and s_{k+1}: the forward and backward rows of eq. (26).
// Likewise max |p'_j| over the interval is bounded by the largest Bernstein coefficient of p'_j, and
// ṡ(σ)² = θ(σ) <= max(θ_k, θ_{k+1}), which bounds |q̇_j| everywhere from bounds on θ_k and θ_{k+1}.

#include <vector>

#include <Eigen/Core>

#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace::detail {

/// Bernstein coefficients b_0..b_d on [0, h] of the polynomial Σ_j c[j] τ^j (degree d).
void bernstein(const double* c, int d, double h, double* b);

struct IntervalRows {
  /// Interval k's acceleration forms (A, B) for joint `joint`, at [offset[k], offset[k+1]); the forms at
  /// s_k and s_{k+1} themselves (the eq. 26 rows) are left out.
  std::vector<std::size_t> offset;
  std::vector<int> joint;
  std::vector<double> A, B;
  /// Bounds of p'_j over interval k: dq_min(k, j) <= p'_j(s) <= dq_max(k, j) on [s_k, s_{k+1}].
  Eigen::MatrixXd dq_min, dq_max;
};

/// The forms and bounds on every interval of `grid` (strictly increasing, inside the path's domain).
IntervalRows interval_rows(const PiecewisePolynomialPath& path, const Eigen::VectorXd& grid);

/// Speed bounds at the grid points that keep v_L <= q̇_j <= v_U on the whole of every interval:
/// out[k] <= ... such that θ_k <= out[k] for all k implies, on interval k,
/// p'_j(σ)² ((1 - λ)θ_k + λθ_{k+1}) <= v² (v the limit on the side of p'_j's sign; the smaller one where
/// p'_j changes sign), checked by the Bernstein coefficients of that polynomial. Each interval starts from
/// the exact end values v²/p'_j(s)² (the line through them is below v²/p'_j² where that is concave) and
/// scales them down until the Bernstein check holds, so the loss is O(Δs²), not O(Δs) as with
/// max |p'_j| over the interval. Entries without a limit are +inf. `rows` = interval_rows(path, grid) and
/// `dq` = p' at the grid points (N+1, n), which the caller has already.
Eigen::VectorXd continuous_speed_bounds(const PiecewisePolynomialPath& path, const Eigen::VectorXd& grid,
                                        const IntervalRows& rows, const Eigen::MatrixXd& dq, const Eigen::VectorXd& vmin,
                                        const Eigen::VectorXd& vmax);

/// Speed bounds at the grid points for a row ‖e(s)‖² ṡ² <= v² whose e (m <= 3 components: a frame's velocity
/// per unit ṡ) is known only at the grid points, with its s-derivative: `e`, `de` (N+1, m). Between grid points
/// e is modelled by its cubic Hermite interpolant (error O(Δs⁴) times e's fourth derivative), so the bounds
/// are exact for the model, not rigorous for e itself: the caller's rows stay audited. On each interval the
/// line θ = (1 - λ) m0 + λ m1 starts from v²/‖e‖² at the ends (no more than `start`, the grid point's own
/// bound over the constraint's rows) and is scaled down until the model's ‖e‖² θ <= v² holds by its Bernstein
/// coefficients (four pieces per interval, as in continuous_speed_bounds); the flat bound v²/max ‖e‖² is kept
/// where it allows more at both ends. v is `hi` for m > 1; for m = 1 it is hi where e > 0 and -lo where
/// e < 0, the smaller where the model may change sign on the interval (lo <= 0 <= hi, ±inf: none). Entries
/// without a bound are +inf.
Eigen::VectorXd hermite_speed_bounds(const Eigen::VectorXd& grid, const Eigen::MatrixXd& e, const Eigen::MatrixXd& de,
                                     double lo, double hi, const Eigen::VectorXd& start);

}  // namespace pathpace::detail
