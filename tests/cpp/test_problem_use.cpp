// What the Python module used to decide on its own and C++ now does for every caller: a problem is read
// or modified, never both at once (TimeScalingProblem::Use), and Trajectory::sample refuses a sampling
// that would not fit in max_memory.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/time_scaling_problem.hpp"
#include "pathpace/trajectory.hpp"
#include "test_util.hpp"

using namespace pathpace;
using pathpace::test::error_of;

namespace {

std::shared_ptr<const Path> line(int dof) {
  Eigen::MatrixXd wp(2, dof);
  wp.row(0).setZero();
  wp.row(1).setOnes();
  return std::make_shared<CubicSplinePath>(wp);
}

// The Error of f(), "" if it throws none (or another type).
std::string pathpace_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput&) {
    return "";
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ProblemUse, AWriteWhileAnotherThreadReadsIsRefusedNamingTheCaller) {
  TimeScalingProblem prob(line(2), 10);
  prob.add_velocity_limits(-Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones());
  std::string msg;
  {
    const TimeScalingProblem::Use reading(prob, TimeScalingProblem::Use::Read, "solve");  // as a solve holds it
    std::thread other([&] {
      msg = pathpace_error([&] { prob.add_acceleration_limits(-Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones()); });
    });
    other.join();
    // Reads go on meanwhile, in this thread and in others.
    EXPECT_TRUE(prob.solve().ok());
    std::string other_read = "unset";
    std::thread reader([&] { other_read = pathpace_error([&] { prob.feasible_set(3); }); });
    reader.join();
    EXPECT_EQ(other_read, "");
  }
  EXPECT_EQ(msg,
            "add_acceleration_limits: this TimeScalingProblem is being solved in another thread; add every "
            "constraint before solving from several threads");
  EXPECT_EQ(prob.constraints().size(), 1u);  // refused: nothing added
  prob.add_acceleration_limits(-Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones());  // released: allowed again
  EXPECT_EQ(prob.constraints().size(), 2u);
}

TEST(ProblemUse, AReadOrWriteWhileAnotherThreadModifiesIsRefused) {
  TimeScalingProblem prob(line(2), 10);
  prob.add_velocity_limits(-Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones());
  std::string solve_msg, set_msg;
  {
    const TimeScalingProblem::Use writing(prob, TimeScalingProblem::Use::Write, "add_contacts");
    // The modifying thread itself may read and modify (add_contacts calls add_constraint).
    prob.set_boundary_speeds(0.0, 0.0);
    EXPECT_EQ(prob.feasible_set(0).index, 0);
    std::thread other([&] {
      solve_msg = pathpace_error([&] { prob.solve(); });
      set_msg = pathpace_error([&] { prob.set_boundary_speeds(0.1, 0.0); });
    });
    other.join();
  }
  EXPECT_EQ(solve_msg.rfind("solve: this TimeScalingProblem is being modified in another thread", 0), 0u) << solve_msg;
  EXPECT_EQ(set_msg.rfind("set_boundary_speeds: this TimeScalingProblem is being modified", 0), 0u) << set_msg;
  EXPECT_EQ(prob.sdot_begin(), 0.0);
  EXPECT_TRUE(prob.solve().ok());  // released
}

TEST(ProblemUse, ACopyStartsUnusedAndConcurrentSolvesShareOneProblem) {
  TimeScalingProblem prob(line(3), 200);
  prob.add_velocity_limits(-Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones());
  prob.add_acceleration_limits(-Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones());
  const TimeScalingProblem::Use reading(prob, TimeScalingProblem::Use::Read, "solve");
  TimeScalingProblem copy = prob;  // not held by `reading`
  copy.set_boundary_speeds(0.0, 0.0);
  std::atomic<int> ok{0};
  std::thread a([&] { ok += prob.solve().ok(); }), b([&] { ok += prob.solve().ok(); });
  a.join();
  b.join();
  EXPECT_EQ(ok.load(), 2);
}

TEST(TrajectorySample, RefusesPastMaxMemoryBeforeAllocatingAndSaysHowMuch) {
  const Trajectory tr(line(2), Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(1.0, 1.0));  // T = 1
  // 1e8 + 2 samples x (1 + 6 x 2) doubles: about 10.4 GB.
  const std::string msg = error_of([&] { tr.sample(1e-8); });
  EXPECT_NE(msg.find("dt = 1e-08 gives 1e+08 samples of a 2-coordinate trajectory of duration 1: about 10.4 GB, more "
                     "than max_memory = 1 GB"),
            std::string::npos)
      << msg;
  EXPECT_NE(error_of([&] { tr.sample(1e-4, 1e6); }).find("about 0.00104 GB, more than max_memory = 0.001 GB"),
            std::string::npos);
  EXPECT_NE(error_of([&] { tr.sample(1e-3, 0.0); }).find("max_memory = 0.000000 must be > 0 (bytes)"), std::string::npos);
  const Trajectory::Samples s = tr.sample(1e-3);
  ASSERT_EQ(s.t.size(), 1001);
  EXPECT_EQ(s.q.rows(), 1001);
  EXPECT_EQ(s.qdd.cols(), 2);
  EXPECT_DOUBLE_EQ(s.t[1000], 1.0);
  // The spline through the grid passes through q(t_k) at the grid times.
  const Trajectory::Samples grid = tr.sample_at(tr.times(), true);
  const Trajectory::Samples exact = tr.sample_at(tr.times());
  EXPECT_LT((grid.q - exact.q).cwiseAbs().maxCoeff(), 1e-12);
}
