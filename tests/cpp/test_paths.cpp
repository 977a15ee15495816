#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"
#include "pathpace/sampled_path.hpp"
#include "test_util.hpp"

using namespace pathpace;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = u(gen);
  return m;
}

VectorXd vec(std::initializer_list<double> v) {
  VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

struct Eval {
  VectorXd q, dq, ddq;
};

Eval eval(const Path& p, double s) {
  Eval e{VectorXd(p.dof()), VectorXd(p.dof()), VectorXd(p.dof())};
  p.evaluate(s, e.q, e.dq, e.ddq);
  return e;
}

// p''' on the piece [a, b] of a cubic spline: p'' is linear there and continuous at the knots.
VectorXd third_derivative(const Path& p, double a, double b) { return (eval(p, b).ddq - eval(p, a).ddq) / (b - a); }

// Runs `stmt` and checks that it throws InvalidInput with exactly `message`.
template <typename F>
void expect_invalid(F&& stmt, const std::string& message) {
  EXPECT_EQ(test::error_of(stmt), message);
}

const SplineBoundary kBoundaries[] = {SplineBoundary::NotAKnot, SplineBoundary::Natural, SplineBoundary::Clamped};

CubicSplinePath make_spline(const MatrixXd& w, KnotSpacing spacing, SplineBoundary b, double s0 = 0.0,
                            double s1 = 1.0) {
  if (b == SplineBoundary::Clamped)
    return CubicSplinePath(w, spacing, b, s0, s1, VectorXd::Constant(w.cols(), 0.7), VectorXd::Constant(w.cols(), -1.3));
  return CubicSplinePath(w, spacing, b, s0, s1);
}

}  // namespace

TEST(CubicSplinePath, InterpolatesWaypointsExactly) {
  for (Eigen::Index k : {2, 3, 4, 7})
    for (auto spacing : {KnotSpacing::Uniform, KnotSpacing::ChordLength})
      for (auto b : kBoundaries) {
        const MatrixXd w = random_matrix(k, 3, 11 * static_cast<unsigned>(k));
        const CubicSplinePath p = make_spline(w, spacing, b, -0.5, 2.0);
        ASSERT_EQ(p.dof(), 3);
        ASSERT_EQ(p.knots().size(), k);
        EXPECT_EQ(p.s_begin(), -0.5);
        EXPECT_EQ(p.s_end(), 2.0);
        EXPECT_EQ(p.knots()[0], -0.5);
        EXPECT_EQ(p.knots()[k - 1], 2.0);
        EXPECT_EQ(p.waypoints(), w);
        for (Eigen::Index i = 0; i < k; ++i)
          EXPECT_LE((eval(p, p.knots()[i]).q - w.row(i).transpose()).norm(), 1e-13) << "knot " << i;
      }
}

TEST(CubicSplinePath, UniformAndChordKnots) {
  MatrixXd w(4, 2);
  w << 0, 0, 3, 4, 3, 5, 3, 7;  // chords 5, 1, 2
  EXPECT_LE((CubicSplinePath(w).knots() - vec({0, 1.0 / 3, 2.0 / 3, 1})).norm(), 1e-15);
  const CubicSplinePath chord(w, KnotSpacing::ChordLength, SplineBoundary::NotAKnot, 1.0, 9.0);
  EXPECT_LE((chord.knots() - vec({1, 6, 7, 9})).norm(), 1e-14);
  const CubicSplinePath explicit_knots(w, vec({-1, 0, 2, 5}));
  EXPECT_EQ(explicit_knots.s_begin(), -1.0);
  EXPECT_EQ(explicit_knots.s_end(), 5.0);
  EXPECT_EQ(explicit_knots.knots(), vec({-1, 0, 2, 5}));
}

TEST(CubicSplinePath, DerivativesMatchCentralDifferences) {
  const double h = 1e-5;
  for (auto b : kBoundaries) {
    const CubicSplinePath p(make_spline(random_matrix(6, 4, 3), KnotSpacing::ChordLength, b));
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> u(0.01, 0.99);
    for (int trial = 0; trial < 50; ++trial) {
      const double s = u(gen);
      const Eval lo = eval(p, s - h), mid = eval(p, s), hi = eval(p, s + h);
      // Error: h^2 p'''/6 plus rounding (~1e-16 / h). A knot inside [s - h, s + h] adds only a jump in p'''
      // (the spline is C2), which costs O(h) in the p'' check: both bounds still hold.
      EXPECT_LE(((hi.q - lo.q) / (2 * h) - mid.dq).norm(), 1e-6 * (1 + mid.dq.norm()));
      EXPECT_LE(((hi.dq - lo.dq) / (2 * h) - mid.ddq).norm(), 1e-4 * (1 + mid.ddq.norm()));
    }
  }
}

TEST(CubicSplinePath, IsTwiceContinuouslyDifferentiableAtKnots) {
  for (auto b : kBoundaries) {
    const CubicSplinePath p(make_spline(random_matrix(7, 2, 8), KnotSpacing::Uniform, b));
    const VectorXd& x = p.knots();
    for (Eigen::Index i = 1; i + 1 < x.size(); ++i) {
      // Each side's cubic, sampled inside its own piece and extended exactly (Taylor up to p''') to the knot.
      const double e = 1e-3;
      const Eval l = eval(p, x[i] - e), r = eval(p, x[i] + e);
      const VectorXd tl = third_derivative(p, x[i - 1], x[i]), tr = third_derivative(p, x[i], x[i + 1]);
      const VectorXd ql = l.q + e * l.dq + (e * e / 2) * l.ddq + (e * e * e / 6) * tl;
      const VectorXd qr = r.q - e * r.dq + (e * e / 2) * r.ddq - (e * e * e / 6) * tr;
      const VectorXd dql = l.dq + e * l.ddq + (e * e / 2) * tl, dqr = r.dq - e * r.ddq + (e * e / 2) * tr;
      const VectorXd ddql = l.ddq + e * tl, ddqr = r.ddq - e * tr;
      EXPECT_LE((ql - qr).norm(), 1e-12) << i;
      EXPECT_LE((dql - dqr).norm(), 1e-10) << i;
      EXPECT_LE((ddql - ddqr).norm(), 1e-8 * (1 + ddql.norm())) << i;
    }
  }
}

TEST(CubicSplinePath, NaturalHasZeroCurvatureAtTheEnds) {
  for (Eigen::Index k : {2, 3, 5, 9}) {
    const CubicSplinePath p(make_spline(random_matrix(k, 3, 21), KnotSpacing::ChordLength, SplineBoundary::Natural));
    EXPECT_LE(eval(p, p.s_begin()).ddq.norm(), 1e-12);
    EXPECT_LE(eval(p, p.s_end()).ddq.norm(), 1e-12);
    EXPECT_GT(eval(p, 0.5 * (p.s_begin() + p.s_end())).q.norm(), 0.0);
  }
}

TEST(CubicSplinePath, ClampedHasTheGivenEndDerivatives) {
  const VectorXd d0 = vec({1.0, -2.0}), d1 = vec({0.5, 3.0});
  for (Eigen::Index k : {2, 3, 6}) {
    const CubicSplinePath p(random_matrix(k, 2, 4), KnotSpacing::Uniform, SplineBoundary::Clamped, 0.0, 2.0, d0, d1);
    EXPECT_LE((eval(p, 0.0).dq - d0).norm(), 1e-12);
    EXPECT_LE((eval(p, 2.0).dq - d1).norm(), 1e-12);
  }
}

TEST(CubicSplinePath, NotAKnotHasContinuousThirdDerivativeAtSecondAndSecondLastKnots) {
  const CubicSplinePath p(random_matrix(6, 3, 9), KnotSpacing::ChordLength);
  const VectorXd& x = p.knots();
  const Eigen::Index k = x.size();
  EXPECT_LE((third_derivative(p, x[0], x[1]) - third_derivative(p, x[1], x[2])).norm(), 1e-9);
  EXPECT_LE((third_derivative(p, x[k - 3], x[k - 2]) - third_derivative(p, x[k - 2], x[k - 1])).norm(), 1e-9);
  // The test can tell: a natural spline through the same points has a jump there.
  const CubicSplinePath natural(p.waypoints(), p.knots(), SplineBoundary::Natural);
  EXPECT_GT((third_derivative(natural, x[0], x[1]) - third_derivative(natural, x[1], x[2])).norm(), 1e-3);
}

TEST(CubicSplinePath, NotAKnotReproducesCubicsAndSpecialCases) {
  auto poly = [](double s, int order) {  // p(s) = 1 - 2 s + 0.5 s^2 + 0.75 s^3 and its derivatives
    if (order == 0) return 1 - 2 * s + 0.5 * s * s + 0.75 * s * s * s;
    if (order == 1) return -2 + s + 2.25 * s * s;
    return 1 + 4.5 * s;
  };
  const VectorXd knots = vec({0.0, 0.3, 1.1, 1.5, 2.6});
  MatrixXd w(5, 1);
  for (int i = 0; i < 5; ++i) w(i, 0) = poly(knots[i], 0);
  const CubicSplinePath cubic(w, knots);
  for (double s : {0.1, 0.7, 1.3, 2.0, 2.5}) {
    const Eval e = eval(cubic, s);
    EXPECT_NEAR(e.q[0], poly(s, 0), 1e-12);
    EXPECT_NEAR(e.dq[0], poly(s, 1), 1e-11);
    EXPECT_NEAR(e.ddq[0], poly(s, 2), 1e-10);
  }
  // K = 3: the parabola through the points (scipy's special case), here s^2 on uneven knots.
  const CubicSplinePath parabola((MatrixXd(3, 1) << 0.0, 0.04, 1.0).finished(), vec({0.0, 0.2, 1.0}));
  for (double s : {0.05, 0.5, 0.9}) {
    const Eval e = eval(parabola, s);
    EXPECT_NEAR(e.q[0], s * s, 1e-14);
    EXPECT_NEAR(e.dq[0], 2 * s, 1e-13);
    EXPECT_NEAR(e.ddq[0], 2.0, 1e-12);
  }
  // K = 2: the straight line.
  const CubicSplinePath line((MatrixXd(2, 2) << 1.0, 2.0, 3.0, -2.0).finished(), KnotSpacing::Uniform,
                             SplineBoundary::NotAKnot, 0.0, 2.0);
  const Eval e = eval(line, 0.5);
  EXPECT_LE((e.q - vec({1.5, 1.0})).norm(), 1e-15);
  EXPECT_LE((e.dq - vec({1.0, -2.0})).norm(), 1e-15);
  EXPECT_LE(e.ddq.norm(), 1e-15);
}

TEST(CubicSplinePath, ClampsOutsideTheDomain) {
  const CubicSplinePath p(random_matrix(5, 2, 1), KnotSpacing::Uniform, SplineBoundary::NotAKnot, 1.0, 3.0);
  const Eval b = eval(p, 1.0), e = eval(p, 3.0);
  for (double s : {0.999, -1e9, -kInf}) {
    const Eval o = eval(p, s);
    EXPECT_EQ(o.q, b.q);
    EXPECT_EQ(o.dq, b.dq);
    EXPECT_EQ(o.ddq, b.ddq);
  }
  for (double s : {3.001, 1e9, kInf}) {
    const Eval o = eval(p, s);
    EXPECT_EQ(o.q, e.q);
    EXPECT_EQ(o.dq, e.dq);
    EXPECT_EQ(o.ddq, e.ddq);
  }
}

TEST(CubicSplinePath, BatchEvaluationMatchesPointwise) {
  // The batch overload has its own fast path for sorted grids; any order, repeats, knots themselves and
  // points outside the domain must give what pointwise evaluation gives.
  const CubicSplinePath p(random_matrix(5, 3, 2));
  const std::vector<VectorXd> grids = {VectorXd::LinSpaced(11, -0.1, 1.1), VectorXd::LinSpaced(11, 1.1, -0.1),
                                       vec({0.3, 0.9, 0.1, 0.75, 0.75, 0.5, 0.0, 1.0, 0.25, 2.0, -3.0}), vec({0.4})};
  for (const VectorXd& s : grids) {
    MatrixXd q, dq, ddq;
    p.evaluate(s, q, dq, ddq);
    ASSERT_EQ(q.rows(), s.size());
    ASSERT_EQ(q.cols(), 3);
    for (Eigen::Index i = 0; i < s.size(); ++i) {
      const Eval e = eval(p, s[i]);
      EXPECT_LE((q.row(i).transpose() - e.q).norm(), 1e-14 * (1 + e.q.norm())) << s[i];
      EXPECT_LE((dq.row(i).transpose() - e.dq).norm(), 1e-14 * (1 + e.dq.norm())) << s[i];
      EXPECT_LE((ddq.row(i).transpose() - e.ddq).norm(), 1e-14 * (1 + e.ddq.norm())) << s[i];
    }
    EXPECT_EQ(p.q(s), q);
    EXPECT_EQ(p.dq(s), dq);
    EXPECT_EQ(p.ddq(s), ddq);
  }
}

TEST(PiecewisePolynomialPath, EvaluatesPiecesInLocalCoordinates) {
  // [0, 1): 1 + 2t (two coordinates: second is 3 t^2); [1, 3]: 3 - t^2 and 3 + 6t + 3t^2.
  std::vector<MatrixXd> c(2, MatrixXd(3, 2));
  c[0] << 1, 0, 2, 0, 0, 3;
  c[1] << 3, 3, 0, 6, -1, 3;
  const PiecewisePolynomialPath p(vec({0.0, 1.0, 3.0}), c);
  EXPECT_EQ(p.dof(), 2);
  EXPECT_EQ(p.s_begin(), 0.0);
  EXPECT_EQ(p.s_end(), 3.0);
  EXPECT_EQ(p.coefficients()[1], c[1]);
  Eval e = eval(p, 0.5);
  EXPECT_EQ(e.q, vec({2.0, 0.75}));
  EXPECT_EQ(e.dq, vec({2.0, 3.0}));
  EXPECT_EQ(e.ddq, vec({0.0, 6.0}));
  e = eval(p, 1.0);  // an interior breakpoint belongs to the interval on its right
  EXPECT_EQ(e.q, vec({3.0, 3.0}));
  EXPECT_EQ(e.dq, vec({0.0, 6.0}));
  EXPECT_EQ(e.ddq, vec({-2.0, 6.0}));
  e = eval(p, 5.0);  // clamped to s_end = 3, t = 2
  EXPECT_EQ(e.q, vec({-1.0, 27.0}));
  EXPECT_EQ(e.dq, vec({-4.0, 18.0}));
  e = eval(p, -1.0);
  EXPECT_EQ(e.q, vec({1.0, 0.0}));
}

TEST(PiecewisePolynomialPath, DegreeZeroIsPiecewiseConstant) {
  const PiecewisePolynomialPath p(vec({0.0, 1.0, 2.0}), {MatrixXd::Constant(1, 1, 4.0), MatrixXd::Constant(1, 1, 5.0)});
  EXPECT_EQ(eval(p, 0.5).q[0], 4.0);
  EXPECT_EQ(eval(p, 1.5).q[0], 5.0);
  EXPECT_EQ(eval(p, 1.5).dq[0], 0.0);
  EXPECT_EQ(eval(p, 1.5).ddq[0], 0.0);
}

TEST(SampledPath, ReproducesAQuinticExactly) {
  // Two coordinates: a generic quintic and its negation plus a line.
  const VectorXd c = vec({0.3, -1.2, 0.8, 2.0, -0.7, 0.45});
  // d^order/ds^order of sum_k c[k] s^k.
  auto ref = [&](double s, int order) {
    double v = 0.0;
    for (int k = order; k <= 5; ++k) {
      double f = 1.0;
      for (int j = 0; j < order; ++j) f *= k - j;
      v += f * c[k] * std::pow(s, k - order);
    }
    return v;
  };
  const VectorXd s = vec({-1.0, -0.2, 0.5, 0.6, 1.7});
  MatrixXd q(5, 2), dq(5, 2), ddq(5, 2);
  for (int i = 0; i < 5; ++i) {
    q.row(i) << ref(s[i], 0), -ref(s[i], 0) + 2 * s[i];
    dq.row(i) << ref(s[i], 1), -ref(s[i], 1) + 2;
    ddq.row(i) << ref(s[i], 2), -ref(s[i], 2);
  }
  const SampledPath path(s, q, dq, ddq);
  EXPECT_EQ(path.dof(), 2);
  EXPECT_EQ(path.s_begin(), -1.0);
  EXPECT_EQ(path.s_end(), 1.7);
  EXPECT_EQ(path.samples(), s);
  for (double x : {-0.9, -0.5, 0.0, 0.55, 1.0, 1.7}) {
    const Eval e = eval(path, x);
    EXPECT_NEAR(e.q[0], ref(x, 0), 1e-12) << x;
    EXPECT_NEAR(e.dq[0], ref(x, 1), 1e-11) << x;
    EXPECT_NEAR(e.ddq[0], ref(x, 2), 1e-10) << x;
    EXPECT_NEAR(e.q[1], -ref(x, 0) + 2 * x, 1e-12) << x;
  }
  for (int i = 0; i < 5; ++i) {
    const Eval e = eval(path, s[i]);
    EXPECT_LE((e.q - q.row(i).transpose()).norm(), 1e-14 * (1 + e.q.norm())) << i;
    EXPECT_LE((e.dq - dq.row(i).transpose()).norm(), 1e-13 * (1 + e.dq.norm())) << i;
    EXPECT_LE((e.ddq - ddq.row(i).transpose()).norm(), 1e-12 * (1 + e.ddq.norm())) << i;
  }
}

TEST(SampledPath, ClampsOutsideTheDomain) {
  const MatrixXd q = random_matrix(3, 2, 7), dq = random_matrix(3, 2, 8), ddq = random_matrix(3, 2, 9);
  const SampledPath p(vec({0.0, 0.5, 2.0}), q, dq, ddq);
  EXPECT_EQ(eval(p, -3.0).q, eval(p, 0.0).q);
  EXPECT_EQ(eval(p, -3.0).dq, VectorXd(dq.row(0).transpose()));
  EXPECT_EQ(eval(p, 9.0).ddq, eval(p, 2.0).ddq);
}

// ---- validation: one test per branch, exact messages ----

TEST(CubicSplinePathValidation, Waypoints) {
  expect_invalid([] { CubicSplinePath(MatrixXd::Zero(1, 2)); },
                 "waypoints has 1 rows, expected at least 2");
  expect_invalid([] { CubicSplinePath(MatrixXd::Zero(3, 0)); },
                 "waypoints has 0 columns, expected at least 1 coordinate");
  MatrixXd w = MatrixXd::Zero(3, 2);
  w(1, 0) = kNan;
  expect_invalid([&] { CubicSplinePath{w}; }, "waypoints[1, 0] = nan must be finite");
  w(1, 0) = 0.0;
  w(2, 1) = -kInf;
  expect_invalid([&] { CubicSplinePath{w}; }, "waypoints[2, 1] = -inf must be finite");
}

TEST(CubicSplinePathValidation, Domain) {
  const MatrixXd w = random_matrix(3, 2, 1);
  const auto nk = SplineBoundary::NotAKnot;
  expect_invalid([&] { CubicSplinePath(w, KnotSpacing::Uniform, nk, kNan, 1.0); },
                 "s_begin = nan must be finite");
  expect_invalid([&] { CubicSplinePath(w, KnotSpacing::Uniform, nk, 0.0, kInf); },
                 "s_end = inf must be finite");
  expect_invalid([&] { CubicSplinePath(w, KnotSpacing::Uniform, nk, 1.0, 1.0); },
                 "s_begin = 1 must be < s_end = 1");
  expect_invalid([&] { CubicSplinePath(w, KnotSpacing::ChordLength, nk, 2.0, -0.5); },
                 "s_begin = 2 must be < s_end = -0.5");
}

TEST(CubicSplinePathValidation, ChordLengthNeedsDistinctConsecutiveWaypoints) {
  MatrixXd w(4, 2);
  w << 0, 0, 1, 1, 1, 1, 2, 0;
  expect_invalid([&] { CubicSplinePath(w, KnotSpacing::ChordLength); },
                 "waypoints[2] equals waypoints[1]: chord-length knots need distinct consecutive waypoints");
  EXPECT_NO_THROW(CubicSplinePath(w, KnotSpacing::Uniform));  // repeated points are fine with uniform knots
}

TEST(CubicSplinePathValidation, EndDerivatives) {
  const MatrixXd w = random_matrix(4, 2, 1);
  const auto clamped = SplineBoundary::Clamped;
  // scipy's "clamped": no derivative given means zero end slopes.
  const CubicSplinePath zero(w, KnotSpacing::Uniform, clamped);
  VectorXd q(2), dq(2), ddq(2);
  zero.evaluate(0.0, q, dq, ddq);
  EXPECT_LT(dq.cwiseAbs().maxCoeff(), 1e-12);  // zero up to the rounding of the spline's coefficients
  zero.evaluate(1.0, q, dq, ddq);
  EXPECT_LT(dq.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(zero.start_derivative(), VectorXd::Zero(2));
  expect_invalid([&] { CubicSplinePath(w, KnotSpacing::Uniform, clamped, 0.0, 1.0, vec({1, 2}), vec({1, 2, 3})); },
                 "end_derivative has size 3, expected 2 (one per coordinate)");
  expect_invalid([&] { CubicSplinePath(w, vec({0, 1, 2, 3}), clamped, vec({1, kNan}), vec({1, 2})); },
                 "start_derivative[1] = nan must be finite");
  expect_invalid([&] { CubicSplinePath(w, vec({0, 1, 2, 3}), clamped, vec({1, 2}), vec({kInf, 2})); },
                 "end_derivative[0] = inf must be finite");
  expect_invalid([&] { CubicSplinePath(w, KnotSpacing::Uniform, SplineBoundary::Natural, 0.0, 1.0, vec({1, 2})); },
                 "start_derivative and end_derivative are only used with the clamped boundary");
  expect_invalid([&] { CubicSplinePath(w, vec({0, 1, 2, 3}), SplineBoundary::NotAKnot, {}, vec({1, 2})); },
                 "start_derivative and end_derivative are only used with the clamped boundary");
}

TEST(CubicSplinePathValidation, ExplicitKnots) {
  const MatrixXd w = random_matrix(4, 1, 1);
  expect_invalid([&] { CubicSplinePath(w, vec({0, 1, 2})); }, "knots has size 3, expected 4 (one per waypoint)");
  expect_invalid([&] { CubicSplinePath(w, vec({0, kNan, 2, 3})); }, "knots[1] = nan must be finite");
  expect_invalid([&] { CubicSplinePath(w, vec({0, 0.5, 0.5, 3})); },
                 "knots[2] = 0.5 must be > knots[1] = 0.5 (strictly increasing)");
  expect_invalid([&] { CubicSplinePath(w, vec({0, 2, 1, 3})); },
                 "knots[2] = 1 must be > knots[1] = 2 (strictly increasing)");
}

TEST(PiecewisePolynomialPathValidation, Breakpoints) {
  const std::vector<MatrixXd> one(1, MatrixXd::Zero(2, 1));
  expect_invalid([&] { PiecewisePolynomialPath(vec({0}), {}); },
                 "breakpoints has 1 entries, expected at least 2");
  expect_invalid([&] { PiecewisePolynomialPath(vec({0, kInf}), one); }, "breakpoints[1] = inf must be finite");
  expect_invalid([&] { PiecewisePolynomialPath(vec({1, 0}), one); },
                 "breakpoints[1] = 0 must be > breakpoints[0] = 1 (strictly increasing)");
}

TEST(PiecewisePolynomialPathValidation, Coefficients) {
  const VectorXd b = vec({0, 1, 2});
  expect_invalid([&] { PiecewisePolynomialPath(b, {MatrixXd::Zero(2, 1)}); },
                 "coefficients has size 1, expected 2 (one piece per interval of breakpoints, which has 3 entries)");
  expect_invalid([&] { PiecewisePolynomialPath(b, {MatrixXd::Zero(0, 2), MatrixXd::Zero(0, 2)}); },
                 "coefficients[0] is empty, expected shape (degree + 1, n)");
  expect_invalid([&] { PiecewisePolynomialPath(b, {MatrixXd::Zero(2, 0), MatrixXd::Zero(2, 0)}); },
                 "coefficients[0] is empty, expected shape (degree + 1, n)");
  expect_invalid([&] { PiecewisePolynomialPath(b, {MatrixXd::Zero(4, 2), MatrixXd::Zero(3, 2)}); },
                 "coefficients[1] has shape (3, 2), expected (4, 2) (as coefficients[0])");
  MatrixXd bad = MatrixXd::Zero(4, 2);
  bad(2, 1) = kNan;
  expect_invalid([&] { PiecewisePolynomialPath(b, {MatrixXd::Zero(4, 2), bad}); },
                 "coefficients[1][2, 1] = nan must be finite");
}

TEST(SampledPathValidation, Shapes) {
  const MatrixXd z1 = MatrixXd::Zero(1, 2), z = MatrixXd::Zero(3, 2);
  expect_invalid([&] { SampledPath(vec({0}), z1, z1, z1); },
                 "s has 1 entries, expected at least 2");
  expect_invalid([&] { SampledPath(vec({0, 1, 2}), MatrixXd::Zero(3, 0), z, z); },
                 "q has 0 columns, expected at least 1 coordinate");
  expect_invalid([&] { SampledPath(vec({0, 1, 2}), MatrixXd::Zero(2, 2), z, z); },
                 "q has shape (2, 2), expected (3, 2) (one row per sample)");
  expect_invalid([&] { SampledPath(vec({0, 1, 2}), z, MatrixXd::Zero(2, 2), z); },
                 "dq has shape (2, 2), expected (3, 2) (as q)");
  expect_invalid([&] { SampledPath(vec({0, 1, 2}), z, z, MatrixXd::Zero(3, 3)); },
                 "ddq has shape (3, 3), expected (3, 2) (as q)");
}

TEST(SampledPathValidation, Values) {
  const MatrixXd z = MatrixXd::Zero(3, 2);
  MatrixXd bad = z;
  bad(2, 0) = kNan;
  expect_invalid([&] { SampledPath(vec({0, kNan, 2}), z, z, z); }, "s[1] = nan must be finite");
  expect_invalid([&] { SampledPath(vec({0, 1, 2}), bad, z, z); }, "q[2, 0] = nan must be finite");
  expect_invalid([&] { SampledPath(vec({0, 1, 2}), z, bad, z); }, "dq[2, 0] = nan must be finite");
  expect_invalid([&] { SampledPath(vec({0, 1, 2}), z, z, bad); }, "ddq[2, 0] = nan must be finite");
  expect_invalid([&] { SampledPath(vec({0, 1, 1}), z, z, z); }, "s[2] = 1 must be > s[1] = 1 (strictly increasing)");
}
