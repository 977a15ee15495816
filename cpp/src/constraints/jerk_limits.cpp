#include "pathpace/constraints/jerk_limits.hpp"

#include <algorithm>
#include <cmath>

#include "base/validate.hpp"

namespace pathpace {

JerkLimits::JerkLimits(Eigen::VectorXd jmin, Eigen::VectorXd jmax, std::vector<std::string> joint_names)
    : jmin_(std::move(jmin)), jmax_(std::move(jmax)), joint_names_(std::move(joint_names)) {
  detail::require_size("jmin", jmin_.size(), jmax_.size(), "one entry per joint, as jmax");
  if (jmax_.size() == 0) detail::fail("jmax has 0 entries, expected one per joint");
  if (!joint_names_.empty())
    detail::require_size("joint_names", static_cast<Eigen::Index>(joint_names_.size()), jmax_.size(), "one per joint, as jmax");
  detail::require_not_nan("jmin", jmin_);
  detail::require_not_nan("jmax", jmax_);
  for (Eigen::Index j = 0; j < jmax_.size(); ++j) {
    const std::string which = joint_names_.empty() ? "" : " (" + joint_names_[static_cast<size_t>(j)] + ")";
    // A jerk bound of 0 on one side would forbid every start from rest: the limits must straddle 0.
    if (!(jmax_[j] > 0.0)) detail::fail(detail::at("jmax", j) + which + " = " + detail::fmt(jmax_[j]) + " must be > 0");
    if (!(jmin_[j] < 0.0)) detail::fail(detail::at("jmin", j) + which + " = " + detail::fmt(jmin_[j]) + " must be < 0");
  }
}

}  // namespace pathpace
