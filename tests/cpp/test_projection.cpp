// Polytope projection by recursive expansion (sec. IV.C) on polytopes whose shadows are known.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "detail/projection.hpp"

using namespace pathpace::detail;

namespace {

double support(const Projection& p, double dx, double du) {
  double best = -INFINITY;
  for (const Vertex& v : p.vertices) best = std::max(best, dx * v.x + du * v.y);
  return best;
}

PolytopeLp octahedron() {
  // |x| + |u| + |y| <= 1 as its 8 facets; its shadow on (x, u) is the diamond |x| + |u| <= 1.
  PolytopeLp lp;
  lp.A.resize(8, 3);
  int r = 0;
  for (int sx : {-1, 1})
    for (int su : {-1, 1})
      for (int sy : {-1, 1}) lp.A.row(r++) << sx, su, sy;
  lp.row_lo = Eigen::VectorXd::Constant(8, -INFINITY);
  lp.row_hi = Eigen::VectorXd::Ones(8);
  lp.col_lo = Eigen::VectorXd::Constant(3, -INFINITY);
  lp.col_hi = Eigen::VectorXd::Constant(3, INFINITY);
  return lp;
}

}  // namespace

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
