#include "pathpace/constraints/velocity_limits.hpp"

#include <cmath>
#include <limits>

#include "base/validate.hpp"

namespace pathpace {

VelocityLimits::VelocityLimits(Eigen::VectorXd vmin, Eigen::VectorXd vmax, std::vector<std::string> joint_names)
    : vmin_(std::move(vmin)), vmax_(std::move(vmax)), joint_names_(std::move(joint_names)) {
  detail::require_size("vmin", vmin_.size(), vmax_.size(), "one entry per joint, as vmax");
  if (!joint_names_.empty())
    detail::require_size("joint_names", static_cast<Eigen::Index>(joint_names_.size()), vmax_.size(), "one per joint, as vmax");
  detail::require_not_nan("vmin", vmin_);
  detail::require_not_nan("vmax", vmax_);
  for (Eigen::Index j = 0; j < vmax_.size(); ++j) {
    // ṡ = 0 (rest at the ends) must be admissible, so each interval has to contain 0.
    const std::string which = joint_names_.empty() ? "" : " (" + joint(j) + ")";
    if (!(vmax_[j] >= 0.0)) detail::fail(detail::at("vmax", j) + which + " = " + detail::fmt(vmax_[j]) + " must be >= 0");
    if (!(vmin_[j] <= 0.0)) detail::fail(detail::at("vmin", j) + which + " = " + detail::fmt(vmin_[j]) + " must be <= 0");
  }
}

std::string VelocityLimits::joint(Eigen::Index j) const {
  return joint_names_.empty() ? "joint " + std::to_string(j) : joint_names_[static_cast<size_t>(j)];
}

ConstraintRows VelocityLimits::evaluate(const PathSamples& samples) const {
  const Eigen::Index n = vmax_.size();
  if (samples.dof() != n)
    detail::fail("velocity limits have " + std::to_string(n) + " entries, the path has " +
                 std::to_string(samples.dof()) + " coordinates");
  ConstraintRows rows;
  const Eigen::Index m = samples.size();
  rows.allocate(m, n);
  rows.b.setZero();
  // From finite samples and limits checked on construction: a = 0 or 1, b = 0, c = (v / p')², which can
  // only overflow to +inf (an inactive row).
  rows.valid_by_construction = true;
  for (Eigen::Index j = 0; j < n; ++j) rows.labels[static_cast<size_t>(j)] = "velocity " + joint(j);
  const double inf = std::numeric_limits<double>::infinity();
  // Branch-free (selects, one division per entry), so that the compiler vectorises the joint's column:
  // this runs at every grid point of every solve. The row-major outputs are written with stride n.
  double* pa = rows.a.data();
  double* pc = rows.c.data();
  for (Eigen::Index j = 0; j < n; ++j) {
    const double* d = samples.dq.col(j).data();
    const double hi = vmax_[j], lo = vmin_[j];
    for (Eigen::Index k = 0; k < m; ++k) {
      const double v = d[k] > 0.0 ? hi : lo;
      const double r = v / d[k];
      // p'_j = 0: the joint does not move here, no bound (eq. 16 skips it); an infinite limit: none either.
      const bool active = d[k] != 0.0 && std::isfinite(v);
      pa[k * n + j] = active ? 1.0 : 0.0;
      pc[k * n + j] = active ? r * r : inf;
    }
  }
  return rows;
}

std::shared_ptr<const Constraint> VelocityLimits::relaxed(double scale) const {
  return std::make_shared<VelocityLimits>(vmin_ * scale, vmax_ * scale, joint_names_);
}

std::shared_ptr<const Constraint> VelocityLimits::with_joint_names(const std::vector<std::string>& names) const {
  return joint_names_.empty() ? std::make_shared<VelocityLimits>(vmin_, vmax_, names) : nullptr;
}

}  // namespace pathpace
