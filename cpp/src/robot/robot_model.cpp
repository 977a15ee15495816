// RobotModel's own small parts: the empty model, the size check every algorithm shares, and rebuilding a
// model from the record of how it was built. The algorithms each have a file of their own: urdf_loader,
// mimic, rnea, torque_lanes, kinematics, combine, free_object.
#include "pathpace/robot_model.hpp"

#include <memory>
#include <string>
#include <utility>

#include "base/validate.hpp"
#include "robot/bodies.hpp"

namespace pathpace {

namespace {
// One empty tree and one record of it for every empty and moved-from model: a move then allocates nothing.
// The record is a combine() of no parts, which rebuild() reads as the empty model.
const std::shared_ptr<const detail::RobotTree>& empty_tree() {
  static const std::shared_ptr<const detail::RobotTree> tree = std::make_shared<const detail::RobotTree>();
  return tree;
}
const std::shared_ptr<const RobotModel::Source>& empty_source() {
  static const std::shared_ptr<const RobotModel::Source> source = [] {
    auto s = std::make_shared<RobotModel::Source>();
    s->kind = RobotModel::Source::Kind::Combine;
    return s;
  }();
  return source;
}
}  // namespace

RobotModel::RobotModel() : tree_(empty_tree()), gravity_(0.0, 0.0, -9.81), source_(empty_source()) {}

RobotModel::RobotModel(RobotModel&& other) noexcept : RobotModel() { swap(other); }

RobotModel& RobotModel::operator=(RobotModel&& other) noexcept {
  if (this != &other) {
    RobotModel taken(std::move(other));
    swap(taken);
  }
  return *this;
}

void RobotModel::swap(RobotModel& o) noexcept {
  using std::swap;
  swap(name_, o.name_);
  swap(tree_, o.tree_);
  swap(joint_names_, o.joint_names_);
  swap(link_names_, o.link_names_);
  swap(q_lo_, o.q_lo_);
  swap(q_hi_, o.q_hi_);
  swap(v_max_, o.v_max_);
  swap(effort_, o.effort_);
  swap(gravity_, o.gravity_);
  swap(source_, o.source_);
  swap(mimic_, o.mimic_);
  swap(frozen_mimics_, o.frozen_mimics_);
}

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
      return source.parts.empty() ? RobotModel() : combine(source.parts, source.name);
    case Source::Kind::FreeObject:
      return free_object(source.name, source.mass, source.com, source.inertia, source.options.gravity);
  }
  detail::fail("source.kind is not a known kind of model");
}

}  // namespace pathpace
