#include "geometry/polygon2d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {

// One envelope of the lines P[t] + Q[t] x, t < m (ids[t]: their line numbers) over [x_lo, x_hi]: the minimum of
// the upper bounds (kUpper) or the maximum of the lower bounds. Pieces in increasing x; a switch at x' < x
// (rounding) happens at x. A template on the side, not a sign factor: the comparisons of the maximum are those of
// the minimum of the negated values (negation is exact), without the multiplications.
template <bool kUpper>
bool envelope(const double* P, const double* Q, const int* ids, std::size_t m, double x_lo, double x_hi,
              EnvelopePiece* out, std::size_t& pieces) {
  // a "beats" b: lies beyond it on the envelope's side (below for the minimum, above for the maximum).
  auto beats = [](double a, double b) { return kUpper ? a < b : a > b; };
  pieces = 0;
  std::size_t cur = 0;
  double best_v = P[0] + Q[0] * x_lo;
  for (std::size_t t = 1; t < m; ++t) {
    const double v = P[t] + Q[t] * x_lo;
    // Ties: the one that stays extreme longer (smaller slope for the minimum, larger for the maximum).
    if (beats(v, best_v) || (v == best_v && beats(Q[t], Q[cur]))) {
      cur = t;
      best_v = v;
    }
  }
  double x = x_lo;
  for (std::size_t guard = 0; guard <= m; ++guard) {
    // The next breakpoint: the nearest x' >= x where a line of steeper descent (ascent) takes over.
    // Candidates are compared as fractions num/den (den > 0), one division for the winner only.
    std::size_t next = m;  // none
    double best_num = x_hi, best_den = 1.0;
    const double Pc = P[cur], Qc = Q[cur];
    for (std::size_t t = 0; t < m; ++t) {
      double den = Qc - Q[t];
      if (!(kUpper ? den > 0.0 : den < 0.0)) continue;  // t never overtakes cur to the right
      double num = P[t] - Pc;
      if (den < 0.0) {
        num = -num;
        den = -den;
      }
      if (num < x * den) {  // behind x by rounding: it takes over at x
        num = x;
        den = 1.0;
      }
      const double lhs = num * best_den, rhs = best_num * den;
      if (lhs < rhs || (lhs == rhs && next < m && beats(Q[t], Q[next]))) {
        next = t;
        best_num = num;
        best_den = den;
      }
    }
    const double next_x = next == m ? x_hi : std::min(x_hi, std::max(x, best_num / best_den));
    EnvelopePiece& pc = out[pieces++];  // member by member (see append_line)
    pc.line = ids[cur];
    pc.at = static_cast<int>(cur);
    pc.x_end = next_x;
    if (next == m) return true;
    cur = next;
    x = next_x;
  }
  return false;  // cannot happen (slopes strictly monotone); be safe
}

// The envelopes' value at x, the hint the piece to start looking from (x only grows).
double envelope_at(const double* P, const double* Q, const EnvelopePiece* pcs, std::size_t count, double x,
                   std::size_t& hint) {
  while (hint + 1 < count && pcs[hint].x_end < x) ++hint;
  const int i = pcs[hint].at;
  return P[i] + Q[i] * x;
}

// The x-range [xa, xb] where the upper envelope U lies above the lower one L: g(x) = U(x) - L(x) is
// concave, so it is read off g at every breakpoint, merged in increasing x. False when it is empty (left
// to clipping, for the certificate) or degenerate (touching envelopes, or rounding that broke concavity).
bool positive_range(const double* Pu, const double* Qu, const EnvelopePiece* upper, std::size_t n_upper,
                    const double* Pl, const double* Ql, const EnvelopePiece* lower, std::size_t n_lower, double x_lo,
                    double x_hi, double& xa, double& xb) {
  std::size_t iu = 0, il = 0, hu = 0, hl = 0;
  xa = xb = std::numeric_limits<double>::quiet_NaN();
  double prev_x = x_lo, prev_g = 0.0;
  bool first = true, inside = false, closed = false;
  while (true) {
    double x;
    if (first) {
      x = x_lo;
    } else {
      const double xu = iu < n_upper ? upper[iu].x_end : x_hi;
      const double xl = il < n_lower ? lower[il].x_end : x_hi;
      x = std::min(xu, xl);
      if (x == xu) ++iu;
      if (x == xl) ++il;
    }
    const double U = envelope_at(Pu, Qu, upper, n_upper, x, hu), L = envelope_at(Pl, Ql, lower, n_lower, x, hl);
    const double g = U - L;
    if (std::abs(g) <= 1e-9 * (std::abs(U) + std::abs(L)) + 1e-300) return false;  // touching: degenerate
    if (first) {
      if (g > 0.0) {
        xa = x_lo;
        inside = true;
      }
    } else if (!inside && g > 0.0) {
      if (closed) return false;  // a second positive stretch: not concave, rounding trouble
      // Entering between prev_x and x: where the active upper and lower lines cross.
      xa = prev_x + (x - prev_x) * (-prev_g) / (g - prev_g);
      inside = true;
    } else if (inside && g < 0.0) {
      xb = prev_x + (x - prev_x) * prev_g / (prev_g - g);
      inside = false;
      closed = true;
    }
    prev_x = x;
    prev_g = g;
    first = false;
    if (x >= x_hi) break;
  }
  if (std::isnan(xa)) return false;  // empty: clip for the certificate
  if (inside) xb = x_hi;
  return xb - xa > 1e-12 * std::max(std::abs(xa), std::abs(xb)) + 1e-300;
}

}  // namespace

// The stages are separate functions, each one loop; the hot ones (envelope, positive_range) take the
// storage as plain pointers, because through the members every store below reloaded them.
bool Polygon2d::build(double x_lo, double x_hi, double y_lo, double y_hi, const Line* lines, std::size_t n,
                      bool edges_only) {
  empty_ = false;
  reserve(n);
  // Line i is lines[i] for i < n, then the box's lower and upper sides (no copies of the input). The
  // box's sides are members, not locals: a local copied into the edges is first spilled by scalar stores
  // and then read back with 16-byte loads, which stalls on store forwarding.
  side_[0] = {0.0, -1.0, -y_lo, kBoxYLow};
  side_[1] = {0.0, 1.0, y_hi, kBoxYHigh};
  side_[2] = {-1.0, 0.0, -x_lo, kBoxXLow};
  side_[3] = {1.0, 0.0, x_hi, kBoxXHigh};
  Sorted s;
  if (!sort_lines(lines, n, x_lo, x_hi, s)) return false;
  if (!(x_lo < x_hi)) return false;  // empty or a single x: leave it to clipping
  const double *const Pu = pu_.data(), *const Qu = qu_.data(), *const Pl = pl_.data(), *const Ql = ql_.data();
  std::size_t n_upper = 0, n_lower = 0;
  if (!envelope<true>(Pu, Qu, up_.data(), s.n_up, x_lo, x_hi, upper_.data(), n_upper) ||
      !envelope<false>(Pl, Ql, low_.data(), s.n_low, x_lo, x_hi, lower_.data(), n_lower))
    return false;
  double xa, xb;
  if (!positive_range(Pu, Qu, upper_.data(), n_upper, Pl, Ql, lower_.data(), n_lower, x_lo, x_hi, xa, xb))
    return false;
  Chains c;
  if (!collect_edges(lines, n, n_upper, n_lower, x_lo, x_hi, xa, xb, c)) return false;
  if (edges_only && s.n_steep == 0) {
    // intersect()'s test for parallel neighbours without its division and products.
    const Line* e = edges_[1 - cur_].data();
    for (std::size_t j = 0; j < c.count; ++j)
      if (!independent(e[j], e[j + 1 == c.count ? 0 : j + 1])) return false;
    cur_ = 1 - cur_;
    m_ = c.count;
    return true;
  }
  if (!vertices_of_edges(c)) return false;
  for (std::size_t t = 0; t < s.n_steep; ++t) {
    clip(line_at(lines, n, steep_[t]));
    if (empty_) return false;  // left to clipping line by line, which gives the certificate
  }
  return true;
}

// Index lists and pieces are written through counts into storage sized for every line: push_back on a
// member vector reloads and stores its end at every push (it may alias the stores), a store-forwarding
// chain through the whole pass.
void Polygon2d::reserve(std::size_t n) {
  if (up_.size() < n + 2) {
    up_.resize(n + 2);
    low_.resize(n + 2);
    steep_.resize(n + 2);
    upper_.resize(n + 3);
    lower_.resize(n + 3);
  }
  if (pu_.size() < n + 2) {
    pu_.resize(n + 2);
    qu_.resize(n + 2);
    pl_.resize(n + 2);
    ql_.resize(n + 2);
  }
}

// Every line (the box's sides included) sorted by what it bounds: x alone (b = 0, tightening the
// x-range, side_[2] and side_[3] with it), y from above or below (y = P + Q x, into up_ or low_), or
// nearly vertical (steep_). False: a line 0 <= c that fails (empty).
bool Polygon2d::sort_lines(const Line* lines, std::size_t n, double& x_lo, double& x_hi, Sorted& s) {
  Line& left = side_[2];
  Line& right = side_[3];
  // Local copies of the storage pointers: through the members, every store below reloaded them.
  double *const Pu = pu_.data(), *const Qu = qu_.data(), *const Pl = pl_.data(), *const Ql = ql_.data();
  int* const up = up_.data();
  int* const low = low_.data();
  int* const steep = steep_.data();
  std::size_t n_up = 0, n_low = 0, n_steep = 0;
  // Line i's kind; false: a line 0 <= c that fails. The input lines, then the box's two y-sides, in two loops
  // (not one through line_at, whose choice between them cost a branch per line).
  auto sort_one = [&](const Line& l, int i) {
    if (l.b == 0.0) {
      // A bound on x alone tightens the box (keeping its id, as clipping would).
      if (l.a > 0.0) {
        if (l.c / l.a < x_hi) {
          x_hi = l.c / l.a;
          right = l;
        }
      } else if (l.a < 0.0) {
        if (l.c / l.a > x_lo) {
          x_lo = l.c / l.a;
          left = l;
        }
      } else if (l.c < 0.0) {
        return false;  // 0 <= c fails: empty
      }
      return true;
    }
    if (std::abs(l.b) <= kSteep * std::abs(l.a)) {
      // Nearly vertical (an edge of a contact polygon between two LP optima whose x differ by rounding):
      // as an envelope line its slope -a/b ~ 1e14 and intercept c/b ~ 1e16 ruin the breakpoints, and
      // its edge was seen to be dropped. It is clipped exactly once the polygon stands (few such lines).
      steep[n_steep++] = i;
      return true;
    }
    const double inv = 1.0 / l.b;
    if (l.b > 0.0) {
      Pu[n_up] = l.c * inv;
      Qu[n_up] = -l.a * inv;
      up[n_up++] = i;
    } else {
      Pl[n_low] = l.c * inv;
      Ql[n_low] = -l.a * inv;
      low[n_low++] = i;
    }
    return true;
  };
  for (std::size_t i = 0; i < n; ++i)
    if (!sort_one(lines[i], static_cast<int>(i))) return false;
  for (std::size_t i = 0; i < 2; ++i)
    if (!sort_one(side_[i], static_cast<int>(n + i))) return false;
  s = {n_up, n_low, n_steep};
  return true;
}

// The edges over [xa, xb] into the other buffer (c says how many of each chain), counter-clockwise: lower pieces left
// to right, the right side if x_hi is reached, upper pieces right to left, the left side if x_lo is
// reached. False: fewer than three.
bool Polygon2d::collect_edges(const Line* lines, std::size_t n, std::size_t n_upper, std::size_t n_lower, double x_lo,
                              double x_hi, double xa, double xb, Chains& c) {
  const int nxt = 1 - cur_;
  const std::size_t cap = n_lower + n_upper + 2;
  if (edges_[nxt].size() < cap) {
    edges_[nxt].resize(2 * cap);
    vertices_[nxt].resize(2 * cap);
  }
  Line* e = edges_[nxt].data();
  std::size_t cnt = 0;
  const bool has_left = xa == x_lo, has_right = xb == x_hi;
  auto overlaps = [&](const EnvelopePiece* pcs, std::size_t k) {
    const double start = k == 0 ? x_lo : pcs[k - 1].x_end;
    return pcs[k].x_end > xa && start < xb;
  };
  for (std::size_t k = 0; k < n_lower; ++k)
    if (overlaps(lower_.data(), k)) e[cnt++] = line_at(lines, n, lower_[k].line);
  c.lower = cnt;
  if (has_right) e[cnt++] = side_[3];
  c.first_upper = cnt;
  for (std::size_t k = n_upper; k-- > 0;)
    if (overlaps(upper_.data(), k)) e[cnt++] = line_at(lines, n, upper_[k].line);
  c.upper = cnt - c.first_upper;
  if (has_left) e[cnt++] = side_[2];
  c.count = cnt;
  return cnt >= 3;
}

// Vertex j = edge j ∩ edge j+1 of the collected edges (Cramer, exact lines); they become the polygon.
bool Polygon2d::vertices_of_edges(const Chains& c) {
  const int nxt = 1 - cur_;
  const Line* e = edges_[nxt].data();
  Vertex* v = vertices_[nxt].data();
  const std::size_t cnt = c.count;
  for (std::size_t j = 0; j < cnt; ++j)
    if (!intersect(e[j], e[j + 1 == cnt ? 0 : j + 1], v[j])) return false;
  if (!chains_monotone(v, cnt, c.lower, c.first_upper, c.upper)) return false;
  cur_ = nxt;
  m_ = cnt;
  return true;
}

bool Polygon2d::chains_monotone(const Vertex* v, std::size_t m, std::size_t n_lower, std::size_t first_upper,
                                std::size_t n_upper) {
  // Vertex j ends edge j, and edge 0 starts at vertex m - 1. A convex polygon's lower chain runs left to right
  // and its upper chain right to left. An envelope that switched lines at a breakpoint that rounding
  // misplaced breaks that: on a fine grid an interval's rows in (θ_k, θ_{k+1}) are nearly parallel (slopes
  // 1 + O(Δs), eq. 26), a breakpoint (P_j - P_i) / (Q_i - Q_j) then errs by eps / |Q_i - Q_j| ~ eps / Δs², and
  // the exact vertex of two such lines lay outside the other edges: the controllable set read off that
  // polygon was 3e-7 too wide, and s̈ broke its limit by 10 % (N = 5e5).
  auto prev = [&](std::size_t j) { return v[j == 0 ? m - 1 : j - 1].x; };
  for (std::size_t j = 0; j < n_lower; ++j)
    if (v[j].x < prev(j)) return false;
  for (std::size_t j = first_upper; j < first_upper + n_upper; ++j)
    if (v[j].x > prev(j)) return false;
  return true;
}

bool Polygon2d::independent(const Line& l1, const Line& l2) {
  const double det = l1.a * l2.b - l2.a * l1.b;
  const double scale = std::abs(l1.a * l2.b) + std::abs(l2.a * l1.b);
  return std::abs(det) > 1e-15 * scale && scale != 0.0;
}

bool Polygon2d::intersect(const Line& l1, const Line& l2, Vertex& v) {
  if (!independent(l1, l2)) return false;
  const double det = l1.a * l2.b - l2.a * l1.b;  // independent()'s (the compiler computes it once)
  const double inv = 1.0 / det;  // one division for both coordinates (within an ulp of dividing twice)
  v.x = (l1.c * l2.b - l2.c * l1.b) * inv;
  v.y = (l1.a * l2.c - l2.a * l1.c) * inv;
  // One step of iterative refinement: Cramer's rule is not backward stable, and for nearly parallel lines
  // its vertex misses both by ~eps / sin(angle) of their terms. On a fine grid an interval's rows in
  // (θ_k, θ_{k+1}) are all nearly θ_{k+1} = θ_k (eq. 26 with Δs -> 0); a slice interpolated between such
  // vertices broke the rows by 1e-8 at N = 5e5. One correction from the residuals leaves the vertex on both
  // lines to rounding of their terms (while cond · eps << 1).
  const double r1 = l1.c - (l1.a * v.x + l1.b * v.y), r2 = l2.c - (l2.a * v.x + l2.b * v.y);
  v.x += (r1 * l2.b - r2 * l1.b) * inv;
  v.y += (l1.a * r2 - l2.a * r1) * inv;
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
    // (Written in place: a Vertex copied out of a temporary stalls on store forwarding, see append_line.)
    Vertex& v = out_v[out++];
    if (!intersect(edges[j], line, v) || !on_segment(v, verts[jp], verts[j])) {
      const double t = dist[jp] / (dist[jp] - dist[j]);
      v.x = verts[jp].x + t * (verts[j].x - verts[jp].x);
      v.y = verts[jp].y + t * (verts[j].y - verts[jp].y);
    }
    // The line's edge ends where the walk re-enters: line ∩ (first edge whose end is inside).
    std::size_t k = j + 1 == m ? 0 : j + 1;
    while (dist[k] > 0.0) k = k + 1 == m ? 0 : k + 1;
    inserted = out;
    out_e[out] = line;
    Vertex& w = out_v[out++];
    const std::size_t k_start = k == 0 ? m - 1 : k - 1;
    if (!intersect(line, edges[k], w) || !on_segment(w, verts[k_start], verts[k])) {
      const double t = dist[k_start] / (dist[k_start] - dist[k]);
      w.x = verts[k_start].x + t * (verts[k].x - verts[k_start].x);
      w.y = verts[k_start].y + t * (verts[k].y - verts[k_start].y);
    }
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

bool Polygon2d::on_segment(const Vertex& v, const Vertex& p, const Vertex& q) {
  // The cut vertex lies on the edge it cuts, or the polygon is no longer convex. A line nearly parallel
  // to the edge (on a fine grid an interval's rows in (θ_k, θ_{k+1}) all are, eq. 26) meets it, by Cramer's
  // rule, anywhere along it: a vertex 50 % beyond the box made K_k that much too wide (N = 1e4, a random
  // grid). The interpolation from the two ends' distances stays between them.
  auto inside = [](double x, double a, double b) {
    const double lo = std::min(a, b), hi = std::max(a, b), tol = 1e-12 * (std::abs(lo) + std::abs(hi));
    return x >= lo - tol && x <= hi + tol;
  };
  return inside(v.x, p.x, q.x) && inside(v.y, p.y, q.y);
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

}  // namespace pathpace::detail
