#include "pathpace/constraints/contact_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lp/projection.hpp"
#include "base/validate.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/result.hpp"
#include "pathpace/errors.hpp"
#include "constraints/contact_tangents.hpp"

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
  // A stretch of s that holds at least one s (±inf: unbounded on that side).
  if (std::isnan(options_.active_begin) || options_.active_begin == std::numeric_limits<double>::infinity())
    detail::fail("active_begin = " + detail::fmt(options_.active_begin) + " must be a number < inf");
  if (std::isnan(options_.active_end) || options_.active_end == -std::numeric_limits<double>::infinity())
    detail::fail("active_end = " + detail::fmt(options_.active_end) + " must be a number > -inf");
  if (!(options_.active_begin <= options_.active_end))
    detail::fail("active_begin = " + detail::fmt(options_.active_begin) + " must be <= active_end = " +
                 detail::fmt(options_.active_end));
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
  phys_tau_min_ = tau_min;
  phys_tau_max_ = tau_max;
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
    std::vector<int> moving = robot_->moving_joints(body_.back()), other_moving = robot_->moving_joints(other);
    moving.insert(moving.end(), other_moving.begin(), other_moving.end());
    std::sort(moving.begin(), moving.end());
    moving.erase(std::unique(moving.begin(), moving.end()), moving.end());
    moving_.push_back(std::move(moving));
    // Cone generators g_e = n + μ' (cos φ_e t1 + sin φ_e t2), inscribed in the cone of μ' = μ (1 -
    // friction_margin) (sec. V.D), in the normal's own frame (the world, or other_link).
    const Eigen::Vector3d& nrm = c.normal;
    Eigen::Vector3d t1, t2;
    detail::contact_tangents(nrm, t1, t2);
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
  for (size_t i = 0; i < contacts_.size(); ++i) {
    const int body = body_[i];
    if (other_body_[i] >= 0) {
      offset_moving_.push_back(static_cast<int>(i));
    } else if (body >= 0) {  // (both ends fixed: no torque)
      auto g = std::find_if(offset_groups_.begin(), offset_groups_.end(),
                            [&](const OffsetGroup& x) { return x.body == body && x.normal == contacts_[i].normal; });
      if (g == offset_groups_.end()) offset_groups_.push_back({body, contacts_[i].normal, point_in_body_[i], 1.0});
      else g->sum += point_in_body_[i], g->count += 1.0;
    }
  }
  reduce_contacts();
}

std::shared_ptr<ContactConstraint> ContactConstraint::with_torque_limits(const Eigen::VectorXd& lo,
                                                                         const Eigen::VectorXd& hi) const {
  const Eigen::Index n = robot_->nq();
  detail::require_size("tau_min", lo.size(), n, "one per joint");
  detail::require_size("tau_max", hi.size(), n, "one per joint");
  auto out = std::make_shared<ContactConstraint>(*this);
  out->tau_min_ = tau_min_.cwiseMax(lo);
  out->tau_max_ = tau_max_.cwiseMin(hi);
  out->phys_tau_min_ = phys_tau_min_.cwiseMax(lo);
  out->phys_tau_max_ = phys_tau_max_.cwiseMin(hi);
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(out->tau_min_[j] <= out->tau_max_[j]))
      detail::fail("torque limits of joint " + std::to_string(j) + " ('" + robot_->joint_names()[static_cast<size_t>(j)] +
                   "'): the contacts' [" + detail::fmt(tau_min_[j]) + ", " + detail::fmt(tau_max_[j]) +
                   "] and the torque limits' [" + detail::fmt(lo[j]) + ", " + detail::fmt(hi[j]) + "] do not intersect");
  return out;
}

std::shared_ptr<ContactConstraint> ContactConstraint::with_physical_torque_limits(const Eigen::VectorXd& lo,
                                                                                  const Eigen::VectorXd& hi) const {
  const Eigen::Index n = robot_->nq();
  detail::require_size("physical_tau_min", lo.size(), n, "one per joint");
  detail::require_size("physical_tau_max", hi.size(), n, "one per joint");
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(lo[j] <= hi[j]))
      detail::fail("physical_tau_min[" + std::to_string(j) + "] = " + detail::fmt(lo[j]) + " must be <= physical_tau_max[" +
                   std::to_string(j) + "] = " + detail::fmt(hi[j]));
  auto out = std::make_shared<ContactConstraint>(*this);
  out->phys_tau_min_ = lo;
  out->phys_tau_max_ = hi;
  return out;
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
