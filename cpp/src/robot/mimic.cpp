// Mimic joints (URDF <mimic>): q_mimic = multiplier · q_joint + offset. The model keeps the tree with one
// coordinate per body as MimicMap::bodies_model, and the map E, o between the two coordinate sets.
#include <algorithm>
#include <cmath>
#include <map>

#include "base/validate.hpp"
#include "robot/bodies.hpp"
#include "robot/tree_builder.hpp"

namespace pathpace {

void RobotModel::remove_mimic_coordinates(const std::vector<MimicJoint>& mimics) {
  auto map = std::make_shared<detail::MimicMap>();
  map->bodies_model = std::make_shared<const RobotModel>(*this);  // as built: one coordinate per body
  map->joints = mimics;
  const Eigen::Index nb = static_cast<Eigen::Index>(tree_->bodies.size());
  std::map<std::string, Eigen::Index> body_of_joint;
  for (Eigen::Index i = 0; i < nb; ++i) body_of_joint[joint_names_[static_cast<size_t>(i)]] = i;
  std::map<std::string, const MimicJoint*> mimic_of;
  for (const MimicJoint& mj : mimics) mimic_of[mj.name] = &mj;
  std::vector<Eigen::Index> coord(static_cast<size_t>(nb), -1);
  std::vector<std::string> names;
  std::vector<double> lo, hi, vel, eff;
  for (Eigen::Index i = 0; i < nb; ++i) {
    const std::string& name = joint_names_[static_cast<size_t>(i)];
    if (mimic_of.count(name)) continue;
    coord[static_cast<size_t>(i)] = static_cast<Eigen::Index>(names.size());
    names.push_back(name);
    lo.push_back(q_lo_[i]);
    hi.push_back(q_hi_[i]);
    vel.push_back(v_max_[i]);
    eff.push_back(effort_[i]);
  }
  map->E = Eigen::MatrixXd::Zero(nb, static_cast<Eigen::Index>(names.size()));
  map->o = Eigen::VectorXd::Zero(nb);
  for (Eigen::Index i = 0; i < nb; ++i) {
    if (coord[static_cast<size_t>(i)] >= 0) {
      map->E(i, coord[static_cast<size_t>(i)]) = 1.0;
      continue;
    }
    const MimicJoint& mj = *mimic_of[joint_names_[static_cast<size_t>(i)]];
    auto target = body_of_joint.find(mj.joint);
    if (target == body_of_joint.end())
      detail::fail("joint '" + mj.name + "' mimics '" + mj.joint + "', which is not a movable joint of robot '" + name_ + "'");
    if (mimic_of.count(mj.joint))
      detail::fail("joint '" + mj.name + "' mimics '" + mj.joint + "', itself a mimic joint: chains of mimic joints are not supported");
    if (!std::isfinite(mj.multiplier) || !std::isfinite(mj.offset))
      detail::fail("joint '" + mj.name + "': mimic multiplier = " + detail::fmt(mj.multiplier) + " and offset = " +
                   detail::fmt(mj.offset) + " must be finite");
    map->E(i, coord[static_cast<size_t>(target->second)]) = mj.multiplier;
    map->o[i] = mj.offset;
  }
  joint_names_ = names;
  q_lo_ = detail::as_vector(lo);
  q_hi_ = detail::as_vector(hi);
  v_max_ = detail::as_vector(vel);
  effort_ = detail::as_vector(eff);
  mimic_ = std::move(map);
}

std::vector<RobotModel::JointType> RobotModel::joint_types() const {
  const std::vector<detail::Body>& bodies = tree_->bodies;
  std::vector<JointType> out;
  if (!mimic_) {  // one body per coordinate
    for (Eigen::Index j = 0; j < nq(); ++j) out.push_back(bodies[static_cast<size_t>(j)].type);
    return out;
  }
  // With mimic joints the bodies keep the names of their joints (bodies_model); a coordinate is its joint's body.
  const std::vector<std::string>& body_joint = mimic_->bodies_model->joint_names();
  for (const std::string& name : joint_names_) {
    const size_t b = static_cast<size_t>(std::find(body_joint.begin(), body_joint.end(), name) - body_joint.begin());
    out.push_back(b < bodies.size() ? bodies[b].type : JointType::Revolute);
  }
  return out;
}

const std::vector<RobotModel::MimicJoint>& RobotModel::mimic_joints() const {
  static const std::vector<MimicJoint> none;
  return mimic_ ? mimic_->joints : none;
}

}  // namespace pathpace
