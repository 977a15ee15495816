// FunctionPath (issue 22, item 1 in C++): a path from a std::function of a vector of s, the C++ twin of
// Python's CallbackPath. Oracles: the CubicSplinePath it wraps (the same values at every s, so the same rows
// and T), a straight line whose timing is known in closed form, and every validation branch.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "pathpace/pathpace.hpp"
#include "test_util.hpp"

using namespace pathpace;
using namespace pathpace::test;

namespace {

std::shared_ptr<const CubicSplinePath> spline() {
  Eigen::MatrixXd w(4, 2);
  w << 0.0, -0.3, 0.6, 0.4, 1.1, -0.2, 0.5, 0.9;
  return std::make_shared<CubicSplinePath>(w);
}

// The spline seen only through a function (its batch evaluate), counting the calls.
FunctionPath::Function through(std::shared_ptr<const Path> p, int* calls = nullptr) {
  return [p, calls](const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                    Eigen::MatrixXd& ddq) {
    if (calls) ++*calls;
    p->evaluate(s, q, dq, ddq);
  };
}

double duration(std::shared_ptr<const Path> path, int N) {
  TimeScalingProblem prob(std::move(path), N);
  prob.add_velocity_limits(-Eigen::Vector2d::Constant(1.0), Eigen::Vector2d::Constant(1.0));
  prob.add_acceleration_limits(-Eigen::Vector2d(2.0, 3.0), Eigen::Vector2d(2.0, 3.0));
  const Result r = prob.solve();
  EXPECT_EQ(r.status, Status::Optimal);
  return r.duration;
}

TEST(FunctionPath, IsThePathItEvaluatesAndTimesLikeIt) {
  auto ref = spline();
  int calls = 0;
  auto fp = std::make_shared<FunctionPath>(through(ref, &calls), 2, ref->s_begin(), ref->s_end());
  EXPECT_EQ(fp->dof(), 2);
  EXPECT_EQ(fp->polynomial(), nullptr);  // no pieces: guarantee = continuous needs a polynomial path
  const Eigen::VectorXd s = Eigen::VectorXd::LinSpaced(37, -0.5, 1.5);  // outside the domain: clamped
  Eigen::MatrixXd q, dq, ddq, rq, rdq, rddq;
  fp->evaluate(s, q, dq, ddq);
  ref->evaluate(s, rq, rdq, rddq);
  EXPECT_EQ(calls, 1);  // one call per batch
  EXPECT_EQ(q, rq);
  EXPECT_EQ(dq, rdq);
  EXPECT_EQ(ddq, rddq);
  Eigen::VectorXd q1(2), dq1(2), ddq1(2);
  fp->evaluate(0.37, q1, dq1, ddq1);
  EXPECT_EQ(q1, ref->q(Eigen::VectorXd::Constant(1, 0.37)).row(0).transpose());
  // The same rows at the same grid: the same T (both paths give bit-equal values).
  EXPECT_EQ(duration(fp, 150), duration(ref, 150));
}

TEST(FunctionPath, TorqueLimitsFromStdFunctionsOnAFunctionPath) {
  // Both of issue 22's std::function entry points together: the path and the dynamics from the user.
  // A point mass on each coordinate under gravity on the second: τ = m q̈ + (0, m g).
  const SecondOrderFunctions::InverseDynamics id = [](const Eigen::MatrixXd& q, const Eigen::MatrixXd&,
                                                      const Eigen::MatrixXd& qdd) {
    Eigen::MatrixXd t = 2.0 * qdd;
    t.col(1).array() += 2.0 * 9.81;
    (void)q;
    return t;
  };
  auto ref = spline();
  auto fp = std::make_shared<FunctionPath>(through(ref), 2);
  double T[2];
  int i = 0;
  for (std::shared_ptr<const Path> p : {std::shared_ptr<const Path>(ref), std::shared_ptr<const Path>(fp)}) {
    TimeScalingProblem prob(p, 120);
    prob.add_torque_limits(id, Eigen::Vector2d(-8.0, 5.0), Eigen::Vector2d(8.0, 35.0));
    const Result r = prob.solve();
    ASSERT_EQ(r.status, Status::Optimal);
    T[i++] = r.duration;
  }
  EXPECT_EQ(T[1], T[0]);
}

TEST(FunctionPath, AStraightLineAtItsVelocityLimitTakesLengthOverSpeed) {
  // q = d·s on [0, 2] with only velocity limits and free end speeds is timed at ṡ = min_j v_j / |d_j|
  // everywhere: T = 2 / ṡ exactly (every row is the same bound on ṡ²).
  const Eigen::Vector3d d(0.5, -2.0, 1.0);
  auto line = std::make_shared<FunctionPath>(
      [d](const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq, Eigen::MatrixXd& ddq) {
        q = s * d.transpose();
        dq = Eigen::VectorXd::Ones(s.size()) * d.transpose();
        ddq = Eigen::MatrixXd::Zero(s.size(), 3);
      },
      3, 0.0, 2.0);
  TimeScalingProblem prob(line, 40);
  prob.add_velocity_limits(-Eigen::Vector3d(1.0, 1.0, 1.0), Eigen::Vector3d(1.0, 1.0, 1.0));
  const double sdot = 1.0 / 2.0;  // joint 2: |d| = 2, v = 1
  prob.set_boundary_speeds(sdot, sdot);
  const Result r = prob.solve();
  ASSERT_EQ(r.status, Status::Optimal);
  EXPECT_NEAR(r.duration, 2.0 / sdot, 1e-9);
}

TEST(FunctionPath, ValidationNamesWhatIsWrong) {
  auto ok = through(spline());
  EXPECT_NE(error_of([&] { FunctionPath(FunctionPath::Function(), 2); }).find("function is empty"), std::string::npos);
  EXPECT_NE(error_of([&] { FunctionPath(ok, 0); }).find("dof = 0 must be >= 1"), std::string::npos);
  EXPECT_NE(error_of([&] { FunctionPath(ok, 2, 1.0, 1.0); }).find("must be finite with s_begin < s_end"),
            std::string::npos);
  EXPECT_NE(error_of([&] { FunctionPath(ok, 2, 0.0, std::numeric_limits<double>::infinity()); })
                .find("(s_begin, s_end) = (0, inf)"),
            std::string::npos);
  // dof 3 declared, the function fills 2 columns.
  const FunctionPath wrong(ok, 3);
  Eigen::MatrixXd q, dq, ddq;
  EXPECT_NE(error_of([&] { wrong.evaluate(Eigen::VectorXd::LinSpaced(5, 0, 1), q, dq, ddq); })
                .find("q has shape (5, 2) for 5 values of s, expected (5, 3)"),
            std::string::npos);
  const FunctionPath nan_dd(
      [](const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq, Eigen::MatrixXd& ddq) {
        q = s;
        dq = Eigen::VectorXd::Ones(s.size());
        ddq = Eigen::VectorXd::Zero(s.size());
        ddq(2) = std::numeric_limits<double>::quiet_NaN();
      },
      1);
  EXPECT_NE(error_of([&] { nan_dd.evaluate(Eigen::VectorXd::LinSpaced(5, 0, 1), q, dq, ddq); })
                .find("ddq(2, 0) = nan at s = 0.5 must be finite"),
            std::string::npos);
  // ... and the problem's construction says so too (it evaluates the path on its grid).
  EXPECT_NE(error_of([&] { TimeScalingProblem(std::make_shared<FunctionPath>(wrong), 10); }).find("FunctionPath"),
            std::string::npos);
}

}  // namespace
