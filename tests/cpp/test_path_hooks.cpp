// Path::polynomial() is the only way the problem learns that a path has polynomial pieces (issue 22): the
// automatic grid's breakpoints, guarantee = continuous and restart's exact tail all follow the hook, not
// the concrete type. A path of another type that answers with pieces gets all three; one that answers
// nullptr gets none of them, and its values are still what it says.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "pathpace/pathpace.hpp"
#include "paths/sub_path.hpp"
#include "test_util.hpp"

using namespace pathpace;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// A path of its own type that evaluates a polynomial path (and answers the hook with it or not).
class Wrapper : public Path {
 public:
  Wrapper(std::shared_ptr<const PiecewisePolynomialPath> inner, bool tell) : inner_(std::move(inner)), tell_(tell) {}
  int dof() const override { return inner_->dof(); }
  double s_begin() const override { return inner_->s_begin(); }
  double s_end() const override { return inner_->s_end(); }
  using Path::evaluate;
  void evaluate(double s, Eigen::Ref<VectorXd> q, Eigen::Ref<VectorXd> dq, Eigen::Ref<VectorXd> ddq) const override {
    inner_->evaluate(s, q, dq, ddq);
  }
  const PiecewisePolynomialPath* polynomial() const override { return tell_ ? inner_.get() : nullptr; }

 private:
  std::shared_ptr<const PiecewisePolynomialPath> inner_;
  bool tell_;
};

std::shared_ptr<const CubicSplinePath> spline() {
  MatrixXd w(5, 2);
  w << 0.0, 0.0, 1.0, 0.5, 0.2, 1.5, -0.4, 0.9, 0.3, -0.2;
  VectorXd knots(5);
  knots << 0.0, 0.13, 0.5, 0.61, 1.0;
  return std::make_shared<CubicSplinePath>(w, knots);
}

TimeScalingProblem problem(std::shared_ptr<const Path> path, int N = 60) {
  TimeScalingProblem p(std::move(path), N);
  p.add_velocity_limits(VectorXd::Constant(2, -1.0), VectorXd::Constant(2, 1.0));
  p.add_acceleration_limits(VectorXd::Constant(2, -2.0), VectorXd::Constant(2, 2.0));
  return p;
}

SolverOptions continuous() {
  SolverOptions o;
  o.guarantee = Guarantee::Continuous;
  return o;
}

TEST(PathHooks, ConcretePolynomialPathsAnswerWithThemselves) {
  auto cs = spline();
  EXPECT_EQ(cs->polynomial(), cs.get());
  MatrixXd q = cs->q(cs->knots()), dq = cs->dq(cs->knots()), ddq = cs->ddq(cs->knots());
  SampledPath sp(cs->knots(), q, dq, ddq);
  EXPECT_EQ(sp.polynomial(), &sp);
  test::ClosedFormPath line(1, [](double s, auto q, auto dq, auto ddq) {
    q[0] = s;
    dq[0] = 1.0;
    ddq[0] = 0.0;
  });
  EXPECT_EQ(line.polynomial(), nullptr);  // the default
}

TEST(PathHooks, AutoGridTakesTheBreakpointsTheHookGives) {
  auto cs = spline();
  const VectorXd own = auto_grid(*cs, 1e-2, 4);
  EXPECT_EQ(auto_grid(Wrapper(cs, true), 1e-2, 4), own);  // the same pieces, so the same grid, bit for bit
  const VectorXd silent = auto_grid(Wrapper(cs, false), 1e-2, 4);
  bool has_013 = false;
  for (Eigen::Index i = 0; i < silent.size(); ++i) has_013 = has_013 || silent[i] == 0.13;
  EXPECT_FALSE(has_013);  // 0.13 is no dyadic point of [0, 1]: it came from the breakpoints alone
  bool own_013 = false;
  for (Eigen::Index i = 0; i < own.size(); ++i) own_013 = own_013 || own[i] == 0.13;
  EXPECT_TRUE(own_013);
}

TEST(PathHooks, ContinuousGuaranteeFollowsTheHook) {
  auto cs = spline();
  const Result own = problem(cs).solve(continuous());
  ASSERT_TRUE(own.ok()) << own.message;
  const Result told = problem(std::make_shared<Wrapper>(cs, true)).solve(continuous());
  EXPECT_EQ(told.duration, own.duration);
  EXPECT_NE(test::error_of([&] { problem(std::make_shared<Wrapper>(cs, false)).solve(continuous()); })
                .find("piecewise-polynomial paths"),
            std::string::npos);
}

TEST(PathHooks, RestartTailHasPiecesExactlyWhenTheHookDoes) {
  auto cs = spline();
  const double s0 = 0.4321;
  const TimeScalingProblem told = problem(std::make_shared<Wrapper>(cs, true)).restarted(s0, 0.5);
  const TimeScalingProblem silent = problem(std::make_shared<Wrapper>(cs, false)).restarted(s0, 0.5);
  ASSERT_NE(told.path()->polynomial(), nullptr);
  EXPECT_EQ(told.path()->s_begin(), s0);
  EXPECT_EQ(silent.path()->polynomial(), nullptr);
  EXPECT_EQ(silent.path()->s_begin(), s0);
  // Both tails are the parent's values from s0 on (the polynomial one after its Taylor shift, to rounding).
  VectorXd s = VectorXd::LinSpaced(41, s0, 1.0);
  EXPECT_EQ(silent.path()->ddq(s), cs->ddq(s));
  EXPECT_LT((told.path()->ddq(s) - cs->ddq(s)).cwiseAbs().maxCoeff(), 1e-12 * cs->ddq(s).cwiseAbs().maxCoeff());
  // Before s0 a tail is clamped to s0.
  EXPECT_EQ(silent.path()->q(VectorXd::Constant(1, 0.1)), cs->q(VectorXd::Constant(1, s0)));
  // The tail of the whole path is the path itself.
  auto whole = std::make_shared<Wrapper>(cs, false);
  EXPECT_EQ(detail::path_tail(whole, 0.0).get(), whole.get());
}

}  // namespace
