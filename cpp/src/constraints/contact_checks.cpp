// ContactConstraint's checks of a path and a timing: the contacts' drift, one point's feasibility, and
// the force distribution of a timed trajectory.
#include "pathpace/constraints/contact_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "base/validate.hpp"
#include "lp/analytic_centre.hpp"
#include "lp/projection.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/robot_workspace.hpp"

namespace pathpace {

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
  // An empty polytope has no rest point either: a second exact confirmation would only repeat the first.
  const double rest[2] = {0.0, 0.0};
  out.rest_feasible = out.feasible == 0 ? 0 : solver.feasible(lp, rest);
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
                                                                 const Eigen::MatrixXd& qdd,
                                                                 ForceDistribution distribution) const {
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
  // The centre (ForceDistribution::Centre): the analytic centre of the physical rows (physical_rows) at
  // each sample, by Newton from the previous sample's centre. It maximises Σ log slack, which is strictly
  // concave on the (bounded) set, so it is unique, and smooth in the rows' data (detail::analytic_centre):
  // continuous in t wherever q, q̇, q̈ are. Without an interior (the motion sits on a physical row, as a
  // zero-margin time-optimal plan does on its bang-bang arcs) there is no centre: the vertex is kept
  // (centred = false).
  detail::PolytopeProjector phase_one;
  Eigen::MatrixXd Aeq, G;
  Eigen::VectorXd beq, h, centre;
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
    physical_rows(T, J, tau, Aeq, beq, G, h);
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
    const Eigen::VectorXd vertex = Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(f.forces.transpose()).data(), 3 * m);
    f.slack = G.rows() ? (h - G * vertex).minCoeff() : 0.0;
    if (distribution != ForceDistribution::Centre || m == 0) continue;
    const double scale = std::max(1.0, beq.size() ? beq.cwiseAbs().maxCoeff() : 0.0);
    if (centre.size() != 3 * m) centre = vertex;
    const detail::CentreResult r = detail::analytic_centre(Aeq, beq, G, h, 1e-7 * scale, phase_one, centre);
    if (r.status == detail::CentreResult::Status::SolverError)
      throw Error("force distribution: the centre's phase-I LP failed (GLPK error or no finish) at sample " +
                  std::to_string(s));
    if (r.status != detail::CentreResult::Status::Centre) {
      centre.resize(0);  // the next sample starts afresh
      continue;
    }
    f.centred = true;
    f.slack = (h - G * centre).minCoeff();
    f.torques = tau - J.transpose() * centre;
    for (int i = 0; i < m; ++i) f.forces.row(i) = centre.segment<3>(3 * i).transpose();
  }
  return out;
}

}  // namespace pathpace
