#pragma once
// Per-grid-point feasible polygons (sec. IV.A): all constraint rows at s_k, bounds on x alone folded
// into [x_lo, x_hi], the rest pruned to the supporting half-planes.

#include <string>
#include <vector>

#include "detail/polygon2d.hpp"
#include "pathpace/constraints/constraint.hpp"
#include "pathpace/path_samples.hpp"

namespace pathpace::detail {

/// Stand-ins for "no limit": box sides far outside any physical ṡ² or s̈. Vertices on them are exact
/// (Polygon2d intersects original lines), so their size costs no precision.
inline constexpr double kInfinityCap = 1e15;

struct PointSet {
  double x_lo = 0.0, x_hi = kInfinityCap;  // x_hi = kInfinityCap when nothing bounds x alone
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
  std::vector<std::string> labels;  // row id -> label ("velocity joint 3", ...)
  double average_rows = 0.0;
  /// Label for an id, including the implicit ones (negative ids).
  std::string label(int id) const;
};

/// Builds every grid point's set. Row ids number the rows of all constraints consecutively.
/// The supporting rows go to the flat storage (GridSets::rows), not to PointSet::rows.
GridSets build_grid_sets(const PathSamples& samples, const std::vector<ConstraintRows>& constraints);

/// One grid point's set; `polygon` is left holding its polygon (cut at kInfinityCap).
PointSet build_point_set(const std::vector<ConstraintRows>& constraints, Eigen::Index k, Polygon2d& polygon);
/// Same, with a caller-owned scratch vector (no allocation per grid point in a loop) and optionally the
/// neighbouring point's supporting rows, which are clipped first (same result, less work). With
/// out_rows the supporting rows are appended there instead of to the returned PointSet::rows.
PointSet build_point_set(const std::vector<ConstraintRows>& constraints, Eigen::Index k, Polygon2d& polygon,
                         std::vector<Line>& scratch, View<Line> hint = {}, std::vector<Line>* out_rows = nullptr);

}  // namespace pathpace::detail
