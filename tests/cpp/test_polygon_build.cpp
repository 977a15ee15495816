// Polygon2d::build (envelopes) against reset + clip (the reference), on seeded random line sets shaped
// like the solver's: slabs (pairs of opposite rows), x-bounds, nearly vertical and nearly horizontal rows,
// boxes far larger than the polygon.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/polygon2d.hpp"

using namespace pathpace::detail;

namespace {

double support(const Polygon2d& p, double dx, double dy) {
  double best = -INFINITY;
  for (const Vertex& v : p.vertices()) best = std::max(best, dx * v.x + dy * v.y);
  return best;
}

}  // namespace

TEST(PolygonBuild, MatchesClippingOnRandomSlabs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int built = 0, declined_empty = 0, declined_nonempty = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::vector<Line> lines;
    const int slabs = 1 + trial % 9;
    int id = 0;
    for (int j = 0; j < slabs; ++j) {
      // lo <= a x + b y <= hi, as acceleration or torque rows are.
      double a = U(rng), b = trial % 17 == 0 && j == 0 ? 0.0 : U(rng);
      // Nearly vertical rows (|b| / |a| = 1e-14 .. 1e-12, edges of contact polygons between LP optima
      // whose x differ by rounding) and nearly horizontal ones (|a| / |b| the same).
      const double tiny = std::pow(10.0, -12.0 - (trial / 7) % 3) * (U(rng) > 0 ? 1.0 : -1.0);
      if (trial % 7 == 3 && j < 2) b = tiny * (a == 0.0 ? 1.0 : a);
      if (trial % 7 == 5 && j < 2) a = tiny * b;
      const double lo = -std::abs(U(rng)) - 0.1, hi = std::abs(U(rng)) + 0.1 + (trial % 5 == 0 ? -1.0 : 0.0);
      const double n = std::hypot(a, b);
      if (n == 0.0) continue;
      lines.push_back({a / n, b / n, hi / n, id++});
      lines.push_back({-a / n, -b / n, -lo / n, id++});
    }
    if (trial % 3 == 0) lines.push_back({1.0, 0.0, 5.0 + U(rng), id++});  // an x-bound row
    const bool huge = trial % 2 == 0;
    const double xhi = huge ? 1e15 : 10.0, yb = huge ? 1e15 : 50.0;
    Polygon2d ref, fast;
    ref.reset(0.0, xhi, -yb, yb);
    for (const Line& l : lines) ref.clip(l);
    // edges_only (the grid's per-point sets): the same decision and the same edges, without the vertices.
    Polygon2d edges;
    const bool edges_built = edges.build(0.0, xhi, -yb, yb, lines.data(), lines.size(), true);
    if (!fast.build(0.0, xhi, -yb, yb, lines.data(), lines.size())) {
      EXPECT_FALSE(edges_built) << "trial " << trial;
      ++(ref.empty() ? declined_empty : declined_nonempty);
      continue;
    }
    EXPECT_TRUE(edges_built) << "trial " << trial;
    ASSERT_EQ(edges.edges().size(), fast.edges().size()) << "trial " << trial;
    for (size_t j = 0; j < fast.edges().size(); ++j)
      EXPECT_EQ(edges.edges()[j].id, fast.edges()[j].id) << "trial " << trial;
    ++built;
    ASSERT_FALSE(ref.empty()) << "trial " << trial;
    for (int d = 0; d < 24; ++d) {
      const double dx = std::cos(0.2618 * d), dy = std::sin(0.2618 * d);
      const double a = support(ref, dx, dy), b = support(fast, dx, dy);
      EXPECT_NEAR(a, b, 1e-9 * std::max(1.0, std::abs(a))) << "trial " << trial << " direction " << d;
    }
    // The same supporting rows (ids), as the solver's rows come from the edges.
    std::vector<int> ids_ref, ids_fast;
    for (const Line& e : ref.edges()) ids_ref.push_back(e.id);
    for (const Line& e : fast.edges()) ids_fast.push_back(e.id);
    std::sort(ids_ref.begin(), ids_ref.end());
    std::sort(ids_fast.begin(), ids_fast.end());
    EXPECT_EQ(ids_ref, ids_fast) << "trial " << trial;
  }
  // The fast path serves nearly every nonempty set; empty ones are left to clipping (certificates).
  EXPECT_GT(declined_empty, 100);
  EXPECT_LT(declined_nonempty, built / 50) << declined_nonempty << " of " << built + declined_nonempty;
}

TEST(PolygonBuild, DeclinesEmptyAndDegenerateSets) {
  Polygon2d p;
  // y <= -1 and y >= 1: empty.
  std::vector<Line> empty = {{0.0, 1.0, -1.0, 0}, {0.0, -1.0, -1.0, 1}};
  EXPECT_FALSE(p.build(0.0, 1.0, -10.0, 10.0, empty.data(), empty.size()));
  // y = x exactly (an equality as two rows): a segment.
  const double r = std::sqrt(0.5);
  std::vector<Line> segment = {{-r, r, 0.0, 0}, {r, -r, 0.0, 1}};
  EXPECT_FALSE(p.build(0.0, 1.0, -10.0, 10.0, segment.data(), segment.size()));
  // x in [2, 1]: empty x-range.
  std::vector<Line> xs = {{-1.0, 0.0, -2.0, 0}};
  EXPECT_FALSE(p.build(0.0, 1.0, -10.0, 10.0, xs.data(), xs.size()));
  // A plain triangle is built: y >= 0, y <= 1 - x on x in [0, 5].
  std::vector<Line> tri = {{0.0, -1.0, 0.0, 0}, {r, r, r, 1}};
  ASSERT_TRUE(p.build(0.0, 5.0, -10.0, 10.0, tri.data(), tri.size()));
  EXPECT_EQ(p.vertices().size(), 3u);
  EXPECT_NEAR(support(p, 1.0, 0.0), 1.0, 1e-15);
  EXPECT_NEAR(support(p, 0.0, 1.0), 1.0, 1e-15);
}

// The rows of one interval of a fine grid (eq. 26): a joint's acceleration limits at s_k and s_{k+1},
// a x + b (y - x) / (2Δs) <= c, in (θ_k, θ_{k+1}) = (x, y). For Δs -> 0 every row is nearly y = x, and a pair
// from the same limit at the two ends is parallel to O(Δs²). Built (envelopes, or clipping where build
// declines) and clipped row by row, the polygon must stay convex and every vertex meet every row to
// rounding of the physical terms |a x| + |b u| + |c|, not of the chain's terms, which are 1/Δs larger:
// the greedy profile read off such polygons broke s̈ limits by up to 10 % at N = 5e5 before.
TEST(PolygonBuild, FineGridIntervalsStayConvexAndExact) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double ds = std::pow(10.0, -3.0 - 3.0 * (trial % 7) / 6.0) * (1.0 + 0.5 * U(rng));  // ~1e-3 .. 1e-6
    const double h = 1.0 / (2.0 * ds);
    std::vector<Line> lines;
    std::vector<std::array<double, 4>> physical;  // a, b, c, and which end (0: s_k, 1: s_{k+1})
    const int joints = 1 + trial % 3;
    for (int j = 0; j < joints; ++j) {
      const double dq = U(rng), ddq = 4.0 * U(rng), dq1 = dq + ds * ddq, ddq1 = ddq + ds * U(rng);
      for (double sign : {1.0, -1.0}) {
        // forward row at s_k: (a - b h) x + b h y <= c; backward at s_{k+1}: -b h x + (a + b h) y <= c
        lines.push_back({sign * ddq - sign * dq * h, sign * dq * h, 1.0, j});
        physical.push_back({sign * ddq, sign * dq, 1.0, 0.0});
        lines.push_back({-sign * dq1 * h, sign * ddq1 + sign * dq1 * h, 1.0, j});
        physical.push_back({sign * ddq1, sign * dq1, 1.0, 1.0});
      }
    }
    const double top = 1.0 / (0.5 + 4.0 * std::abs(U(rng)));
    // As the reachability analysis builds it (interval_polygon): envelopes, or clipping where build declines.
    // (Clipping alone keeps vertices within kTol of the chain's terms, 1/Δs larger than the physical ones.)
    for (int how = 0; how < 1; ++how) {
      Polygon2d p;
      if (!p.build(0.0, 10.0, 0.0, top, lines.data(), lines.size())) {
        p.reset(0.0, 10.0, 0.0, top);
        for (const Line& l : lines) p.clip(l);
      }
      if (p.empty()) continue;
      ++checked;
      const auto v = p.vertices();
      const std::size_t m = v.size();
      // Convex: x changes direction twice around the cycle.
      int turns = 0, dir = 0, first = 0;
      for (std::size_t i = 0; i < m; ++i) {
        const double d = v[(i + 1) % m].x - v[i].x;
        const int s = d > 0 ? 1 : d < 0 ? -1 : 0;
        if (s == 0) continue;
        if (dir == 0) first = s;
        else if (s != dir) ++turns;
        dir = s;
      }
      if (dir != 0 && dir != first) ++turns;
      EXPECT_LE(turns, 2) << "trial " << trial << " how " << how << " ds " << ds;
      for (const Vertex& w : v) {
        EXPECT_LE(w.y, top * (1 + 1e-15)) << "trial " << trial;
        for (const auto& r : physical) {
          const double theta = r[3] == 0.0 ? w.x : w.y, u = (w.y - w.x) * h;
          const double d = r[0] * theta + r[1] * u - r[2];
          // θ resolves s̈ only to ~eps θ / (2Δs) (see detail::grid_violation): that, and 1e-12 of the terms.
          const double scale = std::abs(r[0] * theta) + std::abs(r[1] * u) + std::abs(r[2]) +
                               std::abs(r[1]) * 3.5e-6 * h * std::max(std::abs(w.x), std::abs(w.y));
          EXPECT_LE(d, 1e-9 * scale) << "trial " << trial << " how " << how << " ds " << ds << " vertex (" << w.x
                                     << ", " << w.y << ")";
        }
      }
    }
  }
  EXPECT_GT(checked, 1500);
}
