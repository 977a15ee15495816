#include "pathpace/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <fstream>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "base/validate.hpp"
#include "pathpace/robot_workspace.hpp"
#include "robot/torque_lanes.hpp"

namespace pathpace {

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Isometry3d to_isometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

// Spatial inertia (angular first) about the body origin of mass m, centre of mass c and rotational
// inertia Ic about c, all in body coordinates.
Matrix6 spatial_inertia(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& Ic) {
  const Eigen::Matrix3d C = skew(c);
  Matrix6 I;
  I.topLeftCorner<3, 3>() = Ic + m * C * C.transpose();
  I.topRightCorner<3, 3>() = m * C;
  I.bottomLeftCorner<3, 3>() = m * C.transpose();
  I.bottomRightCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  return I;
}

Eigen::VectorXd as_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// u if the axis is the coordinate axis e_u exactly, else -1.
inline int coordinate_axis(const Eigen::Vector3d& axis) {
  for (int u = 0; u < 3; ++u)
    if (axis[u] == 1.0 && axis[(u + 1) % 3] == 0.0 && axis[(u + 2) % 3] == 0.0) return u;
  return -1;
}

// Gravity in m/s² (the unit of the URDF's lengths per s²): finite, and at most 1e3 m/s² (~100 g, beyond
// any planet's surface or a test centrifuge's usual range). More is a unit error (9810 is g in mm/s²),
// and with 1e308 the torques overflowed to inf and NaN.
void check_gravity(const Eigen::Vector3d& g) {
  detail::require_finite("gravity", g);
  constexpr double kMaxGravity = 1e3;
  if (g.stableNorm() > kMaxGravity)
    detail::fail("gravity = (" + detail::fmt(g.x()) + ", " + detail::fmt(g.y()) + ", " + detail::fmt(g.z()) +
                 ") has |gravity| = " + detail::fmt(g.stableNorm()) + " m/s^2, must be <= 1000 m/s^2 (about 100 g; "
                 "gravity is in m/s^2, e.g. (0, 0, -9.81))");
}

struct Builder {
  const RobotModelOptions& options;
  std::vector<RobotModel::Body>& bodies;
  std::vector<std::string>& joint_names;
  std::vector<std::string>& link_names;
  std::map<std::string, std::pair<int, Eigen::Isometry3d>>& links;
  std::vector<double> q_lo, q_hi, v_max, effort;
  std::map<std::string, bool> locked_used;
  std::vector<RobotModel::MimicJoint> mimics;  // in body order; resolved to coordinates after the tree
  std::vector<std::string> frozen_mimics;       // mimic joints locked without their joint

  int add_body(int parent, RobotModel::JointType type, const Eigen::Vector3d& axis, const Eigen::Isometry3d& tree,
               const std::string& name, double lo, double hi, double vel, double eff) {
    RobotModel::Body b;
    b.parent = parent;
    b.type = type;
    b.axis = axis.normalized();
    b.axis_index = coordinate_axis(b.axis);  // once per model: every sweep branches on it
    b.E_tree = tree.linear().transpose();
    b.r_tree = tree.translation();
    b.inertia.setZero();
    bodies.push_back(b);
    joint_names.push_back(name);
    q_lo.push_back(lo);
    q_hi.push_back(hi);
    v_max.push_back(vel);
    effort.push_back(eff);
    return static_cast<int>(bodies.size()) - 1;
  }

  // The six virtual joints of RobotModelOptions::floating_base (x, y, z, then rotations about z, y, x;
  // unlimited, unactuated). Returns the last one's body, which carries the root link.
  int add_floating_base() {
    const double inf = std::numeric_limits<double>::infinity();
    const char* names[6] = {"floating_x", "floating_y", "floating_z", "floating_rz", "floating_ry", "floating_rx"};
    const Eigen::Vector3d axes[6] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                     Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX()};
    int body = -1;
    for (int i = 0; i < 6; ++i)
      body = add_body(body, i < 3 ? RobotModel::JointType::Prismatic : RobotModel::JointType::Revolute, axes[i],
                      Eigen::Isometry3d::Identity(), names[i], -inf, inf, inf, 0.0);
    return body;
  }

  void store_limits(Eigen::VectorXd& lo, Eigen::VectorXd& hi, Eigen::VectorXd& vel, Eigen::VectorXd& eff) const {
    lo = as_vector(q_lo);
    hi = as_vector(q_hi);
    vel = as_vector(v_max);
    eff = as_vector(effort);
  }

  // A link's inertial, checked: urdfdom reads "nan", "inf" and negative masses as numbers, and a NaN
  // or negative mass silently corrupted (or dropped) the link's inertia.
  static void check_inertial(const urdf::Link& link) {
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
  static void check_joint(const urdf::Joint& joint) {
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

  // Depth-first over the link tree with an explicit stack, in the order a recursion would take (so the
  // joint order is the URDF's): a recursion overflowed the thread's stack at ~10,000 links in a chain.
  // `placement`: the link frame in the coordinates of body `body` (-1: the world).
  void add_tree(const urdf::LinkConstSharedPtr& root, int root_body, const Eigen::Isometry3d& root_placement) {
    struct Frame {
      urdf::LinkConstSharedPtr link;
      int body;
      Eigen::Isometry3d placement;
      size_t next_joint;
    };
    std::vector<Frame> stack;
    auto visit = [&](const urdf::LinkConstSharedPtr& link, int body, const Eigen::Isometry3d& placement) {
      links[link->name] = {body, placement};
      link_names.push_back(link->name);
      if (link->inertial) check_inertial(*link);
      if (link->inertial && body >= 0) {
        const urdf::Inertial& in = *link->inertial;
        const Eigen::Isometry3d frame = placement * to_isometry(in.origin);
        Eigen::Matrix3d I;
        I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
        const Eigen::Matrix3d Ic = frame.linear() * I * frame.linear().transpose();
        bodies[static_cast<size_t>(body)].inertia += spatial_inertia(in.mass, frame.translation(), Ic);
      }
      stack.push_back(Frame{link, body, placement, 0});
    };
    visit(root, root_body, root_placement);
    while (!stack.empty()) {
      Frame& top = stack.back();
      if (top.next_joint == top.link->child_joints.size()) {
        stack.pop_back();
        continue;
      }
      const urdf::JointSharedPtr joint = top.link->child_joints[top.next_joint++];
      const urdf::LinkConstSharedPtr link = top.link;  // copies: visit() may reallocate the stack
      const int body = top.body;
      const Eigen::Isometry3d placement = top.placement;
      check_joint(*joint);
      urdf::LinkConstSharedPtr child_link;
      for (const auto& cl : link->child_links)
        if (cl->name == joint->child_link_name) child_link = cl;
      if (!child_link) detail::fail("joint '" + joint->name + "' has no child link '" + joint->child_link_name + "'");
      const Eigen::Isometry3d origin = placement * to_isometry(joint->parent_to_joint_origin_transform);
      const Eigen::Vector3d axis(joint->axis.x, joint->axis.y, joint->axis.z);
      const bool movable = joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::CONTINUOUS ||
                           joint->type == urdf::Joint::PRISMATIC;
      const bool prismatic = joint->type == urdf::Joint::PRISMATIC;
      if (joint->type != urdf::Joint::FIXED && !movable)
        detail::fail("joint '" + joint->name + "' has a type that is not supported (planar or floating); only revolute, "
                     "continuous, prismatic and fixed joints are");
      auto locked = options.locked_joints.find(joint->name);
      if (!movable || locked != options.locked_joints.end()) {
        Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
        if (movable) {
          locked_used[joint->name] = true;
          const double value = locked->second;
          if (joint->mimic) check_locked_mimic(*joint, value);
          if (prismatic) motion.translation() = axis.normalized() * value;
          else motion.linear() = Eigen::AngleAxisd(value, axis.normalized()).toRotationMatrix();
        }
        visit(child_link, body, origin * motion);
        continue;
      }
      if (joint->mimic) {
        // q = multiplier · q_joint + offset; a locked joint fixes its mimic too.
        auto held = options.locked_joints.find(joint->mimic->joint_name);
        if (held != options.locked_joints.end()) {
          const double value = joint->mimic->multiplier * held->second + joint->mimic->offset;
          Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
          if (prismatic) motion.translation() = axis.normalized() * value;
          else motion.linear() = Eigen::AngleAxisd(value, axis.normalized()).toRotationMatrix();
          visit(child_link, body, origin * motion);
          continue;
        }
        mimics.push_back({joint->name, joint->mimic->joint_name, joint->mimic->multiplier, joint->mimic->offset});
      }
      if (!(axis.norm() > 0.0) || !axis.allFinite()) detail::fail("joint '" + joint->name + "' has a zero or non-finite axis");
      const double inf = std::numeric_limits<double>::infinity();
      double lo = -inf, hi = inf, vel = inf, eff = inf;
      if (joint->limits) {
        if (joint->type != urdf::Joint::CONTINUOUS) {
          lo = joint->limits->lower;
          hi = joint->limits->upper;
        }
        vel = joint->limits->velocity;
        eff = joint->limits->effort;
      }
      const int b = add_body(body, prismatic ? RobotModel::JointType::Prismatic : RobotModel::JointType::Revolute, axis,
                             origin, joint->name, lo, hi, vel, eff);
      visit(child_link, b, Eigen::Isometry3d::Identity());
    }
  }
};

}  // namespace

// Mimic joints: the dynamics run on the same tree with one coordinate per body (bodies_model), with
// q_bodies = E q + o on the way in and τ = Eᵀ τ_bodies on the way out (virtual work).
struct RobotModel::MimicMap {
  std::vector<MimicJoint> joints;
  std::shared_ptr<const RobotModel> bodies_model;
  Eigen::MatrixXd E;  // (bodies, nq): ∂q_bodies/∂q
  Eigen::VectorXd o;  // (bodies): offsets
};

void RobotModel::remove_mimic_coordinates(const std::vector<MimicJoint>& mimics) {
  auto map = std::make_shared<MimicMap>();
  map->bodies_model = std::make_shared<const RobotModel>(*this);  // as built: one coordinate per body
  map->joints = mimics;
  const Eigen::Index nb = static_cast<Eigen::Index>(bodies_.size());
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
  q_lo_ = as_vector(lo);
  q_hi_ = as_vector(hi);
  v_max_ = as_vector(vel);
  effort_ = as_vector(eff);
  mimic_ = std::move(map);
}

std::vector<RobotModel::JointType> RobotModel::joint_types() const {
  std::vector<JointType> out;
  if (!mimic_) {  // one body per coordinate
    for (Eigen::Index j = 0; j < nq(); ++j) out.push_back(bodies_[static_cast<size_t>(j)].type);
    return out;
  }
  // With mimic joints the bodies keep the names of their joints (bodies_model); a coordinate is its joint's body.
  const std::vector<std::string>& body_joint = mimic_->bodies_model->joint_names();
  for (const std::string& name : joint_names_) {
    const size_t b = static_cast<size_t>(std::find(body_joint.begin(), body_joint.end(), name) - body_joint.begin());
    out.push_back(b < bodies_.size() ? bodies_[b].type : JointType::Revolute);
  }
  return out;
}

const std::vector<RobotModel::MimicJoint>& RobotModel::mimic_joints() const {
  static const std::vector<MimicJoint> none;
  return mimic_ ? mimic_->joints : none;
}

RobotModel RobotModel::from_urdf_file(const std::string& path, const RobotModelOptions& options) {
  std::ifstream in(path);
  if (!in) detail::fail("urdf file '" + path + "' cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  return from_urdf_string(ss.str(), options);
}

RobotModel RobotModel::from_urdf_string(const std::string& xml, const RobotModelOptions& options) {
  check_gravity(options.gravity);
  for (const auto& [name, value] : options.locked_joints)
    if (!std::isfinite(value)) detail::fail("locked_joints['" + name + "'] = " + detail::fmt(value) + " must be finite");
  // urdfdom reports parse errors through console_bridge on stderr; the error is ours to report. It
  // also keeps going past some: a <mass value="nan"/> (or "inf", or "abc") is logged, then the link
  // is kept with mass 0. Every error it logs is therefore collected and turned into InvalidInput.
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

  RobotModel m;
  m.name_ = urdf->getName();
  m.gravity_ = options.gravity;
  Builder b{options, m.bodies_, m.joint_names_, m.link_names_, m.links_, {}, {}, {}, {}, {}, {}};
  const int root_body = options.floating_base ? b.add_floating_base() : -1;
  b.add_tree(urdf->getRoot(), root_body, Eigen::Isometry3d::Identity());
  for (const auto& [name, value] : options.locked_joints)
    if (!b.locked_used.count(name))
      detail::fail("locked_joints: '" + name + "' is not a movable joint of robot '" + m.name_ + "'");
  b.store_limits(m.q_lo_, m.q_hi_, m.v_max_, m.effort_);
  if (!b.mimics.empty()) m.remove_mimic_coordinates(b.mimics);
  m.frozen_mimics_ = b.frozen_mimics;
  auto source = std::make_shared<Source>();
  source->kind = Source::Kind::Urdf;
  source->urdf = xml;
  source->options = options;
  m.source_ = std::move(source);
  return m;
}

void RobotModel::check_q(const Eigen::Ref<const Eigen::VectorXd>& v, const char* name) const {
  if (v.size() != nq())
    detail::fail(std::string(name) + " has size " + std::to_string(v.size()) + ", robot '" + name_ + "' has " +
                 std::to_string(nq()) + " joints");
}

namespace {

// The coordinate axis a revolute joint turns about (most URDF joints), else -1. (The test abc_sweep makes:
// an axis with x = 1 after normalisation but a 1e-9 component left is not e_x for either.)
int unit_axis(const RobotModel::Body& b) {
  return b.type == RobotModel::JointType::Revolute ? b.axis_index : -1;
}

// Every helper of the fused sweep is forced inline, so that it is compiled with the instruction set of
// the lane-width variant that calls it (path_torque_lanes below: a function of target("avx2,fma") gets
// AVX2 code for its whole body).
#if defined(__GNUC__)
#define PATHPACE_LANE_INLINE inline __attribute__((always_inline))
#else
#define PATHPACE_LANE_INLINE inline
#endif

template <typename T>
PATHPACE_LANE_INLINE void splat(T& y, double x) {  // every lane x (not 0 + x, which would turn -0 into +0)
  for (size_t l = 0; l < sizeof(T) / sizeof(double); ++l) y[l] = x;
}
PATHPACE_LANE_INLINE void splat(double& y, double x) { y = x; }

// E = E_J E_tree for a rotation by q about coordinate axis `unit`, given cos q and sin q: E_J mixes two
// rows of E_tree only: e_i1 -> c e_i1 + s e_i2, e_i2 -> -s e_i1 + c e_i2. T is double (one sample) or a
// vector of lanes (path_torque_lanes: one sample per lane).
template <typename T>
PATHPACE_LANE_INLINE void unit_axis_rotation(const RobotModel::Body& b, int unit, const T& cq, const T& sq, T* E) {
  const double* Et = b.E_tree.data();
  const int i1 = (unit + 1) % 3, i2 = (unit + 2) % 3;
  for (int col = 0; col < 3; ++col) {
    const double t1 = Et[3 * col + i1], t2 = Et[3 * col + i2];
    splat(E[3 * col + unit], Et[3 * col + unit]);
    E[3 * col + i1] = cq * t1 + sq * t2;
    E[3 * col + i2] = cq * t2 - sq * t1;
  }
}

// ^iX_λ = X_J(q) X_tree of one body as its rotation E (column-major, 9 values) and the origin r of the
// joint frame in parent coordinates.
void joint_transform(const RobotModel::Body& b, double q, double* E, double* r) {
  const double* T = b.E_tree.data();
  if (b.type == RobotModel::JointType::Prismatic) {
    // E = E_tree; r = r_tree + E_tree^T (axis q).
    std::copy(T, T + 9, E);
    Eigen::Map<Eigen::Vector3d> origin(r);
    origin = b.r_tree + b.E_tree.transpose() * (b.axis * q);
    return;
  }
  // E = E_J E_tree with E_J = Rot(axis, q)^T; r = r_tree.
  std::copy(b.r_tree.data(), b.r_tree.data() + 3, r);
  const int unit = unit_axis(b);  // revolute here (prismatic returned above)
  if (unit < 0) {
    Eigen::Map<Eigen::Matrix3d> rotation(E);
    rotation.noalias() = Eigen::AngleAxisd(-q, b.axis).toRotationMatrix() * b.E_tree;
    return;
  }
  unit_axis_rotation<double>(b, unit, std::cos(q), std::sin(q), E);
}

// Joint transforms and motion subspaces, shared by every pass at one q.
void kinematics(const std::vector<RobotModel::Body>& bodies, RobotWorkspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q) {
  for (size_t i = 0; i < bodies.size(); ++i) {
    const RobotModel::Body& b = bodies[i];
    joint_transform(b, q[static_cast<Eigen::Index>(i)], ws.E[i].data(), ws.r[i].data());
    if (b.type == RobotModel::JointType::Revolute) ws.S[i] << b.axis, Eigen::Vector3d::Zero();
    else ws.S[i] << Eigen::Vector3d::Zero(), b.axis;
  }
}

// One RNEA pass over the transforms in ws (Featherstone, motion vectors [ω; v] in body coordinates;
// gravity enters as a fictitious upward acceleration of the base). qd == nullptr means q̇ = 0, which
// drops every velocity product.
void rnea_pass(const std::vector<RobotModel::Body>& bodies, RobotWorkspace& ws, const Eigen::VectorXd* qd,
               const Eigen::Ref<const Eigen::VectorXd>& qdd, const Eigen::Vector3d* gravity, Eigen::Ref<Eigen::VectorXd> tau) {
  const size_t nb = bodies.size();
  Vector6 a0 = Vector6::Zero();
  if (gravity) a0.tail<3>() = -*gravity;
  for (size_t i = 0; i < nb; ++i) {
    const RobotModel::Body& b = bodies[i];
    const Eigen::Matrix3d& E = ws.E[i];
    const Eigen::Vector3d& r = ws.r[i];
    const Vector6& S = ws.S[i];
    auto xform = [&](const Vector6& m) {
      Vector6 out;
      out.head<3>().noalias() = E * m.head<3>();
      out.tail<3>().noalias() = E * (m.tail<3>() - r.cross(m.head<3>()));
      return out;
    };
    const Vector6 ap = b.parent >= 0 ? ws.a[static_cast<size_t>(b.parent)] : a0;
    Vector6& a = ws.a[i];
    Vector6& f = ws.f[i];
    a = xform(ap) + S * qdd[static_cast<Eigen::Index>(i)];
    if (qd) {
      const Vector6 vJ = S * (*qd)[static_cast<Eigen::Index>(i)];
      Vector6& v = ws.v[i];
      v = (b.parent >= 0 ? xform(ws.v[static_cast<size_t>(b.parent)]) : Vector6::Zero()) + vJ;
      // a += v × vJ (crm)
      a.head<3>() += v.head<3>().cross(vJ.head<3>());
      a.tail<3>() += v.head<3>().cross(vJ.tail<3>()) + v.tail<3>().cross(vJ.head<3>());
      // f = I a + v ×* I v (crf)
      const Vector6 Iv = b.inertia * v;
      f.noalias() = b.inertia * a;
      f.head<3>() += v.head<3>().cross(Iv.head<3>()) + v.tail<3>().cross(Iv.tail<3>());
      f.tail<3>() += v.head<3>().cross(Iv.tail<3>());
    } else {
      f.noalias() = b.inertia * a;
    }
  }
  for (size_t i = nb; i-- > 0;) {
    const RobotModel::Body& b = bodies[i];
    const Vector6& f = ws.f[i];
    tau[static_cast<Eigen::Index>(i)] = ws.S[i].dot(f);
    if (b.parent >= 0) {
      // f_λ += ^iX_λ^T f: n' = E^T n + r × (E^T f), f' = E^T f
      const Eigen::Matrix3d& E = ws.E[i];
      const Eigen::Vector3d fl = E.transpose() * f.tail<3>();
      Vector6& fp = ws.f[static_cast<size_t>(b.parent)];
      fp.head<3>() += E.transpose() * f.head<3>() + ws.r[i].cross(fl);
      fp.tail<3>() += fl;
    }
  }
}

}  // namespace

void RobotModel::inverse_dynamics(RobotWorkspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                                  const Eigen::Ref<const Eigen::VectorXd>& qd, const Eigen::Ref<const Eigen::VectorXd>& qdd,
                                  bool with_gravity, Eigen::Ref<Eigen::VectorXd> tau) const {
  if (mimic_) {
    const MimicMap& mm = *mimic_;
    Eigen::VectorXd tau_bodies(static_cast<Eigen::Index>(bodies_.size()));
    mm.bodies_model->inverse_dynamics(ws, mm.E * q + mm.o, mm.E * qd, mm.E * qdd, with_gravity, tau_bodies);
    tau.noalias() = mm.E.transpose() * tau_bodies;
    return;
  }
  kinematics(bodies_, ws, q);
  ws.tmp = qd;
  rnea_pass(bodies_, ws, &ws.tmp, qdd, with_gravity ? &gravity_ : nullptr, tau);
}

Eigen::VectorXd RobotModel::inverse_dynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                             const Eigen::VectorXd& qdd) const {
  check_q(q, "q");
  check_q(qd, "qd");
  check_q(qdd, "qdd");
  detail::require_finite("q", q);
  detail::require_finite("qd", qd);
  detail::require_finite("qdd", qdd);
  RobotWorkspace ws(*this);
  Eigen::VectorXd tau(nq());
  inverse_dynamics(ws, q, qd, qdd, true, tau);
  return tau;
}

Eigen::VectorXd RobotModel::gravity_torques(const Eigen::VectorXd& q) const {
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(nq());
  return inverse_dynamics(q, z, z);
}

Eigen::MatrixXd RobotModel::mass_matrix(const Eigen::VectorXd& q) const {
  check_q(q, "q");
  detail::require_finite("q", q);
  RobotWorkspace ws(*this);
  const int n = nq();
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n), e = Eigen::VectorXd::Zero(n), col(n);
  // Column j is RNEA(q, 0, e_j) without gravity: n passes, O(n²) in all.
  for (int j = 0; j < n; ++j) {
    e[j] = 1.0;
    inverse_dynamics(ws, q, z, e, false, col);
    M.col(j) = col;
    e[j] = 0.0;
  }
  return 0.5 * (M + M.transpose());
}

namespace {

// The fused sweep of path_torque_coefficients, written once for a scalar T (double: one sample) or a
// GCC vector of W doubles (W samples, one per SIMD lane). Plain arrays, E column-major as Eigen stores
// it: the compiler unrolls every 3x3 kernel completely. Aligned to the size of T: outside AVX code (this
// file's baseline) GCC gives a 32- or 64-byte vector type only 16-byte alignment, while the AVX code of
// the variants below moves whole vectors with aligned loads and stores. T members only, m last: each
// lies on a multiple of sizeof(T).
template <typename T>
struct alignas(sizeof(T)) AbcBody {
  T aw[3], al[3];  // channel a (q̇ = p', q̈ = p''): acceleration (ω̇, v̇)
  T v[6];          // its velocity (ω then linear), which is channel b's acceleration (q̇ = 0, q̈ = p')
  T fw[6], fl[6];  // forces (moment, linear) of channel a at [0, 3), b at [3, 6)
  T g[3];          // channel c: the base's upward acceleration -gravity in body coordinates
  T h[3];          // channel c: first moment of mass of the subtree about the body origin
  T E[9], r[3];    // ^iX_λ's rotation and origin (r read for prismatic joints only: see transform_from_parent)
  double m;        // channel c: mass of the subtree
};

template <typename T, typename M>
PATHPACE_LANE_INLINE void mul_E(const M* E, const T* x, T* y) {  // y = E x
  y[0] = E[0] * x[0] + E[3] * x[1] + E[6] * x[2];
  y[1] = E[1] * x[0] + E[4] * x[1] + E[7] * x[2];
  y[2] = E[2] * x[0] + E[5] * x[1] + E[8] * x[2];
}
template <typename T>
PATHPACE_LANE_INLINE void mul_Et(const T* E, const T* x, T* y) {  // y = E^T x
  y[0] = E[0] * x[0] + E[1] * x[1] + E[2] * x[2];
  y[1] = E[3] * x[0] + E[4] * x[1] + E[5] * x[2];
  y[2] = E[6] * x[0] + E[7] * x[1] + E[8] * x[2];
}
template <typename A, typename B, typename T>
PATHPACE_LANE_INLINE void cross(const A* a, const B* b, T* y) {  // y = a × b
  y[0] = a[1] * b[2] - a[2] * b[1];
  y[1] = a[2] * b[0] - a[0] * b[2];
  y[2] = a[0] * b[1] - a[1] * b[0];
}
template <typename A, typename B, typename T>
PATHPACE_LANE_INLINE void add_cross(const A* a, const B* b, T* y) {  // y += a × b
  y[0] += a[1] * b[2] - a[2] * b[1];
  y[1] += a[2] * b[0] - a[0] * b[2];
  y[2] += a[0] * b[1] - a[1] * b[0];
}
template <typename A, typename B, typename T>
PATHPACE_LANE_INLINE void sub_cross(const A* a, const B* b, T* y) {  // y -= a × b
  y[0] -= a[1] * b[2] - a[2] * b[1];
  y[1] -= a[2] * b[0] - a[0] * b[2];
  y[2] -= a[0] * b[1] - a[1] * b[0];
}
template <typename T>
PATHPACE_LANE_INLINE void mul_sym(const double* I, const T* x, T* y) {  // y = Ī x, Ī the 6x6's top-left block
  y[0] = I[0] * x[0] + I[6] * x[1] + I[12] * x[2];
  y[1] = I[1] * x[0] + I[7] * x[1] + I[13] * x[2];
  y[2] = I[2] * x[0] + I[8] * x[1] + I[14] * x[2];
}
template <typename T>
PATHPACE_LANE_INLINE void dot_axis(const double* ax, const T* x, T& y) {  // y = ax · x
  y = ax[0] * x[0] + ax[1] * x[1] + ax[2] * x[2];
}
// abc_sweep's joint terms for the axis e_U (URDF joints mostly have one): vJ = q̇ e_U, and x × vJ =
// q̇ (x[U+2], -x[U+1]) at (U+1, U+2) mod 3, without the products with the axis' zeros. U a constant,
// so that every array stays in registers.
template <int U, typename T>
PATHPACE_LANE_INLINE void joint_motion_on_axis(bool revolute, const T& qd, const T& qdd, T* aw, T* al, T* v) {
  constexpr int i1 = (U + 1) % 3, i2 = (U + 2) % 3;
  if (revolute) {
    aw[U] += qdd;
    v[U] += qd;
    aw[i1] += v[i2] * qd;  // ω × vJ
    aw[i2] -= v[i1] * qd;
    al[i1] += v[3 + i2] * qd;  // v × vJ
    al[i2] -= v[3 + i1] * qd;
  } else {
    al[U] += qdd;
    v[3 + U] += qd;
    al[i1] += v[i2] * qd;  // ω × vJ
    al[i2] -= v[i1] * qd;
  }
}

// abc_sweep's projections on the axis e_U: a component, and one component of the gravity moment.
template <int U, typename T>
PATHPACE_LANE_INLINE void project_on_axis(bool revolute, const AbcBody<T>& B, T& a, T& b, T& c) {
  constexpr int i1 = (U + 1) % 3, i2 = (U + 2) % 3;
  if (revolute) {
    a = B.fw[U];
    b = B.fw[3 + U];
    c = B.h[i1] * B.g[i2] - B.h[i2] * B.g[i1];
  } else {
    a = B.fl[U];
    b = B.fl[3 + U];
    c = B.m * B.g[U];
  }
}

// Body i's channels from its parent's by ^iX_λ: ω' = E ω, v' = E (v - r × ω). r is the joint's
// origin: the same in every lane for a revolute joint (r_tree, so a constant operand), else B.r.
template <typename R, typename T>
PATHPACE_LANE_INLINE void transform_from_parent(const R* r, const AbcBody<T>& P, AbcBody<T>& B) {
  const T* E = B.E;
  mul_E(E, P.aw, B.aw);
  T t[3] = {P.al[0], P.al[1], P.al[2]};
  sub_cross(r, P.aw, t);
  mul_E(E, t, B.al);
  mul_E(E, P.v, B.v);
  T vt[3] = {P.v[3], P.v[4], P.v[5]};
  sub_cross(r, P.v, vt);
  mul_E(E, vt, B.v + 3);
  mul_E(E, P.g, B.g);
}

// f_λ += ^iX_λ^T f: n' = E^T n + r × (E^T f), f' = E^T f, for channels a and b; the first moment of
// mass moves as a point mass. r as in transform_from_parent.
template <typename R, typename T>
PATHPACE_LANE_INLINE void add_to_parent(const R* r, const AbcBody<T>& B, AbcBody<T>& P) {
  for (int ch = 0; ch < 2; ++ch) {
    T fl[3], fw[3];
    mul_Et(B.E, B.fl + 3 * ch, fl);
    mul_Et(B.E, B.fw + 3 * ch, fw);
    for (int k = 0; k < 3; ++k) {
      P.fw[3 * ch + k] += fw[k];
      P.fl[3 * ch + k] += fl[k];
    }
    add_cross(r, fl, P.fw + 3 * ch);
  }
  T hp[3];
  mul_Et(B.E, B.h, hp);
  for (int k = 0; k < 3; ++k) P.h[k] += hp[k] + B.m * r[k];
  P.m += B.m;
}

// eq. (12) by one sweep carrying three RNEA channels: a with q̇ = p', q̈ = p'' (velocity products
// included), b with q̇ = 0, q̈ = p', c with gravity only. S[i].E and S[i].r must hold body i's
// transform. Channel b's acceleration obeys the recursion of channel a's velocity (a_i = ^iX_λ a_λ +
// S_i p'_i from zero at the root), so it is that velocity, and its force I a is the I v that a's velocity
// product needs. Channel c's acceleration is the base's -gravity rotated into each body (no angular
// part), the same vector for every body of a subtree, so its forces need no backward transform of their
// own: the torque about joint i is the subtree's first moment of mass × that acceleration. The spatial
// inertia is applied through its parts (m, h = m c, Ī about the body origin): I (ω, v) = (Ī ω + h × v,
// m v - h × ω).
template <typename T>
PATHPACE_LANE_INLINE void abc_sweep(const std::vector<RobotModel::Body>& bodies, AbcBody<T>* S, const T* dq,
                                    const T* ddq, const Eigen::Vector3d& gravity, T* a, T* b, T* c) {
  const size_t nb = bodies.size();
  const T zero = T{} * 0.0;
  const T root_g[3] = {zero - gravity[0], zero - gravity[1], zero - gravity[2]};  // an upward base acceleration
  for (size_t i = 0; i < nb; ++i) {
    const RobotModel::Body& bd = bodies[i];
    AbcBody<T>& B = S[i];
    const T* E = B.E;
    T* v = B.v;
    if (bd.parent >= 0) {
      const AbcBody<T>& P = S[static_cast<size_t>(bd.parent)];
      if (bd.type == RobotModel::JointType::Revolute) transform_from_parent(bd.r_tree.data(), P, B);
      else transform_from_parent(B.r, P, B);
    } else {
      for (int k = 0; k < 3; ++k) B.aw[k] = B.al[k] = zero;
      for (int k = 0; k < 6; ++k) v[k] = zero;
      mul_E(E, root_g, B.g);
    }
    const T qd = dq[i], qdd = ddq[i];
    const double ax[3] = {bd.axis[0], bd.axis[1], bd.axis[2]};
    const bool revolute = bd.type == RobotModel::JointType::Revolute;
    const int u = bd.axis_index;
    if (u == 0) {
      joint_motion_on_axis<0>(revolute, qd, qdd, B.aw, B.al, v);
    } else if (u == 1) {
      joint_motion_on_axis<1>(revolute, qd, qdd, B.aw, B.al, v);
    } else if (u == 2) {
      joint_motion_on_axis<2>(revolute, qd, qdd, B.aw, B.al, v);
    } else if (revolute) {
      const T vj[3] = {ax[0] * qd, ax[1] * qd, ax[2] * qd};
      for (int k = 0; k < 3; ++k) {
        B.aw[k] += ax[k] * qdd;
        v[k] += vj[k];
      }
      add_cross(v, vj, B.aw);      // ω × vJ
      add_cross(v + 3, vj, B.al);  // v × vJ (angular joint motion)
    } else {
      const T vj[3] = {ax[0] * qd, ax[1] * qd, ax[2] * qd};
      for (int k = 0; k < 3; ++k) {
        B.al[k] += ax[k] * qdd;
        v[3 + k] += vj[k];
      }
      add_cross(v, vj, B.al);  // ω × vJ (linear joint motion)
    }
    const double* I6 = bd.inertia.data();
    const double m = I6[21];
    const double h[3] = {I6[26], I6[30], I6[19]};  // (I(2,4), I(0,5), I(1,3)) of m [c]x
    // Channel b: f = I v.
    T* Iw = B.fw + 3;
    T* Il = B.fl + 3;
    mul_sym(I6, v, Iw);
    add_cross(h, v + 3, Iw);
    T t[3];
    cross(h, v, t);
    for (int k = 0; k < 3; ++k) Il[k] = m * v[3 + k] - t[k];
    // Channel a: f = I a + v ×* I v.
    mul_sym(I6, B.aw, B.fw);
    cross(h, B.aw, t);
    for (int k = 0; k < 3; ++k) B.fl[k] = m * B.al[k] - t[k];
    add_cross(h, B.al, B.fw);
    add_cross(v, Iw, B.fw);
    add_cross(v + 3, Il, B.fw);
    add_cross(v, Il, B.fl);
    // Channel c: the body's own mass and moment; the children add theirs below.
    for (int k = 0; k < 3; ++k) splat(B.h[k], h[k]);
    B.m = m;
  }
  for (size_t i = nb; i-- > 0;) {
    const RobotModel::Body& bd = bodies[i];
    AbcBody<T>& B = S[i];
    const double* ax = bd.axis.data();
    const int u = bd.axis_index;
    if (u == 0) {
      project_on_axis<0>(bd.type == RobotModel::JointType::Revolute, B, a[i], b[i], c[i]);
    } else if (u == 1) {
      project_on_axis<1>(bd.type == RobotModel::JointType::Revolute, B, a[i], b[i], c[i]);
    } else if (u == 2) {
      project_on_axis<2>(bd.type == RobotModel::JointType::Revolute, B, a[i], b[i], c[i]);
    } else if (bd.type == RobotModel::JointType::Revolute) {
      dot_axis(ax, B.fw, a[i]);
      dot_axis(ax, B.fw + 3, b[i]);
      T n[3];
      cross(B.h, B.g, n);
      dot_axis(ax, n, c[i]);
    } else {
      dot_axis(ax, B.fl, a[i]);
      dot_axis(ax, B.fl + 3, b[i]);
      dot_axis(ax, B.g, c[i]);
      c[i] *= B.m;
    }
    if (bd.parent >= 0) {
      // f_λ += ^iX_λ^T f: n' = E^T n + r × (E^T f), f' = E^T f; the first moment moves as a point mass.
      AbcBody<T>& P = S[static_cast<size_t>(bd.parent)];
      if (bd.type == RobotModel::JointType::Revolute) add_to_parent(bd.r_tree.data(), B, P);
      else add_to_parent(B.r, B, P);
    }
  }
}

// The AbcBody array of a workspace's byte buffer, aligned for T, followed by `extra` more T.
template <typename T>
AbcBody<T>* abc_bodies(RobotWorkspace& ws, size_t nb, size_t extra = 0) {
  const size_t size = nb * sizeof(AbcBody<T>) + extra * sizeof(T);
  const size_t bytes = size + alignof(AbcBody<T>);
  if (ws.abc_buffer.size() < bytes) ws.abc_buffer.resize(bytes);
  void* p = ws.abc_buffer.data();
  size_t space = ws.abc_buffer.size();
  p = std::align(alignof(AbcBody<T>), size, p, space);
  return static_cast<AbcBody<T>*>(p);
}

#if defined(__GNUC__)
using Double2 = double __attribute__((vector_size(16)));  // two samples, one per SIMD lane (SSE2, NEON)
#if defined(__x86_64__) || defined(__i386__)
#define PATHPACE_WIDE_LANES 1
using Double4 = double __attribute__((vector_size(32)));  // AVX2
using Double8 = double __attribute__((vector_size(64)));  // AVX-512
#endif

// sin and cos of every lane at once, to within 2 ulp of libm's (checked over 1.6e7 arguments in
// [-1e5, 1e5] and [-7, 7]): the reduction by π/2 in three parts (Cody-Waite, fdlibm's constants; exact for
// |x| <= 1e5, which the caller ensures) and fdlibm's kernels on [-π/4, π/4]. One libm sincos per joint
// and sample was a fifth of the torque rows' time. The quadrant picks and signs the kernels by products
// with 0, 1 and ±1 (exact), not by lane comparisons: GCC does those one lane at a time with AVX-512.
template <typename V>
PATHPACE_LANE_INLINE void sincos_lanes(const V& x, V& s, V& c) {
  const double magic = 6755399441055744.0;  // 1.5 · 2^52: y + magic - magic rounds y to an integer
  const V k = (x * 0.63661977236758134308 + magic) - magic;  // nearest multiple of π/2
  V r = x - k * 1.57079632673412561417e+00;
  r = r - k * 6.07710050630396597660e-11;
  r = r - k * 2.02226624879595063154e-21;
  const V z = r * r;
  const V sp =
      r + r * z *
              (-1.66666666666666324348e-01 +
               z * (8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 +
                         z * (2.75573137070700676789e-06 + z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
  const V cp =
      1.0 - 0.5 * z +
      z * z *
          (4.16666666666666019037e-02 +
           z * (-1.38888888888741095749e-03 +
                z * (2.48015872894767294178e-05 +
                     z * (-2.75573143513906633035e-07 + z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  // The quadrant q = k mod 4 in 0..3 = 2 hi + odd: sin x = ±(sp or cp), cos x = ±(cp or sp); every
  // step is exact in doubles (|k| < 2^50).
  const V q = k - 4.0 * ((k * 0.25 - 0.375 + magic) - magic);
  const V hi = (q * 0.5 - 0.25 + magic) - magic;
  const V odd = q - 2.0 * hi;
  const V even = 1.0 - odd;
  const V sin_sign = 1.0 - 2.0 * hi;
  const V cos_sign = 1.0 - 2.0 * (hi + odd - 2.0 * hi * odd);  // + in quadrants 0 and 3
  s = sin_sign * (sp * even + cp * odd);
  c = cos_sign * (cp * even + sp * odd);
}

// A constraint's row pair of eq. (15) at out's index `at` (see TorqueOutput): (a, b, τ_U - c) and (-a, -b, c - τ_L),
// with limit_or_inf's bounds (no limit: +inf - c and c + inf, an inactive row).
inline void store_row_pair(const detail::TorqueOutput& out, Eigen::Index at, double up, double lo, double a, double b,
                           double c) {
  out.a[at] = a;
  out.a[at + 1] = -a;
  out.b[at] = b;
  out.b[at + 1] = -b;
  out.c[at] = up - c;
  out.c[at + 1] = c - lo;
}

// Joint j's (τ_U, τ_L) for store_row_pair: an infinite limit as +inf and -inf.
inline std::pair<double, double> limit_or_inf(const detail::TorqueOutput& out, size_t j) {
  const double inf = std::numeric_limits<double>::infinity();
  return {std::isfinite(out.upper[j]) ? out.upper[j] : inf, std::isfinite(out.lower[j]) ? out.lower[j] : -inf};
}

// path_torque_coefficients_batch without mimic joints, W = sizeof(V) / 8 samples per sweep. q, dq, ddq
// are column-major (samples, bodies) with leading dimension `count`; a last group of fewer than W
// samples fills its spare lanes with its last sample and stores only its own.
template <typename V>
PATHPACE_LANE_INLINE void path_torque_lanes(const std::vector<RobotModel::Body>& bodies, const Eigen::Vector3d& gravity,
                                            RobotWorkspace& ws, Eigen::Index count, const double* q, const double* dq,
                                            const double* ddq, const detail::TorqueOutput& out) {
  constexpr Eigen::Index W = sizeof(V) / sizeof(double);
  const size_t nb = bodies.size();
  AbcBody<V>* S = abc_bodies<V>(ws, nb, 5 * nb);
  V* qd = reinterpret_cast<V*>(S + nb);
  V *qdd = qd + nb, *av = qdd + nb, *bv = av + nb, *cv = bv + nb;
  // Per body: the coordinate axis of a revolute joint whose angles all lie within sincos_lanes' range,
  // else -1 (joint_transform in each lane, with libm's sin and cos).
  std::vector<int> unit(nb);
  for (size_t i = 0; i < nb; ++i) {
    unit[i] = unit_axis(bodies[i]);
    if (unit[i] < 0) continue;
    const double* col = q + static_cast<Eigen::Index>(i) * count;
    bool in_range = true;
    for (Eigen::Index s = 0; s < count; ++s) in_range &= std::abs(col[s]) <= 1e5;  // false for NaN
    if (!in_range) unit[i] = -1;
  }
  for (Eigen::Index s = 0; s < count; s += W) {
    const Eigen::Index valid = std::min(W, count - s);
    const auto load = [&](const double* x, Eigen::Index j, V& y) {
      const double* col = x + j * count + s;
      if (valid == W) {
        std::memcpy(&y, col, sizeof(V));
      } else {
        for (Eigen::Index l = 0; l < W; ++l) y[l] = col[std::min(l, valid - 1)];
      }
    };
    for (size_t i = 0; i < nb; ++i) {
      const RobotModel::Body& bd = bodies[i];
      const Eigen::Index j = static_cast<Eigen::Index>(i);
      load(dq, j, qd[i]);
      load(ddq, j, qdd[i]);
      V qv;
      load(q, j, qv);
      AbcBody<V>& B = S[i];
      if (unit[i] >= 0) {
        V sq, cq;
        sincos_lanes(qv, sq, cq);
        unit_axis_rotation<V>(bd, unit[i], cq, sq, B.E);
      } else {
        for (Eigen::Index l = 0; l < W; ++l) {
          double E[9], r[3];
          joint_transform(bd, qv[l], E, r);
          for (int k = 0; k < 9; ++k) B.E[k][l] = E[k];
          for (int k = 0; k < 3; ++k) B.r[k][l] = r[k];
        }
      }
    }
    abc_sweep<V>(bodies, S, qd, qdd, gravity, av, bv, cv);
    const Eigen::Index ss = out.sample_stride;
    for (size_t i = 0; i < nb; ++i) {
      const Eigen::Index at = static_cast<Eigen::Index>(i) * out.joint_stride + s * ss;
      if (out.upper) {  // a constraint's row pair, see TorqueOutput
        const auto [up, lo] = limit_or_inf(out, i);
        for (Eigen::Index l = 0; l < valid; ++l) store_row_pair(out, at + l * ss, up, lo, av[i][l], bv[i][l], cv[i][l]);
      } else if (valid == W && ss == 1) {
        std::memcpy(out.a + at, &av[i], sizeof(V));
        std::memcpy(out.b + at, &bv[i], sizeof(V));
        std::memcpy(out.c + at, &cv[i], sizeof(V));
      } else {
        for (Eigen::Index l = 0; l < valid; ++l) {
          out.a[at + l * ss] = av[i][l];
          out.b[at + l * ss] = bv[i][l];
          out.c[at + l * ss] = cv[i][l];
        }
      }
    }
  }
}

void path_torque_lanes2(const std::vector<RobotModel::Body>& bodies, const Eigen::Vector3d& gravity, RobotWorkspace& ws,
                        Eigen::Index count, const double* q, const double* dq, const double* ddq,
                        const detail::TorqueOutput& out) {
  path_torque_lanes<Double2>(bodies, gravity, ws, count, q, dq, ddq, out);
}
#if defined(PATHPACE_WIDE_LANES)
// The same code with the wider registers of newer x86-64 CPUs, chosen at run time (the library itself
// is built for the x86-64 baseline, SSE2). FMA contracts the products and sums: the results differ from
// the SSE2 variant's by rounding.
__attribute__((target("avx2,fma"))) void path_torque_lanes4(const std::vector<RobotModel::Body>& bodies,
                                                             const Eigen::Vector3d& gravity, RobotWorkspace& ws,
                                                             Eigen::Index count, const double* q, const double* dq,
                                                             const double* ddq, const detail::TorqueOutput& out) {
  path_torque_lanes<Double4>(bodies, gravity, ws, count, q, dq, ddq, out);
}
__attribute__((target("avx512f,avx512dq,avx2,fma"))) void path_torque_lanes8(
    const std::vector<RobotModel::Body>& bodies, const Eigen::Vector3d& gravity, RobotWorkspace& ws, Eigen::Index count,
    const double* q, const double* dq, const double* ddq, const detail::TorqueOutput& out) {
  path_torque_lanes<Double8>(bodies, gravity, ws, count, q, dq, ddq, out);
}
#endif
#endif

}  // namespace

namespace detail {

int torque_lanes_supported() {
#if defined(PATHPACE_WIDE_LANES)
  static const int widest = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") ? 8
                            : __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? 4
                                                                                             : 2;
  return widest;
#elif defined(__GNUC__)
  return 2;
#else
  return 1;
#endif
}

int default_torque_lanes() {
  // Read at every call (once per constraint's rows, not per sample), so that a test can switch it.
  const char* forced = std::getenv("PATHPACE_TORQUE_LANES");
  if (!forced || !*forced) return torque_lanes_supported();
  char* end = nullptr;
  const long lanes = std::strtol(forced, &end, 10);
  if (*end != '\0' || lanes < 1 || lanes > torque_lanes_supported() || (lanes & (lanes - 1)) != 0)
    fail(std::string("environment variable PATHPACE_TORQUE_LANES = '") + forced + "' must be a power of 2 <= " +
         std::to_string(torque_lanes_supported()) + " (the widest this CPU runs), or unset");
  return static_cast<int>(lanes);
}

void check_sample_shapes(Eigen::Index n, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq) {
  const Eigen::Index count = q.rows();
  if (q.cols() != n || dq.cols() != n || ddq.cols() != n || dq.rows() != count || ddq.rows() != count)
    fail("q, dq, ddq must all have shape (samples, " + std::to_string(n) + ")");
}

void path_torque_coefficients_into(const RobotModel& robot, RobotWorkspace& ws, const Eigen::MatrixXd& q,
                                   const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, const TorqueOutput& out,
                                   int lanes) {
  const Eigen::Index n = robot.nq(), count = q.rows();
  check_sample_shapes(n, q, dq, ddq);
  if (lanes == 0) lanes = default_torque_lanes();
  if (lanes < 1 || lanes > torque_lanes_supported() || (lanes & (lanes - 1)) != 0)
    fail("lanes = " + std::to_string(lanes) + " must be a power of 2 <= " + std::to_string(torque_lanes_supported()));
  const std::vector<RobotModel::Body>& bodies = robot.bodies();
  if (robot.mimic_joints().empty()) {
    switch (lanes) {
#if defined(PATHPACE_WIDE_LANES)
      case 8:
        path_torque_lanes8(bodies, robot.gravity(), ws, count, q.data(), dq.data(), ddq.data(), out);
        return;
      case 4:
        path_torque_lanes4(bodies, robot.gravity(), ws, count, q.data(), dq.data(), ddq.data(), out);
        return;
#endif
#if defined(__GNUC__)
      case 2:
        path_torque_lanes2(bodies, robot.gravity(), ws, count, q.data(), dq.data(), ddq.data(), out);
        return;
#endif
      default:
        break;
    }
  }
  // One sample at a time, or a robot with mimic joints (the batch maps them onto its bodies' model).
  auto store = [&](Eigen::Index s, const auto& a, const auto& b, const auto& c) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::Index at = s * out.sample_stride + j * out.joint_stride;
      if (out.upper) {
        const auto [up, lo] = limit_or_inf(out, static_cast<size_t>(j));
        store_row_pair(out, at, up, lo, a(j), b(j), c(j));
      } else {
        out.a[at] = a(j);
        out.b[at] = b(j);
        out.c[at] = c(j);
      }
    }
  };
  if (robot.mimic_joints().empty()) {
    // The samples' rows copied into vectors held across the loop (a row of a column-major matrix is not
    // contiguous: passed as it is, each would be copied into a new vector per sample).
    Eigen::VectorXd as(n), bs(n), cs(n), qs(n), dqs(n), ddqs(n);
    for (Eigen::Index s = 0; s < count; ++s) {
      qs = q.row(s).transpose();
      dqs = dq.row(s).transpose();
      ddqs = ddq.row(s).transpose();
      robot.path_torque_coefficients(ws, qs, dqs, ddqs, as, bs, cs);
      store(s, as, bs, cs);
    }
  } else {
    Eigen::MatrixXd A, B, C;
    robot.path_torque_coefficients_batch(ws, q, dq, ddq, A, B, C);
    for (Eigen::Index s = 0; s < count; ++s) store(s, A.row(s), B.row(s), C.row(s));
  }
}

void path_torque_coefficients_lanes(const RobotModel& robot, RobotWorkspace& ws, const Eigen::MatrixXd& q,
                                    const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq, Eigen::MatrixXd& a,
                                    Eigen::MatrixXd& b, Eigen::MatrixXd& c, int lanes) {
  check_sample_shapes(robot.nq(), q, dq, ddq);
  a.resize(q.rows(), robot.nq());
  b.resize(q.rows(), robot.nq());
  c.resize(q.rows(), robot.nq());
  path_torque_coefficients_into(robot, ws, q, dq, ddq, TorqueOutput{a.data(), b.data(), c.data(), 1, q.rows()}, lanes);
}

}  // namespace detail

void RobotModel::path_torque_coefficients(RobotWorkspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                                          const Eigen::Ref<const Eigen::VectorXd>& dq,
                                          const Eigen::Ref<const Eigen::VectorXd>& ddq, Eigen::Ref<Eigen::VectorXd> a,
                                          Eigen::Ref<Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> c) const {
  // eq. (12): τ = M (p'' ṡ² + p' s̈) + C(q, p' ṡ) p' ṡ + g, and C is quadratic in the velocity, so
  // a = M p'' + C(q, p') p' = RNEA(q, p', p'') without gravity, b = M p' = RNEA(q, 0, p') without
  // gravity, c = g(q): three RNEA channels in one sweep (abc_sweep).
  if (mimic_) {
    const MimicMap& mm = *mimic_;
    const Eigen::Index nbodies = static_cast<Eigen::Index>(bodies_.size());
    Eigen::VectorXd ab(nbodies), bb(nbodies), cb(nbodies);
    mm.bodies_model->path_torque_coefficients(ws, mm.E * q + mm.o, mm.E * dq, mm.E * ddq, ab, bb, cb);
    a.noalias() = mm.E.transpose() * ab;
    b.noalias() = mm.E.transpose() * bb;
    c.noalias() = mm.E.transpose() * cb;
    return;
  }
  const size_t nb = bodies_.size();
  AbcBody<double>* S = abc_bodies<double>(ws, nb);
  for (size_t i = 0; i < nb; ++i) joint_transform(bodies_[i], q[static_cast<Eigen::Index>(i)], S[i].E, S[i].r);
  abc_sweep<double>(bodies_, S, dq.data(), ddq.data(), gravity_, a.data(), b.data(), c.data());
}

void RobotModel::path_torque_coefficients_batch(RobotWorkspace& ws, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                                const Eigen::MatrixXd& ddq, Eigen::MatrixXd& a, Eigen::MatrixXd& b,
                                                Eigen::MatrixXd& c) const {
  if (mimic_) {
    detail::check_sample_shapes(nq(), q, dq, ddq);  // before the products below (else _into checks them)
    const MimicMap& mm = *mimic_;
    const Eigen::MatrixXd qb = (q * mm.E.transpose()).rowwise() + mm.o.transpose();
    const Eigen::MatrixXd dqb = dq * mm.E.transpose(), ddqb = ddq * mm.E.transpose();
    Eigen::MatrixXd ab, bb, cb;
    mm.bodies_model->path_torque_coefficients_batch(ws, qb, dqb, ddqb, ab, bb, cb);
    a.noalias() = ab * mm.E;
    b.noalias() = bb * mm.E;
    c.noalias() = cb * mm.E;
    return;
  }
  // As many samples per sweep as the CPU has SIMD lanes (8 with AVX-512, 4 with AVX2, 2 with SSE2).
  detail::path_torque_coefficients_lanes(*this, ws, q, dq, ddq, a, b, c);
}

int RobotModel::body_of_link(const std::string& link, Eigen::Isometry3d& in_body) const {
  auto it = links_.find(link);
  if (it == links_.end()) detail::fail("link '" + link + "' is not a link of robot '" + name_ + "'");
  in_body = it->second.second;
  return it->second.first;
}

void RobotModel::body_placements(const Eigen::Ref<const Eigen::VectorXd>& q, std::vector<Eigen::Isometry3d>& T) const {
  // Every Jacobian and drift computation reads q[i] for each body: a shorter q was a heap overread.
  check_q(q, "q");
  if (mimic_) {
    mimic_->bodies_model->body_placements(mimic_->E * q + mimic_->o, T);
    return;
  }
  T.resize(bodies_.size());
  for (size_t i = 0; i < T.size(); ++i) {
    const Body& b = bodies_[i];
    Eigen::Isometry3d tree = Eigen::Isometry3d::Identity();
    tree.linear() = b.E_tree.transpose();
    tree.translation() = b.r_tree;
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    const double qi = q[static_cast<Eigen::Index>(i)];
    if (b.type == JointType::Revolute) motion.linear() = Eigen::AngleAxisd(qi, b.axis).toRotationMatrix();
    else motion.translation() = b.axis * qi;
    T[i] = (b.parent >= 0 ? T[static_cast<size_t>(b.parent)] : Eigen::Isometry3d::Identity()) * tree * motion;
  }
}

void RobotModel::add_point_jacobian(const std::vector<Eigen::Isometry3d>& T, int body, const Eigen::Vector3d& p,
                                    double sign, Eigen::Ref<Eigen::MatrixXd> J) const {
  if (mimic_) {  // chain rule: a mimic body's column goes to its joint's, times the multiplier
    Eigen::MatrixXd Jb = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(bodies_.size()));
    mimic_->bodies_model->add_point_jacobian(T, body, p, sign, Jb);
    J.noalias() += Jb * mimic_->E;
    return;
  }
  for (int i = body; i >= 0; i = bodies_[static_cast<size_t>(i)].parent) {
    const Body& b = bodies_[static_cast<size_t>(i)];
    // The joint frame is the body frame: its axis is fixed in the body, its origin is the body origin.
    const Eigen::Vector3d z = T[static_cast<size_t>(i)].linear() * b.axis;
    if (b.type == JointType::Revolute) J.col(i) += sign * z.cross(p - T[static_cast<size_t>(i)].translation());
    else J.col(i) += sign * z;
  }
}

Eigen::Matrix4d RobotModel::frame_placement(const Eigen::VectorXd& q, const std::string& link) const {
  check_q(q, "q");
  detail::require_finite("q", q);
  Eigen::Isometry3d in_body;
  const int body = body_of_link(link, in_body);
  std::vector<Eigen::Isometry3d> T;
  body_placements(q, T);
  return ((body >= 0 ? T[static_cast<size_t>(body)] : Eigen::Isometry3d::Identity()) * in_body).matrix();
}

Eigen::MatrixXd RobotModel::point_jacobian(const Eigen::VectorXd& q, const std::string& link,
                                           const Eigen::Vector3d& point) const {
  check_q(q, "q");
  detail::require_finite("q", q);
  detail::require_finite("point", point);
  Eigen::Isometry3d in_body;
  const int body = body_of_link(link, in_body);
  std::vector<Eigen::Isometry3d> T;
  body_placements(q, T);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, nq());
  if (body < 0) return J;
  add_point_jacobian(T, body, T[static_cast<size_t>(body)] * (in_body * point), 1.0, J);
  return J;
}

RobotModel RobotModel::combine(const std::vector<RobotModel>& parts, const std::string& name) {
  if (parts.empty()) detail::fail("parts is empty: expected at least one model");
  RobotModel m;
  m.gravity_ = parts[0].gravity_;
  std::map<std::string, int> joint_count;
  for (const RobotModel& p : parts)
    for (const std::string& j : p.joint_names_) ++joint_count[j];
  std::vector<double> lo, hi, vel, eff;
  for (size_t i = 0; i < parts.size(); ++i) {
    const RobotModel& p = parts[i];
    m.frozen_mimics_.insert(m.frozen_mimics_.end(), p.frozen_mimics_.begin(), p.frozen_mimics_.end());
    if ((p.gravity_ - m.gravity_).norm() > 0.0)
      detail::fail("parts[" + std::to_string(i) + "] ('" + p.name_ + "') has gravity (" + detail::fmt(p.gravity_.x()) + ", " +
                   detail::fmt(p.gravity_.y()) + ", " + detail::fmt(p.gravity_.z()) + "), parts[0] has (" +
                   detail::fmt(m.gravity_.x()) + ", " + detail::fmt(m.gravity_.y()) + ", " + detail::fmt(m.gravity_.z()) +
                   "): they must agree");
    const int offset = static_cast<int>(m.bodies_.size());
    for (Body b : p.bodies_) {
      if (b.parent >= 0) b.parent += offset;
      m.bodies_.push_back(b);
    }
    for (const std::string& j : p.joint_names_) m.joint_names_.push_back(joint_count[j] > 1 ? p.name_ + "/" + j : j);
    for (const std::string& l : p.link_names_) {
      auto it = p.links_.find(l);
      if (m.links_.count(l))
        detail::fail("parts[" + std::to_string(i) + "] ('" + p.name_ + "') has a link '" + l +
                     "' that an earlier part also has: link names must be unique");
      m.links_[l] = {it->second.first >= 0 ? it->second.first + offset : -1, it->second.second};
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
  m.q_lo_ = as_vector(lo);
  m.q_hi_ = as_vector(hi);
  m.v_max_ = as_vector(vel);
  m.effort_ = as_vector(eff);
  bool any_mimic = false;
  for (const RobotModel& p : parts) any_mimic = any_mimic || bool(p.mimic_);
  if (any_mimic) {  // block-diagonal E over the parts; the bodies model combines the parts' bodies models
    auto map = std::make_shared<MimicMap>();
    map->E = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m.bodies_.size()), m.nq());
    map->o = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.bodies_.size()));
    std::vector<RobotModel> full;
    Eigen::Index row = 0, col = 0;
    for (const RobotModel& p : parts) {
      const Eigen::Index nbp = static_cast<Eigen::Index>(p.bodies_.size()), np = p.nq();
      if (p.mimic_) {
        map->E.block(row, col, nbp, np) = p.mimic_->E;
        map->o.segment(row, nbp) = p.mimic_->o;
        map->joints.insert(map->joints.end(), p.mimic_->joints.begin(), p.mimic_->joints.end());
        full.push_back(*p.mimic_->bodies_model);
      } else {
        map->E.block(row, col, nbp, np).setIdentity();
        full.push_back(p);
      }
      row += nbp;
      col += np;
    }
    map->bodies_model = std::make_shared<const RobotModel>(combine(full, m.name_));
    m.mimic_ = std::move(map);
  }
  auto source = std::make_shared<Source>();
  source->kind = Source::Kind::Combine;
  source->parts = parts;
  source->name = name;
  m.source_ = std::move(source);
  return m;
}

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
  check_gravity(gravity);
  RobotModel m;
  m.name_ = name;
  m.gravity_ = gravity;
  RobotModelOptions options;
  options.floating_base = true;
  Builder b{options, m.bodies_, m.joint_names_, m.link_names_, m.links_, {}, {}, {}, {}, {}, {}};
  const int body = b.add_floating_base();
  m.bodies_[static_cast<size_t>(body)].inertia = spatial_inertia(mass, com, inertia);
  m.links_[name] = {body, Eigen::Isometry3d::Identity()};
  m.link_names_.push_back(name);
  b.store_limits(m.q_lo_, m.q_hi_, m.v_max_, m.effort_);
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
