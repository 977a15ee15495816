#include "pathpace/constraints/contact_constraint.hpp"

#include <algorithm>
#include <sstream>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <Eigen/SVD>

#include "base/gather_rows.hpp"
#include "lp/projection.hpp"
#include "base/validate.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/result.hpp"
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
  if (!(options_.cone_offset >= 0.0) || !std::isfinite(options_.cone_offset))
    detail::fail("cone_offset = " + detail::fmt(options_.cone_offset) + " must be >= 0 and finite");
  if (!(options_.torque_scale > 0.0) || !std::isfinite(options_.torque_scale))
    detail::fail("torque_scale = " + detail::fmt(options_.torque_scale) + " must be > 0 and finite");
  if (!(options_.torque_margin >= 0.0) || !std::isfinite(options_.torque_margin))
    detail::fail("torque_margin = " + detail::fmt(options_.torque_margin) + " must be >= 0 and finite");
  if (!(options_.min_link_normal_force >= 0.0) || !std::isfinite(options_.min_link_normal_force))
    detail::fail("min_link_normal_force = " + detail::fmt(options_.min_link_normal_force) + " must be >= 0 and finite");
  if (!(options_.cap > 0.0) || !std::isfinite(options_.cap)) detail::fail("cap = " + detail::fmt(options_.cap) + " must be > 0");
  if (options_.max_lps < 3) detail::fail("max_lps = " + std::to_string(options_.max_lps) + " must be >= 3");
  if (!(options_.projection_tolerance >= 0.0 && options_.projection_tolerance < 1.0))
    detail::fail("projection_tolerance = " + detail::fmt(options_.projection_tolerance) + " must be in [0, 1)");
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
      detail::fail((tau_min[j] <= tau_max[j] ? "torque_margin = " + detail::fmt(options_.torque_margin) + " closes the range: "
                                             : std::string()) +
                   "tau_min[" + std::to_string(j) + "] = " + detail::fmt(tau_min_[j]) + " must be <= tau_max[" +
                   std::to_string(j) + "] = " + detail::fmt(tau_max_[j]) + " (after scale and margin)");
  const int k = options_.cone_edges;
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
    Eigen::Isometry3d other_in_body = Eigen::Isometry3d::Identity();
    int other = -1;
    if (!c.other_link.empty()) {
      if (c.other_link == c.link)
        detail::fail(name + ".other_link = '" + c.other_link + "' must differ from its link");
      other = robot_->body_of_link(c.other_link, other_in_body);
      if (other == body_.back())
        detail::fail(name + ": links '" + c.link + "' and '" + c.other_link +
                     "' are rigidly attached (one body): a force between them does nothing");
    }
    other_body_.push_back(other);
    other_in_body_.push_back(other_in_body);
    // Cone generators g_e = n + μ' (cos φ_e t1 + sin φ_e t2), inscribed in the cone of μ' = μ (1 -
    // friction_margin) (sec. V.D), in the normal's own frame (the world, or other_link).
    const Eigen::Vector3d& nrm = c.normal;
    const Eigen::Vector3d e = std::abs(nrm.x()) > 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d t1 = nrm.cross(e).normalized(), t2 = nrm.cross(t1);
    const double mu = c.friction * (1.0 - options_.friction_margin);
    Eigen::Matrix3Xd g(3, k);
    for (int j = 0; j < k; ++j) {
      const double phi = 2.0 * M_PI * j / k;
      g.col(j) = nrm + mu * (std::cos(phi) * t1 + std::sin(phi) * t2);
    }
    local_generators_.push_back(g);
    // Half the edge vectors of the k-gon of the g_e's tangential parts: for an even k that k-gon is the
    // zonotope Σ_m [-1, 1] w_m (docs/method.md, the per-point minimum's reduction).
    Eigen::Matrix3Xd w(3, k % 2 == 0 ? k / 2 : 0);
    for (int j = 0; j < w.cols(); ++j) w.col(j) = 0.5 * (g.col(j + 1) - g.col(j));
    local_half_edges_.push_back(w);
  }
  // The exact reduction: group the points by (link, body, other body, normal, μ); a group whose points
  // lie in one plane keeps the vertices of their convex hull in that plane. A force f at p = Σ α_j p_j (α
  // a convex combination) has the same generalized force Jᵀ(p) f = Σ α_j Jᵀ(p_j) f (Jᵀ f is affine in p
  // for a point of one body: the wrench (f, p × f)), and α_j f lies in the same cone; so the hull
  // vertices generate every force the group can. The sum of normal forces is unchanged, so a per-link
  // minimum survives. The shifted cone (cone_offset) does not change this: its offsets cone_offset·n_i
  // are a constant wrench, kept over every point in lp_point. A per-point minimum d = min_normal_force -
  // cone_offset > 0 on the cone weights splits each f_i into a point of the cone's cross-section at
  // n·f = d plus a force in the cone: the latter reduce to the hull vertices, the former are d·n_i (a
  // constant wrench) plus, for an even k, k/2 weights in [-d, d] per point (docs/method.md). An odd k
  // has no such zonotope: every point enters, with its row.
  const double section_min = options_.min_normal_force - options_.cone_offset;
  const bool per_point = section_min > 0.0;
  std::vector<char> keep(contacts_.size(), 1), section(contacts_.size(), 0);
  if (!per_point || k % 2 == 0) {
    std::map<std::tuple<std::string, int, int, double, double, double, double>, std::vector<int>> groups;
    for (size_t i = 0; i < contacts_.size(); ++i) {
      const Eigen::Vector3d& nrm = contacts_[i].normal;
      groups[{contacts_[i].link, body_[i], other_body_[i], nrm.x(), nrm.y(), nrm.z(), contacts_[i].friction}].push_back(
          static_cast<int>(i));
    }
    for (const auto& [key, members] : groups) {
      if (members.size() < 4) continue;
      Eigen::Matrix3Xd P(3, members.size());
      for (size_t j = 0; j < members.size(); ++j) P.col(static_cast<Eigen::Index>(j)) = point_in_body_[static_cast<size_t>(members[j])];
      const Eigen::Vector3d mean = P.rowwise().mean();
      P.colwise() -= mean;
      Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(P, Eigen::ComputeFullU);
      const Eigen::Vector3d sv = svd.singularValues();
      if (sv[0] == 0.0) {  // all at one point: one of them (with a per-point minimum: all, with their rows)
        if (per_point) continue;
        for (size_t j = 1; j < members.size(); ++j) keep[static_cast<size_t>(members[j])] = 0;
        continue;
      }
      if (sv[2] > 1e-12 * sv[0]) continue;  // not flat: keep every point
      const Eigen::Vector3d e1 = svd.matrixU().col(0), e2 = svd.matrixU().col(1);
      std::vector<detail::Vertex> flat(members.size());
      for (size_t j = 0; j < members.size(); ++j) {
        const Eigen::Vector3d d = P.col(static_cast<Eigen::Index>(j));
        flat[j] = {e1.dot(d), e2.dot(d)};
      }
      std::vector<int> hull;
      detail::convex_hull(flat, hull);
      // With a per-point minimum the reduction trades k weights and a row per point for k/2 weights per
      // point plus the hull's cones: worth it unless most points are hull vertices.
      if (per_point && 2 * hull.size() > members.size()) continue;
      for (int j : members) {
        keep[static_cast<size_t>(j)] = 0;
        section[static_cast<size_t>(j)] = per_point ? 1 : 0;
      }
      for (int h : hull) keep[static_cast<size_t>(members[static_cast<size_t>(h)])] = 1;
    }
  }
  for (size_t i = 0; i < contacts_.size(); ++i) {
    if (keep[i]) {
      reduced_.cone.push_back(static_cast<int>(i));
      reduced_.point_row.push_back(per_point && !section[i] ? 1 : 0);
    }
    if (section[i]) reduced_.section.push_back(static_cast<int>(i));
  }
  reduced_.jacobians = reduced_.cone;
  reduced_.jacobians.insert(reduced_.jacobians.end(), reduced_.section.begin(), reduced_.section.end());
}

ContactConstraint::LpLayout ContactConstraint::full_layout(bool every_point_row) const {
  LpLayout out;
  for (size_t i = 0; i < contacts_.size(); ++i) out.cone.push_back(static_cast<int>(i));
  out.point_row.assign(contacts_.size(), options_.min_normal_force > 0.0 || every_point_row ? 1 : 0);
  out.jacobians = out.cone;
  return out;
}

Eigen::Matrix3d ContactConstraint::normal_frame(size_t i, const std::vector<Eigen::Isometry3d>& T) const {
  if (other_body_[i] < 0) return Eigen::Matrix3d::Identity();
  return T[static_cast<size_t>(other_body_[i])].linear() * other_in_body_[i].linear();
}

std::shared_ptr<ContactConstraint> ContactConstraint::with_torque_limits(const Eigen::VectorXd& lo,
                                                                         const Eigen::VectorXd& hi) const {
  const Eigen::Index n = robot_->nq();
  detail::require_size("tau_min", lo.size(), n, "one per joint");
  detail::require_size("tau_max", hi.size(), n, "one per joint");
  auto out = std::make_shared<ContactConstraint>(*this);
  out->tau_min_ = tau_min_.cwiseMax(lo);
  out->tau_max_ = tau_max_.cwiseMin(hi);
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(out->tau_min_[j] <= out->tau_max_[j]))
      detail::fail("torque limits of joint " + std::to_string(j) + " ('" + robot_->joint_names()[static_cast<size_t>(j)] +
                   "'): the contacts' [" + detail::fmt(tau_min_[j]) + ", " + detail::fmt(tau_max_[j]) +
                   "] and the torque limits' [" + detail::fmt(lo[j]) + ", " + detail::fmt(hi[j]) + "] do not intersect");
  return out;
}

void ContactConstraint::contact_jacobians(const Eigen::Ref<const Eigen::VectorXd>& q, std::vector<Eigen::Isometry3d>& T,
                                          Eigen::MatrixXd& J, Eigen::Matrix3Xd& gen, const std::vector<int>* use) const {
  const int m = use ? static_cast<int>(use->size()) : static_cast<int>(contacts_.size()), k = options_.cone_edges;
  robot_->body_placements(q, T);
  J.setZero(3 * m, robot_->nq());
  gen.resize(3, m * k);
  auto pose = [&](int body) { return body >= 0 ? T[static_cast<size_t>(body)] : Eigen::Isometry3d::Identity(); };
  for (int i = 0; i < m; ++i) {
    const size_t u = use ? static_cast<size_t>((*use)[static_cast<size_t>(i)]) : static_cast<size_t>(i);
    const Eigen::Vector3d p = pose(body_[u]) * point_in_body_[u];
    auto Ji = J.middleRows(3 * i, 3);
    if (body_[u] >= 0) robot_->add_point_jacobian(T, body_[u], p, 1.0, Ji);
    if (other_body_[u] >= 0) {
      // The reaction acts on other_link at the same world point (eq. 17 with both bodies moving).
      robot_->add_point_jacobian(T, other_body_[u], p, -1.0, Ji);
      gen.middleCols(i * k, k) = pose(other_body_[u]).linear() * other_in_body_[u].linear() * local_generators_[u];
    } else {
      gen.middleCols(i * k, k) = local_generators_[u];
    }
  }
}

namespace {
// The tolerance of a phase's ends: 1e-12 relative to s.
double end_tolerance(double s) { return 1e-12 * std::max(1.0, std::abs(s)); }
}  // namespace

bool ContactConstraint::active_at(double s) const {
  const double tol = end_tolerance(s);
  return s >= options_.active_begin - tol && s <= options_.active_end + tol;
}

bool ContactConstraint::at_active_begin(double s) const {
  return std::abs(s - options_.active_begin) <= end_tolerance(s);
}

void ContactConstraint::point_velocities(const PathSamples& samples, Eigen::MatrixXd& normal, Eigen::MatrixXd& speed) const {
  if (samples.dof() != robot_->nq())
    detail::fail("path has " + std::to_string(samples.dof()) + " coordinates, robot '" + robot_->name() + "' has " +
                 std::to_string(robot_->nq()) + " joints");
  const int m = static_cast<int>(contacts_.size()), k = options_.cone_edges;
  normal.resize(samples.size(), m);
  speed.resize(samples.size(), m);
  std::vector<Eigen::Isometry3d> T;
  Eigen::MatrixXd J;
  Eigen::Matrix3Xd gen;
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    contact_jacobians(samples.q.row(p).transpose(), T, J, gen);
    const Eigen::VectorXd v = J * samples.dq.row(p).transpose();  // c_i' = J_i p' (eq. 10 for a point)
    for (int i = 0; i < m; ++i) {
      // The generators are n + μ (cos φ t1 + sin φ t2) over a full turn: their mean is the normal, in
      // the world frame (other_link's turned into the world).
      const Eigen::Vector3d n = gen.middleCols(i * k, k).rowwise().mean().normalized();
      normal(p, i) = n.dot(v.segment<3>(3 * i));
      speed(p, i) = v.segment<3>(3 * i).norm();
    }
  }
}

double ContactConstraint::max_drift(const PathSamples& samples, int* which, double* at_s) const {
  double worst = 0.0;
  std::vector<Eigen::Isometry3d> T;
  std::vector<Eigen::Vector3d> first(contacts_.size());
  bool started = false;
  for (Eigen::Index s = 0; s < samples.size(); ++s) {
    if (!active_at(samples.s[s])) continue;
    const bool at_first = !started;
    started = true;
    robot_->body_placements(samples.q.row(s).transpose(), T);
    auto pose = [&](int body) { return body >= 0 ? T[static_cast<size_t>(body)] : Eigen::Isometry3d::Identity(); };
    for (size_t i = 0; i < contacts_.size(); ++i) {
      // Where the point is, in the frame that must keep it: the world, or the other body.
      const Eigen::Vector3d p = pose(other_body_[i]).inverse() * (pose(body_[i]) * point_in_body_[i]);
      if (at_first) {
        first[i] = p;
        continue;
      }
      const double d = (p - first[i]).norm();
      if (d > worst) {
        worst = d;
        if (which) *which = static_cast<int>(i);
        if (at_s) *at_s = samples.s[s];
      }
    }
  }
  return worst;
}

void ContactConstraint::lp_structure(const LpLayout& layout, int extra, detail::PolytopeLp& lp) const {
  const int n = robot_->nq(), m = static_cast<int>(layout.cone.size()), k = options_.cone_edges;
  const int ms = static_cast<int>(layout.section.size()), h = k / 2;
  const double inf = std::numeric_limits<double>::infinity();
  // Rows: n torque rows, a per-point minimum per contact with point_row, a per-link minimum per link,
  // `extra` more. Columns: x, u, the cone weights, the cross-section weights.
  std::vector<std::string> links;
  std::vector<int> link_of(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) {
    const std::string& l = contacts_[static_cast<size_t>(layout.cone[static_cast<size_t>(i)])].link;
    auto it = std::find(links.begin(), links.end(), l);
    link_of[static_cast<size_t>(i)] = static_cast<int>(it - links.begin());
    if (it == links.end()) links.push_back(l);
  }
  const int point_rows = static_cast<int>(std::count(layout.point_row.begin(), layout.point_row.end(), 1));
  const int link_rows = options_.min_link_normal_force > 0.0 ? static_cast<int>(links.size()) : 0;
  const int cols = 2 + m * k + ms * h, rows = n + point_rows + link_rows + extra;
  lp.A.setZero(rows, cols);
  lp.row_lo = Eigen::VectorXd::Constant(rows, -inf);
  lp.row_hi = Eigen::VectorXd::Constant(rows, inf);
  lp.col_lo = Eigen::VectorXd::Zero(cols);
  lp.col_hi = Eigen::VectorXd::Constant(cols, inf);
  lp.col_hi[0] = options_.cap;
  lp.col_lo[1] = -options_.cap;
  lp.col_hi[1] = options_.cap;
  lp.stand_in = options_.cap;
  // The cross-section at n·f = d (d = min_normal_force - cone_offset): f = d n + Σ_m β_m w_m with
  // β_m in [-d, d] (w_m: μ' times half an edge of the unit k-gon, local_half_edges_).
  const double d = options_.min_normal_force - options_.cone_offset;
  lp.col_lo.tail(ms * h).setConstant(-1.0);
  lp.col_hi.tail(ms * h).setConstant(1.0);
  // n·f_i = Σ_e λ_ie since n·g_ie = 1 (sec. V.D's minimum normal force, per point and per link).
  // With the shifted cone, n·f_i = cone_offset + Σ_e λ_ie; with a cross-section, n·f_i = cone_offset + d
  // + (its cone part's weights, on the hull vertices). A link's sum counts the offsets of every one of
  // its points, those the reduction left out of the LPs too.
  for (int i = 0, r = n; i < m; ++i) {
    if (!layout.point_row[static_cast<size_t>(i)]) continue;
    lp.A.block(r, 2 + i * k, 1, k).setOnes();
    lp.row_lo[r++] = options_.min_normal_force - options_.cone_offset;
  }
  for (int l = 0; l < link_rows; ++l) {
    const std::string& name = links[static_cast<size_t>(l)];
    auto on = [&](int c) { return contacts_[static_cast<size_t>(c)].link == name; };
    const auto on_link = std::count_if(contacts_.begin(), contacts_.end(), [&](const Contact& c) { return c.link == name; });
    const auto in_section = std::count_if(layout.section.begin(), layout.section.end(), on);
    lp.row_lo[n + point_rows + l] = options_.min_link_normal_force - options_.cone_offset * static_cast<double>(on_link) -
                                    d * static_cast<double>(in_section);
  }
  for (int i = 0; i < m && link_rows > 0; ++i)
    lp.A.block(n + point_rows + link_of[static_cast<size_t>(i)], 2 + i * k, 1, k).setOnes();
}

void ContactConstraint::lp_point(const LpLayout& layout, const Eigen::Ref<const Eigen::VectorXd>& q,
                                 const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
                                 const Eigen::Ref<const Eigen::VectorXd>& c, detail::PolytopeLp& lp) const {
  thread_local std::vector<Eigen::Isometry3d> T;
  thread_local Eigen::MatrixXd J;
  thread_local Eigen::Matrix3Xd gen;
  const int n = robot_->nq(), m = static_cast<int>(layout.cone.size()), k = options_.cone_edges, h = k / 2;
  // eq. (17): τ = a x + b u + c - Σ J_iᵀ f_i, with τ eliminated into row bounds (sec. IV.B).
  lp.A.col(0).head(n) = a;  // the minimum-normal-force rows below n keep zeros in x and u
  lp.A.col(1).head(n) = b;
  contact_jacobians(q, T, J, gen, &layout.jacobians);
  for (int i = 0; i < m; ++i)
    lp.A.block(0, 2 + i * k, n, k).noalias() = -J.middleRows(3 * i, 3).transpose() * gen.middleCols(i * k, k);
  lp.row_lo.head(n) = tau_min_ - c;
  lp.row_hi.head(n) = tau_max_ - c;
  if (options_.cone_offset > 0.0) {
    // The shifted cone: f_i = cone_offset n_i + Σ_e λ_ie g_ie at every contact, reduced or not, so that
    // τ = a x + b u + c - w - Σ J_iᵀ G_i λ_i with the constant w = cone_offset Σ_i J_iᵀ n_i (eq. 17),
    // moved into the row bounds like c.
    const Eigen::VectorXd w = offset_torques(q);
    lp.row_lo.head(n) += w;
    lp.row_hi.head(n) += w;
  }
  if (!layout.section.empty()) {
    // Each section point's part d n_i + Σ_m β_im w_im: the constant d Σ J_iᵀ n_i into the row bounds,
    // the k/2 weights' columns -J_iᵀ w_im.
    const double d = options_.min_normal_force - options_.cone_offset;
    Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
    for (size_t j = 0; j < layout.section.size(); ++j) {
      const size_t u = static_cast<size_t>(layout.section[j]);
      const auto Ji = J.middleRows(3 * (m + static_cast<Eigen::Index>(j)), 3);
      const Eigen::Matrix3d R = normal_frame(u, T);
      lp.A.block(0, 2 + m * k + static_cast<Eigen::Index>(j) * h, n, h).noalias() = -d * (Ji.transpose() * (R * local_half_edges_[u]));
      w.noalias() += Ji.transpose() * (R * contacts_[u].normal);
    }
    lp.row_lo.head(n) += d * w;
    lp.row_hi.head(n) += d * w;
  }
  // Rounding residue (1e-17 where a joint axis is orthogonal to a force) is not a coefficient: as a
  // pivot it makes the simplex basis ill-conditioned and its optimum miss the polytope by 1e-5.
  const double tiny = 1e-13 * lp.A.topRows(n).cwiseAbs().maxCoeff();
  lp.A.topRows(n) = (lp.A.topRows(n).array().abs() < tiny).select(0.0, lp.A.topRows(n));
}

Eigen::VectorXd ContactConstraint::offset_torques(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  thread_local std::vector<Eigen::Isometry3d> T;
  thread_local Eigen::MatrixXd J;
  thread_local Eigen::Matrix3Xd gen;
  contact_jacobians(q, T, J, gen);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(robot_->nq());
  for (size_t i = 0; i < contacts_.size(); ++i) {
    // The normal in the world: the contact's own, or other_link's turned into the world.
    const Eigen::Vector3d n = other_body_[i] >= 0 ? Eigen::Vector3d(T[static_cast<size_t>(other_body_[i])].linear() *
                                                                    other_in_body_[i].linear() * contacts_[i].normal)
                                                  : contacts_[i].normal;
    w.noalias() += J.middleRows(3 * static_cast<Eigen::Index>(i), 3).transpose() * n;
  }
  return options_.cone_offset * w;
}

std::vector<std::string> ContactConstraint::binding_names(const LpLayout& layout) const {
  // The layout of lp_structure: n torque rows, then the per-point and per-link minimum normal force rows;
  // columns x, u, then the k cone-edge weights of each cone contact, the k/2 weights of each section
  // contact. Entry 2r / 2r + 1: row r at its lower / upper bound; then one entry per column.
  const std::vector<int>& use = layout.cone;
  const int n = robot_->nq(), m = static_cast<int>(use.size()), k = options_.cone_edges;
  auto name_of = [&](int contact) {
    const Contact& c = contacts_[static_cast<size_t>(contact)];
    std::ostringstream os;
    os.precision(4);
    os << "link '" << c.link << "' point (" << c.point.x() << ", " << c.point.y() << ", " << c.point.z() << ")";
    return os.str();
  };
  auto contact_name = [&](int i) { return name_of(use[static_cast<size_t>(i)]); };
  std::vector<std::string> links;
  for (int i = 0; i < m; ++i) {
    const std::string& l = contacts_[static_cast<size_t>(use[static_cast<size_t>(i)])].link;
    if (std::find(links.begin(), links.end(), l) == links.end()) links.push_back(l);
  }
  const int link_rows = options_.min_link_normal_force > 0.0 ? static_cast<int>(links.size()) : 0;
  std::vector<std::string> out;
  for (int j = 0; j < n; ++j) {
    const std::string& name = robot_->joint_names()[static_cast<size_t>(j)];
    const bool unactuated = tau_min_[j] == 0.0 && tau_max_[j] == 0.0;
    out.push_back(unactuated ? "balance of unactuated " + name : "torque " + name + " lower");
    out.push_back(unactuated ? "balance of unactuated " + name : "torque " + name + " upper");
  }
  for (int i = 0; i < m; ++i) {
    if (!layout.point_row[static_cast<size_t>(i)]) continue;
    out.push_back("minimum normal force at " + contact_name(i));
    out.push_back("minimum normal force at " + contact_name(i));
  }
  for (int l = 0; l < link_rows; ++l) {
    out.push_back("minimum normal force on link '" + links[static_cast<size_t>(l)] + "'");
    out.push_back("minimum normal force on link '" + links[static_cast<size_t>(l)] + "'");
  }
  out.push_back("sdot^2 >= 0");
  out.push_back("sddot");
  for (int i = 0; i < m; ++i)
    for (int e = 0; e < k; ++e) out.push_back("friction at " + contact_name(i));
  // A cross-section weight at its bound: the point pushes its minimum and uses its friction there.
  for (int j : layout.section)
    for (int e = 0; e < k / 2; ++e) out.push_back("minimum normal force at " + name_of(j));
  return out;
}

std::string ContactConstraint::binding_label(const LpLayout& layout, const std::vector<std::string>& names, int code) const {
  const int rows_entries = static_cast<int>(names.size()) - 2 - static_cast<int>(layout.cone.size()) * options_.cone_edges -
                           static_cast<int>(layout.section.size()) * (options_.cone_edges / 2);
  size_t i = names.size();
  if (code == detail::kBindingUnknown) return "contact forces";
  if (detail::binding_is_row(code)) i = static_cast<size_t>(code);
  else i = static_cast<size_t>(rows_entries + detail::binding_column(code));
  return i < names.size() ? names[i] : std::string("contact forces");
}

ConstraintRows ContactConstraint::evaluate(const PathSamples& samples) const {
  const int n = robot_->nq();
  if (samples.dof() != n)
    detail::fail("path has " + std::to_string(samples.dof()) + " coordinates, robot '" + robot_->name() + "' has " +
                 std::to_string(n) + " joints");
  std::vector<Eigen::Index> in;
  for (Eigen::Index p = 0; p < samples.size(); ++p)
    if (active_at(samples.s[p])) in.push_back(p);
  const bool rest = !options_.rest_at_begin.empty();
  if (static_cast<Eigen::Index>(in.size()) == samples.size() && !rest && options_.label.empty()) return project(samples);
  // A phase: project only its own points; the others get inactive rows (c = +inf), as the contacts do
  // not hold there.
  ConstraintRows sub;
  if (in.empty()) {
    sub.resize(0, 0);
  } else if (static_cast<Eigen::Index>(in.size()) == samples.size()) {
    sub = project(samples);
  } else {
    PathSamples ps;
    ps.s = detail::gather_rows(samples.s, in);
    ps.q = detail::gather_rows(samples.q, in);
    ps.dq = detail::gather_rows(samples.dq, in);
    ps.ddq = detail::gather_rows(samples.ddq, in);
    sub = project(ps);
  }
  const Eigen::Index r = sub.rows() + (rest ? 1 : 0);
  ConstraintRows out;
  out.resize(samples.size(), r);
  out.lp_solves = sub.lp_solves;
  out.lp_by_cause = sub.lp_by_cause;
  for (size_t i = 0; i < in.size(); ++i) {
    const Eigen::Index j = static_cast<Eigen::Index>(i);
    out.a.row(in[i]).head(sub.rows()) = sub.a.row(j);
    out.b.row(in[i]).head(sub.rows()) = sub.b.row(j);
    out.c.row(in[i]).head(sub.rows()) = sub.c.row(j);
  }
  for (Eigen::Index p : sub.inexact_points) out.inexact_points.push_back(in[static_cast<size_t>(p)]);
  const std::string prefix = options_.label.empty() ? std::string() : options_.label + ": ";
  for (Eigen::Index j = 0; j < sub.rows(); ++j) out.labels[static_cast<size_t>(j)] = prefix + sub.labels[static_cast<size_t>(j)];
  if (rest) {
    // ṡ² <= 0 at the switch (a·x + b·u <= c with a = 1, b = 0, c = 0): the no-impact rule.
    out.labels[static_cast<size_t>(r - 1)] = prefix + options_.rest_at_begin;
    for (Eigen::Index p = 0; p < samples.size(); ++p)
      if (at_active_begin(samples.s[p])) {
        out.a(p, r - 1) = 1.0;
        out.c(p, r - 1) = 0.0;
      }
  }
  return out;
}

ConstraintRows ContactConstraint::project(const PathSamples& samples) const {
  detail::PolytopeLp lp;
  lp_structure(reduced_, 0, lp);

  RobotWorkspace ws(*robot_);
  Eigen::MatrixXd a, b, c;  // eq. (12) at every grid point, row p
  robot_->path_torque_coefficients_batch(ws, samples.q, samples.dq, samples.ddq, a, b, c);
  detail::PolytopeProjector projector;  // one GLPK problem, warm-started from grid point to grid point
  std::vector<std::vector<detail::Line>> polys(static_cast<size_t>(samples.size()));
  std::vector<std::vector<std::string>> names(static_cast<size_t>(samples.size()));
  const std::vector<std::string> what = binding_names(reduced_);
  std::vector<char> empty_point(static_cast<size_t>(samples.size()), 0);
  ConstraintRows r;
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    lp_point(reduced_, samples.q.row(p).transpose(), a.row(p).transpose(), b.row(p).transpose(), c.row(p).transpose(), lp);
    detail::Projection pr = projector.project(lp, 1e-9, options_.max_lps, options_.projection_tolerance);
    if (pr.outcome == detail::Projection::Outcome::Failed ||
        (pr.outcome == detail::Projection::Outcome::Polygon && !pr.complete)) {
      // Once more from a cold start (a fresh basis), keeping the larger result.
      detail::Projection cold = detail::project_polytope(lp, 1e-9, options_.max_lps, options_.projection_tolerance);
      r.lp_solves += pr.lp_solves + cold.lp_solves;  // both ran, whichever is kept
      r.lp_by_cause += pr.by_cause;
      r.lp_by_cause.cold_retry += cold.lp_solves;
      if (cold.outcome != detail::Projection::Outcome::Failed &&
          (pr.outcome == detail::Projection::Outcome::Failed || cold.complete || cold.vertices.size() > pr.vertices.size()))
        pr = std::move(cold);
    } else {
      r.lp_solves += pr.lp_solves;
      r.lp_by_cause += pr.by_cause;
    }
    auto& out = polys[static_cast<size_t>(p)];
    if (pr.outcome != detail::Projection::Outcome::Polygon) {
      // Empty (confirmed in exact arithmetic), or no support point at all (the solver failed: reported
      // inexact, and solve() re-checks such a point before it calls it infeasible).
      empty_point[static_cast<size_t>(p)] = 1;
      if (pr.outcome == detail::Projection::Outcome::Failed) r.inexact_points.push_back(p);
    } else {
      if (!pr.complete) r.inexact_points.push_back(p);
      for (size_t e = 0; e < pr.halfplanes.size(); ++e) {
        const detail::Line& h = pr.halfplanes[e];
        // Edges on the stand-in bounds are not limits.
        // (the stand-in the projection used: options_.cap, or larger where the shadow lies beyond it).
        const double cap = pr.stand_in;
        const bool on_cap = (std::abs(h.b) < 1e-12 && h.a > 0 && std::abs(h.c - cap) <= 1e-6 * cap) ||
                            (std::abs(h.a) < 1e-12 && std::abs(std::abs(h.c) - cap) <= 1e-6 * cap);
        if (on_cap) continue;
        out.push_back(h);
        names[static_cast<size_t>(p)].push_back(binding_label(reduced_, what, pr.binding[e]));
      }
    }
  }
  // One column per (label, occurrence at a grid point): an edge is reported by what binds it (a torque
  // limit, a contact's friction or minimum normal force), which is what a user can act on; the edge's
  // position in the polygon means nothing from one grid point to the next.
  std::map<std::pair<std::string, int>, Eigen::Index> column;
  std::vector<std::string> labels;
  std::vector<std::vector<Eigen::Index>> at(static_cast<size_t>(samples.size()));
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    std::map<std::string, int> seen;
    for (const std::string& l : names[static_cast<size_t>(p)]) {
      const int occurrence = seen[l]++;
      auto it = column.find({l, occurrence});
      if (it == column.end()) {
        it = column.emplace(std::make_pair(l, occurrence), static_cast<Eigen::Index>(labels.size())).first;
        labels.push_back(occurrence == 0 ? l : l + " [polygon edge " + std::to_string(occurrence + 1) + " of this limit]");
      }
      at[static_cast<size_t>(p)].push_back(it->second);
    }
  }
  // The last row marks grid points where no contact forces balance the robot: 0 <= -1 there.
  const Eigen::Index marker = static_cast<Eigen::Index>(labels.size());
  r.resize(samples.size(), marker + 1);  // a, b, c and labels only: inexact_points and lp_solves stay
  for (size_t j = 0; j < labels.size(); ++j) r.labels[j] = labels[j];
  r.labels[static_cast<size_t>(marker)] = "contact forces cannot balance the robot";
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    const auto& out = polys[static_cast<size_t>(p)];
    for (size_t j = 0; j < out.size(); ++j) {
      const Eigen::Index col = at[static_cast<size_t>(p)][j];
      r.a(p, col) = out[j].a;
      r.b(p, col) = out[j].b;
      r.c(p, col) = out[j].c;
    }
    if (empty_point[static_cast<size_t>(p)]) r.c(p, marker) = -1.0;
  }
  return r;
}

ContactConstraint::PointCheck ContactConstraint::check_point(const PathSamples& samples, Eigen::Index k,
                                                             const Eigen::Matrix<double, Eigen::Dynamic, 3>& extra) const {
  const int n = robot_->nq();
  if (samples.dof() != n)
    detail::fail("path has " + std::to_string(samples.dof()) + " coordinates, robot '" + robot_->name() + "' has " +
                 std::to_string(n) + " joints");
  if (k < 0 || k >= samples.size())
    detail::fail("k = " + std::to_string(k) + " must be in [0, " + std::to_string(samples.size() - 1) + "]");
  const LpLayout all = full_layout(false);
  detail::PolytopeLp lp;
  const int e = static_cast<int>(extra.rows());
  lp_structure(all, e, lp);
  RobotWorkspace ws(*robot_);
  Eigen::VectorXd a(n), b(n), c(n);
  robot_->path_torque_coefficients(ws, samples.q.row(k).transpose(), samples.dq.row(k).transpose(),
                                   samples.ddq.row(k).transpose(), a, b, c);
  lp_point(all, samples.q.row(k).transpose(), a, b, c, lp);
  const Eigen::Index r0 = lp.A.rows() - e;
  for (int i = 0; i < e; ++i) {
    lp.A(r0 + i, 0) = extra(i, 0);
    lp.A(r0 + i, 1) = extra(i, 1);
    lp.row_hi[r0 + i] = extra(i, 2);
  }
  // Nothing bounds (x, u) here but what the rows say: no stand-in caps in a feasibility question.
  lp.col_hi[0] = lp.col_hi[1] = std::numeric_limits<double>::infinity();
  lp.col_lo[1] = -std::numeric_limits<double>::infinity();
  // The no-impact row of a phase (ṡ² <= 0 at its first point) is part of this constraint.
  if (!options_.rest_at_begin.empty() && at_active_begin(samples.s[k])) lp.col_hi[0] = 0.0;
  detail::PolytopeProjector solver;
  PointCheck out;
  out.feasible = solver.feasible(lp);
  const double rest[2] = {0.0, 0.0};
  out.rest_feasible = solver.feasible(lp, rest);
  return out;
}

namespace {

// The force-distribution LP (ContactForces' margin) from a projection polytope of lp_structure's layout
// at x = u = 0: columns x, u, then the cone weights λ; the first `torque_rows` rows are the torque rows,
// the rest minimum normal force rows Σ λ >= f_min (per point, per link). With λ = μ + δ 1 and μ >= 0,
// δ <= cap, maximising δ makes δ the smallest of every λ_ie and of every minimum row's excess: a minimum
// row becomes Σ λ - δ >= f_min (coefficient of δ: its weights' count minus one), a torque row keeps
// Σ λ (its coefficients' sum times δ). Columns: μ, then δ.
void margin_lp(const detail::PolytopeLp& polytope, int torque_rows, double cap, detail::PolytopeLp& lp) {
  const Eigen::Index rows = polytope.A.rows(), w = polytope.A.cols() - 2;
  lp.A.resize(rows, w + 1);
  lp.A.leftCols(w) = polytope.A.rightCols(w);
  lp.A.col(w) = polytope.A.rightCols(w).rowwise().sum();
  lp.A.col(w).tail(rows - torque_rows).array() -= 1.0;
  lp.row_lo = polytope.row_lo;
  lp.row_hi = polytope.row_hi;
  lp.col_lo = Eigen::VectorXd::Zero(w + 1);
  lp.col_hi = Eigen::VectorXd::Constant(w + 1, std::numeric_limits<double>::infinity());
  lp.col_lo[w] = -std::numeric_limits<double>::infinity();
  lp.col_hi[w] = cap;
}

}  // namespace

std::vector<ContactForces> ContactConstraint::force_distribution(const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd,
                                                                 const Eigen::MatrixXd& qdd) const {
  const int n = robot_->nq(), m = static_cast<int>(contacts_.size()), k = options_.cone_edges;
  const std::pair<const Eigen::MatrixXd*, const char*> args[3] = {{&q, "q"}, {&qd, "qd"}, {&qdd, "qdd"}};
  for (const auto& [arr, name] : args) {
    if (arr->cols() != n)
      detail::fail(std::string(name) + " has " + std::to_string(arr->cols()) + " columns, robot '" + robot_->name() +
                   "' has " + std::to_string(n) + " joints");
    if (arr->rows() != q.rows())
      detail::fail(std::string(name) + " has " + std::to_string(arr->rows()) + " rows, q has " + std::to_string(q.rows()));
    detail::require_finite(name, *arr);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  std::vector<ContactForces> out(static_cast<size_t>(q.rows()));
  // The projection's polytope (lp_structure, lp_point: the same torque rows, cones and minimum normal
  // force rows, per point and per link) at x = u = 0 with c = τ_id, as the margin LP of margin_lp.
  const LpLayout all = full_layout(true);
  detail::PolytopeLp polytope, lp;
  lp_structure(all, 0, polytope);
  RobotWorkspace ws(*robot_);
  std::vector<Eigen::Isometry3d> T;
  Eigen::MatrixXd J;
  Eigen::Matrix3Xd gen;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd tau(n), z;
  Eigen::VectorXd objective = Eigen::VectorXd::Zero(m * k + 1);
  objective[m * k] = 1.0;  // maximise δ
  detail::PolytopeProjector solver;  // one GLPK problem, warm-started from sample to sample
  for (Eigen::Index s = 0; s < q.rows(); ++s) {
    const Eigen::VectorXd qs = q.row(s).transpose();
    robot_->inverse_dynamics(ws, qs, qd.row(s).transpose(), qdd.row(s).transpose(), true, tau);
    // The shifted cone (cone_offset): lp_point moves w = offset_torques(q) into the torque rows' bounds
    // (τ_id - w is what the cones' generators carry) and lp_structure puts each minimum row at
    // min - offset, so tau stays τ_id here and the offsets are added to the forces below.
    lp_point(all, qs, zero, zero, tau, polytope);
    margin_lp(polytope, n, options_.cap, lp);
    const int st = solver.maximize(lp, objective, z);
    if (st == -2) throw Error("force distribution: the LP solver failed (GLPK error) at sample " + std::to_string(s));
    if (st < 0) throw Error("force distribution: the LP solver did not finish at sample " + std::to_string(s));
    ContactForces& f = out[static_cast<size_t>(s)];
    f.forces.resize(m, 3);
    if (st == 0) {
      f.feasible = false;
      f.margin = -inf;
      f.forces.setConstant(nan);
      f.torques = Eigen::VectorXd::Constant(n, nan);
      continue;
    }
    contact_jacobians(qs, T, J, gen);
    const double delta = z[m * k];
    f.feasible = true;
    f.margin = delta;
    f.torques = tau;
    for (int i = 0; i < m; ++i) {
      const Eigen::VectorXd lambda = z.segment(i * k, k).array() + delta;
      Eigen::Vector3d fi = gen.middleCols(i * k, k) * lambda;
      // The offset along the normal: the generators' mean is n (their tangents cancel over a full turn).
      if (options_.cone_offset > 0.0) fi += options_.cone_offset * gen.middleCols(i * k, k).rowwise().mean().normalized();
      f.forces.row(i) = fi.transpose();
      f.torques.noalias() -= J.middleRows(3 * i, 3).transpose() * fi;
    }
  }
  return out;
}

std::shared_ptr<const Constraint> ContactConstraint::relaxed(const std::string& family, double scale) const {
  // The stored limits already include torque_scale and torque_margin: the copy takes them as they are.
  ContactOptions o = options_;
  o.torque_scale = 1.0;
  o.torque_margin = 0.0;
  Eigen::VectorXd lo = tau_min_, hi = tau_max_;
  std::vector<Contact> contacts = contacts_;
  if (family == "torque") {
    for (Eigen::Index j = 0; j < lo.size(); ++j) {
      lo[j] = widen_lower(lo[j], scale);
      hi[j] = widen_upper(hi[j], scale);
    }
  } else if (family == "friction") {
    for (Contact& c : contacts) c.friction *= scale;
    o.min_normal_force /= scale;
    o.min_link_normal_force /= scale;
    o.cone_offset /= scale;
  } else {
    return nullptr;
  }
  return std::make_shared<ContactConstraint>(robot_, std::move(contacts), o, std::move(lo), std::move(hi));
}

bool ContactConstraint::can_absorb(const Constraint& other) const {
  const auto* torque = dynamic_cast<const TorqueLimits*>(&other);
  return torque && torque->robot() == robot_;
}

std::shared_ptr<const Constraint> ContactConstraint::absorb(const Constraint& other) const {
  const auto& torque = dynamic_cast<const TorqueLimits&>(other);
  return with_torque_limits(torque.tau_min(), torque.tau_max());
}

void ContactConstraint::report(Result& result, int& torque_rank) const {
  result.robot = robot_;
  result.contacts = shared_from_this();
  if (torque_rank <= 1) {
    result.tau_min = tau_min_;
    result.tau_max = tau_max_;
    torque_rank = 1;
  }
  if (std::isfinite(options_.active_begin) || std::isfinite(options_.active_end))
    result.contact_phases.push_back(shared_from_this());
}

}  // namespace pathpace
