// ContactConstraint::slice (guarantee = continuous's membership test): the polygon's slice at a given s̈
// from two LPs equals the slice of the projected polygon, at every sample and for s̈ inside, at the rim of
// and beyond the polygon's range.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pathpace/pathpace.hpp"
#include "test_fixtures.hpp"

using namespace pathpace;
using test::box_options;
using test::corners;
using test::lifter_with_box;

namespace {

// The box carried by the lifter's slide along x while the lift raises it: a polygon with edges of
// both signs of a (friction limits and the box's weight).
PathSamples lifter_samples(int n) {
  PathSamples ps;
  ps.s = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  ps.q = Eigen::MatrixXd::Zero(n, 7);
  ps.dq = ps.q;
  ps.ddq = ps.q;
  for (int p = 0; p < n; ++p) {
    const double s = ps.s[p];
    ps.q(p, 0) = ps.q(p, 1) = s;
    ps.dq(p, 0) = ps.dq(p, 1) = 1.0;
    ps.q(p, 2) = 0.3 * std::sin(3.0 * s);  // the lift
    ps.dq(p, 2) = 0.9 * std::cos(3.0 * s);
    ps.ddq(p, 2) = -2.7 * std::sin(3.0 * s);
  }
  return ps;
}

// [lo, hi] of {x : a x + b u <= c for every row} at sample p.
void row_slice(const ConstraintRows& r, Eigen::Index p, double u, double& lo, double& hi) {
  const double inf = std::numeric_limits<double>::infinity();
  lo = -inf;
  hi = inf;
  for (Eigen::Index j = 0; j < r.rows(); ++j) {
    if (r.c(p, j) == inf) continue;
    const double a = r.a(p, j), rest = r.c(p, j) - r.b(p, j) * u;
    if (a > 0) hi = std::min(hi, rest / a);
    else if (a < 0) lo = std::max(lo, rest / a);
    else if (rest < 0) lo = inf, hi = -inf;
  }
}

}  // namespace

TEST(ContactSlice, EqualsTheProjectedPolygonsSlice) {
  auto model = lifter_with_box();
  ContactOptions opt = box_options(0.5);
  const ContactConstraint c(model, corners(0.5), opt);
  const PathSamples ps = lifter_samples(7);
  const ConstraintRows rows = c.evaluate(ps);
  int compared = 0, empty = 0;
  for (double u : {-20.0, -3.0, -1.0, 0.0, 0.7, 2.0, 4.0, 20.0}) {
    const Eigen::VectorXd uu = Eigen::VectorXd::Constant(ps.size(), u);
    Eigen::VectorXd lo, hi;
    const int lps = c.slice(ps, uu, lo, hi);
    EXPECT_EQ(lps, 2 * static_cast<int>(ps.size()) - static_cast<int>((lo.array() > hi.array()).count()))
        << "an empty slice takes one LP";
    for (Eigen::Index p = 0; p < ps.size(); ++p) {
      double rlo, rhi;
      row_slice(rows, p, u, rlo, rhi);
      if (rlo > rhi + 1e-7 * std::max(1.0, std::abs(rhi))) {
        EXPECT_GT(lo[p], hi[p]) << "u " << u << " p " << p;
        ++empty;
        continue;
      }
      if (lo[p] > hi[p]) {  // empty by the LPs, non-empty by the rows: only at the polygon's rim
        EXPECT_LE(rhi - rlo, 1e-7 * std::max(1.0, std::abs(rhi))) << "u " << u << " p " << p;
        continue;
      }
      // The polygon is exact to 1e-9 of its size (sec. IV.C); x's bounds here are O(10).
      const double scale = 1e-7 * std::max({1.0, std::abs(rhi), std::abs(rlo)});
      if (std::isfinite(rhi)) EXPECT_NEAR(hi[p], rhi, scale) << "u " << u << " p " << p;
      else EXPECT_TRUE(std::isinf(hi[p]) && hi[p] > 0) << "u " << u << " p " << p;
      EXPECT_NEAR(std::max(lo[p], 0.0), std::max(rlo, 0.0), scale) << "u " << u << " p " << p;
      ++compared;
    }
  }
  EXPECT_GT(compared, 10);
  EXPECT_GT(empty, 2);  // u = ±20 is beyond what friction can carry
}

TEST(ContactSlice, InactiveSamplesAreUnboundedAndArgumentsAreChecked) {
  auto model = lifter_with_box();
  ContactOptions opt;
  opt.cone_edges = 4;
  opt.active_begin = 0.0;
  opt.active_end = 0.5;
  const ContactConstraint c(model, corners(0.5), opt);
  const PathSamples ps = lifter_samples(5);  // s = 0, 0.25, 0.5, 0.75, 1
  Eigen::VectorXd lo, hi;
  EXPECT_EQ(c.slice(ps, Eigen::VectorXd::Zero(5), lo, hi), 6);
  for (Eigen::Index p : {3, 4}) {
    EXPECT_TRUE(std::isinf(lo[p]) && lo[p] < 0);
    EXPECT_TRUE(std::isinf(hi[p]) && hi[p] > 0);
  }
  EXPECT_LE(lo[0], hi[0]);  // the box at rest on the slide, lifted: feasible
  EXPECT_THROW(c.slice(ps, Eigen::VectorXd::Zero(4), lo, hi), InvalidInput);
  PathSamples narrow = ps;
  narrow.q = ps.q.leftCols(3);
  EXPECT_THROW(c.slice(narrow, Eigen::VectorXd::Zero(5), lo, hi), InvalidInput);
}

// Several s̈ asked at one path point in a row (as the continuous audit once asked u - δ, u, u + δ):
// slice() builds that point's LP once and keeps GLPK's matrix for the next ones. The answers are those of one call per
// sample (to the LPs' rounding: a warm GLPK problem keeps its own factorisation), also where a slice
// is empty (u = ±20) and the next sample at the same point is not.
TEST(ContactSlice, RepeatedPointsGiveTheSlicesOfOneCallPerSample) {
  auto model = lifter_with_box();
  const ContactConstraint c(model, corners(0.5), box_options(0.5));
  const PathSamples ps = lifter_samples(7);
  const std::vector<double> us = {-20.0, -3.0, 0.0, 0.7, 4.0, 20.0, 2.0};
  PathSamples rep;
  const Eigen::Index m = ps.size() * static_cast<Eigen::Index>(us.size());
  rep.s.resize(m);
  rep.q.resize(m, ps.dof());
  rep.dq.resize(m, ps.dof());
  rep.ddq.resize(m, ps.dof());
  Eigen::VectorXd u(m);
  for (Eigen::Index p = 0, i = 0; p < ps.size(); ++p)
    for (size_t j = 0; j < us.size(); ++j, ++i) {
      rep.s[i] = ps.s[p];
      rep.q.row(i) = ps.q.row(p);
      rep.dq.row(i) = ps.dq.row(p);
      rep.ddq.row(i) = ps.ddq.row(p);
      u[i] = us[(j + static_cast<size_t>(p)) % us.size()];  // every order of empty and non-empty slices
    }
  Eigen::VectorXd lo, hi;
  c.slice(rep, u, lo, hi);
  int empty = 0, compared = 0;
  for (Eigen::Index i = 0; i < m; ++i) {
    PathSamples one;
    one.s = rep.s.segment(i, 1);
    one.q = rep.q.row(i);
    one.dq = rep.dq.row(i);
    one.ddq = rep.ddq.row(i);
    Eigen::VectorXd lo1, hi1;
    c.slice(one, u.segment(i, 1), lo1, hi1);
    if (lo1[0] > hi1[0]) {
      EXPECT_GT(lo[i], hi[i]) << "sample " << i << " u " << u[i];
      ++empty;
      continue;
    }
    for (auto [a, b] : {std::pair{lo[i], lo1[0]}, std::pair{hi[i], hi1[0]}}) {
      if (std::isinf(b)) EXPECT_EQ(a, b) << "sample " << i;
      else EXPECT_NEAR(a, b, 1e-9 * std::max(1.0, std::abs(b))) << "sample " << i << " u " << u[i];
    }
    ++compared;
  }
  EXPECT_GT(empty, 2 * ps.size() - 2);
  EXPECT_GT(compared, 4 * ps.size());
}

// With x given: where x is above the slice's top the bottom's LP is skipped (x_lo = -inf), elsewhere the
// slices are those without x; a wrong-sized x is an input error.
TEST(ContactSlice, AnXAboveTheTopSkipsTheBottomsLp) {
  auto model = lifter_with_box();
  const ContactConstraint c(model, corners(0.5), box_options(0.5));
  const PathSamples ps = lifter_samples(9);
  const Eigen::VectorXd u = Eigen::VectorXd::Constant(ps.size(), 0.7);
  Eigen::VectorXd lo, hi, lo_x, hi_x;
  const int all = c.slice(ps, u, lo, hi);
  ASSERT_TRUE((lo.array() <= hi.array()).all());
  Eigen::VectorXd x = hi;
  int above = 0;
  for (Eigen::Index p = 0; p < ps.size(); ++p)
    if (p % 2 == 0 && std::isfinite(hi[p])) x[p] = 1.5 * hi[p] + 1.0, ++above;
    else x[p] = 0.5 * (lo[p] + (std::isfinite(hi[p]) ? hi[p] : lo[p] + 1.0));
  ASSERT_GT(above, 2);
  EXPECT_EQ(c.slice(ps, u, lo_x, hi_x, &x), all - above);
  for (Eigen::Index p = 0; p < ps.size(); ++p) {
    // The same LPs from other warm starts (the bottom's projector skips samples): equal to their rounding.
    if (std::isinf(hi[p])) EXPECT_EQ(hi_x[p], hi[p]) << p;
    else EXPECT_NEAR(hi_x[p], hi[p], 1e-9 * std::max(1.0, std::abs(hi[p]))) << p;
    if (x[p] > hi[p]) EXPECT_TRUE(std::isinf(lo_x[p]) && lo_x[p] < 0) << p;
    else EXPECT_NEAR(lo_x[p], lo[p], 1e-9 * std::max(1.0, std::abs(lo[p]))) << p;
  }
  const Eigen::VectorXd short_x = x.head(3);
  EXPECT_THROW(c.slice(ps, u, lo_x, hi_x, &short_x), InvalidInput);
}

// SliceEdges: each end's line is the polygon's boundary, exactly, over its range of u (the end's LP keeps
// its basis there), and bounds that end from its side everywhere else (x_hi is concave and x_lo convex in
// u), checked against the slices at 41 other values of u from their own LPs; the labels name a limit of
// the projected polygon. A range that never left its u, or a line that never bent, would fail the counts.
TEST(ContactSlice, EdgesAreThePolygonsBoundaryAlongU) {
  auto model = lifter_with_box();
  const ContactConstraint c(model, corners(0.5), box_options(0.5));
  const PathSamples ps = lifter_samples(7);
  const ConstraintRows rows = c.evaluate(ps);
  const double inf = std::numeric_limits<double>::infinity();
  int inside = 0, outside = 0, wide = 0, sloped = 0;
  for (double u0 : {-3.0, -1.0, 0.0, 0.7, 2.0, 4.0}) {
    const Eigen::VectorXd uu = Eigen::VectorXd::Constant(ps.size(), u0);
    Eigen::VectorXd lo, hi;
    SliceEdges e;
    e.labels = true;
    c.slice(ps, uu, lo, hi, nullptr, &e);
    ASSERT_EQ(e.hi_label.size(), static_cast<size_t>(ps.size()));
    for (Eigen::Index p = 0; p < ps.size(); ++p) {
      if (lo[p] > hi[p]) continue;
      EXPECT_LE(e.hi_from[p], u0);
      EXPECT_GE(e.hi_to[p], u0);
      EXPECT_LE(e.lo_from[p], u0);
      EXPECT_GE(e.lo_to[p], u0);
      wide += (e.hi_to[p] - e.hi_from[p] > 0.1) + (e.lo_to[p] - e.lo_from[p] > 0.1);
      sloped += std::abs(e.hi_slope[p]) > 1e-3;
      if (std::isfinite(hi[p])) {
        bool named = false;
        for (const std::string& l : rows.labels) named = named || l.rfind(e.hi_label[static_cast<size_t>(p)], 0) == 0;
        EXPECT_TRUE(!e.hi_label[static_cast<size_t>(p)].empty() && named) << "'" << e.hi_label[static_cast<size_t>(p)] << "'";
      }
      for (int j = 0; j <= 40; ++j) {
        const double u = -6.0 + 0.3 * j;
        Eigen::VectorXd lo1, hi1;
        PathSamples one;
        one.s = ps.s.segment(p, 1);
        one.q = ps.q.row(p);
        one.dq = ps.dq.row(p);
        one.ddq = ps.ddq.row(p);
        c.slice(one, Eigen::VectorXd::Constant(1, u), lo1, hi1);
        if (lo1[0] > hi1[0]) continue;
        const double line_hi = hi[p] + e.hi_slope[p] * (u - u0), line_lo = lo[p] + e.lo_slope[p] * (u - u0);
        const double tol = 1e-8 * std::max({1.0, std::abs(hi1[0] == inf ? 0.0 : hi1[0]), std::abs(line_hi)});
        const bool in_hi = e.hi_from[p] <= u && u <= e.hi_to[p], in_lo = e.lo_from[p] <= u && u <= e.lo_to[p];
        if (std::isfinite(hi[p])) {
          if (in_hi) EXPECT_NEAR(hi1[0], line_hi, tol) << "u0 " << u0 << " p " << p << " u " << u;
          else EXPECT_LE(hi1[0], line_hi + tol) << "u0 " << u0 << " p " << p << " u " << u;
        }
        if (in_lo) EXPECT_NEAR(lo1[0], line_lo, tol) << "u0 " << u0 << " p " << p << " u " << u;
        else EXPECT_GE(lo1[0], line_lo - tol) << "u0 " << u0 << " p " << p << " u " << u;
        in_hi && in_lo ? ++inside : ++outside;
      }
    }
  }
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 50);
  EXPECT_GT(wide, 20);
  EXPECT_GT(sloped, 10);
}

// Warm starts across calls (SliceStarts): a call's samples started from the optimal bases another call found
// at other points, from bases that do not fit (the wrong size, or no basis at all), or from none, give the
// same slices; found holds a basis per end that had an optimum.
TEST(ContactSlice, StartsAreUsedAndTheGlpkLpsCounted) {
  // A call without starts: GLPK answers the first sample (no basis nearby yet), the dense simplex then
  // restarts from the previous sample's. The same samples again, each end started from its own optimal
  // basis of the first call: GLPK answers only what has no such basis (an empty slice or a failed LP), so
  // the starts are used, not only harmless (the test below), and glpk_lps counts what GLPK did.
  auto model = lifter_with_box();
  const ContactConstraint c(model, corners(0.5), box_options(0.5));
  const PathSamples samples = lifter_samples(9);
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(samples.size(), -2.0, 3.0);
  Eigen::VectorXd lo, hi, lo_w, hi_w;
  SliceStarts cold;
  const int lps = c.slice(samples, u, lo, hi, nullptr, nullptr, &cold);
  EXPECT_GE(cold.glpk_lps, 1);
  EXPECT_LE(cold.glpk_lps, lps);
  SliceStarts warm;
  int without = 0;
  for (int end = 0; end < 2; ++end) {
    warm.start[end] = cold.found[end];
    for (const auto& b : cold.found[end]) without += b.empty();
  }
  const int lps_w = c.slice(samples, u, lo_w, hi_w, nullptr, nullptr, &warm);
  EXPECT_EQ(lps_w, lps);
  EXPECT_LT(without, lps);  // most LPs have a start
  EXPECT_LE(warm.glpk_lps, without);
  for (Eigen::Index p = 0; p < samples.size(); ++p)
    for (auto [a, b] : {std::pair{lo_w[p], lo[p]}, std::pair{hi_w[p], hi[p]}}) {
      if (std::isinf(b)) EXPECT_EQ(a, b) << "sample " << p;
      else EXPECT_NEAR(a, b, 1e-9 * std::max(1.0, std::abs(b))) << "sample " << p;
    }
}

TEST(ContactSlice, StartsFromAnotherCallGiveTheSameSlices) {
  auto model = lifter_with_box();
  const ContactConstraint c(model, corners(0.5), box_options(0.5));
  const PathSamples first = lifter_samples(6), second = lifter_samples(11);
  const Eigen::VectorXd u1 = Eigen::VectorXd::LinSpaced(first.size(), -2.0, 3.0);
  const Eigen::VectorXd u2 = Eigen::VectorXd::LinSpaced(second.size(), 3.5, -2.5);
  Eigen::VectorXd lo, hi, lo_ref, hi_ref, lo_w, hi_w;
  SliceStarts found;
  c.slice(first, u1, lo, hi, nullptr, nullptr, &found);
  int kept = 0;
  for (int end = 0; end < 2; ++end) {
    ASSERT_EQ(found.found[end].size(), static_cast<size_t>(first.size()));
    for (Eigen::Index p = 0; p < first.size(); ++p) {
      const bool optimum = end == 0 ? std::isfinite(hi[p]) : std::isfinite(lo[p]);
      if (optimum && lo[p] <= hi[p]) EXPECT_FALSE(found.found[end][static_cast<size_t>(p)].empty()) << p;
      kept += !found.found[end][static_cast<size_t>(p)].empty();
    }
  }
  EXPECT_GT(kept, first.size());
  c.slice(second, u2, lo_ref, hi_ref);
  // The second call's samples in reverse order of s against the first's: each starts from the first call's
  // basis at the nearest point, every third from a start of the wrong size, every fifth from a non-basis.
  SliceStarts warm;
  for (int end = 0; end < 2; ++end)
    for (Eigen::Index p = 0; p < second.size(); ++p) {
      const Eigen::Index near = std::min<Eigen::Index>(first.size() - 1, (second.size() - 1 - p) / 2);
      std::vector<signed char> b = found.found[end][static_cast<size_t>(near)];
      if (p % 3 == 2) b.push_back(1);
      if (p % 5 == 4) b.assign(b.size(), 1);
      warm.start[end].push_back(b);
    }
  c.slice(second, u2, lo_w, hi_w, nullptr, nullptr, &warm);
  for (Eigen::Index p = 0; p < second.size(); ++p)
    for (auto [a, b] : {std::pair{lo_w[p], lo_ref[p]}, std::pair{hi_w[p], hi_ref[p]}}) {
      if (std::isinf(b)) EXPECT_EQ(a, b) << "sample " << p;
      else EXPECT_NEAR(a, b, 1e-9 * std::max(1.0, std::abs(b))) << "sample " << p << " u " << u2[p];
    }
}
