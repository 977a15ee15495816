#include "geometry/convex_hull.hpp"

#include <algorithm>
#include <utility>

namespace pathpace::detail {

namespace {

double cross(const Vertex& o, const Vertex& a, const Vertex& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

}  // namespace

void convex_hull(const std::vector<Vertex>& points, std::vector<int>& order) {
  std::vector<int> idx(points.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  std::sort(idx.begin(), idx.end(), [&](int i, int j) {
    const Vertex &p = points[static_cast<size_t>(i)], &q = points[static_cast<size_t>(j)];
    return p.x < q.x || (p.x == q.x && p.y < q.y);
  });
  idx.erase(std::unique(idx.begin(), idx.end(),
                        [&](int i, int j) {
                          const Vertex &p = points[static_cast<size_t>(i)], &q = points[static_cast<size_t>(j)];
                          return p.x == q.x && p.y == q.y;
                        }),
            idx.end());
  order.clear();
  if (idx.size() <= 2) {
    order = idx;
    return;
  }
  // Lower hull left to right, then upper hull right to left; a turn that is not strictly
  // counter-clockwise drops the middle point.
  std::vector<int> h(2 * idx.size());
  size_t k = 0;
  auto P = [&](int i) -> const Vertex& { return points[static_cast<size_t>(i)]; };
  for (size_t i = 0; i < idx.size(); ++i) {
    while (k >= 2 && cross(P(h[k - 2]), P(h[k - 1]), P(idx[i])) <= 0) --k;
    h[k++] = idx[i];
  }
  for (size_t i = idx.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(P(h[k - 2]), P(h[k - 1]), P(idx[i])) <= 0) --k;
    h[k++] = idx[i];
  }
  h.resize(k - 1);  // the last point is the first
  order = std::move(h);
}

}  // namespace pathpace::detail
