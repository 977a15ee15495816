#include "pathpace/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/gather_rows.hpp"
#include "base/jerk_interval.hpp"
#include "solve/jerk_scp.hpp"
#include "base/validate.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/contact_phase.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/robot_workspace.hpp"
#include "paths/third_derivatives.hpp"

namespace pathpace {

Trajectory::Trajectory(std::shared_ptr<const Path> path, Eigen::VectorXd s, Eigen::VectorXd sdot)
    : path_(std::move(path)), s_(std::move(s)), sdot_(std::move(sdot)) {
  if (!path_) detail::fail("path must not be None");
  if (s_.size() < 2) detail::fail("grid has " + std::to_string(s_.size()) + " points, expected at least 2");
  detail::require_size("sdot", sdot_.size(), s_.size(), "one speed per grid point");
  detail::require_finite("grid", s_);
  detail::require_finite("sdot", sdot_);
  detail::require_increasing("grid", s_);
  const Eigen::Index n = s_.size() - 1;
  times_.resize(n + 1);
  sddot_.resize(n);
  times_[0] = 0.0;
  for (Eigen::Index k = 0; k <= n; ++k)
    if (sdot_[k] < 0.0) detail::fail(detail::at("sdot", k) + " = " + detail::fmt(sdot_[k]) + " must be >= 0");
  for (Eigen::Index k = 0; k < n; ++k) {
    const double w = sdot_[k] + sdot_[k + 1];
    if (!(w > 0.0))
      detail::fail("sdot[" + std::to_string(k) + "] + sdot[" + std::to_string(k + 1) +
                   "] = 0 must be > 0 (the interval would take forever)");
    const double ds = s_[k + 1] - s_[k];
    times_[k + 1] = times_[k] + 2.0 * ds / w;                                        // eq. (25)
    sddot_[k] = (sdot_[k + 1] * sdot_[k + 1] - sdot_[k] * sdot_[k]) / (2.0 * ds);  // constant on the interval
    // Speeds so large that ṡ² or s̈ overflows, or that an interval takes no time at all, give a
    // trajectory whose t -> s map is not invertible: refuse them rather than return infinities.
    if (!std::isfinite(sddot_[k]) || !(times_[k + 1] > times_[k])) {
      const Eigen::Index j = sdot_[k] >= sdot_[k + 1] ? k : k + 1;
      detail::fail(detail::at("sdot", j) + " = " + detail::fmt(sdot_[j]) + " is too large for interval " +
                   std::to_string(k) + " of length " + detail::fmt(ds) + " (s̈ = " + detail::fmt(sddot_[k]) +
                   ", time " + detail::fmt(times_[k + 1] - times_[k]) + ")");
    }
  }
}

Trajectory::Trajectory(std::shared_ptr<const Path> path, Eigen::VectorXd s, Eigen::VectorXd sdot,
                       Eigen::VectorXd sddot_points)
    : Trajectory(path, s, sdot) {
  const Eigen::Index n = s_.size() - 1;
  detail::require_size("sddot_points", sddot_points.size(), n + 1, "one per grid point");
  detail::require_finite("sddot_points", sddot_points);
  if (n < 2) detail::fail("a jerk-limited timing needs at least 2 intervals, the grid has " + std::to_string(n));
  if (sdot_[0] == 0 && sddot_points[0] != 0)
    detail::fail("sddot_points[0] = " + detail::fmt(sddot_points[0]) + " must be 0 at a start from rest");
  if (sdot_[n] == 0 && sddot_points[n] != 0)
    detail::fail(detail::at("sddot_points", n) + " = " + detail::fmt(sddot_points[n]) + " must be 0 at a stop at rest");
  const Eigen::VectorXd theta = sdot_.array().square();
  for (Eigen::Index k = 0; k < n; ++k) {
    const double ds = s_[k + 1] - s_[k];
    double expect;
    if (k == 0 && sdot_[0] == 0) expect = 1.5 * ds * sddot_points[1];
    else if (k == n - 1 && sdot_[n] == 0) expect = theta[k] + 1.5 * ds * sddot_points[k];  // θ_N = 0
    else expect = theta[k] + ds * (sddot_points[k] + sddot_points[k + 1]);
    const double target = k == n - 1 && sdot_[n] == 0 ? 0.0 : theta[k + 1];
    if (std::abs(expect - target) > 1e-9 * std::max(theta[k], theta[k + 1]))
      detail::fail("sdot and sddot_points disagree on interval " + std::to_string(k) + ": sdot[" + std::to_string(k + 1) +
                   "]^2 = " + detail::fmt(theta[k + 1]) + ", the interval's s̈ gives " + detail::fmt(expect));
  }
  sddot_points_ = std::move(sddot_points);
  const Eigen::VectorXd dt = detail::jerk_interval_times(s_, theta, sddot_points_);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!(dt[k] > 0) || !std::isfinite(dt[k]))
      detail::fail("interval " + std::to_string(k) + " of the jerk-limited timing takes " + detail::fmt(dt[k]) +
                   " s (its speed reaches 0 inside)");
    times_[k + 1] = times_[k] + dt[k];
    sddot_[k] = (sdot_[k + 1] - sdot_[k]) / dt[k];  // the interval's mean s̈
  }
}

void Trajectory::jerk_motion(Eigen::Index k, double t, double& s, double& sd, double& sdd, double& sddd) const {
  const Eigen::Index n = s_.size() - 1;
  const double ds = s_[k + 1] - s_[k];
  if (k == 0 && sdot_[0] == 0) {  // s = j τ³/6 from rest
    const double j = detail::rest_interval_jerk(sdot_[1] * sdot_[1], ds), tau = t - times_[0];
    s = std::min(s_[0] + j * tau * tau * tau / 6, s_[1]), sd = 0.5 * j * tau * tau, sdd = j * tau, sddd = j;
    return;
  }
  if (k == n - 1 && sdot_[n] == 0) {  // mirrored: s_N - s = j τ'³/6 with τ' = T - t
    const double j = detail::rest_interval_jerk(sdot_[n - 1] * sdot_[n - 1], ds), tau = std::max(times_[n] - t, 0.0);
    s = std::max(s_[n] - j * tau * tau * tau / 6, s_[n - 1]), sd = 0.5 * j * tau * tau, sdd = -j * tau, sddd = j;
    return;
  }
  const double c = (sddot_points_[k + 1] - sddot_points_[k]) / ds;
  const detail::IntervalMotion m = detail::linear_b_motion(sdot_[k], sddot_points_[k], c, t - times_[k]);
  s = std::min(s_[k] + m.sigma, s_[k + 1]), sd = std::max(m.sdot, 0.0), sdd = m.sddot, sddd = c * sd;
}

Eigen::MatrixXd Trajectory::qddd(const Eigen::Ref<const Eigen::VectorXd>& t) const {
  Eigen::VectorXd s, sd, sdd, sddd;
  evaluate_s(t, s, sd, sdd, &sddd);
  Eigen::MatrixXd q, dq, ddq, l, r;
  path_->evaluate(s, q, dq, ddq);
  detail::third_derivatives(*path_, s, l, r);
  const Eigen::ArrayXd sd3 = sd.array().cube(), sdsdd = sd.array() * sdd.array();
  return (dq.array().colwise() * sddd.array() + (3 * ddq.array()).colwise() * sdsdd + r.array().colwise() * sd3).matrix();
}

Eigen::Index Trajectory::interval(double t) const {
  const Eigen::Index n = s_.size() - 1;
  const auto it = std::upper_bound(times_.data(), times_.data() + n + 1, t);
  Eigen::Index k = static_cast<Eigen::Index>(it - times_.data()) - 1;
  return std::clamp<Eigen::Index>(k, 0, n - 1);
}

void Trajectory::evaluate_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::VectorXd& sd,
                            Eigen::VectorXd& sdd) const {
  evaluate_s(t, s, sd, sdd, nullptr);
}

void Trajectory::evaluate_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::VectorXd& sd,
                            Eigen::VectorXd& sdd, Eigen::VectorXd* sddd) const {
  s.resize(t.size());
  sd.resize(t.size());
  sdd.resize(t.size());
  if (sddd) sddd->setZero(t.size());  // s̈ constant on each interval unless jerk-limited
  const double T = duration();
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    if (std::isnan(t[i])) detail::fail(detail::at("t", i) + " = nan must be a number");
    const double ti = std::clamp(t[i], 0.0, T);
    const Eigen::Index k = interval(ti);
    if (sddot_points_.size()) {
      double j;
      jerk_motion(k, ti, s[i], sd[i], sdd[i], j);
      if (sddd) (*sddd)[i] = j;
      continue;
    }
    const double tau = ti - times_[k];
    // eq. (24): s(t) = s̈_k τ²/2 + ṡ_k τ + s_k on interval k
    s[i] = std::min(s_[k] + sdot_[k] * tau + 0.5 * sddot_[k] * tau * tau, s_[k + 1]);
    sd[i] = std::max(sdot_[k] + sddot_[k] * tau, 0.0);
    sdd[i] = sddot_[k];
  }
}

void Trajectory::evaluate(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::MatrixXd& q, Eigen::MatrixXd& qd,
                          Eigen::MatrixXd& qdd) const {
  Eigen::VectorXd s;
  evaluate_with_s(t, s, q, qd, qdd);
}

void Trajectory::evaluate_with_s(const Eigen::Ref<const Eigen::VectorXd>& t, Eigen::VectorXd& s, Eigen::MatrixXd& q,
                                 Eigen::MatrixXd& qd, Eigen::MatrixXd& qdd) const {
  Eigen::VectorXd sd, sdd;
  evaluate_s(t, s, sd, sdd);
  Eigen::MatrixXd dq, ddq;
  path_->evaluate(s, q, dq, ddq);
  qd = dq.array().colwise() * sd.array();                                             // eq. (10)
  qdd = ddq.array().colwise() * (sd.array() * sd.array()) + dq.array().colwise() * sdd.array();  // eq. (11)
}

Eigen::MatrixXd Trajectory::q(const Eigen::Ref<const Eigen::VectorXd>& t) const {
  Eigen::MatrixXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  return q;
}

Eigen::MatrixXd Trajectory::qd(const Eigen::Ref<const Eigen::VectorXd>& t) const {
  Eigen::MatrixXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  return qd;
}

Eigen::MatrixXd Trajectory::qdd(const Eigen::Ref<const Eigen::VectorXd>& t) const {
  Eigen::MatrixXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  return qdd;
}

Eigen::MatrixXd Trajectory::torques(const Eigen::Ref<const Eigen::VectorXd>& t, const RobotModel& robot) const {
  if (robot.nq() != path_->dof())
    detail::fail("robot '" + robot.name() + "' has " + std::to_string(robot.nq()) + " joints, the path has " +
                 std::to_string(path_->dof()) + " coordinates");
  Eigen::MatrixXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  RobotWorkspace ws(robot);
  Eigen::MatrixXd tau(t.size(), robot.nq());
  Eigen::VectorXd out(robot.nq());
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    robot.inverse_dynamics(ws, q.row(i).transpose(), qd.row(i).transpose(), qdd.row(i).transpose(), true, out);
    tau.row(i) = out.transpose();
  }
  return tau;
}

Eigen::VectorXi Trajectory::contact_phase(const Eigen::Ref<const Eigen::VectorXd>& t) const {
  if (contact_phases_.empty()) return Eigen::VectorXi::Constant(t.size(), -1);
  Eigen::VectorXd s, sd, sdd;
  evaluate_s(t, s, sd, sdd);
  return contact_phase_of_s(contact_phases_, s);
}

std::vector<ContactForces> Trajectory::contact_forces(const Eigen::Ref<const Eigen::VectorXd>& t,
                                                      Eigen::VectorXi* phase_out, ForceDistribution distribution) const {
  if (!contacts_ && contact_phases_.empty())
    throw Error("no contact constraint shaped this trajectory: use ContactConstraint.force_distribution");
  Eigen::VectorXd s;
  Eigen::MatrixXd q, qd, qdd;
  evaluate_with_s(t, s, q, qd, qdd);
  if (contact_phases_.empty()) {
    if (phase_out) *phase_out = Eigen::VectorXi::Constant(t.size(), -1);
    return contacts_->force_distribution(q, qd, qdd, distribution);
  }
  // One force-distribution batch per phase, each with that phase's contacts.
  Eigen::VectorXi phase = contact_phase_of_s(contact_phases_, s);
  std::vector<ContactForces> out(static_cast<size_t>(t.size()));
  for (size_t p = 0; p < contact_phases_.size(); ++p) {
    std::vector<Eigen::Index> idx;
    for (Eigen::Index i = 0; i < t.size(); ++i)
      if (phase[i] == static_cast<int>(p)) idx.push_back(i);
    if (idx.empty()) continue;
    std::vector<ContactForces> f = contact_phases_[p]->force_distribution(
        detail::gather_rows(q, idx), detail::gather_rows(qd, idx), detail::gather_rows(qdd, idx), distribution);
    for (size_t j = 0; j < idx.size(); ++j) out[static_cast<size_t>(idx[j])] = std::move(f[j]);
  }
  if (phase_out) *phase_out = std::move(phase);
  return out;
}

CubicSplinePath Trajectory::time_spline() const {
  const Eigen::Index last = s_.size() - 1;
  Eigen::MatrixXd q, dq, ddq;
  path_->evaluate(s_, q, dq, ddq);
  // Clamped ends: the exact joint velocities p'(s) ṡ (eq. 10) at t = 0 and t = T.
  const Eigen::VectorXd v0 = dq.row(0).transpose() * sdot_[0], v1 = dq.row(last).transpose() * sdot_[last];
  return CubicSplinePath(q, times_, SplineBoundary::Clamped, v0, v1);
}

Eigen::VectorXd Trajectory::sample_times(double dt) const {
  if (!(dt > 0.0) || !std::isfinite(dt)) detail::fail("dt = " + detail::fmt(dt) + " must be > 0 and finite");
  const double T = duration();
  const double count = std::floor(T / dt);
  if (count > 1e8) detail::fail("dt = " + detail::fmt(dt) + " gives more than 1e8 samples for T = " + detail::fmt(T));
  const Eigen::Index m = static_cast<Eigen::Index>(count) + 1;
  const bool append = T - static_cast<double>(m - 1) * dt > 1e-12 * std::max(1.0, T);
  Eigen::VectorXd t(m + (append ? 1 : 0));
  for (Eigen::Index i = 0; i < m; ++i) t[i] = static_cast<double>(i) * dt;
  if (append) t[m] = T;
  return t;
}

Trajectory::Samples Trajectory::sample_at(Eigen::VectorXd t, bool spline) const {
  Samples out;
  if (spline)
    time_spline().evaluate(t, out.q, out.qd, out.qdd);
  else
    evaluate(t, out.q, out.qd, out.qdd);
  out.t = std::move(t);
  return out;
}

Trajectory::Samples Trajectory::sample(double dt, double max_memory, bool spline) const {
  if (!(max_memory > 0.0)) detail::fail("max_memory = " + std::to_string(max_memory) + " must be > 0 (bytes)");
  if (dt > 0.0 && std::isfinite(dt)) {
    // t, q, qd and qdd as doubles, plus the path's own p, p', p'' while evaluating.
    const double samples = std::floor(duration() / dt) + 2.0;
    const double bytes = samples * (1.0 + 6.0 * path_->dof()) * 8.0;
    if (bytes > max_memory) {
      char msg[320];
      std::snprintf(msg, sizeof msg,
                    "dt = %g gives %.3g samples of a %d-coordinate trajectory of duration %g: about %.3g GB, more "
                    "than max_memory = %.3g GB; use a larger dt or raise max_memory",
                    dt, samples, path_->dof(), duration(), bytes / 1e9, max_memory / 1e9);
      detail::fail(msg);
    }
  }
  return sample_at(sample_times(dt), spline);
}

}  // namespace pathpace
