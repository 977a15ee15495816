#include "pathpace/constraints/contact_constraint.hpp"

#include <cmath>

#include "detail/projection.hpp"
#include "detail/validate.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/robot_workspace.hpp"

namespace pathpace {

ContactConstraint::ContactConstraint(std::shared_ptr<const RobotModel> robot, std::vector<Contact> contacts,
                                     const ContactOptions& options, Eigen::VectorXd tau_min, Eigen::VectorXd tau_max)
    : robot_(std::move(robot)), contacts_(std::move(contacts)), options_(options) {
  if (!robot_) detail::fail("robot must not be None");
  if (options_.cone_edges < 3) detail::fail("cone_edges = " + std::to_string(options_.cone_edges) + " must be >= 3");
  if (!(options_.friction_margin >= 0.0 && options_.friction_margin < 1.0))
    detail::fail("friction_margin = " + detail::fmt(options_.friction_margin) + " must be in [0, 1)");
  if (!(options_.min_normal_force >= 0.0) || !std::isfinite(options_.min_normal_force))
    detail::fail("min_normal_force = " + detail::fmt(options_.min_normal_force) + " must be >= 0 and finite");
  if (!(options_.torque_scale > 0.0) || !std::isfinite(options_.torque_scale))
    detail::fail("torque_scale = " + detail::fmt(options_.torque_scale) + " must be > 0 and finite");
  if (!(options_.torque_margin >= 0.0) || !std::isfinite(options_.torque_margin))
    detail::fail("torque_margin = " + detail::fmt(options_.torque_margin) + " must be >= 0 and finite");
  if (!(options_.cap > 0.0) || !std::isfinite(options_.cap)) detail::fail("cap = " + detail::fmt(options_.cap) + " must be > 0");
  const int n = robot_->nq();
  if (tau_max.size() == 0) tau_max = robot_->effort_limits();
  if (tau_min.size() == 0) tau_min = -robot_->effort_limits();
  detail::require_size("tau_min", tau_min.size(), n, "one per joint");
  detail::require_size("tau_max", tau_max.size(), n, "one per joint");
  detail::require_not_nan("tau_min", tau_min);
  detail::require_not_nan("tau_max", tau_max);
  tau_min_ = options_.torque_scale * tau_min.array() + options_.torque_margin;
  tau_max_ = options_.torque_scale * tau_max.array() - options_.torque_margin;
  // Unactuated joints (zero range) stay equalities whatever the margin.
  for (int j = 0; j < n; ++j)
    if (tau_min[j] == 0.0 && tau_max[j] == 0.0) tau_min_[j] = tau_max_[j] = 0.0;
  for (int j = 0; j < n; ++j)
    if (tau_min_[j] > tau_max_[j])
      detail::fail("tau_min[" + std::to_string(j) + "] = " + detail::fmt(tau_min_[j]) + " must be <= tau_max[" +
                   std::to_string(j) + "] = " + detail::fmt(tau_max_[j]) + " (after scale and margin)");
  for (size_t i = 0; i < contacts_.size(); ++i) {
    Contact& c = contacts_[i];
    const std::string name = "contacts[" + std::to_string(i) + "]";
    detail::require_finite(name + ".point", c.point);
    detail::require_finite(name + ".normal", c.normal);
    const double len = c.normal.norm();
    if (!(len > 1e-12)) detail::fail(name + ".normal = (0, 0, 0) must be nonzero");
    c.normal /= len;  // normalised, as documented
    if (!(c.friction > 0.0) || !std::isfinite(c.friction))
      detail::fail(name + ".friction = " + detail::fmt(c.friction) + " must be > 0");
    Eigen::Isometry3d in_body;
    body_.push_back(robot_->body_of_link(c.link, in_body));
    point_in_body_.push_back(in_body * c.point);
  }
}

double ContactConstraint::max_drift(const PathSamples& samples, int* which) const {
  double worst = 0.0;
  for (size_t i = 0; i < contacts_.size(); ++i) {
    const Eigen::Vector3d p0 =
        (robot_->frame_placement(samples.q.row(0).transpose(), contacts_[i].link) * contacts_[i].point.homogeneous()).head<3>();
    for (Eigen::Index k = 1; k < samples.size(); ++k) {
      const Eigen::Vector3d pk =
          (robot_->frame_placement(samples.q.row(k).transpose(), contacts_[i].link) * contacts_[i].point.homogeneous()).head<3>();
      const double d = (pk - p0).norm();
      if (d > worst) {
        worst = d;
        if (which) *which = static_cast<int>(i);
      }
    }
  }
  return worst;
}

ConstraintRows ContactConstraint::evaluate(const PathSamples& samples) const {
  const int n = robot_->nq();
  if (samples.dof() != n)
    detail::fail("path has " + std::to_string(samples.dof()) + " coordinates, robot '" + robot_->name() + "' has " +
                 std::to_string(n) + " joints");
  const int m = static_cast<int>(contacts_.size()), k = options_.cone_edges;
  // Cone generators in world coordinates, fixed along the path for robot-world contacts.
  std::vector<Eigen::Matrix3Xd> gen(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector3d& nrm = contacts_[static_cast<size_t>(i)].normal;
    Eigen::Vector3d e = Eigen::Vector3d::UnitX();
    if (std::abs(nrm.x()) > 0.9) e = Eigen::Vector3d::UnitY();
    const Eigen::Vector3d t1 = nrm.cross(e).normalized(), t2 = nrm.cross(t1);
    const double mu = contacts_[static_cast<size_t>(i)].friction * (1.0 - options_.friction_margin);
    gen[static_cast<size_t>(i)].resize(3, k);
    for (int eidx = 0; eidx < k; ++eidx) {
      const double phi = 2.0 * M_PI * eidx / k;
      gen[static_cast<size_t>(i)].col(eidx) = nrm + mu * (std::cos(phi) * t1 + std::sin(phi) * t2);
    }
  }
  const int cols = 2 + m * k;
  const int rows = n + (options_.min_normal_force > 0.0 ? m : 0);
  detail::PolytopeLp lp;
  lp.A.setZero(rows, cols);
  lp.row_lo.resize(rows);
  lp.row_hi.resize(rows);
  lp.col_lo = Eigen::VectorXd::Zero(cols);
  lp.col_hi = Eigen::VectorXd::Constant(cols, std::numeric_limits<double>::infinity());
  lp.col_hi[0] = options_.cap;
  lp.col_lo[1] = -options_.cap;
  lp.col_hi[1] = options_.cap;
  for (int i = 0; i < m && options_.min_normal_force > 0.0; ++i) {
    lp.A.block(n + i, 2 + i * k, 1, k).setOnes();  // n·f_i = Σ_e λ_ie since n·g_ie = 1
    lp.row_lo[n + i] = options_.min_normal_force;
    lp.row_hi[n + i] = std::numeric_limits<double>::infinity();
  }

  RobotWorkspace ws(*robot_);
  Eigen::VectorXd a(n), b(n), c(n);
  std::vector<std::vector<detail::Line>> polys(static_cast<size_t>(samples.size()));
  std::vector<char> empty_point(static_cast<size_t>(samples.size()), 0);
  size_t widest = 0;
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    const Eigen::VectorXd q = samples.q.row(p).transpose();
    robot_->path_torque_coefficients(ws, q, samples.dq.row(p).transpose(), samples.ddq.row(p).transpose(), a, b, c);
    // eq. (17): τ = a x + b u + c - Σ J_iᵀ f_i, with τ eliminated into row bounds (sec. IV.B).
    lp.A.col(0).head(n) = a;  // the min-normal-force rows below n keep zeros in x and u
    lp.A.col(1).head(n) = b;
    for (int i = 0; i < m; ++i) {
      const Eigen::MatrixXd J = robot_->point_jacobian(q, contacts_[static_cast<size_t>(i)].link,
                                                       contacts_[static_cast<size_t>(i)].point);
      lp.A.block(0, 2 + i * k, n, k) = -J.transpose() * gen[static_cast<size_t>(i)];
    }
    lp.row_lo.head(n) = tau_min_ - c;
    lp.row_hi.head(n) = tau_max_ - c;
    const detail::Projection pr = detail::project_polytope(lp);
    if (pr.outcome == detail::Projection::Outcome::Failed)
      throw Error("contact projection failed at grid index " + std::to_string(p) + " (s = " + detail::fmt(samples.s[p]) +
                  "): the LP solver did not finish");
    auto& out = polys[static_cast<size_t>(p)];
    if (pr.outcome == detail::Projection::Outcome::Empty) {
      empty_point[static_cast<size_t>(p)] = 1;
    } else {
      for (const detail::Line& h : pr.halfplanes) {
        // Edges on the stand-in bounds are not limits.
        const bool on_cap = (std::abs(h.b) < 1e-12 && h.a > 0 && std::abs(h.c - options_.cap) <= 1e-6 * options_.cap) ||
                            (std::abs(h.a) < 1e-12 && std::abs(std::abs(h.c) - options_.cap) <= 1e-6 * options_.cap);
        if (!on_cap) out.push_back(h);
      }
    }
    widest = std::max(widest, out.size());
  }
  // The last row marks grid points where no contact forces balance the robot: 0 <= -1 there.
  ConstraintRows r;
  const Eigen::Index marker = static_cast<Eigen::Index>(widest);
  r.resize(samples.size(), marker + 1);
  for (size_t j = 0; j < widest; ++j) r.labels[j] = "contact polygon edge " + std::to_string(j);
  r.labels[static_cast<size_t>(marker)] = "contact forces cannot balance the robot";
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    const auto& out = polys[static_cast<size_t>(p)];
    for (size_t j = 0; j < out.size(); ++j) {
      r.a(p, static_cast<Eigen::Index>(j)) = out[j].a;
      r.b(p, static_cast<Eigen::Index>(j)) = out[j].b;
      r.c(p, static_cast<Eigen::Index>(j)) = out[j].c;
    }
    if (empty_point[static_cast<size_t>(p)]) r.c(p, marker) = -1.0;
  }
  return r;
}

}  // namespace pathpace
