// Polytope projection by recursive expansion (sec. IV.C) on polytopes whose shadows are known.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glpk.h>

#include "geometry/convex_hull.hpp"
#include "lp/projection.hpp"
#include "pathpace/pathpace.hpp"
#include "test_fixtures.hpp"

using namespace pathpace::detail;
using pathpace::test::beyond_stand_in;
using pathpace::test::octahedron;
using pathpace::test::one_row_lp;
using pathpace::test::support;

TEST(Projection, OctahedronShadowIsTheDiamond) {
  const Projection p = project_polytope(octahedron());
  ASSERT_EQ(p.outcome, Projection::Outcome::Polygon);
  EXPECT_EQ(p.halfplanes.size(), 4u);
  for (int k = 0; k < 64; ++k) {
    const double a = 2 * M_PI * k / 64;
    EXPECT_NEAR(support(p, std::cos(a), std::sin(a)), std::max(std::abs(std::cos(a)), std::abs(std::sin(a))), 1e-9);
  }
  // Every half-plane holds at every vertex and supports an edge.
  for (const Line& h : p.halfplanes) {
    int on = 0;
    for (const Vertex& v : p.vertices) {
      EXPECT_LE(h.a * v.x + h.b * v.y, h.c + 1e-9);
      on += std::abs(h.a * v.x + h.b * v.y - h.c) < 1e-9;
    }
    EXPECT_GE(on, 2);
  }
}

TEST(Projection, EqualityRowsAndBoundsAreRespected) {
  // x = y + 0.5 u, 0 <= y <= 1, -1 <= u <= 1, x <= 1.2: shadow {(x, u): 0.5u <= x <= 1 + 0.5u, x <= 1.2, |u| <= 1}.
  PolytopeLp lp;
  lp.A.resize(2, 3);
  lp.A.row(0) << 1, -0.5, -1;  // x - 0.5 u - y = 0
  lp.A.row(1) << 1, 0, 0;      // x <= 1.2
  lp.row_lo = Eigen::Vector2d(0, -INFINITY);
  lp.row_hi = Eigen::Vector2d(0, 1.2);
  lp.col_lo = Eigen::Vector3d(-INFINITY, -1, 0);
  lp.col_hi = Eigen::Vector3d(INFINITY, 1, 1);
  const Projection p = project_polytope(lp);
  ASSERT_EQ(p.outcome, Projection::Outcome::Polygon);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(-2, 2);
  for (int k = 0; k < 2000; ++k) {
    const double x = U(gen), u = U(gen);
    const bool truth = 0.5 * u <= x && x <= 1 + 0.5 * u && x <= 1.2 && std::abs(u) <= 1;
    bool inside = true;
    for (const Line& h : p.halfplanes) inside &= h.a * x + h.b * u <= h.c + 1e-12;
    if (std::abs(x - 0.5 * u) > 1e-6 && std::abs(x - 1 - 0.5 * u) > 1e-6 && std::abs(x - 1.2) > 1e-6 &&
        std::abs(std::abs(u) - 1) > 1e-6)
      EXPECT_EQ(inside, truth) << x << " " << u;
  }
}

TEST(Projection, EmptyPolytopeIsReported) {
  PolytopeLp lp = octahedron();
  lp.col_lo[2] = 2.0;  // y >= 2 contradicts |y| <= 1
  EXPECT_EQ(project_polytope(lp).outcome, Projection::Outcome::Empty);
}

TEST(Projection, ShadowBeyondTheStandInBoundsIsFoundNotCalledEmpty) {
  // y = 1e-8 u with 100 <= y <= 200 and 0 <= x <= 1: the shadow is the rectangle [0, 1] x [1e10, 2e10],
  // entirely beyond the stand-in bounds |u| <= 1e6 (a grid point where b ~ 1e-8: Talos swaying with
  // 90 N per sole corner). Those bounds mean "no limit": the projection must not call it empty.
  PolytopeLp lp = beyond_stand_in();
  PolytopeProjector projector;
  for (int round = 0; round < 2; ++round) {  // cold, then warm from the grown problem's basis
    const Projection p = projector.project(lp);
    ASSERT_EQ(p.outcome, Projection::Outcome::Polygon) << p.note;
    // Every edge was certified, yet it is reported inexact: such shadows come from b ~ 1e-8 (see there).
    EXPECT_FALSE(p.complete);
    EXPECT_NE(p.note.find("beyond the stand-in bounds"), std::string::npos) << p.note;
    EXPECT_GE(p.stand_in, 2e10);
    // Exact to the projection's tolerance, 1e-9 of the polygon's size (1e10 along u).
    for (int d = 0; d < 16; ++d) {
      const double dx = std::cos(0.4 * d), du = std::sin(0.4 * d);
      const double ref = std::max(0.0, dx) + std::max(1e10 * du, 2e10 * du);
      EXPECT_NEAR(support(p, dx, du), ref, p.tolerance) << d;
      EXPECT_LE(p.tolerance, 1e-9 * 1e10 + 1e-6);
    }
  }
  // Truly empty with the same stand-in bounds (y <= 200 and y >= 300): still empty.
  lp.A.row(1) << 0, 0, 1;
  lp.row_lo[1] = 300;
  lp.row_hi[1] = INFINITY;
  EXPECT_EQ(projector.project(lp).outcome, Projection::Outcome::Empty);
}

TEST(Projection, WarmProjectorAlongASequenceMatchesColdProjections) {
  // A family of rotated, scaled octahedra (one per "grid point"), projected with one warm projector
  // and each from scratch: the same polygons.
  PolytopeProjector warm;
  for (int k = 0; k < 20; ++k) {
    PolytopeLp lp = octahedron();
    const double ang = 0.07 * k, scale = 1.0 + 0.1 * k;
    Eigen::Matrix2d R;
    R << std::cos(ang), -std::sin(ang), std::sin(ang), std::cos(ang);
    lp.A.leftCols(2) = lp.A.leftCols(2) * R / scale;
    const Projection a = warm.project(lp), b = project_polytope(lp);
    ASSERT_EQ(a.outcome, Projection::Outcome::Polygon);
    ASSERT_EQ(b.outcome, Projection::Outcome::Polygon);
    for (int d = 0; d < 32; ++d) {
      const double dx = std::cos(0.2 * d), du = std::sin(0.2 * d);
      EXPECT_NEAR(support(a, dx, du), support(b, dx, du), 1e-9);
    }
    EXPECT_NEAR(support(a, 1.0, 0.0), scale * std::max(std::abs(std::cos(ang)), std::abs(std::sin(ang))) , 1e-9);
  }
}

namespace {

// A square [-1, 1]² whose corners are rounded with radius r by `per_corner` vertices each: a polygon
// with 4·per_corner vertices and edges of about r·(π/2)/per_corner (micrometres for r = 3e-5).
std::vector<Vertex> rounded_square(int per_corner, double r) {
  std::vector<Vertex> v;
  const double cx[4] = {1 - r, -1 + r, -1 + r, 1 - r}, cy[4] = {1 - r, 1 - r, -1 + r, -1 + r};
  for (int c = 0; c < 4; ++c)
    for (int i = 0; i < per_corner; ++i) {
      const double ang = M_PI / 2 * c + M_PI / 2 * i / (per_corner - 1);
      v.push_back({cx[c] + r * std::cos(ang), cy[c] + r * std::sin(ang)});
    }
  return v;
}

// The polytope {(x, u, y): polygon's half-planes on (x, u), y = x + u, |y| <= 10}: its shadow is the
// polygon (counter-clockwise vertices).
PolytopeLp lifted_polygon(const std::vector<Vertex>& v) {
  const int m = static_cast<int>(v.size());
  PolytopeLp lp;
  lp.A.setZero(m + 1, 3);
  lp.row_lo = Eigen::VectorXd::Constant(m + 1, -INFINITY);
  lp.row_hi.resize(m + 1);
  for (int i = 0; i < m; ++i) {
    const Vertex &a = v[static_cast<size_t>(i)], &b = v[static_cast<size_t>((i + 1) % m)];
    const double len = std::hypot(b.y - a.y, b.x - a.x), nx = (b.y - a.y) / len, nu = -(b.x - a.x) / len;
    lp.A.row(i) << nx, nu, 0;
    lp.row_hi[i] = nx * a.x + nu * a.y;
  }
  lp.A.row(m) << 1, 1, -1;
  lp.row_lo[m] = lp.row_hi[m] = 0;
  lp.col_lo = Eigen::Vector3d(-INFINITY, -INFINITY, -10);
  lp.col_hi = Eigen::Vector3d(INFINITY, INFINITY, 10);
  return lp;
}

}  // namespace

TEST(Projection, MicrometreEdgesOfA160GonAreAllFoundAndCertified) {
  const std::vector<Vertex> truth = rounded_square(40, 3e-5);
  double shortest = INFINITY;
  for (size_t i = 0; i < truth.size(); ++i)
    shortest = std::min(shortest, std::hypot(truth[(i + 1) % truth.size()].x - truth[i].x,
                                             truth[(i + 1) % truth.size()].y - truth[i].y));
  ASSERT_LT(shortest, 2e-6);
  const Projection p = project_polytope(lifted_polygon(truth));
  ASSERT_EQ(p.outcome, Projection::Outcome::Polygon);
  EXPECT_TRUE(p.complete) << p.note;
  // Every true vertex, and perhaps a few points on long edges that were outside the hull when found.
  EXPECT_GE(p.vertices.size(), truth.size());
  EXPECT_LE(p.vertices.size(), truth.size() + 8);
  EXPECT_EQ(p.halfplanes.size(), p.vertices.size());
  // Every true vertex is a vertex of the projection (to 1e-9 of the size 2).
  for (const Vertex& t : truth) {
    double best = INFINITY;
    for (const Vertex& v : p.vertices) best = std::min(best, std::hypot(v.x - t.x, v.y - t.y));
    EXPECT_LT(best, 2e-9);
  }
  // Support values in 256 directions.
  for (int d = 0; d < 256; ++d) {
    const double dx = std::cos(2 * M_PI * d / 256), du = std::sin(2 * M_PI * d / 256);
    double ref = -INFINITY;
    for (const Vertex& t : truth) ref = std::max(ref, dx * t.x + du * t.y);
    EXPECT_NEAR(support(p, dx, du), ref, 2e-9);
  }
}

TEST(Projection, BudgetExhaustionIsReportedAndKeepsAnInnerHull) {
  const std::vector<Vertex> truth = rounded_square(40, 3e-5);
  const PolytopeLp lp = lifted_polygon(truth);
  const Projection p = project_polytope(lp, 1e-9, 20);
  ASSERT_EQ(p.outcome, Projection::Outcome::Polygon);
  EXPECT_FALSE(p.complete);
  EXPECT_NE(p.note.find("budget"), std::string::npos) << p.note;
  EXPECT_EQ(p.lp_solves, 20);
  EXPECT_GE(p.vertices.size(), 3u);
  // Inner: every vertex found lies in the true polygon.
  for (const Vertex& v : p.vertices)
    for (int i = 0; i < lp.A.rows() - 1; ++i) EXPECT_LE(lp.A(i, 0) * v.x + lp.A(i, 1) * v.y, lp.row_hi[i] + 1e-12);
}

TEST(Projection, SegmentAndPointShadowsAreClosed) {
  // x = u (y = x - u = 0), 0 <= x <= 1: the shadow is the segment from (0, 0) to (1, 1).
  PolytopeLp lp;
  lp.A.resize(1, 3);
  lp.A.row(0) << 1, -1, -1;
  lp.row_lo = lp.row_hi = Eigen::VectorXd::Zero(1);
  lp.col_lo = Eigen::Vector3d(0, -INFINITY, 0);
  lp.col_hi = Eigen::Vector3d(1, INFINITY, 0);
  Projection p = project_polytope(lp);
  ASSERT_EQ(p.outcome, Projection::Outcome::Polygon);
  EXPECT_TRUE(p.complete);
  ASSERT_EQ(p.vertices.size(), 2u);
  EXPECT_EQ(p.halfplanes.size(), 4u);  // two sides and two ends
  for (int d = 0; d < 16; ++d) {
    const double dx = std::cos(0.4 * d), du = std::sin(0.4 * d);
    EXPECT_NEAR(support(p, dx, du), std::max(0.0, dx + du), 1e-12);
  }
  const double ins[2][2] = {{0.5, 0.5}, {1.0, 1.0}}, outs[3][2] = {{0.5, 0.6}, {1.1, 1.1}, {-0.1, -0.1}};
  for (const auto& z : ins)
    for (const Line& h : p.halfplanes) EXPECT_LE(h.a * z[0] + h.b * z[1], h.c + 1e-12);
  for (const auto& z : outs) {
    bool cut = false;
    for (const Line& h : p.halfplanes) cut |= h.a * z[0] + h.b * z[1] > h.c + 1e-9;
    EXPECT_TRUE(cut) << z[0] << " " << z[1];
  }
  lp.col_hi[0] = 0;  // now only (0, 0)
  p = project_polytope(lp);
  ASSERT_EQ(p.outcome, Projection::Outcome::Polygon);
  ASSERT_EQ(p.vertices.size(), 1u);
  EXPECT_EQ(p.halfplanes.size(), 4u);
  EXPECT_EQ(p.lp_solves, 3);
}

TEST(Projection, FeasibilityLpWithAFixedPoint) {
  PolytopeProjector solver;
  const PolytopeLp lp = octahedron();
  const double inside[2] = {0.3, -0.3}, outside[2] = {0.8, 0.8};
  EXPECT_EQ(solver.feasible(lp), 1);
  EXPECT_EQ(solver.feasible(lp, inside), 1);
  EXPECT_EQ(solver.feasible(lp, outside), 0);
  EXPECT_EQ(solver.feasible(lp), 1);  // the fixed point is not left behind
}

TEST(Projection, ConvexHullDropsInteriorCollinearAndDuplicatePoints) {
  const std::vector<Vertex> pts = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {1, 1}, {0, 0}};
  std::vector<int> order;
  convex_hull(pts, order);
  ASSERT_EQ(order.size(), 4u);
  EXPECT_EQ(order[0], 0);  // lowest x, then lowest y; counter-clockwise
  EXPECT_EQ(order[1], 1);
  EXPECT_EQ(order[2], 2);
  EXPECT_EQ(order[3], 3);
}

TEST(Projection, A160GonWithMicrometreEdgesSurvivesPruningIntoTheFeasibleSet) {
  // The projected rounded square, shifted to x in [1, 3], as a constraint of a time-scaling problem:
  // the per-grid-point pruning (sec. IV.A) keeps every one of its edges.
  std::vector<Vertex> truth = rounded_square(40, 3e-5);
  for (Vertex& v : truth) v.x += 2.0;
  const Projection p = project_polytope(lifted_polygon(truth));
  ASSERT_TRUE(p.complete);
  const Eigen::Index r = static_cast<Eigen::Index>(p.halfplanes.size());
  ASSERT_GE(r, 160);
  Eigen::MatrixXd A(2, r), B(2, r), C = Eigen::MatrixXd::Zero(2, r), lo(2, r), hi(2, r);
  for (Eigen::Index j = 0; j < r; ++j) {
    const Line& h = p.halfplanes[static_cast<size_t>(j)];
    A.col(j).setConstant(h.a);
    B.col(j).setConstant(h.b);
    hi.col(j).setConstant(h.c);
  }
  lo.setConstant(-INFINITY);
  Eigen::MatrixXd q(2, 1), dq(2, 1), ddq = Eigen::MatrixXd::Zero(2, 1);
  q << 0, 1;
  dq << 1, 1;
  auto path = std::make_shared<pathpace::SampledPath>(Eigen::Vector2d(0, 1), q, dq, ddq);
  pathpace::TimeScalingProblem prob(path, 1);
  prob.add_linear_constraint(A, B, C, lo, hi);
  const pathpace::FeasibleSet fs = prob.feasible_set(0);
  ASSERT_FALSE(fs.empty);
  // Two sides are bounds on x alone (folded into x_min / x_max), every other edge is a half-plane.
  EXPECT_GE(fs.halfplanes.rows() + 2, 160);
  EXPECT_EQ(fs.vertices.rows(), r);
  for (int d = 0; d < 256; ++d) {
    const double dx = std::cos(2 * M_PI * d / 256), du = std::sin(2 * M_PI * d / 256);
    double ref = -INFINITY, got = -INFINITY;
    for (const Vertex& t : truth) ref = std::max(ref, dx * t.x + du * t.y);
    for (Eigen::Index i = 0; i < fs.vertices.rows(); ++i) got = std::max(got, dx * fs.vertices(i, 0) + du * fs.vertices(i, 1));
    EXPECT_NEAR(got, ref, 2e-9);
  }
}

TEST(Projection, RangingCertificatesGiveTheSamePolygonsWithAboutOneLpPerEdge) {
  // The 160-gon and a sequence of random lifted polygons (one projector, warm across them), with edges
  // certified by their endpoints' bases (ranging) and each by its own LP: the same vertices, and the
  // ranging needs about one LP per edge where the LPs alone need about two. GLPK in both (the vertices
  // are compared to 1e-12: the dense simplex's degenerate optima may be other points of a micrometre
  // edge); the dense simplex's polygons (the default) match in support value to 1e-9 of the size.
  std::mt19937 gen(27);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  PolytopeProjector with, without, dense;
  with.dense = false;
  without.ranging = false;
  for (int k = 0; k < 12; ++k) {
    std::vector<Vertex> truth;
    if (k == 0) {
      truth = rounded_square(40, 3e-5);
    } else {
      const int m = 12 + 4 * k;
      for (int i = 0; i < m; ++i) {
        const double a = 2 * M_PI * (i + 0.5 + jitter(gen)) / m;
        truth.push_back({std::cos(a) * (2.0 + k), 0.5 * std::sin(a)});
      }
    }
    // 30 more columns z_j in [0, 1] with rows z_j - 0.01 y <= 1 (always met: the shadow is the polygon's),
    // so that the LP is large enough for the ranging (30 columns).
    const PolytopeLp small = lifted_polygon(truth);
    PolytopeLp lp;
    const int r0 = static_cast<int>(small.A.rows()), extra = 30;
    lp.A.setZero(r0 + extra, 3 + extra);
    lp.A.topLeftCorner(r0, 3) = small.A;
    lp.row_lo = Eigen::VectorXd::Constant(r0 + extra, -INFINITY);
    lp.row_hi = Eigen::VectorXd::Ones(r0 + extra);
    lp.row_lo.head(r0) = small.row_lo;
    lp.row_hi.head(r0) = small.row_hi;
    lp.col_lo = Eigen::VectorXd::Zero(3 + extra);
    lp.col_hi = Eigen::VectorXd::Ones(3 + extra);
    lp.col_lo.head(3) = small.col_lo;
    lp.col_hi.head(3) = small.col_hi;
    for (int j = 0; j < extra; ++j) {
      lp.A(r0 + j, 3 + j) = 1.0;
      lp.A(r0 + j, 2) = -0.01;
    }
    const Projection a = with.project(lp), b = without.project(lp);
    ASSERT_TRUE(a.complete && b.complete) << a.note << b.note;
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    for (size_t i = 0; i < a.vertices.size(); ++i) {
      EXPECT_NEAR(a.vertices[i].x, b.vertices[i].x, 1e-12 * (2.0 + k));
      EXPECT_NEAR(a.vertices[i].y, b.vertices[i].y, 1e-12 * (2.0 + k));
    }
    const Projection c = dense.project(lp);
    ASSERT_TRUE(c.complete) << c.note;
    EXPECT_GT(c.by_cause.dense, 0);
    for (int d = 0; d < 256; ++d) {
      const double dx = std::cos(2 * M_PI * (d + 0.5) / 256), du = std::sin(2 * M_PI * (d + 0.5) / 256);
      EXPECT_NEAR(support(c, dx, du), support(b, dx, du), 1e-9 * 2.0 * (2.0 + k)) << "polygon " << k << " direction " << d;
    }
    const int edges = static_cast<int>(a.halfplanes.size());
    EXPECT_GT(a.by_cause.ranged, edges / 2);
    EXPECT_LE(a.lp_solves, edges + 6);
    EXPECT_GE(b.lp_solves, 2 * edges - 3);
    EXPECT_EQ(a.lp_solves, a.by_cause.initial + a.by_cause.vertex + a.by_cause.certificate + a.by_cause.cap_growth);
    EXPECT_EQ(b.by_cause.ranged, 0);
  }
}

TEST(Projection, ApproximationKeepsAnInnerPolygonWithinEpsilonOfTheShadowWithFewerLps) {
  // Round polygons (many short edges: where the expansion spends its LPs) projected exactly and with
  // projection_tolerance ε: the approximate polygon lies inside the exact one (every vertex), its support
  // function is within ε times the polygon's size of the true one in 1024 directions, and it takes
  // fewer LPs; ε = 0 is the exact projection itself.
  std::mt19937 gen(4);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int trial = 0; trial < 6; ++trial) {
    const int m = 100 + 60 * trial;
    std::vector<Vertex> truth;
    for (int i = 0; i < m; ++i) {
      const double a = 2 * M_PI * (i + 0.5 + jitter(gen)) / m;
      truth.push_back({3.0 * std::cos(a) + 1.0, (1.0 + trial) * std::sin(a) - 2.0});
    }
    double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
    for (const Vertex& t : truth) xlo = std::min(xlo, t.x), xhi = std::max(xhi, t.x), ylo = std::min(ylo, t.y), yhi = std::max(yhi, t.y);
    const double size = std::max(xhi - xlo, yhi - ylo);
    const PolytopeLp lp = lifted_polygon(truth);
    const Projection exact = project_polytope(lp, 1e-9, 2000, 0.0);
    ASSERT_TRUE(exact.complete) << exact.note;
    EXPECT_EQ(exact.approximate_edges, 0);
    for (double eps : {1e-4, 1e-3, 1e-2}) {
      const Projection p = project_polytope(lp, 1e-9, 2000, eps);
      ASSERT_EQ(p.outcome, Projection::Outcome::Polygon);
      ASSERT_TRUE(p.complete) << p.note;
      EXPECT_GT(p.approximate_edges, 0) << "eps " << eps << " trial " << trial;
      EXPECT_LT(p.lp_solves, exact.lp_solves) << "eps " << eps << " trial " << trial;
      double worst = 0.0;
      for (int d = 0; d < 1024; ++d) {
        const double dx = std::cos(2 * M_PI * (d + 0.37) / 1024), du = std::sin(2 * M_PI * (d + 0.37) / 1024);
        double ref = -INFINITY;
        for (const Vertex& t : truth) ref = std::max(ref, dx * t.x + du * t.y);
        const double gap = ref - support(p, dx, du);
        EXPECT_GE(gap, -1e-9 * size);  // inner
        worst = std::max(worst, gap);
      }
      EXPECT_LE(worst, eps * size) << "eps " << eps << " trial " << trial;
      // Not trivially inner: the bound is used (the worst gap is a fair share of it) at the larger ε.
      if (eps >= 1e-2) EXPECT_GT(worst, 0.05 * eps * size) << "trial " << trial;
      for (const Vertex& v : p.vertices)
        for (int i = 0; i < lp.A.rows() - 1; ++i) EXPECT_LE(lp.A(i, 0) * v.x + lp.A(i, 1) * v.y, lp.row_hi[i] + 1e-9 * size);
    }
  }
}

namespace {

// A random polytope of the projection LPs' shape: x, u and 80 columns y in [0, 1]; 40 ranged rows
// lo <= a x + b u + G y <= hi around a point that satisfies them all (so it is not empty), and the
// stand-in bounds on x and u.
PolytopeLp random_polytope(std::mt19937& gen) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int rows = 40, cols = 82;
  PolytopeLp lp;
  lp.A.resize(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) lp.A(i, j) = unit(gen) < 0.7 ? g(gen) : 0.0;
  Eigen::VectorXd z(cols);
  z[0] = unit(gen);
  z[1] = g(gen);
  for (int j = 2; j < cols; ++j) z[j] = unit(gen);
  const Eigen::VectorXd r = lp.A * z;
  lp.row_lo = r.array() - 0.5 - Eigen::ArrayXd::NullaryExpr(rows, [&] { return 2.0 * unit(gen); });
  lp.row_hi = r.array() + 0.5 + Eigen::ArrayXd::NullaryExpr(rows, [&] { return 2.0 * unit(gen); });
  lp.col_lo = Eigen::VectorXd::Zero(cols);
  lp.col_hi = Eigen::VectorXd::Ones(cols);
  lp.col_lo[0] = 0.0, lp.col_hi[0] = 1e6, lp.col_lo[1] = -1e6, lp.col_hi[1] = 1e6;
  lp.stand_in = 1e6;
  return lp;
}

// The larger side of b's bounding box, after checking a's support values against b's in 256 directions to
// 1e-9 of it (the projection's tolerance relative to the polygon's size).
double expect_same_support(const Projection& a, const Projection& b, int k) {
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  for (const Vertex& v : b.vertices) xlo = std::min(xlo, v.x), xhi = std::max(xhi, v.x), ylo = std::min(ylo, v.y), yhi = std::max(yhi, v.y);
  const double size = std::max(xhi - xlo, yhi - ylo);
  for (int d = 0; d < 256; ++d) {
    const double dx = std::cos(2 * M_PI * (d + 0.5) / 256), du = std::sin(2 * M_PI * (d + 0.5) / 256);
    EXPECT_NEAR(support(a, dx, du), support(b, dx, du), 1e-9 * size) << "polytope " << k << " direction " << d;
  }
  return size;
}

}  // namespace

TEST(Projection, RandomPolytopesGiveTheSamePolygonsWarmAndCold) {
  // A sequence of random polytopes of one shape, through one projector (warm across them, ranging on)
  // and each from a cold start: the same polygons (support values to 1e-9 of the size in 256
  // directions), whatever basis each LP started from.
  std::mt19937 gen(2);
  PolytopeProjector warm;
  for (int k = 0; k < 10; ++k) {
    const PolytopeLp lp = random_polytope(gen);
    const Projection a = warm.project(lp), b = project_polytope(lp);
    ASSERT_EQ(a.outcome, Projection::Outcome::Polygon);
    ASSERT_EQ(b.outcome, Projection::Outcome::Polygon);
    ASSERT_TRUE(a.complete && b.complete) << a.note << b.note;
    const double size = expect_same_support(a, b, k);
    ASSERT_GT(size, 0.0);
    EXPECT_GE(a.vertices.size(), 8u);
    if (k > 0) EXPECT_GT(a.by_cause.ranged, 0);  // the ranging path is among those compared
  }
}

namespace {

// Checks one focused projection against the full one of the same polytope (to 1e-9 of its size): the outer
// polygon holds the shadow, the hull lies in it, and every focus point is settled: one well inside the shadow
// is inside the hull, one well outside it is cut off by an outer half-plane.
void expect_focus_contract(const Projection& r, const Projection& full, const std::vector<Vertex>& focus, int k) {
  ASSERT_EQ(r.outcome, Projection::Outcome::Polygon) << r.note;
  ASSERT_TRUE(r.complete) << r.note;
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  for (const Vertex& v : full.vertices) xlo = std::min(xlo, v.x), xhi = std::max(xhi, v.x), ylo = std::min(ylo, v.y), yhi = std::max(yhi, v.y);
  const double size = std::max(xhi - xlo, yhi - ylo), tol = 1e-9 * size;
  for (const Line& h : r.halfplanes) EXPECT_LE(support(full, h.a, h.b), h.c + tol) << "polytope " << k;
  auto inside = [&](const std::vector<Line>& rows, const Vertex& q, double margin) {
    for (const Line& h : rows)
      if (h.a * q.x + h.b * q.y > h.c + margin) return false;
    return true;
  };
  for (const Vertex& v : r.vertices) EXPECT_TRUE(inside(full.halfplanes, v, tol)) << "polytope " << k;
  ASSERT_EQ(r.hull.size(), r.hull_certified.size());
  for (const Vertex& q : focus) {
    if (inside(full.halfplanes, q, -1e-6 * size)) EXPECT_TRUE(inside(r.hull, q, tol)) << "polytope " << k;
    if (!inside(full.halfplanes, q, 1e-6 * size)) EXPECT_FALSE(inside(r.halfplanes, q, 0.0)) << "polytope " << k;
  }
}

}  // namespace

TEST(Projection, FocusedProjectionBracketsTheShadowSettlesItsPointsAndResumes) {
  // project_on_demand's projections: random polytopes of the projection LPs' shape (the dense simplex on,
  // the initial LPs warm from the previous polytope's), focus points inside and outside each shadow (a
  // vertex of it scaled about the centre by 0.5 ... 2), first three of them, then all six from where the
  // first call left off: both meet the contract; the second call spends no initial LP and fewer LPs than a
  // fresh call with all six; and the focused calls fewer than the full projection.
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PolytopeProjector projector;
  int focused = 0, full_lps = 0;
  for (int k = 0; k < 10; ++k) {
    const PolytopeLp lp = random_polytope(gen);
    const Projection full = project_polytope(lp);
    ASSERT_TRUE(full.complete);
    Vertex c{0.0, 0.0};
    for (const Vertex& v : full.vertices) c.x += v.x / full.vertices.size(), c.y += v.y / full.vertices.size();
    std::vector<Vertex> focus;
    const double scales[6] = {0.5, 2.0, 0.9, 1.2, 0.99, 1.05};
    for (double t : scales) {
      const Vertex& v = full.vertices[static_cast<size_t>(unit(gen) * full.vertices.size()) % full.vertices.size()];
      focus.push_back({c.x + t * (v.x - c.x), c.y + t * (v.y - c.y)});
    }
    const std::vector<Vertex> first(focus.begin(), focus.begin() + 3);
    ProjectionState state;
    const Projection a = projector.project(lp, 1e-9, 2000, 0.0, &first, &state);
    expect_focus_contract(a, full, first, k);
    ASSERT_TRUE(state.resumable);
    const Projection b = projector.project(lp, 1e-9, 2000, 0.0, &focus, &state);
    expect_focus_contract(b, full, focus, k);
    const Projection fresh = project_polytope(lp, 1e-9, 2000, 0.0, &focus);
    expect_focus_contract(fresh, full, focus, k);
    EXPECT_EQ(b.by_cause.initial, 0);
    EXPECT_LT(b.lp_solves, fresh.lp_solves) << "polytope " << k;
    focused += a.lp_solves + b.lp_solves;
    full_lps += full.lp_solves;
  }
  EXPECT_LT(focused, full_lps);
}

TEST(Projection, DenseSimplexGivesTheSamePolygonsAsGlpkAndEveryVertexIsInThePolytope) {
  // Random polytopes through a projector with the dense simplex (the default) and one with GLPK alone:
  // the same polygons (support values to 1e-9 of the size in 256 directions), most LPs solved by the
  // dense simplex, and every vertex (x, u) extends to a point of the polytope (one LP with (x, u) fixed:
  // the certificate's primal feasibility, checked by an independent solve).
  std::mt19937 gen(5);
  PolytopeProjector with, without, check;
  without.dense = false;
  int dense = 0, total = 0;
  for (int k = 0; k < 10; ++k) {
    const PolytopeLp lp = random_polytope(gen);
    const Projection a = with.project(lp), b = without.project(lp);
    ASSERT_EQ(a.outcome, Projection::Outcome::Polygon);
    ASSERT_EQ(b.outcome, Projection::Outcome::Polygon);
    ASSERT_TRUE(a.complete && b.complete) << a.note << b.note;
    EXPECT_EQ(b.by_cause.dense, 0);
    const double size = expect_same_support(a, b, k);
    ASSERT_GT(size, 0.0);
    for (const Vertex& v : a.vertices) {  // within 1e-9 of the size: the projection's own tolerance
      PolytopeLp near = lp;
      near.col_lo[0] = v.x - 1e-9 * size, near.col_hi[0] = v.x + 1e-9 * size;
      near.col_lo[1] = v.y - 1e-9 * size, near.col_hi[1] = v.y + 1e-9 * size;
      EXPECT_EQ(check.feasible(near), 1) << "polytope " << k << " vertex " << v.x << ", " << v.y;
    }
    EXPECT_GE(a.vertices.size(), 8u);
    dense += a.by_cause.dense;
    total += a.lp_solves;
    const pathpace::LpCounts& c = a.by_cause;
    EXPECT_EQ(c.dense_fallback, c.fallback_cap + c.fallback_small_pivot + c.fallback_unbounded +
                                    c.fallback_singular + c.fallback_certificate);
  }
  EXPECT_GT(dense, total / 2);
}

TEST(Projection, EveryDenseFallbackIsCountedByItsCauseAndGlpkGivesTheSamePolygon) {
  // With no pivot allowed the dense simplex gives back every LP that is not optimal at its start: each
  // counted as a fallback by its cause (the pivot cap), none by another, and GLPK's answers make the
  // same polygon as GLPK alone.
  std::mt19937 gen(5);
  PolytopeProjector capped, without;
  capped.dense_limits().max_pivots = 0;
  without.dense = false;
  int fallbacks = 0;
  for (int k = 0; k < 5; ++k) {
    const PolytopeLp lp = random_polytope(gen);
    const Projection a = capped.project(lp), b = without.project(lp);
    ASSERT_EQ(a.outcome, Projection::Outcome::Polygon);
    ASSERT_TRUE(a.complete) << a.note;
    expect_same_support(a, b, k);
    const pathpace::LpCounts& c = a.by_cause;
    EXPECT_EQ(c.fallback_cap, c.dense_fallback);
    EXPECT_EQ(c.fallback_small_pivot + c.fallback_unbounded + c.fallback_singular + c.fallback_certificate, 0);
    fallbacks += c.dense_fallback;
  }
  EXPECT_GT(fallbacks, 0);
}

namespace {
// 0 <= x (no upper bound), 0 <= u <= 1, row 0: x + u <= 1.5; the basis: the row's auxiliary basic, x and u
// at their lower bounds (the point (0, 0)). Variables in GLPK's order: the auxiliary 0, x 1, u 2.
PolytopeLp wedge() { return one_row_lp(1, 1, -INFINITY, 1.5, Eigen::Vector2d(0, 0), Eigen::Vector2d(INFINITY, 1)); }
const signed char kWedgeStart[] = {GLP_BS, GLP_NL, GLP_NL};
}  // namespace

TEST(DenseSimplex, FindsAndCertifiesTheWedgesOptimum) {
  const PolytopeLp lp = wedge();
  DenseSimplex ds;
  ds.load(lp);
  ASSERT_TRUE(ds.set_basis(kWedgeStart));
  ASSERT_EQ(ds.maximize(0.0, 1.0), DenseSimplex::kOptimal);  // u to its bound 1 (a flip)
  EXPECT_EQ(ds.u(), 1.0);
  ASSERT_EQ(ds.maximize(1.0, 0.0), DenseSimplex::kOptimal);  // x to the row's 1.5, u back to 0
  EXPECT_NEAR(ds.x(), 1.5, 1e-15);
  EXPECT_NEAR(ds.u(), 0.0, 1e-15);
  EXPECT_EQ(ds.maximize(1.0, 0.0), DenseSimplex::kOptimal);  // already optimal: no pivot
}

TEST(DenseSimplex, EachWayOfGivingUpHasItsOwnOutcome) {
  const PolytopeLp lp = wedge();
  auto run = [&](auto setup, double vx, double vu) {
    DenseSimplex ds;
    ds.load(lp);
    EXPECT_TRUE(ds.set_basis(kWedgeStart));
    setup(ds);
    return ds.maximize(vx, vu);
  };
  DenseSimplex none;
  EXPECT_EQ(none.maximize(1.0, 0.0), DenseSimplex::kNoBasis);
  // The pivot cap: x must enter, no pivot is allowed.
  EXPECT_EQ(run([](DenseSimplex& ds) { ds.limits.max_pivots = 0; }, 1.0, 0.0), DenseSimplex::kIterationCap);
  // A pivot tolerance above the row's coefficient 1: the only row that stops x is passed over.
  EXPECT_EQ(run([](DenseSimplex& ds) { ds.limits.tol_pivot = 10.0; }, 1.0, 0.0), DenseSimplex::kSmallPivot);
  // Refactorised after every update, with no condition good enough: singular.
  EXPECT_EQ(run([](DenseSimplex& ds) { ds.limits.refactor = 1, ds.limits.min_rcond = 2.0; }, 1.0, 0.0),
            DenseSimplex::kSingular);
  // A start point outside u's bound (a stale state), already optimal along (-1, -1): the certificate fails.
  EXPECT_EQ(run([](DenseSimplex& ds) {
              DenseSimplex::State st = ds.state();
              st.value[2] = 5.0;
              ds.restore(st);
            }, -1.0, -1.0),
            DenseSimplex::kCertificate);
  // No row at all on x: a ray.
  PolytopeLp ray = lp;
  ray.A << 0, 1;
  DenseSimplex ds;
  ds.load(ray);
  ASSERT_TRUE(ds.set_basis(kWedgeStart));
  EXPECT_EQ(ds.maximize(1.0, 0.0), DenseSimplex::kUnbounded);
}

// A basis of three binding equality rows and three basic columns: B^-1 is A's own inverse, and A's zero
// diagonal makes the elimination exchange rows at every step (factorize's Gauss-Jordan inverse, with its
// column unscrambling); with A's third column the sum of the other two the basis is refused.
TEST(DenseSimplex, TheInverseOfABasisThatNeedsRowExchangesAndASingularOneRefused) {
  PolytopeLp lp;
  lp.A.resize(3, 3);
  lp.A << 0, 1, 2,
          1, 0, 3,
          4, 5, 0;
  lp.row_lo = lp.row_hi = Eigen::Vector3d(1, 2, 3);
  lp.col_lo = Eigen::Vector3d(0, -10, -INFINITY);
  lp.col_hi = Eigen::Vector3d(INFINITY, 10, INFINITY);
  const signed char stat[] = {GLP_NS, GLP_NS, GLP_NS, GLP_BS, GLP_BS, GLP_BS};
  DenseSimplex ds;
  ds.load(lp);
  ASSERT_TRUE(ds.set_basis(stat, false));
  const Eigen::MatrixXd I = ds.state().inv * lp.A;
  EXPECT_LT((I - Eigen::MatrixXd::Identity(3, 3)).cwiseAbs().maxCoeff(), 1e-15);
  // The basic values solve A z = b.
  const Eigen::Vector3d z(ds.state().value[3], ds.state().value[4], ds.state().value[5]);
  EXPECT_LT((lp.A * z - lp.row_lo).cwiseAbs().maxCoeff(), 1e-14);
  PolytopeLp singular = lp;
  singular.A.col(2) = singular.A.col(0) + singular.A.col(1);
  DenseSimplex ds2;
  ds2.load(singular);
  EXPECT_FALSE(ds2.set_basis(stat, false));
}

namespace {
// x >= 0, 0 <= u <= 1, and p columns w_j fixed at values of about +-1000 (alternating signs: the terms of
// a gravity row cancel the same way); row 0: x + Σ w_j = b, an equality whose solution x = 1.3 comes out
// of much larger terms; row 1: x + u <= 5. Basis: x and row 1's auxiliary (rows' and w's nonbasic).
struct CancellingRow {
  PolytopeLp lp;
  std::vector<signed char> start;
  explicit CancellingRow(int p) {
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> frac(0.0, 1.0);
    lp.A = Eigen::MatrixXd::Zero(2, 2 + p);
    lp.A(0, 0) = lp.A(1, 0) = lp.A(1, 1) = 1.0;
    lp.col_lo = Eigen::VectorXd::Zero(2 + p);
    lp.col_hi = Eigen::VectorXd::Constant(2 + p, INFINITY);
    lp.col_hi[1] = 1.0;
    double sum = 0.0;
    for (int j = 0; j < p; ++j) {
      lp.A(0, 2 + j) = 1.0;
      lp.col_lo[2 + j] = lp.col_hi[2 + j] = (j % 2 ? -1.0 : 1.0) * (1000.0 + frac(gen)) - (j % 2 ? 27.6 : 0.0);
      sum += lp.col_lo[2 + j];
    }
    lp.row_lo = Eigen::Vector2d(sum + 1.3, -INFINITY);
    lp.row_hi = Eigen::Vector2d(sum + 1.3, 5.0);
    start.assign(static_cast<size_t>(2 + 2 + p), GLP_NS);
    start[1] = GLP_BS;  // row 1's auxiliary
    start[2] = GLP_BS;  // x
    start[3] = GLP_NL;  // u
  }
};
}  // namespace

TEST(DenseSimplex, AnEqualityRowSummedWithCancellationIsCertifiedAndAViolatedOneIsNot) {
  // The row's double rounding bound (n + 2) u Σ |a_j z_j| exceeds GLPK's tolerance on its bound
  // (1e-10 + 1e-13 |b|), so a double evaluation cannot certify any point on it; the extended-precision
  // look does, and still rejects the row when it is off by 10 times the tolerance.
  const CancellingRow c(60);
  const double b = c.lp.row_lo[0], tol = 1e-10 + 1e-13 * std::abs(b);
  ASSERT_GT(b, -1000.0);
  ASSERT_LT(b, -600.0);  // a gravity-sized right side
  double magnitude = 1.3;
  for (int j = 2; j < c.lp.A.cols(); ++j) magnitude += std::abs(c.lp.col_lo[j]);
  ASSERT_GT((c.lp.A.cols() + 2) * std::numeric_limits<double>::epsilon() * magnitude, tol);  // the precondition
  DenseSimplex ds;
  ds.load(c.lp);
  ASSERT_TRUE(ds.set_basis(c.start.data()));
  ASSERT_EQ(ds.maximize(0.0, 1.0), DenseSimplex::kOptimal);  // u to its bound (a flip), then certified
  EXPECT_EQ(ds.u(), 1.0);
  EXPECT_NEAR(ds.x(), 1.3, 1e-11);
  // A stale state whose row 0 sits 10 tolerances off its bound: x follows it, the row does not hold.
  DenseSimplex off;
  off.load(c.lp);
  ASSERT_TRUE(off.set_basis(c.start.data()));
  DenseSimplex::State st = off.state();
  st.value[0] = b + 10 * tol;
  off.restore(st);
  EXPECT_EQ(off.maximize(0.0, 1.0), DenseSimplex::kCertificate);
}
