#include "robot/tree_builder.hpp"

#include <limits>

#include "base/validate.hpp"

namespace pathpace::detail {

namespace {

// u if the axis is the coordinate axis e_u exactly, else -1.
int coordinate_axis(const Eigen::Vector3d& axis) {
  for (int u = 0; u < 3; ++u)
    if (axis[u] == 1.0 && axis[(u + 1) % 3] == 0.0 && axis[(u + 2) % 3] == 0.0) return u;
  return -1;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

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

// Gravity in m/s² (the unit of the URDF's lengths per s²): finite, and at most 1e3 m/s² (~100 g, beyond
// any planet's surface or a test centrifuge's usual range). More is a unit error (9810 is g in mm/s²),
// and with 1e308 the torques overflowed to inf and NaN.
void check_gravity(const Eigen::Vector3d& g) {
  require_finite("gravity", g);
  constexpr double kMaxGravity = 1e3;
  if (g.stableNorm() > kMaxGravity)
    fail("gravity = (" + fmt(g.x()) + ", " + fmt(g.y()) + ", " + fmt(g.z()) + ") has |gravity| = " +
         fmt(g.stableNorm()) + " m/s^2, must be <= 1000 m/s^2 (about 100 g; gravity is in m/s^2, e.g. (0, 0, -9.81))");
}

int TreeBuilder::add_body(int parent, RobotModel::JointType type, const Eigen::Vector3d& axis,
                          const Eigen::Isometry3d& tree, const std::string& name, double lo, double hi, double vel,
                          double eff) {
  Body b;
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

int TreeBuilder::add_floating_base() {
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

void TreeBuilder::add_link(const std::string& name, int body, const Eigen::Isometry3d& placement) {
  links[name] = {body, placement};
  link_names.push_back(name);
}

void TreeBuilder::store_limits(Eigen::VectorXd& lo, Eigen::VectorXd& hi, Eigen::VectorXd& vel,
                               Eigen::VectorXd& eff) const {
  lo = as_vector(q_lo);
  hi = as_vector(q_hi);
  vel = as_vector(v_max);
  eff = as_vector(effort);
}

}  // namespace pathpace::detail
