#include "pathpace/constraints/second_order_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/validate.hpp"

namespace pathpace {

namespace {

using detail::fail;
using detail::fmt;

std::string shape(Eigen::Index r, Eigen::Index c) { return "(" + std::to_string(r) + ", " + std::to_string(c) + ")"; }

// Which of eq. 12's three evaluations row `row` of W (3m rows) is.
const char* evaluation(Eigen::Index row, Eigen::Index m) {
  if (row < m) return "c = id(p, 0, 0)";
  return row < 2 * m ? "id(p, 0, p')" : "id(p, p', p'')";
}

std::string at_sample(const PathSamples& samples, Eigen::Index i) {
  return "at grid point " + std::to_string(i) + " (s = " + fmt(samples.s[i]) + ")";
}

// g may hold +inf (an absent limit), never NaN or -inf (a row no (x, u) satisfies is a modelling error).
bool bad_limit(double v) { return std::isnan(v) || v == -std::numeric_limits<double>::infinity(); }

void check_constant(const std::string& who, const SecondOrderFunctions& f) {
  if (!f.inverse_dynamics) fail(who + ": inverse_dynamics must be given");
  if (!f.F) {
    if (f.F_constant.rows() < 1 || f.F_constant.cols() < 1)
      fail(who + ": F has shape " + shape(f.F_constant.rows(), f.F_constant.cols()) +
           ", expected (r, nw) with r >= 1 rows and nw >= 1 (the size of w)");
    detail::require_finite(who + ": F", f.F_constant);
  }
  if (!f.g) {
    if (!f.F && f.g_constant.size() != f.F_constant.rows())
      fail(who + ": g has size " + std::to_string(f.g_constant.size()) + ", expected " +
           std::to_string(f.F_constant.rows()) + " (one per row of F)");
    for (Eigen::Index j = 0; j < f.g_constant.size(); ++j)
      if (bad_limit(f.g_constant[j]))
        fail(who + ": " + detail::at("g", j) + " = " + fmt(f.g_constant[j]) + " must be a number or +inf");
  }
}

// W = id([p; p; p], [0; 0; p'], [0; p'; p'']): eq. 12's three evaluations per grid point in one call.
Eigen::MatrixXd batched_inverse_dynamics(const std::string& who, const SecondOrderFunctions& f,
                                         const PathSamples& samples) {
  const Eigen::Index m = samples.size(), n = samples.dof();
  Eigen::MatrixXd q(3 * m, n), qd = Eigen::MatrixXd::Zero(3 * m, n), qdd = Eigen::MatrixXd::Zero(3 * m, n);
  q << samples.q, samples.q, samples.q;
  qd.bottomRows(m) = samples.dq;
  qdd.middleRows(m, m) = samples.dq;
  qdd.bottomRows(m) = samples.ddq;
  Eigen::MatrixXd w = f.inverse_dynamics(q, qd, qdd);
  if (w.rows() != 3 * m || w.cols() < 1)
    fail(who + ": inverse_dynamics(q, qd, qdd) returned shape " + shape(w.rows(), w.cols()) + ", expected (" +
         std::to_string(3 * m) + ", nw): one row per row of q (3 per grid point, eq. 12), nw >= 1");
  for (Eigen::Index k = 0; k < w.rows(); ++k)
    for (Eigen::Index j = 0; j < w.cols(); ++j)
      if (!std::isfinite(w(k, j)))
        fail(who + ": inverse_dynamics returned w[" + std::to_string(j) + "] = " + fmt(w(k, j)) + " " +
             at_sample(samples, k % m) + ", in " + evaluation(k, m) + " (row " + std::to_string(k) +
             "), expected finite");
  return w;
}

Eigen::MatrixXd called_F(const std::string& who, const SecondOrderFunctions& f, const PathSamples& samples,
                         Eigen::Index nw) {
  const Eigen::Index m = samples.size();
  Eigen::MatrixXd F = f.F(samples.q);
  if (F.rows() < m || F.rows() % m != 0 || F.cols() != nw)
    fail(who + ": F(q) returned shape " + shape(F.rows(), F.cols()) + ", expected (" + std::to_string(m) +
         "·r, " + std::to_string(nw) + "): the " + std::to_string(m) +
         " matrices F(q_i) (r, nw) stacked, nw = the size of w from inverse_dynamics");
  const Eigen::Index r = F.rows() / m;
  for (Eigen::Index k = 0; k < F.rows(); ++k)
    for (Eigen::Index j = 0; j < nw; ++j)
      if (!std::isfinite(F(k, j)))
        fail(who + ": F(q) returned F[" + std::to_string(k % r) + ", " + std::to_string(j) + "] = " + fmt(F(k, j)) +
             " " + at_sample(samples, k / r) + ", expected finite");
  return F;
}

Eigen::MatrixXd called_g(const std::string& who, const SecondOrderFunctions& f, const PathSamples& samples,
                         Eigen::Index r) {
  const Eigen::Index m = samples.size();
  Eigen::MatrixXd g = f.g(samples.q);
  if (g.rows() != m || g.cols() != r)
    fail(who + ": g(q) returned shape " + shape(g.rows(), g.cols()) + ", expected " + shape(m, r) +
         ": one row per grid point, one entry per row of F");
  for (Eigen::Index k = 0; k < m; ++k)
    for (Eigen::Index j = 0; j < r; ++j)
      if (bad_limit(g(k, j)))
        fail(who + ": g(q) returned g[" + std::to_string(j) + "] = " + fmt(g(k, j)) + " " + at_sample(samples, k) +
             ", expected a number or +inf");
  return g;
}

}  // namespace

SecondOrderConstraint::SecondOrderConstraint(std::shared_ptr<const SecondOrderFunctions> functions, Options options)
    : functions_(std::move(functions)), user_functions_(functions_), options_(std::move(options)) {
  if (!functions_) fail("functions must not be None");
  check_constant("constraint '" + options_.name + "'", *functions_);
  const Eigen::Index r = constant_rows();
  if (r >= 0 && !options_.labels.empty() && static_cast<Eigen::Index>(options_.labels.size()) != r)
    fail("labels has " + std::to_string(options_.labels.size()) + " entries, expected " + std::to_string(r) +
         " (one per row of F)");
}

SecondOrderConstraint::SecondOrderConstraint(SecondOrderFunctions::InverseDynamics inverse_dynamics,
                                             SecondOrderFunctions::OfQ F, SecondOrderFunctions::OfQ g,
                                             SecondOrderOptions options)
    : SecondOrderConstraint(
          [&] {
            auto f = std::make_shared<SecondOrderFunctions>();
            f->inverse_dynamics = std::move(inverse_dynamics);
            f->F = std::move(F);
            f->g = std::move(g);
            if (!f->F) fail("F must be given (a function of q)");
            if (!f->g) fail("g must be given (a function of q)");
            return f;
          }(),
          std::move(options)) {}

std::shared_ptr<const SecondOrderConstraint> SecondOrderConstraint::torque_limits(
    std::shared_ptr<const SecondOrderFunctions> functions, const Eigen::VectorXd& tau_min,
    const Eigen::VectorXd& tau_max, double scale, double margin, std::vector<std::string> joint_names) {
  if (!functions || !functions->inverse_dynamics) fail("inverse_dynamics must be given");
  const Eigen::Index n = tau_max.size();
  if (tau_min.size() == 0 || n == 0)
    fail(std::string(tau_min.size() == 0 ? "tau_min" : "tau_max") +
         " must be given (one per joint) with inverse_dynamics: there is no URDF effort limit to default to");
  detail::require_size("tau_min", tau_min.size(), n, "one per joint, as tau_max");
  detail::require_not_nan("tau_min", tau_min);
  detail::require_not_nan("tau_max", tau_max);
  if (!joint_names.empty()) detail::require_size("joint_names", static_cast<Eigen::Index>(joint_names.size()), n);
  if (!(scale > 0.0) || !std::isfinite(scale)) fail("scale = " + fmt(scale) + " must be > 0 and finite");
  if (!(margin >= 0.0) || !std::isfinite(margin)) fail("margin = " + fmt(margin) + " must be >= 0 and finite");
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(tau_min[j] <= tau_max[j]))
      fail(detail::at("tau_min", j) + " = " + fmt(tau_min[j]) + " must be <= " + detail::at("tau_max", j) + " = " +
           fmt(tau_max[j]));
  const Eigen::VectorXd lo = scale * tau_min.array() + margin, hi = scale * tau_max.array() - margin;
  for (Eigen::Index j = 0; j < n; ++j)
    if (lo[j] > hi[j])
      fail("margin = " + fmt(margin) + " closes the torque range of joint " + std::to_string(j) + " ([" +
           fmt(scale * tau_min[j]) + ", " + fmt(scale * tau_max[j]) + "])");
  // F = [e_0; -e_0; e_1; -e_1; ...], g = [τ_U,0; -τ_L,0; ...]: eq. 15's rows in TorqueLimits' order.
  auto f = std::make_shared<SecondOrderFunctions>(*functions);
  f->F = nullptr;
  f->g = nullptr;
  f->F_constant = Eigen::MatrixXd::Zero(2 * n, n);
  f->g_constant.resize(2 * n);
  for (Eigen::Index j = 0; j < n; ++j) {
    f->F_constant(2 * j, j) = 1.0;
    f->F_constant(2 * j + 1, j) = -1.0;
    f->g_constant[2 * j] = hi[j];
    f->g_constant[2 * j + 1] = -lo[j];
  }
  Options o;
  o.name = "torque limits";
  o.family = "torque";
  auto c = std::make_shared<SecondOrderConstraint>(std::move(f), std::move(o));
  c->torque_ = true;
  c->tau_min_ = lo;
  c->tau_max_ = hi;
  c->joint_names_ = std::move(joint_names);
  // Keep the user's functions object (its owner, e.g. the Python callables that pickling needs) reachable.
  c->user_functions_ = std::move(functions);
  return c;
}

std::shared_ptr<const SecondOrderConstraint> SecondOrderConstraint::torque_limits(
    SecondOrderFunctions::InverseDynamics inverse_dynamics, const Eigen::VectorXd& tau_min,
    const Eigen::VectorXd& tau_max, double scale, double margin) {
  auto f = std::make_shared<SecondOrderFunctions>();
  f->inverse_dynamics = std::move(inverse_dynamics);
  return torque_limits(std::move(f), tau_min, tau_max, scale, margin);
}

Eigen::Index SecondOrderConstraint::constant_rows() const {
  return functions_->F ? -1 : functions_->F_constant.rows();
}

std::vector<std::string> SecondOrderConstraint::row_labels(Eigen::Index r) const {
  std::vector<std::string> labels(static_cast<size_t>(r));
  if (torque_) {
    for (Eigen::Index j = 0; 2 * j < r; ++j) {
      const std::string joint = joint_names_.empty() ? "joint " + std::to_string(j) : joint_names_[static_cast<size_t>(j)];
      labels[static_cast<size_t>(2 * j)] = "torque " + joint + " upper";
      labels[static_cast<size_t>(2 * j + 1)] = "torque " + joint + " lower";
    }
    return labels;
  }
  if (!options_.labels.empty()) {
    if (static_cast<Eigen::Index>(options_.labels.size()) != r)
      fail("constraint '" + options_.name + "': labels has " + std::to_string(options_.labels.size()) +
           " entries, F(q) has " + std::to_string(r) + " rows");
    return options_.labels;
  }
  for (Eigen::Index j = 0; j < r; ++j) labels[static_cast<size_t>(j)] = options_.name + " row " + std::to_string(j);
  return labels;
}

ConstraintRows SecondOrderConstraint::evaluate(const PathSamples& samples) const {
  const std::string who = "constraint '" + options_.name + "'";
  const SecondOrderFunctions& f = *functions_;
  const Eigen::Index m = samples.size();
  if (torque_ && samples.dof() != tau_max_.size())
    fail("path has " + std::to_string(samples.dof()) + " coordinates, " + who + " has " +
         std::to_string(tau_max_.size()) + " joints (tau_min, tau_max)");
  ConstraintRows rows;
  if (m == 0) {  // labels only (set_joint_names); a callable F tells its rows only when called with samples
    const Eigen::Index r = std::max<Eigen::Index>(constant_rows(), 0);
    rows.allocate(0, r);
    rows.labels = row_labels(r);
    return rows;
  }
  const Eigen::MatrixXd w = batched_inverse_dynamics(who, f, samples);
  const Eigen::Index nw = w.cols();
  if (!f.F && f.F_constant.cols() != nw)
    fail(who + ": inverse_dynamics returned w of size " + std::to_string(nw) + ", expected " +
         std::to_string(f.F_constant.cols()) + " (the columns of F)");
  const Eigen::MatrixXd F = f.F ? called_F(who, f, samples, nw) : Eigen::MatrixXd();
  const Eigen::Index r = f.F ? F.rows() / m : f.F_constant.rows();
  if (!f.g && f.g_constant.size() != r)
    fail(who + ": g has size " + std::to_string(f.g_constant.size()) + ", F(q) has " + std::to_string(r) + " rows");
  const Eigen::MatrixXd g = f.g ? called_g(who, f, samples, r) : Eigen::MatrixXd();
  rows.allocate(m, r);
  rows.labels = row_labels(r);
  Eigen::VectorXd cw(nw), aw(nw), bw(nw), gi(r);
  for (Eigen::Index i = 0; i < m; ++i) {
    // w = a_w x + b_w u + c at grid point i (eq. 12), then F w <= g row by row.
    cw = w.row(i).transpose();
    bw = w.row(m + i).transpose() - cw;
    aw = w.row(2 * m + i).transpose() - cw;
    const auto Fi = f.F ? F.middleRows(i * r, r) : f.F_constant.topRows(r);
    gi = f.g ? Eigen::VectorXd(g.row(i).transpose()) : f.g_constant;
    if (g_scale_ != 1.0)
      for (Eigen::Index j = 0; j < r; ++j) gi[j] = widen_upper(gi[j], g_scale_);
    rows.a.row(i) = (Fi * aw).transpose();
    rows.b.row(i) = (Fi * bw).transpose();
    rows.c.row(i) = (gi - Fi * cw).transpose();
  }
  return rows;
}

std::shared_ptr<const Constraint> SecondOrderConstraint::relaxed(double scale) const {
  if (torque_) {
    Eigen::VectorXd lo = tau_min_, hi = tau_max_;
    for (Eigen::Index j = 0; j < lo.size(); ++j) {
      lo[j] = widen_lower(lo[j], scale);
      hi[j] = widen_upper(hi[j], scale);
    }
    return torque_limits(user_functions_, lo, hi, 1.0, 0.0, joint_names_);
  }
  return with_g_scale(scale);
}

std::shared_ptr<const SecondOrderConstraint> SecondOrderConstraint::with_g_scale(double scale) const {
  if (torque_) fail("constraint '" + options_.name + "': torque limits widen tau_min and tau_max, not g (relaxed)");
  if (!(scale >= 1.0) || !std::isfinite(scale)) fail("scale = " + fmt(scale) + " must be >= 1 and finite");
  auto c = std::make_shared<SecondOrderConstraint>(*this);
  c->g_scale_ = g_scale_ * scale;
  return c;
}

std::shared_ptr<const Constraint> SecondOrderConstraint::with_joint_names(const std::vector<std::string>& names) const {
  if (!torque_ || !joint_names_.empty() || static_cast<Eigen::Index>(names.size()) != tau_max_.size()) return nullptr;
  auto c = std::make_shared<SecondOrderConstraint>(*this);
  c->joint_names_ = names;
  return c;
}

}  // namespace pathpace
