// ContactConstraint::evaluate: every grid point's polygon, projected from its LP (sec. IV.C).
#include "pathpace/constraints/contact_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/gather_rows.hpp"
#include "base/validate.hpp"
#include "lp/projection.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/robot_workspace.hpp"

namespace pathpace {

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

}  // namespace pathpace
