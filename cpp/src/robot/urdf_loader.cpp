// RobotModel::from_urdf_file / from_urdf_string: URDF text -> the bodies of a RobotTree. The only file
// that includes urdfdom (no urdfdom type reaches a header).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "base/validate.hpp"
#include "robot/bodies.hpp"
#include "robot/tree_builder.hpp"

namespace pathpace {

namespace {

Eigen::Isometry3d to_isometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

// The motion of a joint held at `value` (locked, or the mimic of a locked joint).
Eigen::Isometry3d held_motion(bool prismatic, const Eigen::Vector3d& axis, double value) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  if (prismatic) motion.translation() = axis.normalized() * value;
  else motion.linear() = Eigen::AngleAxisd(value, axis.normalized()).toRotationMatrix();
  return motion;
}

// A link's inertial, checked: urdfdom reads "nan", "inf" and negative masses as numbers, and a NaN
// or negative mass silently corrupted (or dropped) the link's inertia.
void check_inertial(const urdf::Link& link) {
  const urdf::Inertial& in = *link.inertial;
  const std::string where = "urdf link '" + link.name + "' inertial ";
  if (!std::isfinite(in.mass) || in.mass < 0.0)
    detail::fail(where + "mass = " + detail::fmt(in.mass) + " must be >= 0 and finite");
  const double origin[7] = {in.origin.position.x, in.origin.position.y, in.origin.position.z, in.origin.rotation.x,
                            in.origin.rotation.y, in.origin.rotation.z, in.origin.rotation.w};
  const char* origin_names[7] = {"origin x", "origin y", "origin z", "origin rotation x", "origin rotation y",
                                 "origin rotation z", "origin rotation w"};
  for (int i = 0; i < 7; ++i)
    if (!std::isfinite(origin[i])) detail::fail(where + origin_names[i] + " = " + detail::fmt(origin[i]) + " must be finite");
  const double inertia[6] = {in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz};
  const char* inertia_names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(inertia[i])) detail::fail(where + inertia_names[i] + " = " + detail::fmt(inertia[i]) + " must be finite");
  for (int i : {0, 3, 5})
    if (inertia[i] < 0.0) detail::fail(where + inertia_names[i] + " = " + detail::fmt(inertia[i]) + " must be >= 0");
}

// One joint's limits and origin, checked: a negative effort became "tau_min[j] = 5 must be <= tau_max[j] = -5".
void check_joint(const urdf::Joint& joint) {
  const std::string where = "urdf joint '" + joint.name + "' ";
  const urdf::Pose& o = joint.parent_to_joint_origin_transform;
  for (double v : {o.position.x, o.position.y, o.position.z, o.rotation.x, o.rotation.y, o.rotation.z, o.rotation.w})
    if (!std::isfinite(v)) detail::fail(where + "origin = " + detail::fmt(v) + " must be finite");
  if (!joint.limits) return;
  const urdf::JointLimits& l = *joint.limits;
  if (std::isnan(l.effort) || l.effort < 0.0) detail::fail(where + "limit effort = " + detail::fmt(l.effort) + " must be >= 0");
  if (std::isnan(l.velocity) || l.velocity < 0.0)
    detail::fail(where + "limit velocity = " + detail::fmt(l.velocity) + " must be >= 0");
  if (std::isnan(l.lower)) detail::fail(where + "limit lower = nan must be a number");
  if (std::isnan(l.upper)) detail::fail(where + "limit upper = nan must be a number");
}

// urdfdom's parse. It reports parse errors through console_bridge on stderr; the error is ours to
// report. It also keeps going past some: a <mass value="nan"/> (or "inf", or "abc") is logged, then the
// link is kept with mass 0. Every error it logs is therefore collected and turned into InvalidInput.
urdf::ModelInterfaceSharedPtr parse_urdf(const std::string& xml) {
  struct Collect : console_bridge::OutputHandler {
    std::string first;
    void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
      // urdfdom names the field first ("mass [nan] is not a float"), then the link: keep both.
      if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && std::count(first.begin(), first.end(), ';') < 3)
        first += (first.empty() ? "" : "; ") + text;
    }
  } collect;
  urdf::ModelInterfaceSharedPtr urdf;
  {
    // console_bridge's handler and level are process-wide.
    static std::mutex console_mutex;
    std::lock_guard<std::mutex> lock(console_mutex);
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_ERROR);
    console_bridge::useOutputHandler(&collect);
    try {
      urdf = urdf::parseURDF(xml);
    } catch (...) {
      console_bridge::restorePreviousOutputHandler();
      console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
      throw;
    }
    console_bridge::restorePreviousOutputHandler();
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  }
  if (!urdf || !urdf->getRoot())
    detail::fail("urdf: the XML is not a valid URDF robot (urdfdom could not parse it" +
                 (collect.first.empty() ? std::string(")") : ": " + collect.first + ")"));
  if (!collect.first.empty()) detail::fail("urdf: " + collect.first);
  return urdf;
}

// The URDF's link tree as bodies: fixed and locked joints merge their child link into the parent's
// body, every other joint adds a body.
struct UrdfBuilder {
  const RobotModelOptions& options;
  detail::TreeBuilder& tree;
  std::map<std::string, bool> locked_used{};
  std::vector<RobotModel::MimicJoint> mimics{};  // in body order; resolved to coordinates after the tree
  std::vector<std::string> frozen_mimics{};       // mimic joints locked without their joint

  // A link on the explicit stack of add_tree, with the index of its next child joint.
  struct Frame {
    urdf::LinkConstSharedPtr link;
    int body;
    Eigen::Isometry3d placement;
    size_t next_joint;
  };
  std::vector<Frame> stack{};

  // A mimic joint locked together with its joint must agree with the relation (else the two locks
  // contradict each other: refused, naming both). Locked alone it is frozen where it is while its joint
  // moves: the relation is dropped for it, which is what a model reduced on that joint alone does
  // (pinocchio's buildReducedModel, MuJoCo's weld), so such a lock is kept, and recorded
  // (RobotModel::frozen_mimic_joints) so that it is not silent.
  void check_locked_mimic(const urdf::Joint& joint, double value) {
    const urdf::JointMimic& m = *joint.mimic;
    auto held = options.locked_joints.find(m.joint_name);
    if (held == options.locked_joints.end()) {
      frozen_mimics.push_back(joint.name);
      return;
    }
    const double implied = m.multiplier * held->second + m.offset;
    if (std::abs(implied - value) > 1e-9 * std::max(1.0, std::abs(implied)))
      detail::fail("locked_joints: '" + joint.name + "' = " + detail::fmt(value) + " breaks its mimic relation (q = " +
                   detail::fmt(m.multiplier) + " * q_" + m.joint_name + " + " + detail::fmt(m.offset) + "): '" +
                   m.joint_name + "' = " + detail::fmt(held->second) + " gives " + detail::fmt(implied) +
                   "; lock '" + m.joint_name + "' alone (its mimics follow it)");
  }

  // A link carried by `body` at `placement` (the link frame in the body's coordinates): its inertia
  // joins the body's (none for the world, body -1), and its child joints are pushed for add_tree.
  void visit(const urdf::LinkConstSharedPtr& link, int body, const Eigen::Isometry3d& placement) {
    tree.add_link(link->name, body, placement);
    if (link->inertial) check_inertial(*link);
    if (link->inertial && body >= 0) {
      const urdf::Inertial& in = *link->inertial;
      const Eigen::Isometry3d frame = placement * to_isometry(in.origin);
      Eigen::Matrix3d I;
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      const Eigen::Matrix3d Ic = frame.linear() * I * frame.linear().transpose();
      tree.bodies[static_cast<size_t>(body)].inertia += detail::spatial_inertia(in.mass, frame.translation(), Ic);
    }
    stack.push_back(Frame{link, body, placement, 0});
  }

  // The joint from `link` (carried by `body` at `placement`) to its child: a new body, or the child
  // link merged into `body` if the joint does not move.
  void add_joint(const urdf::Joint& joint, const urdf::Link& link, int body, const Eigen::Isometry3d& placement) {
    check_joint(joint);
    urdf::LinkConstSharedPtr child_link;
    for (const auto& cl : link.child_links)
      if (cl->name == joint.child_link_name) child_link = cl;
    if (!child_link) detail::fail("joint '" + joint.name + "' has no child link '" + joint.child_link_name + "'");
    const Eigen::Isometry3d origin = placement * to_isometry(joint.parent_to_joint_origin_transform);
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    const bool movable = joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
                         joint.type == urdf::Joint::PRISMATIC;
    const bool prismatic = joint.type == urdf::Joint::PRISMATIC;
    if (joint.type != urdf::Joint::FIXED && !movable)
      detail::fail("joint '" + joint.name + "' has a type that is not supported (planar or floating); only revolute, "
                   "continuous, prismatic and fixed joints are");
    auto locked = options.locked_joints.find(joint.name);
    if (!movable || locked != options.locked_joints.end()) {
      Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
      if (movable) {
        locked_used[joint.name] = true;
        const double value = locked->second;
        if (joint.mimic) check_locked_mimic(joint, value);
        motion = held_motion(prismatic, axis, value);
      }
      visit(child_link, body, origin * motion);
      return;
    }
    if (joint.mimic) {
      // q = multiplier · q_joint + offset; a locked joint fixes its mimic too.
      auto held = options.locked_joints.find(joint.mimic->joint_name);
      if (held != options.locked_joints.end()) {
        const double value = joint.mimic->multiplier * held->second + joint.mimic->offset;
        visit(child_link, body, origin * held_motion(prismatic, axis, value));
        return;
      }
      mimics.push_back({joint.name, joint.mimic->joint_name, joint.mimic->multiplier, joint.mimic->offset});
    }
    if (!(axis.norm() > 0.0) || !axis.allFinite()) detail::fail("joint '" + joint.name + "' has a zero or non-finite axis");
    const double inf = std::numeric_limits<double>::infinity();
    double lo = -inf, hi = inf, vel = inf, eff = inf;
    if (joint.limits) {
      if (joint.type != urdf::Joint::CONTINUOUS) {
        lo = joint.limits->lower;
        hi = joint.limits->upper;
      }
      vel = joint.limits->velocity;
      eff = joint.limits->effort;
    }
    const int b = tree.add_body(body, prismatic ? RobotModel::JointType::Prismatic : RobotModel::JointType::Revolute,
                                axis, origin, joint.name, lo, hi, vel, eff);
    visit(child_link, b, Eigen::Isometry3d::Identity());
  }

  // Depth-first over the link tree with an explicit stack, in the order a recursion would take (so the
  // joint order is the URDF's): a recursion overflows the thread's stack on a long chain (test_robustness).
  void add_tree(const urdf::LinkConstSharedPtr& root, int root_body) {
    visit(root, root_body, Eigen::Isometry3d::Identity());
    while (!stack.empty()) {
      Frame& top = stack.back();
      if (top.next_joint == top.link->child_joints.size()) {
        stack.pop_back();
        continue;
      }
      const urdf::JointSharedPtr joint = top.link->child_joints[top.next_joint++];
      const urdf::LinkConstSharedPtr link = top.link;  // copies: visit() may reallocate the stack
      const Eigen::Isometry3d placement = top.placement;
      add_joint(*joint, *link, top.body, placement);
    }
  }
};

}  // namespace

RobotModel RobotModel::from_urdf_file(const std::string& path, const RobotModelOptions& options) {
  std::ifstream in(path);
  if (!in) detail::fail("urdf file '" + path + "' cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  return from_urdf_string(ss.str(), options);
}

RobotModel RobotModel::from_urdf_string(const std::string& xml, const RobotModelOptions& options) {
  detail::check_gravity(options.gravity);
  for (const auto& [name, value] : options.locked_joints)
    if (!std::isfinite(value)) detail::fail("locked_joints['" + name + "'] = " + detail::fmt(value) + " must be finite");
  const urdf::ModelInterfaceSharedPtr urdf = parse_urdf(xml);

  RobotModel m;
  m.name_ = urdf->getName();
  m.gravity_ = options.gravity;
  auto tree = std::make_shared<detail::RobotTree>();
  detail::TreeBuilder t{tree->bodies, m.joint_names_, m.link_names_, tree->links};
  UrdfBuilder b{options, t};
  b.add_tree(urdf->getRoot(), options.floating_base ? t.add_floating_base() : -1);
  for (const auto& [name, value] : options.locked_joints)
    if (!b.locked_used.count(name))
      detail::fail("locked_joints: '" + name + "' is not a movable joint of robot '" + m.name_ + "'");
  t.store_limits(m.q_lo_, m.q_hi_, m.v_max_, m.effort_);
  m.tree_ = std::move(tree);
  if (!b.mimics.empty()) m.remove_mimic_coordinates(b.mimics);
  m.frozen_mimics_ = b.frozen_mimics;
  auto source = std::make_shared<Source>();
  source->kind = Source::Kind::Urdf;
  source->urdf = xml;
  source->options = options;
  m.source_ = std::move(source);
  return m;
}

}  // namespace pathpace
