#pragma once
// Convex polygons cut out of a box by half-planes a·x + b·y <= c, kept as a cycle of edge lines.
//
// Every vertex is the intersection of two *original* lines (Cramer's rule), never an interpolation of
// earlier vertices, so vertices keep full relative precision even when the box is huge (an absent
// limit is a box side at 1e15). This is what lets the per-grid-point feasible sets (sec. IV.A) and the
// per-interval controllable-set LPs of the reachability pass be exact to rounding.
//
// This is the innermost loop of every solve (one polygon per grid point and two per interval), so the
// storage is two flat buffers swapped on each cut, with no allocation once warm.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace pathpace::detail {

struct Line {
  double a = 0, b = 0, c = 0;
  int id = -1;  // caller's row id; box sides get negative ids (kBoxXLow, ...)
};

/// Sets l to {a, b, c, id} member by member. A Line built by scalar stores in a temporary and then copied
/// with 16-byte loads stalls each copy on store forwarding (the load spans two smaller stores): that was
/// half the time of the per-grid-point loop.
inline void assign_line(Line& l, double a, double b, double c, int id) {
  l.a = a;
  l.b = b;
  l.c = c;
  l.id = id;
}

/// Appends {a, b, c, id}, written member by member into the vector's own storage (see assign_line).
inline void append_line(std::vector<Line>& v, double a, double b, double c, int id) {
  v.emplace_back();
  assign_line(v.back(), a, b, c, id);
}

/// 2^-floor(log2 m) for a normal m > 0, else 1: a factor that scales by a power of two, so that
/// multiplying by it is exact (no rounding) and every result computed from the scaled numbers is the
/// same, scaled.
inline double inverse_power_of_two(double m) {
  std::uint64_t bits;
  std::memcpy(&bits, &m, sizeof bits);
  const int e = static_cast<int>((bits >> 52) & 0x7ff);
  if (e == 0 || e >= 2046) return 1.0;  // zero, subnormal, inf, nan, or a result that would be subnormal
  const std::uint64_t r = static_cast<std::uint64_t>(2046 - e) << 52;
  double out;
  std::memcpy(&out, &r, sizeof out);
  return out;
}

/// The line scaled by the power of two that brings max(|a|, |b|) into [1, 2). Exact, so vertices and
/// tests computed from it are those of the original line; but the products of Cramer's rule cannot
/// overflow (coordinates at 1e200 give coefficients ~1e200, whose products are inf) nor underflow.
inline Line power_of_two_normalised(const Line& l) {
  const double f = inverse_power_of_two(std::max(std::abs(l.a), std::abs(l.b)));
  const double c = l.c * f;
  if (!std::isfinite(c) && std::isfinite(l.c)) return l;  // would overflow: keep it as it is
  return {l.a * f, l.b * f, c, l.id};
}

inline constexpr int kBoxXLow = -1;
inline constexpr int kBoxXHigh = -2;
inline constexpr int kBoxYLow = -3;
inline constexpr int kBoxYHigh = -4;

struct Vertex {
  double x = 0, y = 0;
};

/// A piece of an envelope built by Polygon2d::build: `line` is the extreme one up to `x_end`.
struct EnvelopePiece {
  int line;      // lines[line], or the box's lower (n) or upper (n + 1) side
  int at;        // its place in its envelope's own y = P + Q x arrays (Polygon2d's pu_/qu_ or pl_/ql_)
  double x_end;  // where the next piece takes over
};

/// A read-only view of a contiguous range (edges or vertices).
template <typename T>
struct View {
  const T* ptr = nullptr;
  std::size_t n = 0;
  const T* begin() const { return ptr; }
  const T* end() const { return ptr + n; }
  std::size_t size() const { return n; }
  bool empty() const { return n == 0; }
  const T& operator[](std::size_t i) const { return ptr[i]; }
};

class Polygon2d {
 public:
  /// Relative tolerance of the inside test: a vertex with a·x + b·y - c <= tol·(|a x| + |b y| + |c|)
  /// is on the inner side.
  static constexpr double kTol = 1e-12;
  /// build(): a line with |b| <= kSteep·|a| is nearly vertical; it is clipped after the envelopes.
  static constexpr double kSteep = 1e-8;

  /// Starts from the box [x_lo, x_hi] x [y_lo, y_hi] (finite, x_lo <= x_hi, y_lo <= y_hi).
  void reset(double x_lo, double x_hi, double y_lo, double y_hi);

  /// The box cut by n lines in one pass, the same polygon as reset() followed by clip() of each line:
  /// every line with b != 0 bounds y from above (b > 0) or below (b < 0), so the polygon is the region
  /// between the lower envelope of the upper bounds and the upper envelope of the lower bounds (the
  /// x-range where they do not cross), found by walking the two envelopes; lines with b = 0 tighten the
  /// x-range; nearly vertical lines (|b| <= kSteep·|a|) are clipped once the rest is built (robustly, as
  /// x-bounds would not be: their x moves by b·y/a over the box's y). O(n · pieces) instead of
  /// O(n · vertices) clips. Returns false, with the polygon left
  /// unspecified, when the result is empty or nearly degenerate (touching envelopes, parallel lines):
  /// the caller then clips line by line, which also yields the emptiness certificate.
  /// With edges_only, a caller that reads only edges() afterwards (the per-grid-point sets keep the
  /// supporting rows) spares the vertices' divisions: unless a nearly vertical line must be clipped in,
  /// vertices() and x_range() are then unspecified and the polygon must not be clipped until rebuilt.
  /// Whether it succeeds is the same either way (adjacent edges are still checked for being parallel).
  bool build(double x_lo, double x_hi, double y_lo, double y_hi, const Line* lines, std::size_t n,
             bool edges_only = false);

  /// Becomes a copy of `other` (no allocation once warm).
  void assign(const Polygon2d& other);

  /// Intersects with a·x + b·y <= c. Returns true if the line now supports an edge of the polygon
  /// (it cut something off), false if it was redundant. After an intersection that empties the polygon,
  /// empty() is true and the line that emptied it is recorded in emptied_by().
  bool clip(const Line& line);

  bool empty() const { return empty_; }
  View<Line> edges() const { return {edges_[cur_].data(), m_}; }
  /// vertices()[j] is the end of edges()[j] (= edges()[j] ∩ edges()[j+1]), counter-clockwise.
  View<Vertex> vertices() const { return {vertices_[cur_].data(), m_}; }

  /// The polygon's extent in x: the smallest and largest x of its vertices (one pass over them).
  void x_range(double& lo, double& hi) const {
    // Inline (once per interval of each reachability analysis). Two accumulators per extreme, not one chain of
    // min/max through every vertex (a latency chain); min and max are exact: the same extremes.
    const Vertex* v = vertices_[cur_].data();
    double l[2] = {v[0].x, v[0].x}, h[2] = {v[0].x, v[0].x};
    for (std::size_t j = 1; j < m_; ++j) {
      l[j & 1] = std::min(l[j & 1], v[j].x);
      h[j & 1] = std::max(h[j & 1], v[j].x);
    }
    lo = std::min(l[0], l[1]);
    hi = std::max(h[0], h[1]);
  }

  /// After empty(): the line that emptied the polygon and the two edges meeting at the vertex that
  /// violated it least. Those three half-planes alone are infeasible (a 2-D Helly certificate).
  const Line& emptied_by() const { return emptied_by_; }
  const Line& certificate_edge(int i) const { return certificate_[i]; }

 private:
  static bool intersect(const Line& l1, const Line& l2, Vertex& v);
  static bool independent(const Line& l1, const Line& l2);  // intersect() would succeed
  // build(): the lower chain's vertices run left to right, the upper chain's right to left (convex).
  static bool chains_monotone(const Vertex* v, std::size_t m, std::size_t n_lower, std::size_t first_upper,
                              std::size_t n_upper);
  static bool on_segment(const Vertex& v, const Vertex& p, const Vertex& q);  // within the box of p, q
  bool degenerate(std::size_t j) const;
  // build()'s stages (see the .cpp).
  struct Sorted {
    std::size_t n_up, n_low, n_steep;  // lines bounding y from above, from below, nearly vertical
  };
  struct Chains {
    std::size_t count, lower, first_upper, upper;  // edges; of the lower chain; where the upper starts, its count
  };
  void reserve(std::size_t n);
  bool sort_lines(const Line* lines, std::size_t n, double& x_lo, double& x_hi, Sorted& s);
  bool collect_edges(const Line* lines, std::size_t n, std::size_t n_upper, std::size_t n_lower, double x_lo,
                     double x_hi, double xa, double xb, Chains& c);
  bool vertices_of_edges(const Chains& c);
  // Line i of build(): lines[i] for i < n, then the box's lower and upper sides.
  const Line& line_at(const Line* lines, std::size_t n, int i) const {
    const std::size_t u = static_cast<std::size_t>(i);
    return u < n ? lines[u] : side_[u - n];
  }
  void erase(std::size_t j);

  std::vector<Line> edges_[2];
  std::vector<Vertex> vertices_[2];
  std::vector<double> dist_;
  // build(): y = p + q x of the lines bounding y from above (pu_, qu_, in up_'s order) and from below (pl_, ql_):
  // contiguous per envelope, so that its walk reads them without going through the index lists.
  std::vector<double> pu_, qu_, pl_, ql_;
  std::vector<int> up_, low_, steep_;
  std::vector<EnvelopePiece> upper_, lower_;
  Line side_[4];  // build(): the box's lower and upper sides, then the left and right x-bounds
  int cur_ = 0;
  std::size_t m_ = 0;
  bool empty_ = false;
  Line emptied_by_;
  Line certificate_[2];
};

}  // namespace pathpace::detail
