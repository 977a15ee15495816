#pragma once

#include <vector>

#include "geometry/polygon2d.hpp"

namespace pathpace::detail {

/// Convex hull of points, counter-clockwise, collinear and duplicate points dropped (Andrew's monotone
/// chain). `order` receives, for each hull vertex, its index in `points`.
void convex_hull(const std::vector<Vertex>& points, std::vector<int>& order);

}  // namespace pathpace::detail
