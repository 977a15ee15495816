// The one GLPK guard (lp/glpk_guard.hpp): a GLPK error injected at every guarded call of the
// projection, the feasibility and maximisation LPs and the contact force distribution becomes a status
// or an exception, and the GLPK problems that were alive at the time (which GLPK frees with its
// environment) are rebuilt, not used after being freed. Run under ASan by scripts/sanitize.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "lp/glpk_guard.hpp"
#include "lp/glpk_lp.hpp"
#include "lp/projection.hpp"
#include "pathpace/pathpace.hpp"
#include "test_fixtures.hpp"

using namespace pathpace;
using detail::GlpkLp;
using detail::Projection;
using detail::PolytopeLp;
using detail::PolytopeProjector;
using test::box_options;
using test::corners;
using test::lifter_with_box;
using test::beyond_stand_in;
using test::octahedron;
using test::support;

namespace {



// The octahedron with 30 more columns y_j in [0, 1], each row also + 1e-3 sum_j y_j: the same diamond
// (y_j = 0 at every support point), but wide enough (33 columns) for the ranging certificates, whose
// tableau rows are read inside the LPs' guarded calls.
PolytopeLp wide_octahedron() {
  PolytopeLp lp = octahedron();
  const int extra = 30;
  lp.A.conservativeResize(8, 3 + extra);
  lp.A.rightCols(extra).setConstant(1e-3);
  lp.col_lo.conservativeResize(3 + extra);
  lp.col_hi.conservativeResize(3 + extra);
  lp.col_lo.tail(extra).setZero();
  lp.col_hi.tail(extra).setOnes();
  return lp;
}


double diamond(double dx, double du) { return std::max(std::abs(dx), std::abs(du)); }
double rectangle(double dx, double du) { return std::max(0.0, dx) + std::max(1e10 * du, 2e10 * du); }

// A bystander LP with every kind of change GlpkLp copies: min -x0 - 2 x1 over x0 + x1 <= 1, x1 <= 0.5
// (appended after the first solve), 0 <= x0 <= 0.7, 0 <= x1 <= 2 (then x0 <= 0.4).
// Optimum: x = (0.4, 0.5), -1.4.
struct Bystander {
  GlpkLp lp;
  Bystander() {
    lp.reset(2);
    lp.add_row_upper({0, 1}, {1.0, 1.0}, 1.0);
    EXPECT_TRUE(lp.load());
    lp.set_col_bounds(0, 0.0, 0.7);
    lp.set_col_bounds(1, 0.0, 2.0);
    lp.set_objective({-1.0, -2.0});
    EXPECT_EQ(lp.solve(1e-10), GlpkLp::Outcome::Optimal);
    lp.append_row_upper({1}, {1.0}, 0.5);
    lp.set_col_bounds(0, 0.0, 0.4);
    check();
  }
  void check() {
    ASSERT_EQ(lp.solve(1e-10), GlpkLp::Outcome::Optimal);
    std::vector<double> x;
    lp.column_values(x);
    ASSERT_EQ(x.size(), 2u);
    EXPECT_NEAR(x[0], 0.4, 1e-12);
    EXPECT_NEAR(x[1], 0.5, 1e-12);
    EXPECT_NEAR(lp.lagrangian_bound({-1.0, -2.0}), -1.4, 1e-12);
  }
};

// Arms the injected error for the guarded call after `k` more; true if it fired during f().
template <typename F>
bool fired_at(long k, F&& f) {
  detail::glpk_test_fail_after(k);
  f();
  const bool fired = !detail::glpk_test_failure_pending();
  detail::glpk_test_fail_after(-1);
  return fired;
}

}  // namespace

TEST(GlpkGuard, ErrorHookTurnsAGlpkErrorIntoFalseAndAdvancesTheEpoch) {
  const unsigned long before = detail::glpk_epoch();
  int ran = 0;
  EXPECT_TRUE(detail::guarded([&] { ++ran; }));
  EXPECT_EQ(detail::glpk_epoch(), before);
  detail::glpk_test_fail_after(0);
  EXPECT_FALSE(detail::guarded([&] { ++ran; }));  // the error comes before f runs
  EXPECT_FALSE(detail::glpk_test_failure_pending());
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(detail::glpk_epoch(), before + 1);
  // A problem created before the error is gone, and is neither used nor deleted again.
  detail::GlpkProblem p;
  ASSERT_TRUE(p.create());
  EXPECT_NE(p.get(), nullptr);
  detail::glpk_test_fail_after(0);
  EXPECT_FALSE(detail::guarded([] {}));
  EXPECT_EQ(p.get(), nullptr);
  EXPECT_TRUE(p.create());
  EXPECT_NE(p.get(), nullptr);
}

TEST(GlpkGuard, AnErrorAtAnyCallOfAProjectionFailsItAndSparesTheOtherProblems) {
  const struct {
    PolytopeLp lp;
    double (*shadow)(double, double);
    long guarded_calls;  // at least: parameters, load, the LPs and the certificates' bindings
  } cases[] = {{octahedron(), diamond, 10}, {beyond_stand_in(), rectangle, 10}, {wide_octahedron(), diamond, 6}};
  for (const auto& c : cases) {
    Bystander other;
    PolytopeProjector warm, p;  // `warm` holds its warm-start problem throughout
    // GLPK for every LP (the dense simplex makes no GLPK call, so with it on the wide case has only 3):
    // an error at each of GLPK's calls is what this test walks through.
    warm.dense = p.dense = false;
    const Projection first = warm.project(c.lp);
    ASSERT_EQ(first.outcome, Projection::Outcome::Polygon);
    if (c.lp.A.cols() >= 30) EXPECT_GT(first.by_cause.ranged, 0);  // the ranging path is among the calls hit
    ASSERT_EQ(p.project(c.lp).outcome, Projection::Outcome::Polygon);  // p warm too: the error hits a loaded problem
    long k = 0;
    for (;; ++k) {
      Projection r;
      const unsigned long epoch = detail::glpk_epoch();
      if (!fired_at(k, [&] { r = p.project(c.lp); })) break;  // past the projection's last guarded call
      EXPECT_EQ(r.outcome, Projection::Outcome::Failed) << k;
      EXPECT_EQ(r.note, "GLPK error") << k;
      EXPECT_EQ(detail::glpk_epoch(), epoch + 1);
      other.check();  // rebuilt from its copy
      for (PolytopeProjector* q : {&p, &warm}) {  // the next projections work, from a cold start
        const Projection again = q->project(c.lp);
        ASSERT_EQ(again.outcome, Projection::Outcome::Polygon) << k << " " << again.note;
        for (int d = 0; d < 16; ++d) {
          const double dx = std::cos(0.4 * d), du = std::sin(0.4 * d);
          EXPECT_NEAR(support(again, dx, du), c.shadow(dx, du), again.tolerance + 1e-12) << k << " " << d;
        }
      }
    }
    EXPECT_GE(k, c.guarded_calls);  // every guarded call of the projection was hit once
  }
}

TEST(GlpkGuard, AnErrorInTheFeasibilityAndMaximisationLpsIsAStatus) {
  const PolytopeLp lp = octahedron();
  PolytopeProjector p;
  Bystander other;
  const Eigen::VectorXd c = Eigen::Vector3d(1.0, 1.0, 1.0);
  Eigen::VectorXd z;
  long k = 0;
  for (;; ++k) {
    int feasible = 2;
    if (!fired_at(k, [&] { feasible = p.feasible(lp); })) break;
    EXPECT_EQ(feasible, -1) << k;
    other.check();
    EXPECT_EQ(p.feasible(lp), 1);
  }
  EXPECT_GE(k, 3);
  for (k = 0;; ++k) {
    int st = 2;
    if (!fired_at(k, [&] { st = p.maximize(lp, c, z); })) break;
    EXPECT_EQ(st, -2) << k;
    other.check();
    ASSERT_EQ(p.maximize(lp, c, z), 1);
    EXPECT_NEAR(c.dot(z), 1.0, 1e-12);  // max x + u + y over the octahedron
  }
  EXPECT_GE(k, 3);
}

TEST(GlpkGuard, AnErrorInTheForceDistributionThrowsAndTheNextOneWorks) {
  auto model = lifter_with_box();
  ContactOptions opt = box_options(1.0);
  const ContactConstraint c(model, corners(0.5), opt);
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(3, 7), qd = q, qdd = q;
  qdd(1, 0) = qdd(1, 1) = 0.2 * 9.81;
  qdd(2, 0) = qdd(2, 1) = 2.0 * 9.81;  // friction cannot: a negative margin
  const std::vector<ContactForces> ref = c.force_distribution(q, qd, qdd, ForceDistribution::Vertex);
  ASSERT_EQ(ref.size(), 3u);
  Bystander other;
  PolytopeProjector warm;
  ASSERT_EQ(warm.project(octahedron()).outcome, Projection::Outcome::Polygon);
  long threw_count = 0;
  long k = 0;
  for (;; ++k) {
    bool threw = false;
    std::vector<ContactForces> got;
    if (!fired_at(k, [&] {
          try {
            got = c.force_distribution(q, qd, qdd, ForceDistribution::Vertex);
          } catch (const Error& e) {
            threw = true;
            EXPECT_NE(std::string(e.what()).find("GLPK error"), std::string::npos) << e.what();
          }
        }))
      break;
    // Only an error in the last call (deleting the LP at the end) leaves the result whole.
    if (!threw) ASSERT_EQ(got.size(), ref.size()) << k;
    other.check();
    EXPECT_EQ(warm.project(octahedron()).outcome, Projection::Outcome::Polygon);
    const std::vector<ContactForces> again = c.force_distribution(q, qd, qdd, ForceDistribution::Vertex);
    for (size_t s = 0; s < ref.size(); ++s) {
      ASSERT_TRUE(again[s].feasible);
      EXPECT_NEAR(again[s].margin, ref[s].margin, 1e-9 * (1.0 + std::abs(ref[s].margin))) << k << " " << s;
      if (!threw) EXPECT_NEAR(got[s].margin, ref[s].margin, 1e-9 * (1.0 + std::abs(ref[s].margin))) << k << " " << s;
    }
    threw_count += threw;
  }
  EXPECT_EQ(threw_count, k - 1);  // every call but the last
  EXPECT_GE(k, 6);  // a few guarded calls per sample
}

namespace {

// The active half-planes (a, b, c) of grid point p, sorted: the polygon, whatever its labels say (which of
// the four symmetric corners' friction binds depends on the LP's start).
std::vector<std::array<double, 3>> halfplanes(const ConstraintRows& r, Eigen::Index p) {
  std::vector<std::array<double, 3>> out;
  for (Eigen::Index j = 0; j < r.c.cols(); ++j)
    if (std::isfinite(r.c(p, j))) out.push_back({r.a(p, j) + 0.0, r.b(p, j) + 0.0, r.c(p, j) + 0.0});  // -0 as 0
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(GlpkGuard, AContactProjectionRecoversFromAnErrorAtAGridPoint) {
  // ContactConstraint::evaluate retries a failed grid point from a cold start: with one GLPK error
  // anywhere in it, the polygons are those of a run without.
  auto model = lifter_with_box();
  ContactOptions opt = box_options();
  const ContactConstraint c(model, corners(0.5), opt);
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(4, 0.0, 1.0);
  ps.q = Eigen::MatrixXd::Zero(4, 7);
  ps.dq = ps.q;
  ps.ddq = ps.q;
  ps.q.col(0) = ps.q.col(1) = ps.s;
  ps.dq.col(0).setOnes();
  ps.dq.col(1).setOnes();
  const ConstraintRows ref = c.evaluate(ps);
  ASSERT_TRUE(ref.inexact_points.empty());
  long k = 0;
  for (;; k += 7) {
    ConstraintRows r;
    if (!fired_at(k, [&] { r = c.evaluate(ps); })) break;
    EXPECT_TRUE(r.inexact_points.empty()) << k;
    for (Eigen::Index p = 0; p < ps.s.size(); ++p) {
      const auto got = halfplanes(r, p), want = halfplanes(ref, p);
      ASSERT_EQ(got.size(), want.size()) << k << " " << p;
      for (size_t i = 0; i < got.size(); ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(got[i][j], want[i][j], 1e-9 * (1.0 + std::abs(want[i][j]))) << k << " " << p;
    }
  }
  EXPECT_GE(k, 50);
}
