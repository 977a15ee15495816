// Built against an installed pathpace via find_package(pathpace): solves a small problem through the
// installed headers and library only; exits non-zero on failure.
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

}  // namespace

int main() {
  pathpace::TimeScalingProblem prob(std::make_shared<Line>(), 1024);
  prob.add_velocity_limits(Eigen::VectorXd::Constant(1, -1.0), Eigen::VectorXd::Constant(1, 1.0));
  prob.add_acceleration_limits(Eigen::VectorXd::Constant(1, -1.0), Eigen::VectorXd::Constant(1, 1.0));
  const pathpace::Result r = prob.solve();
  std::printf("consumer: status %s, T = %.6f (expected 4)\n", pathpace::to_string(r.status), r.duration);
  return (r.status == pathpace::Status::Optimal && std::abs(r.duration - 4.0) < 1e-3) ? 0 : 1;
}
