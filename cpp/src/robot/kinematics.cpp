// Kinematics of a RobotModel: link lookup, body placements, frame placements, point Jacobians (the
// contact constraints' J of eq. 17), frame Jacobians and a point's motion along a path (the frame
// limits' rows) and the centre of mass.
#include <algorithm>
#include <vector>

#include "base/validate.hpp"
#include "robot/bodies.hpp"
#include "robot/joint_transform.hpp"

namespace pathpace {

namespace {

using detail::Body;

// Mass and first moment m·c of a spatial inertia in Featherstone's layout (angular first):
// I = [[Ī + m c× c×ᵀ, m c×], [m c×ᵀ, m 1]], so the lower-left block is m c×ᵀ = -m c×.
void mass_and_moment(const Eigen::Matrix<double, 6, 6>& I, double& m, Eigen::Vector3d& mc) {
  m = I(3, 3);
  const Eigen::Matrix3d mcx = I.block<3, 3>(0, 3);  // m c×
  mc = Eigen::Vector3d(mcx(2, 1), mcx(0, 2), mcx(1, 0));
}

}  // namespace

int RobotModel::body_of_link(const std::string& link, Eigen::Isometry3d& in_body) const {
  auto it = tree_->links.find(link);
  if (it == tree_->links.end()) detail::fail("link '" + link + "' is not a link of robot '" + name_ + "'");
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
  const std::vector<Body>& bodies = tree_->bodies;
  T.resize(bodies.size());
  for (size_t i = 0; i < T.size(); ++i) {
    const Body& b = bodies[i];
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

namespace {

// J += sign · (the linear Jacobian of world point p moving with `body`), the axis of joint i being
// z(i): the one chain walk behind both forms of add_point_jacobian. The joint frame is the body frame:
// its axis is fixed in the body, its origin is the body origin.
template <class Axis>
void add_chain_jacobian(const std::vector<Body>& bodies, const std::vector<Eigen::Isometry3d>& T, int body,
                        const Eigen::Vector3d& p, double sign, Eigen::Ref<Eigen::MatrixXd> J, const Axis& z) {
  for (int i = body; i >= 0; i = bodies[static_cast<size_t>(i)].parent) {
    const Eigen::Vector3d v = bodies[static_cast<size_t>(i)].type == RobotModel::JointType::Revolute
                                  ? Eigen::Vector3d(sign * z(i).cross(p - T[static_cast<size_t>(i)].translation()))
                                  : Eigen::Vector3d(sign * z(i));
    // Coefficient by coefficient: J.col(i) of a Ref has a run-time length, three of them cost a loop.
    J(0, i) += v[0];
    J(1, i) += v[1];
    J(2, i) += v[2];
  }
}

}  // namespace

void RobotModel::add_point_jacobian(const std::vector<Eigen::Isometry3d>& T, int body, const Eigen::Vector3d& p,
                                    double sign, Eigen::Ref<Eigen::MatrixXd> J) const {
  if (mimic_) {  // chain rule: a mimic body's column goes to its joint's, times the multiplier
    Eigen::MatrixXd Jb = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(tree_->bodies.size()));
    mimic_->bodies_model->add_point_jacobian(T, body, p, sign, Jb);
    J.noalias() += Jb * mimic_->E;
    return;
  }
  const std::vector<Body>& bodies = tree_->bodies;
  add_chain_jacobian(bodies, T, body, p, sign, J, [&](int i) -> Eigen::Vector3d {
    return T[static_cast<size_t>(i)].linear() * bodies[static_cast<size_t>(i)].axis;
  });
}

void RobotModel::joint_axes(const std::vector<Eigen::Isometry3d>& T, Eigen::Matrix3Xd& z) const {
  const std::vector<Body>& bodies = tree_->bodies;
  z.resize(3, static_cast<Eigen::Index>(bodies.size()));
  for (size_t i = 0; i < bodies.size(); ++i) z.col(static_cast<Eigen::Index>(i)) = T[i].linear() * bodies[i].axis;
}

void RobotModel::add_point_jacobian(const std::vector<Eigen::Isometry3d>& T, const Eigen::Matrix3Xd& z, int body,
                                    const Eigen::Vector3d& p, double sign, Eigen::Ref<Eigen::MatrixXd> J) const {
  if (mimic_) {
    Eigen::MatrixXd Jb = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(tree_->bodies.size()));
    add_chain_jacobian(tree_->bodies, T, body, p, sign, Jb, [&](int i) -> Eigen::Vector3d { return z.col(i); });
    J.noalias() += Jb * mimic_->E;
    return;
  }
  add_chain_jacobian(tree_->bodies, T, body, p, sign, J, [&](int i) -> Eigen::Vector3d { return z.col(i); });
}

std::vector<int> RobotModel::moving_joints(int body) const {
  const std::vector<Body>& bodies = tree_->bodies;
  std::vector<int> out;
  for (int i = body; i >= 0; i = bodies[static_cast<size_t>(i)].parent) {
    if (!mimic_) {
      out.push_back(i);
      continue;
    }
    for (Eigen::Index j = 0; j < mimic_->E.cols(); ++j)  // body i's coordinate in terms of q
      if (mimic_->E(i, j) != 0.0) out.push_back(static_cast<int>(j));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
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
  return frame_jacobian(q, link, point).topRows(3);
}

// The point's linear rows (add_point_jacobian) and the link's angular rows: the world axis of every
// revolute joint on the chain to the root. A mimic model's columns are its bodies model's, times E.
Eigen::MatrixXd RobotModel::frame_jacobian(const Eigen::VectorXd& q, const std::string& link,
                                           const Eigen::Vector3d& point) const {
  check_q(q, "q");
  detail::require_finite("q", q);
  detail::require_finite("point", point);
  Eigen::Isometry3d in_body;
  const int body = body_of_link(link, in_body);
  if (mimic_) return mimic_->bodies_model->frame_jacobian(mimic_->E * q + mimic_->o, link, point) * mimic_->E;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, nq());
  if (body < 0) return J;
  std::vector<Eigen::Isometry3d> T;
  body_placements(q, T);
  add_point_jacobian(T, body, T[static_cast<size_t>(body)] * (in_body * point), 1.0, J.topRows(3));
  const std::vector<Body>& bodies = tree_->bodies;
  for (int i = body; i >= 0; i = bodies[static_cast<size_t>(i)].parent)
    if (bodies[static_cast<size_t>(i)].type == JointType::Revolute)
      J.block<3, 1>(3, i) = T[static_cast<size_t>(i)].linear() * bodies[static_cast<size_t>(i)].axis;
  return J;
}

namespace {

// The world state of one body's frame in the forward pass of path_frame_motion: its rotation, its origin's
// velocity and classical acceleration, the body's angular velocity and acceleration.
struct FrameState {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero();
  Eigen::Vector3d w = Eigen::Vector3d::Zero(), al = Eigen::Vector3d::Zero();
};

// From the parent's state to body b's at (q, q̇, q̈) of its joint. The joint frame's origin sits at r (world
// coordinates, from the parent's origin; a prismatic joint's slide included) and its world axis z turns
// with the parent (ż = ω_p × z), so d/dt r = ω_p × r, plus z q̇ for a prismatic joint.
void advance(const Body& b, double q, double qd, double qdd, FrameState& f) {
  double E[9], rp[3];
  detail::joint_transform(b, q, E, rp);  // parent -> body rotation, joint origin in parent coordinates
  const Eigen::Matrix3d R = f.R * Eigen::Map<const Eigen::Matrix3d>(E).transpose();
  const Eigen::Vector3d z = R * b.axis, r = f.R * Eigen::Map<const Eigen::Vector3d>(rp);
  f.a += f.al.cross(r) + f.w.cross(f.w.cross(r));
  f.v += f.w.cross(r);
  if (b.type == RobotModel::JointType::Revolute) {
    f.al += f.w.cross(z) * qd + z * qdd;
    f.w += z * qd;
  } else {
    f.a += 2.0 * qd * f.w.cross(z) + z * qdd;
    f.v += z * qd;
  }
  f.R = R;
}

}  // namespace

RobotModel::FrameMotion RobotModel::path_frame_motion(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                                      const Eigen::MatrixXd& ddq, const std::string& link,
                                                      const Eigen::Vector3d& point) const {
  const Eigen::Index m = q.rows();
  detail::require_shape("q", q.rows(), q.cols(), m, nq(), "one row per sample, one column per joint");
  detail::require_shape("dq", dq.rows(), dq.cols(), m, nq(), "the shape of q");
  detail::require_shape("ddq", ddq.rows(), ddq.cols(), m, nq(), "the shape of q");
  detail::require_finite("point", point);
  Eigen::Isometry3d in_body;
  const int body = body_of_link(link, in_body);
  if (mimic_) {  // q_bodies = E q + o, so q̇_bodies = E q̇ and q̈_bodies = E q̈: the same pass on the bodies
    const Eigen::MatrixXd Et = mimic_->E.transpose();
    const Eigen::MatrixXd qb = (q * Et).rowwise() + mimic_->o.transpose();
    return mimic_->bodies_model->path_frame_motion(qb, dq * Et, ddq * Et, link, point);
  }
  std::vector<int> chain;  // root first
  for (int i = body; i >= 0; i = tree_->bodies[static_cast<size_t>(i)].parent) chain.insert(chain.begin(), i);
  FrameMotion out;
  out.rotation.resize(m, 9);
  for (Eigen::MatrixXd* x : {&out.velocity, &out.angular_velocity, &out.acceleration, &out.angular_acceleration})
    x->resize(m, 3);
  const Eigen::Vector3d p_body = in_body * point;
  for (Eigen::Index k = 0; k < m; ++k) {
    FrameState f;
    for (int i : chain) advance(tree_->bodies[static_cast<size_t>(i)], q(k, i), dq(k, i), ddq(k, i), f);
    const Eigen::Vector3d d = f.R * p_body;  // the point from the body's origin, world coordinates
    const Eigen::Matrix3d R = f.R * in_body.linear();
    out.rotation.row(k) = Eigen::Map<const Eigen::Matrix<double, 1, 9>>(R.data());
    out.velocity.row(k) = (f.v + f.w.cross(d)).transpose();
    out.angular_velocity.row(k) = f.w.transpose();
    out.acceleration.row(k) = (f.a + f.al.cross(d) + f.w.cross(f.w.cross(d))).transpose();
    out.angular_acceleration.row(k) = f.al.transpose();
  }
  return out;
}

double RobotModel::mass() const {
  double total = 0.0;
  for (const Body& b : tree_->bodies) total += b.inertia(3, 3);
  return total;
}

Eigen::Vector3d RobotModel::center_of_mass(const Eigen::VectorXd& q) const {
  check_q(q, "q");
  detail::require_finite("q", q);
  std::vector<Eigen::Isometry3d> T;
  body_placements(q, T);
  double total = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  const std::vector<Body>& bodies = tree_->bodies;
  for (size_t i = 0; i < bodies.size(); ++i) {
    double m;
    Eigen::Vector3d mc;
    mass_and_moment(bodies[i].inertia, m, mc);
    total += m;
    moment += m * T[i].translation() + T[i].linear() * mc;  // m · (world position of the body's com)
  }
  if (!(total > 0.0)) detail::fail("robot '" + name_ + "' has no moving mass: its centre of mass is undefined");
  return moment / total;
}

}  // namespace pathpace
