// RobotModel::free_object: a rigid body on six floating coordinates (sec. III.b), e.g. a carried box.
#include <algorithm>
#include <cmath>
#include <memory>

#include <Eigen/Eigenvalues>

#include "base/validate.hpp"
#include "robot/bodies.hpp"
#include "robot/tree_builder.hpp"

namespace pathpace {

RobotModel RobotModel::free_object(const std::string& name, double mass, const Eigen::Vector3d& com,
                                   const Eigen::Matrix3d& inertia, const Eigen::Vector3d& gravity) {
  if (name.empty()) detail::fail("name must not be empty");
  if (!(mass > 0.0) || !std::isfinite(mass)) detail::fail("mass = " + detail::fmt(mass) + " must be > 0 and finite");
  detail::require_finite("com", com);
  detail::require_finite("inertia", inertia);
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * std::max(1.0, inertia.cwiseAbs().maxCoeff()))
    detail::fail("inertia must be symmetric");
  const double min_eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues().minCoeff();
  if (min_eig < -1e-12 * std::max(1.0, inertia.cwiseAbs().maxCoeff()))
    detail::fail("inertia has eigenvalue " + detail::fmt(min_eig) + ": it must be positive semi-definite");
  detail::check_gravity(gravity);
  RobotModel m;
  m.name_ = name;
  m.gravity_ = gravity;
  auto tree = std::make_shared<detail::RobotTree>();
  detail::TreeBuilder b{tree->bodies, m.joint_names_, m.link_names_, tree->links};
  const int body = b.add_floating_base();
  tree->bodies[static_cast<size_t>(body)].inertia = detail::spatial_inertia(mass, com, inertia);
  b.add_link(name, body, Eigen::Isometry3d::Identity());
  b.store_limits(m.q_lo_, m.q_hi_, m.v_max_, m.effort_);
  m.tree_ = std::move(tree);
  auto source = std::make_shared<Source>();
  source->kind = Source::Kind::FreeObject;
  source->options.gravity = gravity;
  source->name = name;
  source->mass = mass;
  source->com = com;
  source->inertia = inertia;
  m.source_ = std::move(source);
  return m;
}

}  // namespace pathpace
