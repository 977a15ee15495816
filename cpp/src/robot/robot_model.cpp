// RobotModel's own small parts: the empty model, the size check every algorithm shares, and rebuilding a
// model from the record of how it was built. The algorithms each have a file of their own: urdf_loader,
// mimic, rnea, torque_lanes, kinematics, combine, free_object.
#include "pathpace/robot_model.hpp"

#include <memory>
#include <string>

#include "base/validate.hpp"
#include "robot/bodies.hpp"

namespace pathpace {

RobotModel::RobotModel() : tree_(std::make_shared<const detail::RobotTree>()), gravity_(0.0, 0.0, -9.81) {}

void RobotModel::check_q(const Eigen::Ref<const Eigen::VectorXd>& v, const char* name) const {
  if (v.size() != nq())
    detail::fail(std::string(name) + " has size " + std::to_string(v.size()) + ", robot '" + name_ + "' has " +
                 std::to_string(nq()) + " joints");
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
