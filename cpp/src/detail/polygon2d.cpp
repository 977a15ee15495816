#include "detail/polygon2d.hpp"

#include <algorithm>
#include <cmath>

namespace pathpace::detail {

void Polygon2d::reset(double x_lo, double x_hi, double y_lo, double y_hi) {
  empty_ = false;
  cur_ = 0;
  m_ = 4;
  for (int b = 0; b < 2; ++b) {
    if (edges_[b].size() < 16) {
      edges_[b].resize(16);
      vertices_[b].resize(16);
    }
  }
  if (dist_.size() < 16) dist_.resize(16);
  Line* e = edges_[0].data();
  Vertex* v = vertices_[0].data();
  // Counter-clockwise: bottom, right, top, left; vertex j ends edge j.
  e[0] = {0.0, -1.0, -y_lo, kBoxYLow};
  e[1] = {1.0, 0.0, x_hi, kBoxXHigh};
  e[2] = {0.0, 1.0, y_hi, kBoxYHigh};
  e[3] = {-1.0, 0.0, -x_lo, kBoxXLow};
  v[0] = {x_hi, y_lo};
  v[1] = {x_hi, y_hi};
  v[2] = {x_lo, y_hi};
  v[3] = {x_lo, y_lo};
}

void Polygon2d::assign(const Polygon2d& other) {
  empty_ = other.empty_;
  emptied_by_ = other.emptied_by_;
  certificate_[0] = other.certificate_[0];
  certificate_[1] = other.certificate_[1];
  m_ = other.m_;
  cur_ = 0;
  if (edges_[0].size() < m_ + 2) {
    edges_[0].resize(2 * m_ + 2);
    vertices_[0].resize(2 * m_ + 2);
  }
  if (edges_[1].size() < 16) {
    edges_[1].resize(16);
    vertices_[1].resize(16);
  }
  if (dist_.size() < 16) dist_.resize(16);
  std::copy(other.edges_[other.cur_].begin(), other.edges_[other.cur_].begin() + static_cast<long>(m_), edges_[0].begin());
  std::copy(other.vertices_[other.cur_].begin(), other.vertices_[other.cur_].begin() + static_cast<long>(m_),
            vertices_[0].begin());
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
  const std::size_t m = m_;
  const Line* edges = edges_[cur_].data();
  const Vertex* verts = vertices_[cur_].data();
  if (dist_.size() < m) dist_.resize(2 * m);
  double* dist = dist_.data();
  // dist[j] <= 0 marks an inside vertex (within the tolerance); outside ones keep their distance, which
  // the empty-set certificate and the parallel-line fallback below use.
  std::size_t n_in = 0;
  bool on_line = false;  // some vertex lies on the new line: a zero-length edge may appear
  for (std::size_t j = 0; j < m; ++j) {
    const double ax = line.a * verts[j].x, by = line.b * verts[j].y;
    const double d = ax + by - line.c;
    const double tol = kTol * (std::abs(ax) + std::abs(by) + std::abs(line.c));
    const bool in = d <= tol;
    on_line |= std::abs(d) <= tol;
    dist[j] = in ? std::min(d, 0.0) : d;
    n_in += in;
  }
  if (n_in == m) return false;
  if (n_in == 0) {
    std::size_t lv = 0;
    for (std::size_t j = 1; j < m; ++j)
      if (dist[j] < dist[lv]) lv = j;
    empty_ = true;
    emptied_by_ = line;
    certificate_[0] = edges[lv];
    certificate_[1] = edges[lv + 1 == m ? 0 : lv + 1];
    m_ = 0;
    return true;
  }
  // Edge j runs from vertex j-1 to vertex j. Keep every edge with an inside end; where the walk leaves
  // the half-plane, the new line's edge is inserted. At most m + 1 edges result.
  const int nxt = 1 - cur_;
  if (edges_[nxt].size() < m + 2) {
    edges_[nxt].resize(2 * m + 2);
    vertices_[nxt].resize(2 * m + 2);
  }
  Line* out_e = edges_[nxt].data();
  Vertex* out_v = vertices_[nxt].data();
  std::size_t out = 0, inserted = 0;
  bool maybe_degenerate = false;
  for (std::size_t j = 0, jp = m - 1; j < m; jp = j++) {
    const bool start_in = dist[jp] <= 0.0, end_in = dist[j] <= 0.0;
    if (!start_in && !end_in) continue;
    out_e[out] = edges[j];
    if (end_in) {
      out_v[out++] = verts[j];
      continue;
    }
    // Leaves through `line`: the vertex is edge_j ∩ line, then the line's own edge follows.
    Vertex v;
    if (!intersect(edges[j], line, v)) {
      const double t = dist[jp] / (dist[jp] - dist[j]);
      v = {verts[jp].x + t * (verts[j].x - verts[jp].x), verts[jp].y + t * (verts[j].y - verts[jp].y)};
    }
    out_v[out++] = v;
    // The line's edge ends where the walk re-enters: line ∩ (first edge whose end is inside).
    std::size_t k = j + 1 == m ? 0 : j + 1;
    while (dist[k] > 0.0) k = k + 1 == m ? 0 : k + 1;
    Vertex w;
    if (!intersect(line, edges[k], w)) {
      const std::size_t kp = k == 0 ? m - 1 : k - 1;
      const double t = dist[kp] / (dist[kp] - dist[k]);
      w = {verts[kp].x + t * (verts[k].x - verts[kp].x), verts[kp].y + t * (verts[k].y - verts[kp].y)};
    }
    inserted = out;
    out_e[out] = line;
    out_v[out++] = w;
    // A new vertex on top of an old one (the line passed through a vertex) leaves a zero-length edge.
    maybe_degenerate = on_line || (v.x == w.x && v.y == w.y);
  }
  cur_ = nxt;
  m_ = out;
  if (maybe_degenerate) {
    // Only the new edge and its two neighbours can have become degenerate; highest index first so that
    // an erase does not shift the indices still to check.
    std::size_t cand[3] = {inserted + 1 == m_ ? 0 : inserted + 1, inserted, inserted == 0 ? m_ - 1 : inserted - 1};
    if (cand[0] < cand[1]) std::swap(cand[0], cand[1]);
    if (cand[1] < cand[2]) std::swap(cand[1], cand[2]);
    if (cand[0] < cand[1]) std::swap(cand[0], cand[1]);
    for (int c = 0; c < 3; ++c) {
      if (c > 0 && cand[c] == cand[c - 1]) continue;
      if (m_ > 2 && cand[c] < m_ && degenerate(cand[c])) erase(cand[c]);
    }
  }
  return true;
}

bool Polygon2d::degenerate(std::size_t j) const {
  // An edge whose two ends coincide supports nothing, unless its neighbours are antiparallel (the ends
  // of a segment cut by equality rows): it is redundant only if its neighbours' outward normals turn
  // counter-clockwise by less than 180 degrees, so that they alone close the corner.
  const std::size_t m = m_;
  const Line* e = edges_[cur_].data();
  const Vertex* v = vertices_[cur_].data();
  const std::size_t jp = j == 0 ? m - 1 : j - 1;
  const Vertex& s = v[jp];
  const Vertex& t = v[j];
  const double scale = std::abs(s.x) + std::abs(s.y) + std::abs(t.x) + std::abs(t.y);
  if (std::abs(s.x - t.x) + std::abs(s.y - t.y) > 1e-13 * scale + 1e-300) return false;
  const Line& l1 = e[jp];
  const Line& l3 = e[j + 1 == m ? 0 : j + 1];
  const double cross = l1.a * l3.b - l1.b * l3.a;
  const double norms = std::sqrt((l1.a * l1.a + l1.b * l1.b) * (l3.a * l3.a + l3.b * l3.b));
  return cross > 1e-12 * norms;
}

void Polygon2d::erase(std::size_t j) {
  // The vertex before the edge stays (it is the same point); the edge and its end vertex go.
  Line* e = edges_[cur_].data();
  Vertex* v = vertices_[cur_].data();
  for (std::size_t i = j; i + 1 < m_; ++i) {
    e[i] = e[i + 1];
    v[i] = v[i + 1];
  }
  --m_;
}

int Polygon2d::argmax_x() const {
  const Vertex* v = vertices_[cur_].data();
  int best = 0;
  for (std::size_t j = 1; j < m_; ++j)
    if (v[j].x > v[best].x) best = static_cast<int>(j);
  return best;
}

int Polygon2d::argmin_x() const {
  const Vertex* v = vertices_[cur_].data();
  int best = 0;
  for (std::size_t j = 1; j < m_; ++j)
    if (v[j].x < v[best].x) best = static_cast<int>(j);
  return best;
}

}  // namespace pathpace::detail
