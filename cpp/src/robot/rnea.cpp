// The recursive Newton-Euler algorithm (Featherstone): inverse dynamics τ = M(q) q̈ + C(q, q̇) q̇ + g(q),
// gravity torques and the mass matrix, one sample at a time. (The torque coefficients of eq. 12 over
// many samples are torque_lanes.cpp's.)
#include "base/validate.hpp"
#include "robot/bodies.hpp"
#include "robot/joint_transform.hpp"

namespace pathpace {

namespace {

using detail::Body;
using detail::RobotScratch;
using detail::Vector6;

// Joint transforms and motion subspaces, shared by every pass at one q.
void joint_transforms(const std::vector<Body>& bodies, RobotScratch& ws, const Eigen::Ref<const Eigen::VectorXd>& q) {
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    detail::joint_transform(b, q[static_cast<Eigen::Index>(i)], ws.E[i].data(), ws.r[i].data());
    if (b.type == RobotModel::JointType::Revolute) ws.S[i] << b.axis, Eigen::Vector3d::Zero();
    else ws.S[i] << Eigen::Vector3d::Zero(), b.axis;
  }
}

// One RNEA pass over the transforms in ws (Featherstone, motion vectors [ω; v] in body coordinates;
// gravity enters as a fictitious upward acceleration of the base). qd == nullptr means q̇ = 0, which
// drops every velocity product.
void rnea_pass(const std::vector<Body>& bodies, RobotScratch& ws, const Eigen::VectorXd* qd,
               const Eigen::Ref<const Eigen::VectorXd>& qdd, const Eigen::Vector3d* gravity, Eigen::Ref<Eigen::VectorXd> tau) {
  const size_t nb = bodies.size();
  Vector6 a0 = Vector6::Zero();
  if (gravity) a0.tail<3>() = -*gravity;
  for (size_t i = 0; i < nb; ++i) {
    const Body& b = bodies[i];
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
    const Body& b = bodies[i];
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

void RobotModel::inverse_dynamics(RobotWorkspace& workspace, const Eigen::Ref<const Eigen::VectorXd>& q,
                                  const Eigen::Ref<const Eigen::VectorXd>& qd, const Eigen::Ref<const Eigen::VectorXd>& qdd,
                                  bool with_gravity, Eigen::Ref<Eigen::VectorXd> tau) const {
  if (mimic_) {
    const detail::MimicMap& mm = *mimic_;
    Eigen::VectorXd tau_bodies(static_cast<Eigen::Index>(tree_->bodies.size()));
    mm.bodies_model->inverse_dynamics(workspace, mm.E * q + mm.o, mm.E * qd, mm.E * qdd, with_gravity, tau_bodies);
    tau.noalias() = mm.E.transpose() * tau_bodies;
    return;
  }
  RobotScratch& ws = detail::RobotInternals::scratch(workspace, *this);
  joint_transforms(tree_->bodies, ws, q);
  ws.qd = qd;
  rnea_pass(tree_->bodies, ws, &ws.qd, qdd, with_gravity ? &gravity_ : nullptr, tau);
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

}  // namespace pathpace
