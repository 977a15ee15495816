// RobotModel: centre of mass, and rebuilding a model from the record of how it was built.
#include <vector>

#include "base/validate.hpp"
#include "pathpace/robot_model.hpp"

namespace pathpace {

namespace {

// Mass and first moment m·c of a spatial inertia in Featherstone's layout (angular first):
// I = [[Ī + m c× c×ᵀ, m c×], [m c×ᵀ, m 1]], so the lower-left block is m c×ᵀ = -m c×.
void mass_and_moment(const Eigen::Matrix<double, 6, 6>& I, double& m, Eigen::Vector3d& mc) {
  m = I(3, 3);
  const Eigen::Matrix3d mcx = I.block<3, 3>(0, 3);  // m c×
  mc = Eigen::Vector3d(mcx(2, 1), mcx(0, 2), mcx(1, 0));
}

}  // namespace

double RobotModel::mass() const {
  double total = 0.0;
  for (const Body& b : bodies_) total += b.inertia(3, 3);
  return total;
}

Eigen::Vector3d RobotModel::center_of_mass(const Eigen::VectorXd& q) const {
  check_q(q, "q");
  detail::require_finite("q", q);
  std::vector<Eigen::Isometry3d> T;
  body_placements(q, T);
  double total = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < bodies_.size(); ++i) {
    double m;
    Eigen::Vector3d mc;
    mass_and_moment(bodies_[i].inertia, m, mc);
    total += m;
    moment += m * T[i].translation() + T[i].linear() * mc;  // m · (world position of the body's com)
  }
  if (!(total > 0.0)) detail::fail("robot '" + name_ + "' has no moving mass: its centre of mass is undefined");
  return moment / total;
}

RobotModel RobotModel::rebuild(const Source& source) {
  switch (source.kind) {
    case Source::Kind::Urdf:
      return from_urdf_string(source.urdf, source.options);
    case Source::Kind::Combine:
      return combine(source.parts, source.name);
    case Source::Kind::FreeObject:
      return free_object(source.name, source.mass, source.com, source.inertia, source.options.gravity);
  }
  detail::fail("source.kind is not a known kind of model");
}

}  // namespace pathpace
