// RobotModel::combine: one model of several independent trees (robots and free objects, sec. III.b).
#include <map>
#include <memory>

#include "base/validate.hpp"
#include "robot/bodies.hpp"
#include "robot/tree_builder.hpp"

namespace pathpace {

namespace {

using detail::MimicMap;
using detail::RobotInternals;

// The mimic map of the combined model (nq coordinates) if a part has mimic joints, else null: E is
// block-diagonal over the parts (identity for a part without), and the bodies model combines the parts'
// bodies models under `name`.
std::shared_ptr<const MimicMap> combined_mimic_map(const std::vector<RobotModel>& parts, int nq, const std::string& name) {
  bool any_mimic = false;
  for (const RobotModel& p : parts) any_mimic = any_mimic || RobotInternals::mimic(p);
  if (!any_mimic) return nullptr;
  Eigen::Index nb = 0;
  for (const RobotModel& p : parts) nb += static_cast<Eigen::Index>(RobotInternals::bodies(p).size());
  auto map = std::make_shared<MimicMap>();
  map->E = Eigen::MatrixXd::Zero(nb, nq);
  map->o = Eigen::VectorXd::Zero(nb);
  std::vector<RobotModel> full;
  Eigen::Index row = 0, col = 0;
  for (const RobotModel& p : parts) {
    const Eigen::Index nbp = static_cast<Eigen::Index>(RobotInternals::bodies(p).size()), np = p.nq();
    if (const MimicMap* pm = RobotInternals::mimic(p)) {
      map->E.block(row, col, nbp, np) = pm->E;
      map->o.segment(row, nbp) = pm->o;
      map->joints.insert(map->joints.end(), pm->joints.begin(), pm->joints.end());
      full.push_back(*pm->bodies_model);
    } else {
      map->E.block(row, col, nbp, np).setIdentity();
      full.push_back(p);
    }
    row += nbp;
    col += np;
  }
  map->bodies_model = std::make_shared<const RobotModel>(RobotModel::combine(full, name));
  return map;
}

}  // namespace

RobotModel RobotModel::combine(const std::vector<RobotModel>& parts, const std::string& name) {
  if (parts.empty()) detail::fail("parts is empty: expected at least one model");
  RobotModel m;
  m.gravity_ = parts[0].gravity_;
  std::map<std::string, int> joint_count;
  for (const RobotModel& p : parts)
    for (const std::string& j : p.joint_names_) ++joint_count[j];
  auto tree = std::make_shared<detail::RobotTree>();
  std::vector<double> lo, hi, vel, eff;
  for (size_t i = 0; i < parts.size(); ++i) {
    const RobotModel& p = parts[i];
    m.frozen_mimics_.insert(m.frozen_mimics_.end(), p.frozen_mimics_.begin(), p.frozen_mimics_.end());
    if ((p.gravity_ - m.gravity_).norm() > 0.0)
      detail::fail("parts[" + std::to_string(i) + "] ('" + p.name_ + "') has gravity (" + detail::fmt(p.gravity_.x()) + ", " +
                   detail::fmt(p.gravity_.y()) + ", " + detail::fmt(p.gravity_.z()) + "), parts[0] has (" +
                   detail::fmt(m.gravity_.x()) + ", " + detail::fmt(m.gravity_.y()) + ", " + detail::fmt(m.gravity_.z()) +
                   "): they must agree");
    const int offset = static_cast<int>(tree->bodies.size());
    for (detail::Body b : p.tree_->bodies) {
      if (b.parent >= 0) b.parent += offset;
      tree->bodies.push_back(b);
    }
    for (const std::string& j : p.joint_names_) m.joint_names_.push_back(joint_count[j] > 1 ? p.name_ + "/" + j : j);
    for (const std::string& l : p.link_names_) {
      auto it = p.tree_->links.find(l);
      if (tree->links.count(l))
        detail::fail("parts[" + std::to_string(i) + "] ('" + p.name_ + "') has a link '" + l +
                     "' that an earlier part also has: link names must be unique");
      tree->links[l] = {it->second.first >= 0 ? it->second.first + offset : -1, it->second.second};
      m.link_names_.push_back(l);
    }
    m.name_ += (i ? "+" : "") + p.name_;
    lo.insert(lo.end(), p.q_lo_.data(), p.q_lo_.data() + p.q_lo_.size());
    hi.insert(hi.end(), p.q_hi_.data(), p.q_hi_.data() + p.q_hi_.size());
    vel.insert(vel.end(), p.v_max_.data(), p.v_max_.data() + p.v_max_.size());
    eff.insert(eff.end(), p.effort_.data(), p.effort_.data() + p.effort_.size());
  }
  std::map<std::string, int> seen;
  for (const std::string& j : m.joint_names_)
    if (seen[j]++) detail::fail("combined joint name '" + j + "' is not unique (two parts share a name and a joint)");
  if (!name.empty()) m.name_ = name;
  m.tree_ = std::move(tree);
  m.q_lo_ = detail::as_vector(lo);
  m.q_hi_ = detail::as_vector(hi);
  m.v_max_ = detail::as_vector(vel);
  m.effort_ = detail::as_vector(eff);
  m.mimic_ = combined_mimic_map(parts, m.nq(), m.name_);
  auto source = std::make_shared<Source>();
  source->kind = Source::Kind::Combine;
  source->parts = parts;
  source->name = name;
  m.source_ = std::move(source);
  return m;
}

}  // namespace pathpace
