// TimeScalingProblem::set_boundary_velocities: boundary conditions given as joint velocities.
#include <algorithm>
#include <cmath>
#include <string>

#include "base/validate.hpp"
#include "pathpace/time_scaling_problem.hpp"

namespace pathpace {

namespace {

// ṡ with q̇ = p' ṡ (eq. 10) in the least-squares sense, after checking that q̇ lies on the ray of p'.
// `dp_scale` is the largest |p'| on the grid: a tangent below 1e-9 of it is a rest point of the path
// (e.g. a clamped spline's end, where p' is 0 up to rounding) and admits only q̇ = 0.
double speed_from_velocity(const std::string& name, const Eigen::VectorXd& qd, const Eigen::VectorXd& dp, double s,
                           double dp_scale, double tolerance) {
  detail::require_size(name, qd.size(), dp.size(), "one per path coordinate");
  detail::require_finite(name, qd);
  const double qd_norm = qd.stableNorm(), dp_norm2 = dp.squaredNorm();
  if (qd_norm == 0.0) return 0.0;
  if (!(std::sqrt(dp_norm2) > 1e-9 * dp_scale))
    detail::fail(name + " = " + detail::fmt(qd_norm) + " (norm) must be 0: the path does not move at s = " + detail::fmt(s) +
                 " (p'(s) = 0), so no speed along it gives a joint velocity");
  const double sdot = dp.dot(qd) / dp_norm2;
  if (!std::isfinite(sdot))
    detail::fail(name + " = " + detail::fmt(qd_norm) + " (norm) is too large: the speed along the path it gives at s = " +
                 detail::fmt(s) + " overflows (" + detail::fmt(sdot) + ")");
  // The residual q̇ - p' ṡ is what no speed along the path can give: name its largest entry.
  const Eigen::VectorXd residual = qd - dp * std::max(sdot, 0.0);
  Eigen::Index j = 0;
  const double worst = residual.cwiseAbs().maxCoeff(&j);
  if (sdot < 0.0 || worst > tolerance * qd_norm)
    detail::fail(detail::at(name, j) + " = " + detail::fmt(qd[j]) + " must be " + detail::fmt(dp[j] * std::max(sdot, 0.0)) +
                 ": " + name + " must be a non-negative multiple of the path tangent p'(s = " + detail::fmt(s) +
                 ") (best multiple " + detail::fmt(sdot) + ", relative mismatch " + detail::fmt(worst / qd_norm) + ")");
  return sdot;
}

}  // namespace

void TimeScalingProblem::set_boundary_velocities(const Eigen::VectorXd& qd_begin, const Eigen::VectorXd& qd_end,
                                                 double tolerance) {
  const Use use(*this, Use::Write, "set_boundary_velocities");
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    detail::fail("tolerance = " + detail::fmt(tolerance) + " must be >= 0 and finite");
  const PathSamples& ps = samples();
  const Eigen::Index last = ps.size() - 1;
  const double scale = ps.dq.rowwise().norm().maxCoeff();
  const double b = speed_from_velocity("qd_begin", qd_begin, ps.dq.row(0).transpose(), ps.s[0], scale, tolerance);
  const double e = speed_from_velocity("qd_end", qd_end, ps.dq.row(last).transpose(), ps.s[last], scale, tolerance);
  set_boundary_speeds(b, e);
}

}  // namespace pathpace
