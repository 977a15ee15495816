// Built against an installed pathpace via find_package(pathpace): solves small problems through the
// installed headers and library only; exits non-zero on failure. The part between the README markers is
// README.md's C++ example verbatim (tests/python/test_readme.py checks that they agree), so `make test`
// compiles and runs the example a user pastes.
#include <cmath>
#include <cstdio>
#include <memory>

#include <pathpace/pathpace.hpp>

namespace {

class Line : public pathpace::Path {
 public:
  int dof() const override { return 1; }
  double s_begin() const override { return 0.0; }
  double s_end() const override { return 1.0; }
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override {
    q[0] = 3.0 * s;
    dq[0] = 3.0;
    ddq[0] = 0.0;
  }
};

// README example begin
// Time a 2-joint spline through three waypoints under velocity and acceleration limits.
int readme_example() {
  Eigen::MatrixXd waypoints(3, 2);  // one waypoint per row
  waypoints << 0.0, 0.0,
               1.0, 0.5,
               0.2, 1.5;
  auto path = std::make_shared<pathpace::CubicSplinePath>(waypoints);  // s in [0, 1], not-a-knot

  pathpace::TimeScalingProblem problem(path, 1000);  // N = 1000 uniform grid intervals
  const Eigen::Vector2d vmax(1.0, 1.0), amax(2.0, 2.0);
  problem.add_velocity_limits(-vmax, vmax);          // rad/s
  problem.add_acceleration_limits(-amax, amax);      // rad/s²
  const pathpace::Result result = problem.solve();
  if (!result.ok()) {
    std::printf("%s: %s\n", pathpace::to_string(result.status), result.message.c_str());
    return 1;
  }
  const pathpace::Trajectory trajectory = result.trajectory();
  Eigen::MatrixXd q, qd, qdd;  // (samples, joints)
  trajectory.evaluate(trajectory.sample_times(0.01), q, qd, qdd);
  std::printf("T = %.4f s, %ld samples at 100 Hz\n", trajectory.duration(), static_cast<long>(q.rows()));
  return 0;
}
// README example end

}  // namespace

int main() {
  pathpace::TimeScalingProblem prob(std::make_shared<Line>(), 1024);
  prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1.0), Eigen::VectorXd::Constant(1, 1.0));
  prob.add_acceleration_limits(Eigen::VectorXd::Constant(1, -1.0), Eigen::VectorXd::Constant(1, 1.0));
  const pathpace::Result r = prob.solve();
  std::printf("consumer: status %s, T = %.6f (expected 4)\n", pathpace::to_string(r.status), r.duration);
  if (!(r.status == pathpace::Status::Optimal && std::abs(r.duration - 4.0) < 1e-3)) return 1;
  return readme_example();
}
