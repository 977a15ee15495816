#pragma once
// The reachability analyses (sec. V, eq. 26) and the SLP's repair pass without polygons, for the common case.
//
// On interval k (x = θ_k, y = θ_{k+1}) a chain row α x + β y <= c with β > 0 bounds y from above by the
// line (c - α x) / β, one with β < 0 from below, one with β = 0 bounds x alone. With y also in K_{k+1},
// the interval's set is {Lo(x) <= y <= Hi(x)}: Hi a minimum of lines (concave), Lo a maximum (convex). So
// g = Hi - Lo is concave and K_k = {x : g(x) >= 0} an interval, whose top is g's largest root (Newton's
// method from the top of the box with g's left derivative: from the right of the root each step lands in
// [root, x), and on it once the two active lines are the root's), and the greedy pass takes y = Hi(θ_k).
// detail::reachability's polygons (Polygon2d per interval, with vertices) give the same analyses to rounding;
// the reports (which rows empty a set) and avoid_stopped_profile still need them.
//
// The common case: every K_k's bottom is the box's (x_lo[k], as from rest on velocity and acceleration
// limits), no row is steep (kSteep in the .cpp: the polygons read a near-vertical edge as vertical, lines
// cannot), Newton ends on every interval and no number overflows. Anywhere else this says so and the
// polygons decide. What the lines return is made exact in the grid points' own terms (eq. 26) before it is
// used (line_stage and by_slp in solve/pipeline.cpp).

#include <Eigen/Core>

#include "solve/reachability.hpp"

namespace pathpace::detail {

/// One analysis by lines: K_k = [x_lo[k], k_hi[k]] (K_N = {theta_end}) and the greedy profile.
struct LineAnalysis {
  bool relaxed = false;  ///< on Chain::relaxed_rows (θ', the relaxed feasible set's greatest element)
  double theta_end = 0.0;
  Eigen::VectorXd k_hi, theta;
};

/// The relaxed (`relaxed` = true) or the full analysis from θ_0 = theta_begin to θ_N = theta_end. False when
/// the case is not the common one above (nothing reliable in `out` then). `base`: the relaxed analysis of the
/// same chain and ends, whose K_k and steps the full one takes over, to the bit, on the intervals without
/// coupling rows that meet the same K_{k+1} (most of them).
bool line_analysis(const Chain& chain, bool relaxed, double theta_begin, double theta_end, LineAnalysis& out,
                   const LineAnalysis* base = nullptr);

/// detail::forward_pass's capped greedy pass by lines: θ_{k+1} = caps_{k+1} clamped into interval k's slice at
/// θ_k (θ_k clamped into K_k for the slice), along a's own greedy profile wherever the pass meets it (the same
/// x gives the same slice, to the bit) with a cap at or above it.
Eigen::VectorXd line_forward_pass(const Chain& chain, const LineAnalysis& a, double theta_begin,
                                  const Eigen::VectorXd& caps);

}  // namespace pathpace::detail
