#include "solve/grid_sets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathpace::detail {

std::string GridSets::label(int id) const {
  if (id >= 0 && labels && static_cast<size_t>(id) < labels->size()) return (*labels)[static_cast<size_t>(id)];
  switch (id) {
    case kBoxXLow: return "sdot^2 >= 0";
    default: return "no limit on sdot";
  }
}

PointSet build_point_set(const std::vector<ConstraintRows>& constraints, Eigen::Index k, Polygon2d& polygon) {
  std::vector<Line> lines;
  return build_point_set(constraints, k, polygon, lines);
}

Scale problem_scale(const Eigen::VectorXd& s, const std::vector<ConstraintRows>& constraints) {
  Scale sc;
  sc.cap = kSolveCap;
  const Eigen::Index n_pts = s.size();
  const double length = s[n_pts - 1] - s[0];
  if (!(length > 0.0)) return sc;
  sc.s_unit = 1.0 / inverse_power_of_two(length);
  const Eigen::Index samples = std::min<Eigen::Index>(n_pts, 33);
  std::vector<double> est;
  est.reserve(static_cast<size_t>(samples));
  for (Eigen::Index i = 0; i < samples; ++i) {
    const Eigen::Index k = samples == 1 ? 0 : (i * (n_pts - 1)) / (samples - 1);
    double e = std::numeric_limits<double>::infinity();
    for (const ConstraintRows& cr : constraints)
      for (Eigen::Index j = 0; j < cr.rows(); ++j) {
        const double a = std::abs(cr.a(k, j)), b = std::abs(cr.b(k, j)), c = cr.c(k, j);
        if (!(c > 0.0) || c == std::numeric_limits<double>::infinity()) continue;  // no scale (or inactive)
        if (a * e > c) e = c / a;  // a division only when the estimate shrinks
        if (b * e > 2.0 * length * c) e = 2.0 * length * (c / b);
      }
    if (e > 0.0 && std::isfinite(e)) est.push_back(e);
  }
  if (est.empty()) return sc;
  auto mid = est.begin() + static_cast<long>(est.size() / 2);
  std::nth_element(est.begin(), mid, est.end());
  sc.x_unit = 1.0 / inverse_power_of_two(*mid);
  sc.u_unit = sc.x_unit / sc.s_unit;
  return sc;
}

PointSet build_point_set(const std::vector<ConstraintRows>& constraints, Eigen::Index k, Polygon2d& polygon,
                         std::vector<Line>& lines, View<Line> hint, std::vector<Line>* out_rows, const Scale& scale) {
  PointSet ps;
  ps.x_hi = scale.cap;
  int offset = 0;
  // The rows are written through a pointer into storage sized for all of them (the vector keeps that size
  // from point to point): appending row by row reloaded and stored the vector's end at every row (it may
  // alias the stores of the row), a chain of store-to-load forwards through the whole gather.
  Eigen::Index total = 0;
  for (const ConstraintRows& cr : constraints) total += cr.rows();
  if (lines.size() < static_cast<size_t>(total)) lines.resize(static_cast<size_t>(total));
  Line* out = lines.data();
  size_t count = 0;
  for (const ConstraintRows& cr : constraints) {
    const Eigen::Index r = cr.rows();
    // Row-major: the rows of grid point k are contiguous.
    const double* pa = cr.a.data() + k * r;
    const double* pb = cr.b.data() + k * r;
    const double* pc = cr.c.data() + k * r;
    for (Eigen::Index j = 0; j < r; ++j) {
      const int id = offset + static_cast<int>(j);
      const double c = pc[j];
      if (c == std::numeric_limits<double>::infinity()) continue;  // inactive here
      const double a = pa[j] * scale.x_unit, b = pb[j] * scale.u_unit;
      if (b == 0.0) {
        // A bound on x alone (eq. 16, or p'_j = 0 in eq. 14): fold it into the x range.
        if (a > 0.0) {
          if (c / a < ps.x_hi) { ps.x_hi = c / a; ps.x_hi_id = id; }
        } else if (a < 0.0) {
          if (c / a > ps.x_lo) { ps.x_lo = c / a; ps.x_lo_id = id; }
        } else if (c < -1e-12) {
          ps.empty = true;  // 0 <= c fails whatever the timing
          ps.certificate = {id};
          return ps;
        }
        continue;
      }
      // Normalised to unit norm below, only if it supports the polygon. Coefficients beyond 1e±100 (the
      // products of Cramer's rule overflow at 1e154) are first brought to ~1 by a power of two (exact).
      const double m = std::max(std::abs(a), std::abs(b));
      Line& l = out[count++];
      if (m > 1e-100 && m < 1e100) {
        assign_line(l, a, b, c, id);
      } else {
        l = power_of_two_normalised({a, b, c, id});  // rare: no store-forwarding concern
      }
    }
    offset += static_cast<int>(r);
  }
  // lines[0, count) are this point's rows; the vector keeps its size for the next point.
  Line* const lines_end = out + count;
  if (ps.x_lo > ps.x_hi * (1 + 1e-12) + 1e-300) {
    ps.empty = true;
    ps.certificate = {ps.x_lo_id, ps.x_hi_id};
    return ps;
  }
  if (ps.x_hi < ps.x_lo) ps.x_hi = ps.x_lo;  // within rounding: a single speed
  // One pass over the envelopes; clipping row by row only when that declines (empty or degenerate
  // sets: clipping also names the rows that empty it).
  // Into the grid's storage (out_rows) only the rows go: the polygon's vertices are not computed.
  if (!polygon.build(ps.x_lo, ps.x_hi, -scale.cap, scale.cap, out, count, out_rows != nullptr)) {
    if (!hint.empty()) {
      // The rows that supported the previous grid point's polygon most likely support this one too.
      // Cut with them first: the polygon is then nearly final early and the other rows are rejected by
      // the cheap inside test instead of rebuilding it.
      std::partition(out, lines_end, [hint](const Line& l) {
        for (const Line& h : hint)
          if (h.id == l.id) return true;
        return false;
      });
    }
    polygon.reset(ps.x_lo, ps.x_hi, -scale.cap, scale.cap);
    for (const Line* l = out; l != lines_end; ++l) {
      polygon.clip(*l);
      if (polygon.empty()) {
        ps.empty = true;
        ps.certificate = {polygon.emptied_by().id, polygon.certificate_edge(0).id, polygon.certificate_edge(1).id};
        return ps;
      }
    }
  }
  std::vector<Line>& dest = out_rows ? *out_rows : ps.rows;
  for (const Line& e : polygon.edges())
    if (e.id >= 0) {
      const double norm = std::sqrt(e.a * e.a + e.b * e.b);
      append_line(dest, e.a / norm, e.b / norm, e.c / norm, e.id);
    }
  return ps;
}

GridSets build_grid_sets(const PathSamples& samples, const std::vector<ConstraintRows>& constraints,
                         const Scale& scale) {
  GridSets gs;
  auto labels = std::make_shared<std::vector<std::string>>();
  for (const ConstraintRows& cr : constraints) labels->insert(labels->end(), cr.labels.begin(), cr.labels.end());
  gs.labels = std::move(labels);
  const Eigen::Index n_points = samples.size();
  gs.points.resize(static_cast<size_t>(n_points));
  gs.row_offset.assign(static_cast<size_t>(n_points) + 1, 0);
  gs.row_data.reserve(static_cast<size_t>(n_points) * 6);
  Polygon2d polygon;
  std::vector<Line> lines;
  for (Eigen::Index k = 0; k < n_points; ++k) {
    // The hint views row_data; build_point_set reads it only before appending to row_data.
    gs.points[static_cast<size_t>(k)] =
        build_point_set(constraints, k, polygon, lines, k > 0 ? gs.rows(k - 1) : View<Line>{}, &gs.row_data, scale);
    gs.row_offset[static_cast<size_t>(k) + 1] = gs.row_data.size();
  }
  gs.average_rows = n_points ? static_cast<double>(gs.row_data.size()) / static_cast<double>(n_points) : 0.0;
  return gs;
}

}  // namespace pathpace::detail
