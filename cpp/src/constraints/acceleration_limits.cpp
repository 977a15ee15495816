#include "pathpace/constraints/acceleration_limits.hpp"

#include <cmath>
#include <limits>

#include "base/validate.hpp"

namespace pathpace {

AccelerationLimits::AccelerationLimits(Eigen::VectorXd amin, Eigen::VectorXd amax, std::vector<std::string> joint_names)
    : amin_(std::move(amin)), amax_(std::move(amax)), joint_names_(std::move(joint_names)) {
  detail::require_size("amin", amin_.size(), amax_.size(), "one entry per joint, as amax");
  if (!joint_names_.empty())
    detail::require_size("joint_names", static_cast<Eigen::Index>(joint_names_.size()), amax_.size(), "one per joint, as amax");
  detail::require_not_nan("amin", amin_);
  detail::require_not_nan("amax", amax_);
  for (Eigen::Index j = 0; j < amax_.size(); ++j) {
    const std::string which = joint_names_.empty() ? "" : " (" + joint(j) + ")";
    if (amax_[j] == -std::numeric_limits<double>::infinity())
      detail::fail(detail::at("amax", j) + which + " = -inf must be > -inf");
    if (amin_[j] == std::numeric_limits<double>::infinity())
      detail::fail(detail::at("amin", j) + which + " = inf must be < inf");
    if (!(amin_[j] <= amax_[j]))
      detail::fail(detail::at("amin", j) + which + " = " + detail::fmt(amin_[j]) + " must be <= " + detail::at("amax", j) +
                   " = " + detail::fmt(amax_[j]));
  }
}

std::string AccelerationLimits::joint(Eigen::Index j) const {
  return joint_names_.empty() ? "joint " + std::to_string(j) : joint_names_[static_cast<size_t>(j)];
}

ConstraintRows AccelerationLimits::evaluate(const PathSamples& samples) const {
  const Eigen::Index n = amax_.size();
  if (samples.dof() != n)
    detail::fail("acceleration limits have " + std::to_string(n) + " entries, the path has " +
                 std::to_string(samples.dof()) + " coordinates");
  ConstraintRows rows;
  rows.allocate(samples.size(), 2 * n);  // every entry is written below
  // From finite samples and limits checked on construction: a = ±p'' or 0, b = ±p' or 0, c a limit or +inf.
  rows.valid_by_construction = true;
  for (Eigen::Index j = 0; j < n; ++j) {
    rows.labels[static_cast<size_t>(2 * j)] = "acceleration " + joint(j) + " upper";
    rows.labels[static_cast<size_t>(2 * j + 1)] = "acceleration " + joint(j) + " lower";
  }
  const double inf = std::numeric_limits<double>::infinity();
  // eq. (14): q̈_j = p''_j ṡ² + p'_j s̈; an infinite limit leaves its row inactive (c = +inf, a = b = 0).
  // Per row a factor (1, -1 or 0) and a constant c, so that the loop over grid points has no branch and
  // writes each joint's row pair with one paired store (this runs on every problem's set-up).
  const Eigen::Index m = samples.size(), r = 2 * n;
  for (Eigen::Index j = 0; j < n; ++j) {
    const bool up = std::isfinite(amax_[j]), lo = std::isfinite(amin_[j]);
    const double su = up ? 1.0 : 0.0, sl = lo ? -1.0 : 0.0, cu = up ? amax_[j] : inf, cl = lo ? -amin_[j] : inf;
    const double* pp = samples.ddq.col(j).data();
    const double* p = samples.dq.col(j).data();
    double* pa = rows.a.data() + 2 * j;
    double* pb = rows.b.data() + 2 * j;
    double* pc = rows.c.data() + 2 * j;
    for (Eigen::Index k = 0; k < m; ++k) {
      pa[k * r] = su * pp[k];
      pa[k * r + 1] = sl * pp[k];
      pb[k * r] = su * p[k];
      pb[k * r + 1] = sl * p[k];
      pc[k * r] = cu;
      pc[k * r + 1] = cl;
    }
  }
  return rows;
}

std::shared_ptr<const Constraint> AccelerationLimits::relaxed(double scale) const {
  Eigen::VectorXd lo = amin_, hi = amax_;
  for (Eigen::Index j = 0; j < lo.size(); ++j) {
    lo[j] = widen_lower(lo[j], scale);
    hi[j] = widen_upper(hi[j], scale);
  }
  return std::make_shared<AccelerationLimits>(lo, hi, joint_names_);
}

std::shared_ptr<const Constraint> AccelerationLimits::with_joint_names(const std::vector<std::string>& names) const {
  return joint_names_.empty() ? std::make_shared<AccelerationLimits>(amin_, amax_, names) : nullptr;
}

}  // namespace pathpace
