#pragma once
// guarantee = continuous: limits that hold at every instant, not only at the grid points.
//
// Velocity and acceleration limits get rows that are sufficient by construction (Bernstein bounds of
// the path's polynomial pieces, geometry/interval_bounds.hpp): per grid point, a speed bound from the
// largest |p'_j| on the two adjacent intervals (ṡ² is linear on an interval, so it never exceeds its
// larger end value); per interval, the Bernstein forms of q̈_j. Every other constraint (torque,
// contact, linear) is audited at interior points of every interval, and where the timing breaks a
// row there, that row is added to its interval: at s = s_k + λΔs_k a row a x + b u <= c reads
//   (a (1 - λ) - b / (2Δs_k)) θ_k + (a λ + b / (2Δs_k)) θ_{k+1} <= c
// (θ(s) = (1 - λ)θ_k + λθ_{k+1}, u = (θ_{k+1} - θ_k)/(2Δs_k)): an exact constraint of the timing, not a
// margin, so the cuts cost T only what the limits between grid points really demand.

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "solve/reachability.hpp"
#include "pathpace/constraints/constraint.hpp"
#include "pathpace/path.hpp"

namespace pathpace::detail {

/// Appends to `rows` the grid-point speed bounds, and to `extra` the interval forms, of every
/// VelocityLimits and AccelerationLimits in `constraints` (whose own rows are rows[0..constraints.size())).
/// Throws InvalidInput if the path is not piecewise polynomial.
void add_kinematic_continuous_rows(const Path& path, const PathSamples& samples,
                                   const std::vector<std::shared_ptr<const Constraint>>& constraints,
                                   std::vector<ConstraintRows>& rows, IntervalExtra& extra);

/// What earlier audits of one solve found per constraint and interval: an interval whose θ_k, θ_{k+1} are
/// (bitwise) those it was audited at has the same rows and the same violation, so it is not audited again
/// (after a cut, the re-solve changes θ near it and leaves most of the path as it was).
struct AuditMemory {
  std::vector<std::vector<double>> theta0, theta1, worst;  // [constraint][interval]
  /// [constraint]: its rows at the audit's Chebyshev points of every interval (row k·points + m), which do
  /// not depend on the timing: evaluated in the first round only.
  std::vector<ConstraintRows> coarse;
  /// [constraint][k·points + m]: a contact polygon's slice at its Chebyshev point m of interval k, as the
  /// edges through its ends (SliceEdges: each end is linear in u, exactly, over its range), from the last
  /// round that solved its LPs: a later round whose u lies in the ranges has the slice without an LP.
  struct Slices {
    double u = 0.0;                                    // the u it was solved at
    double hi = 0.0, hi_slope = 0.0, hi_from = 1.0, hi_to = 0.0;  // hi_from > hi_to: the top unknown
    double lo = 0.0, lo_slope = 0.0, lo_from = 1.0, lo_to = 0.0;  // the bottom (its LP is skipped above the top)
    bool hi_capped = false;                            // the top is the stand-in cap (no limit)
    bool lo_skipped = false;  // the bottom not solved, its interval's far from the timing (Auditor::bottoms)
  };
  std::vector<std::vector<Slices>> slices;
  /// [constraint][2k + end]: a contact constraint's slices at both grid points of interval k (end 0: s_k, 1:
  /// s_{k+1}) where its rows there bound it from outside only (Constraint::refines): solved like the
  /// Chebyshev points' (an outer polygon's slice would overstate the room at the grid points).
  std::vector<std::vector<Slices>> grid_slices;
  /// [constraint][interval]: the rows at each point where the interval was cut.
  struct Point {
    double lam;
    Eigen::VectorXd a, b, c;
    Slices slice;  // a contact constraint's slice there (as at a Chebyshev point)
  };
  std::vector<std::vector<std::vector<Point>>> cut_points;
  /// [constraint][interval]: the λ of every row cut into the interval (a contact constraint's peaks and
  /// spread points): the cuts that flank a new peak bound where its spread rows go (contact_cuts).
  std::vector<std::vector<std::vector<double>>> cut_at;
  /// [constraint][interval]: a contact constraint's points of the peak search (a, b, c empty), with their
  /// slices: later rounds sample them again where the slices' edges cover the new u (no LP), so that the
  /// brackets start between them and most close by the bump bound, not by new LPs. At most kProbes each.
  std::vector<std::vector<std::vector<Point>>> probes;
  static constexpr size_t kProbes = 16;
  /// [constraint][interval]: the largest concavity of v in s that the interval's samples showed in any
  /// round (part of the screen's bound, kept from round to round).
  std::vector<std::vector<double>> curvature;
  /// [constraint][interval]: 1 where the guess that the slices' bottoms are far (Auditor::contact_batch)
  /// failed once: its samples solve their bottoms in every later round.
  std::vector<std::vector<char>> bottoms_near;
  /// [constraint][interval]: the last optimal bases of a contact constraint's slice LPs in the interval
  /// (top, bottom), the warm starts of its next samples there (SliceStarts).
  std::vector<std::vector<std::array<std::vector<signed char>, 2>>> bases;
};

struct Audit {
  double worst = 0.0;  ///< largest violation found, relative to max(|c|, |a θ(s)| + |b u|) (<= 0: none)
  int cuts = 0;        ///< rows added to `extra`
  int lps = 0;         ///< contact slice LPs (ContactConstraint::slice) spent
  int glpk_lps = 0;    ///< of which GLPK answered (the rest: the warm-started dense simplex)
  int projections = 0; ///< polygons projected (at cut points whose slice is empty)
  int reused = 0;      ///< contact samples settled by the slices' edges kept from an earlier round (no LP)
};

/// Checks every constraint other than velocity and acceleration limits between the grid points of `s` under
/// the timing θ: at `points` Chebyshev points of each interval (their rows kept in `memory` for later
/// rounds), both grid points and the interval's earlier cut points, then, where a concavity bound from
/// those samples reaches `tolerance`, at the peak found by parabolic/golden search. Adds to `extra` each
/// row violated by more than `tolerance` (relative) at the interval's worst point, one point per interval
/// and round. Rows are followed by their label (a contact polygon's columns differ from one evaluation to
/// the next); `grid_rows[i]` are constraint i's rows on the grid and `row_offset[i]` the label id of its
/// first row, which name the cuts.
Audit audit_and_cut(const Path& path, const Eigen::VectorXd& s, const Eigen::VectorXd& theta,
                    const std::vector<std::shared_ptr<const Constraint>>& constraints,
                    const std::vector<ConstraintRows>& grid_rows, const std::vector<int>& row_offset, int points,
                    double tolerance, IntervalExtra& extra, AuditMemory& memory);

}  // namespace pathpace::detail
