#pragma once
// Per-grid-point feasible polygons (sec. IV.A): all constraint rows at s_k, bounds on x alone folded
// into [x_lo, x_hi], the rest pruned to the supporting half-planes.

#include <memory>
#include <string>
#include <vector>

#include "geometry/polygon2d.hpp"
#include "pathpace/constraints/constraint.hpp"
#include "pathpace/path_samples.hpp"

namespace pathpace::detail {

/// Stand-ins for "no limit": box sides far outside any physical ṡ² or s̈. Vertices on them are exact
/// (Polygon2d intersects original lines), so their size costs no precision.
inline constexpr double kInfinityCap = 1e15;
/// The same inside a solve, where ṡ² and s̈ are in units of their typical size (Scale): far beyond any
/// speed a bounded problem has, even with limits over twenty decades (the backward-controllable speeds
/// then reach 1e18 of the typical ones, and a cap at 1e15 read them as "nothing bounds the speed").
inline constexpr double kSolveCap = 1e100;

/// Units of the solve: x = ṡ² = x_unit · x̃ and u = s̈ = u_unit · ũ, both powers of two, so a row
/// a x + b u <= c is read, exactly, as (a x_unit) x̃ + (b u_unit) ũ <= c. The discretised problem (eq. 25-27)
/// is homogeneous: scaling a path's length or its limits only moves the speeds by orders of magnitude,
/// and in these units they are ~1 whatever the problem, so that kInfinityCap and the few absolute
/// floors of the reachability and SLP code mean the same thing for every problem (a cap on ṡ² itself
/// made a velocity-limited path of length 1e-9 UNBOUNDED). u_unit = x_unit / s_unit, s = s_unit · s̃.
struct Scale {
  double x_unit = 1.0, u_unit = 1.0, s_unit = 1.0;
  double cap = kInfinityCap;  // box sides standing in for "no limit" on x̃ and ũ
};

/// Units for a problem: s_unit ~ the path's parameter length, x_unit ~ the median over (at most 33) grid
/// points of the smallest ṡ² the rows there allow with s̈ = 0 (c/a) or reach by accelerating along the path
/// at the s̈ they allow at ṡ² = 0 (2 L c / b). O(rows) on those points, homogeneous in the problem.
Scale problem_scale(const Eigen::VectorXd& s, const std::vector<ConstraintRows>& constraints);

struct PointSet {
  double x_lo = 0.0, x_hi = kInfinityCap;  // x_hi = Scale::cap when nothing bounds x alone
  int x_lo_id = -1, x_hi_id = -1;          // row ids giving the bounds (-1: ṡ² >= 0 / none)
  std::vector<Line> rows;                  // supporting half-planes with b != 0, (a, b) of unit norm
  bool empty = false;
  std::vector<int> certificate;            // when empty: row ids that together are infeasible
};

struct GridSets {
  std::vector<PointSet> points;  // x bounds, emptiness; their `rows` stay empty: see rows(k)
  std::vector<Line> row_data;    // supporting rows of all points, point k at [row_offset[k], row_offset[k+1])
  std::vector<size_t> row_offset;
  View<Line> rows(Eigen::Index k) const {
    const size_t o = row_offset[static_cast<size_t>(k)];
    return {row_data.data() + o, row_offset[static_cast<size_t>(k) + 1] - o};
  }
  // row id -> label ("velocity joint 3", ...); shared (never copied) with the Result's binding labels
  std::shared_ptr<const std::vector<std::string>> labels;
  double average_rows = 0.0;
  /// Label for an id, including the implicit ones (negative ids).
  std::string label(int id) const;
};

/// Builds every grid point's set. Row ids number the rows of all constraints consecutively.
/// The supporting rows go to the flat storage (GridSets::rows), not to PointSet::rows.
GridSets build_grid_sets(const PathSamples& samples, const std::vector<ConstraintRows>& constraints,
                         const Scale& scale = {});

/// One grid point's set; `polygon` is left holding its polygon (cut at kInfinityCap, unscaled).
PointSet build_point_set(const std::vector<ConstraintRows>& constraints, Eigen::Index k, Polygon2d& polygon);
/// Same, with a caller-owned scratch vector (no allocation per grid point in a loop) and optionally the
/// neighbouring point's supporting rows, which are clipped first (same result, less work). With
/// out_rows the supporting rows are appended there instead of to the returned PointSet::rows, and
/// `polygon` keeps only its edges (Polygon2d::build's edges_only).
/// Rows and bounds are in the units of `scale`.
PointSet build_point_set(const std::vector<ConstraintRows>& constraints, Eigen::Index k, Polygon2d& polygon,
                         std::vector<Line>& scratch, View<Line> hint = {}, std::vector<Line>* out_rows = nullptr,
                         const Scale& scale = {});

}  // namespace pathpace::detail
