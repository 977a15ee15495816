#include "pathpace/constraints/contact_constraint.hpp"

#include <cmath>
#include <limits>

#include "detail/glpk_guard.hpp"
#include "detail/glpk_util.hpp"
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
  }
}

void ContactConstraint::contact_jacobians(const Eigen::Ref<const Eigen::VectorXd>& q, std::vector<Eigen::Isometry3d>& T,
                                          Eigen::MatrixXd& J, Eigen::Matrix3Xd& gen) const {
  const int m = static_cast<int>(contacts_.size()), k = options_.cone_edges;
  robot_->body_placements(q, T);
  J.setZero(3 * m, robot_->nq());
  gen.resize(3, m * k);
  auto pose = [&](int body) { return body >= 0 ? T[static_cast<size_t>(body)] : Eigen::Isometry3d::Identity(); };
  for (int i = 0; i < m; ++i) {
    const size_t u = static_cast<size_t>(i);
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

double ContactConstraint::max_drift(const PathSamples& samples, int* which) const {
  double worst = 0.0;
  std::vector<Eigen::Isometry3d> T;
  std::vector<Eigen::Vector3d> first(contacts_.size());
  for (Eigen::Index s = 0; s < samples.size(); ++s) {
    robot_->body_placements(samples.q.row(s).transpose(), T);
    auto pose = [&](int body) { return body >= 0 ? T[static_cast<size_t>(body)] : Eigen::Isometry3d::Identity(); };
    for (size_t i = 0; i < contacts_.size(); ++i) {
      // Where the point is, in the frame that must keep it: the world, or the other body.
      const Eigen::Vector3d p = pose(other_body_[i]).inverse() * (pose(body_[i]) * point_in_body_[i]);
      if (s == 0) {
        first[i] = p;
        continue;
      }
      const double d = (p - first[i]).norm();
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
  Eigen::MatrixXd a, b, c;  // eq. (12) at every grid point, row p
  robot_->path_torque_coefficients_batch(ws, samples.q, samples.dq, samples.ddq, a, b, c);
  std::vector<Eigen::Isometry3d> T;
  Eigen::MatrixXd J;
  Eigen::Matrix3Xd gen;
  detail::PolytopeProjector projector;  // one GLPK problem, warm-started from grid point to grid point
  std::vector<std::vector<detail::Line>> polys(static_cast<size_t>(samples.size()));
  std::vector<char> empty_point(static_cast<size_t>(samples.size()), 0);
  size_t widest = 0;
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    const Eigen::VectorXd q = samples.q.row(p).transpose();
    // eq. (17): τ = a x + b u + c - Σ J_iᵀ f_i, with τ eliminated into row bounds (sec. IV.B).
    lp.A.col(0).head(n) = a.row(p).transpose();  // the min-normal-force rows below n keep zeros in x and u
    lp.A.col(1).head(n) = b.row(p).transpose();
    contact_jacobians(q, T, J, gen);
    for (int i = 0; i < m; ++i)
      lp.A.block(0, 2 + i * k, n, k).noalias() = -J.middleRows(3 * i, 3).transpose() * gen.middleCols(i * k, k);
    lp.row_lo.head(n) = tau_min_ - c.row(p).transpose();
    lp.row_hi.head(n) = tau_max_ - c.row(p).transpose();
    const detail::Projection pr = projector.project(lp);
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
  // Columns: μ_ie >= 0 (λ_ie = μ_ie + δ), then δ <= cap (free below). Rows: the n torque rows
  //   τ_L - τ_id <= -Σ_i J_iᵀ G_i (μ_i + δ 1) <= τ_U - τ_id
  // and per contact n·f_i - f_min >= δ, i.e. Σ_e μ_ie + (k - 1) δ >= f_min. Maximise δ.
  const int cols = m * k + 1, rows = n + m;
  RobotWorkspace ws(*robot_);
  std::vector<Eigen::Isometry3d> T;
  Eigen::MatrixXd J, A(rows, cols);
  Eigen::Matrix3Xd gen;
  Eigen::VectorXd tau(n);
  std::vector<int> ia, ja;
  std::vector<double> ar;
  glp_term_out(GLP_OFF);
  detail::GlpkHookState state;
  glp_prob* lp = nullptr;
  glp_error_hook(detail::pathpace_glpk_error_hook, &state);
  if (setjmp(state.env)) {
    glp_error_hook(nullptr, nullptr);
    glp_free_env();
    throw Error("force distribution: the LP solver failed (GLPK error)");
  }
  lp = glp_create_prob();
  glp_set_obj_dir(lp, GLP_MAX);
  glp_add_rows(lp, rows);
  glp_add_cols(lp, cols);
  for (int j = 0; j < m * k; ++j) detail::glpk_set_bounds(lp, false, j + 1, 0.0, inf);
  detail::glpk_set_bounds(lp, false, cols, -inf, options_.cap);
  glp_set_obj_coef(lp, cols, 1.0);
  for (int i = 0; i < m; ++i) detail::glpk_set_bounds(lp, true, n + i + 1, options_.min_normal_force, inf);
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.it_lim = 100 * (rows + cols) + 1000;
  bool first = true;
  for (Eigen::Index s = 0; s < q.rows(); ++s) {
    const Eigen::VectorXd qs = q.row(s).transpose();
    robot_->inverse_dynamics(ws, qs, qd.row(s).transpose(), qdd.row(s).transpose(), true, tau);
    contact_jacobians(qs, T, J, gen);
    A.setZero();
    for (int i = 0; i < m; ++i) {
      A.block(0, i * k, n, k).noalias() = -J.middleRows(3 * i, 3).transpose() * gen.middleCols(i * k, k);
      A.col(cols - 1).head(n) += A.block(0, i * k, n, k).rowwise().sum();
      A.block(n + i, i * k, 1, k).setOnes();
      A(n + i, cols - 1) = k - 1;
    }
    detail::glpk_load_dense(lp, A, ia, ja, ar);
    for (int j = 0; j < n; ++j) detail::glpk_set_bounds(lp, true, j + 1, tau_min_[j] - tau[j], tau_max_[j] - tau[j]);
    if (first) glp_adv_basis(lp, 0);
    first = false;
    const int st = detail::glpk_solve_robust(lp, parm);
    if (st < 0) {
      glp_delete_prob(lp);
      glp_error_hook(nullptr, nullptr);
      throw Error("force distribution: the LP solver did not finish at sample " + std::to_string(s));
    }
    ContactForces& f = out[static_cast<size_t>(s)];
    f.forces.resize(m, 3);
    if (st != GLP_OPT) {
      f.feasible = false;
      f.margin = -inf;
      f.forces.setConstant(nan);
      f.torques = Eigen::VectorXd::Constant(n, nan);
      continue;
    }
    const double delta = glp_get_col_prim(lp, cols);
    f.feasible = true;
    f.margin = delta;
    f.torques = tau;
    for (int i = 0; i < m; ++i) {
      Eigen::VectorXd lambda(k);
      for (int e = 0; e < k; ++e) lambda[e] = glp_get_col_prim(lp, i * k + e + 1) + delta;
      const Eigen::Vector3d fi = gen.middleCols(i * k, k) * lambda;
      f.forces.row(i) = fi.transpose();
      f.torques.noalias() -= J.middleRows(3 * i, 3).transpose() * fi;
    }
  }
  glp_delete_prob(lp);
  glp_error_hook(nullptr, nullptr);
  return out;
}

}  // namespace pathpace
