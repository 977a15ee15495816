// Inverse dynamics per call in C++ (no Python on either side): pathpace's RNEA against pinocchio's on
// the same URDF and the same random states. Built and run by bench/rnea_cpp.sh.
#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include <pinocchio/algorithm/joint-configuration.hpp>
#include <pinocchio/algorithm/model.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/parsers/urdf.hpp>

#include <pathpace/pathpace.hpp>

template <typename F>
double us_per_call(F&& f, int reps) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < reps; ++i) f(i);
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / reps;
}

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const std::string urdf = argv[1];
  const bool floating = argc > 2 && std::string(argv[2]) == "floating";
  std::vector<std::string> lock;
  for (int i = 3; i < argc; ++i) lock.push_back(argv[i]);

  pinocchio::Model full;
  if (floating) {
    pinocchio::JointModelComposite jc;
    jc.addJoint(pinocchio::JointModelPX());
    jc.addJoint(pinocchio::JointModelPY());
    jc.addJoint(pinocchio::JointModelPZ());
    jc.addJoint(pinocchio::JointModelRZ());
    jc.addJoint(pinocchio::JointModelRY());
    jc.addJoint(pinocchio::JointModelRX());
    pinocchio::urdf::buildModel(urdf, jc, full);
  } else {
    pinocchio::urdf::buildModel(urdf, full);
  }
  std::vector<pinocchio::JointIndex> ids;
  for (const auto& n : lock) ids.push_back(full.getJointId(n));
  const pinocchio::Model model = pinocchio::buildReducedModel(full, ids, pinocchio::neutral(full));
  pinocchio::Data data(model);

  pathpace::RobotModelOptions o;
  o.floating_base = floating;
  for (const auto& n : lock) o.locked_joints[n] = 0.0;
  const pathpace::RobotModel robot = pathpace::RobotModel::from_urdf_file(urdf, o);
  pathpace::RobotWorkspace ws(robot);

  const int n = robot.nq(), m = 256, reps = 200000;
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::MatrixXd Q(n, m), V(n, m), A(n, m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) Q(i, j) = U(gen), V(i, j) = U(gen), A(i, j) = U(gen);
  Eigen::VectorXd tau(n);
  double sink = 0;
  const double t_pin = us_per_call([&](int i) { sink += pinocchio::rnea(model, data, Q.col(i % m), V.col(i % m), A.col(i % m))[0]; }, reps);
  const double t_ours = us_per_call([&](int i) {
    robot.inverse_dynamics(ws, Q.col(i % m), V.col(i % m), A.col(i % m), true, tau);
    sink += tau[0];
  }, reps);
  // Agreement on the last state, as a sanity check of what is timed.
  const Eigen::VectorXd d = pinocchio::rnea(model, data, Q.col(0), V.col(0), A.col(0));
  robot.inverse_dynamics(ws, Q.col(0), V.col(0), A.col(0), true, tau);
  std::printf("nq=%d pinocchio %.3f us, pathpace %.3f us, ratio %.2f, max |diff| %.1e (sink %g)\n", n, t_pin, t_ours,
              t_ours / t_pin, (d - tau).cwiseAbs().maxCoeff(), sink > 0 ? 1.0 : 0.0);
  return 0;
}
