#include "detail/polygon2d.hpp"

#include <algorithm>
#include <cmath>

namespace pathpace::detail {

void Polygon2d::reset(double x_lo, double x_hi, double y_lo, double y_hi) {
  empty_ = false;
  edges_.clear();
  vertices_.clear();
  // Counter-clockwise: bottom, right, top, left; vertex j ends edge j.
  edges_.push_back({0.0, -1.0, -y_lo, kBoxYLow});
  edges_.push_back({1.0, 0.0, x_hi, kBoxXHigh});
  edges_.push_back({0.0, 1.0, y_hi, kBoxYHigh});
  edges_.push_back({-1.0, 0.0, -x_lo, kBoxXLow});
  vertices_.push_back({x_hi, y_lo});
  vertices_.push_back({x_hi, y_hi});
  vertices_.push_back({x_lo, y_hi});
  vertices_.push_back({x_lo, y_lo});
}

bool Polygon2d::intersect(const Line& l1, const Line& l2, Vertex& v) {
  const double det = l1.a * l2.b - l2.a * l1.b;
  const double scale = std::abs(l1.a * l2.b) + std::abs(l2.a * l1.b);
  if (!(std::abs(det) > 1e-15 * scale) || scale == 0.0) return false;
  v.x = (l1.c * l2.b - l2.c * l1.b) / det;
  v.y = (l1.a * l2.c - l2.a * l1.c) / det;
  return true;
}

bool Polygon2d::clip(const Line& line) {
  if (empty_) return false;
  const size_t m = edges_.size();
  dist_.resize(m);
  inside_.resize(m);
  size_t n_in = 0;
  int least_violating = 0;
  for (size_t j = 0; j < m; ++j) {
    const Vertex& v = vertices_[j];
    const double ax = line.a * v.x, by = line.b * v.y;
    const double d = ax + by - line.c;
    dist_[j] = d;
    inside_[j] = d <= kTol * (std::abs(ax) + std::abs(by) + std::abs(line.c));
    n_in += inside_[j];
    if (d < dist_[least_violating]) least_violating = static_cast<int>(j);
  }
  if (n_in == m) return false;
  if (n_in == 0) {
    empty_ = true;
    emptied_by_ = line;
    certificate_[0] = edges_[least_violating];
    certificate_[1] = edges_[(least_violating + 1) % m];
    edges_.clear();
    vertices_.clear();
    return true;
  }
  // Edge j runs from vertex j-1 to vertex j. Keep every edge with an inside end; where the walk leaves
  // the half-plane, the new line's edge is inserted.
  new_edges_.clear();
  new_vertices_.clear();
  size_t inserted = 0;
  for (size_t j = 0, jp = m - 1; j < m; jp = j++) {
    const bool start_in = inside_[jp], end_in = inside_[j];
    if (!start_in && !end_in) continue;
    new_edges_.push_back(edges_[j]);
    if (end_in) {
      new_vertices_.push_back(vertices_[j]);
    } else {
      // Leaves through `line`: the vertex is edge_j ∩ line, then the line's own edge follows.
      Vertex v;
      if (!intersect(edges_[j], line, v)) {
        const double t = dist_[jp] / (dist_[jp] - dist_[j]);
        v.x = vertices_[jp].x + t * (vertices_[j].x - vertices_[jp].x);
        v.y = vertices_[jp].y + t * (vertices_[j].y - vertices_[jp].y);
      }
      new_vertices_.push_back(v);
      inserted = new_edges_.size();
      new_edges_.push_back(line);
      // The line's edge ends where the walk re-enters: line ∩ (first edge whose end is inside).
      size_t k = j + 1 == m ? 0 : j + 1;
      while (!inside_[k]) k = k + 1 == m ? 0 : k + 1;
      Vertex w;
      if (!intersect(line, edges_[k], w)) {
        const size_t kp = k == 0 ? m - 1 : k - 1;
        const double t = dist_[kp] / (dist_[kp] - dist_[k]);
        w.x = vertices_[kp].x + t * (vertices_[k].x - vertices_[kp].x);
        w.y = vertices_[kp].y + t * (vertices_[k].y - vertices_[kp].y);
      }
      new_vertices_.push_back(w);
    }
  }
  // The re-entering edge's start vertex was pushed as the line's end; that edge itself is kept by the
  // loop (its end is inside), so the cycle is consistent.
  edges_.swap(new_edges_);
  vertices_.swap(new_vertices_);
  remove_degenerate_edges(inserted);
  return true;
}

void Polygon2d::remove_degenerate_edges(size_t inserted) {
  // An edge whose two ends coincide (the new line passed through a vertex) supports nothing; dropping
  // it keeps edges() equal to the set of supporting half-planes. Only the new edge and its two
  // neighbours can have become degenerate; they are checked from the highest index down so that an
  // erase does not shift the indices still to check.
  const size_t m0 = edges_.size();
  size_t cand[3] = {inserted + 1 == m0 ? 0 : inserted + 1, inserted, inserted == 0 ? m0 - 1 : inserted - 1};
  // Descending order (the wrapped ones may be out of place); three elements, sorted by hand.
  if (cand[0] < cand[1]) std::swap(cand[0], cand[1]);
  if (cand[1] < cand[2]) std::swap(cand[1], cand[2]);
  if (cand[0] < cand[1]) std::swap(cand[0], cand[1]);
  for (int c = 0; c < 3; ++c) {
    const size_t m = edges_.size();
    const size_t j = cand[c];
    if (m <= 2 || j >= m || (c > 0 && cand[c] == cand[c - 1])) continue;
    const size_t jp = j == 0 ? m - 1 : j - 1;
    const Vertex& s = vertices_[jp];
    const Vertex& e = vertices_[j];
    const double scale = std::abs(s.x) + std::abs(s.y) + std::abs(e.x) + std::abs(e.y);
    if (std::abs(s.x - e.x) + std::abs(s.y - e.y) > 1e-13 * scale + 1e-300) continue;
    // A zero-length edge may still be needed: at the ends of a segment (equality rows) the two
    // neighbours are antiparallel. It is redundant only if its neighbours' outward normals turn
    // counter-clockwise by less than 180 degrees, so that they alone close the corner.
    const Line& l1 = edges_[jp];
    const Line& l3 = edges_[j + 1 == m ? 0 : j + 1];
    const double cross = l1.a * l3.b - l1.b * l3.a;
    const double norms = std::sqrt((l1.a * l1.a + l1.b * l1.b) * (l3.a * l3.a + l3.b * l3.b));
    if (cross > 1e-12 * norms) {
      // Merge: the vertex before the edge stays, the edge and its end vertex go.
      edges_.erase(edges_.begin() + static_cast<long>(j));
      vertices_.erase(vertices_.begin() + static_cast<long>(j));
    }
  }
}

int Polygon2d::argmax_x() const {
  int best = 0;
  for (size_t j = 1; j < vertices_.size(); ++j)
    if (vertices_[j].x > vertices_[best].x) best = static_cast<int>(j);
  return best;
}

int Polygon2d::argmin_x() const {
  int best = 0;
  for (size_t j = 1; j < vertices_.size(); ++j)
    if (vertices_[j].x < vertices_[best].x) best = static_cast<int>(j);
  return best;
}

}  // namespace pathpace::detail
