// ContactConstraint::slice: the polygon's slice at the timing's own s̈ (guarantee = continuous).
// Kept apart from contact_constraint.cpp: it uses the projection polytope only through lp_structure and
// lp_point and PolytopeLp's contract (columns 0 and 1 are x and u), not the layout of its other columns.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lp/projection.hpp"
#include "lp/slice_lp.hpp"
#include "base/validate.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/robot_workspace.hpp"

namespace pathpace {

int ContactConstraint::slice(const PathSamples& samples, const Eigen::VectorXd& u, Eigen::VectorXd& x_lo,
                             Eigen::VectorXd& x_hi, const Eigen::VectorXd* x, SliceEdges* edges,
                             SliceStarts* starts) const {
  const int n = robot_->nq();
  if (samples.dof() != n)
    detail::fail("path has " + std::to_string(samples.dof()) + " coordinates, robot '" + robot_->name() + "' has " +
                 std::to_string(n) + " joints");
  if (u.size() != samples.size())
    detail::fail("u has " + std::to_string(u.size()) + " entries, samples has " + std::to_string(samples.size()));
  if (x && x->size() != samples.size())
    detail::fail("x has " + std::to_string(x->size()) + " entries, samples has " + std::to_string(samples.size()));
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  x_lo.resize(samples.size());
  x_hi.resize(samples.size());
  int lps = 0;
  const Eigen::Index P = samples.size();
  std::vector<std::string> what;
  if (edges) {
    for (Eigen::VectorXd* v : {&edges->lo_slope, &edges->hi_slope}) v->setZero(P);
    for (Eigen::VectorXd* v : {&edges->lo_from, &edges->lo_to, &edges->hi_from, &edges->hi_to}) *v = u;
    edges->lo_label.assign(edges->labels ? static_cast<size_t>(P) : 0, std::string());
    edges->hi_label = edges->lo_label;
    if (edges->labels) what = binding_names(reduced_);
  }
  detail::PolytopeProjector::FixedColumn fixed;  // u's column: its sensitivity, for `edges`
  fixed.label = edges && edges->labels;
  // One end's edge from its LP (sign -1: the bottom, an LP on -x).
  auto edge = [&](Eigen::Index p, double sign, Eigen::VectorXd& slope, Eigen::VectorXd& from, Eigen::VectorXd& to,
                  std::vector<std::string>& label) {
    slope[p] = sign * fixed.slope;
    from[p] = fixed.from;
    to[p] = fixed.to;
    if (fixed.label && fixed.binding != detail::kBindingUnknown)
      label[static_cast<size_t>(p)] = binding_label(reduced_, what, fixed.binding);
  };
  detail::PolytopeLp lp;
  lp_structure(reduced_, 0, lp);
  RobotWorkspace ws(*robot_);
  Eigen::MatrixXd a, b, c;  // eq. (12) at every sample
  robot_->path_torque_coefficients_batch(ws, samples.q, samples.dq, samples.ddq, a, b, c);
  detail::SliceLp solver;
  // Each end starts from the caller's basis for the sample if it has one (an earlier call's, nearby: a peak
  // search's samples lie in intervals far apart, each near its own interval's earlier samples), else from
  // the sample before.
  const bool have_starts = starts && starts->start[0].size() == static_cast<size_t>(P) &&
                           starts->start[1].size() == static_cast<size_t>(P);
  if (starts)
    for (auto& f : starts->found) f.assign(static_cast<size_t>(P), {});
  auto start_of = [&](int end, Eigen::Index p) -> const std::vector<signed char>* {
    if (!have_starts) return nullptr;
    const std::vector<signed char>& b = starts->start[end][static_cast<size_t>(p)];
    return b.empty() ? nullptr : &b;
  };
  auto keep = [&](int end, Eigen::Index p, int st) {
    if (starts && st == 1) starts->found[end][static_cast<size_t>(p)] = solver.basis(end);
  };
  // A sample at the same path point as the one that built `lp` (a caller asking several s̈ at one point)
  // has the same LP but for u's bounds: not built again.
  Eigen::Index built = -1;
  auto same_point = [&](Eigen::Index p, Eigen::Index o) {
    return o >= 0 && samples.s[p] == samples.s[o] && samples.q.row(p) == samples.q.row(o) &&
           samples.dq.row(p) == samples.dq.row(o) && samples.ddq.row(p) == samples.ddq.row(o);
  };
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    if (!active_at(samples.s[p])) {
      x_lo[p] = -inf;
      x_hi[p] = inf;
      continue;
    }
    if (!same_point(p, built)) {
      lp_point(reduced_, samples.q.row(p).transpose(), a.row(p).transpose(), b.row(p).transpose(),
               c.row(p).transpose(), lp);
      built = p;
    }
    lp.col_lo[1] = lp.col_hi[1] = u[p];
    lp.col_hi[0] = !options_.rest_at_begin.empty() && at_active_begin(samples.s[p]) ? 0.0 : options_.cap;
    solver.load(lp);
    double top = 0.0, bottom = 0.0;
    ++lps;
    const int st = solver.extreme(1.0, top, edges ? &fixed : nullptr, start_of(0, p));
    keep(0, p, st);
    if (st == 0) {
      x_lo[p] = inf;
      x_hi[p] = -inf;
      continue;
    }
    // On the stand-in cap: no limit on x there (as the projection drops such edges).
    x_hi[p] = st < 0 ? nan : (top >= options_.cap * (1.0 - 1e-9) ? inf : top);
    if (edges && st == 1) edge(p, 1.0, edges->hi_slope, edges->hi_from, edges->hi_to, edges->hi_label);
    if (x && (*x)[p] > x_hi[p]) {  // above the slice: its bottom does not change how far
      x_lo[p] = -inf;
      continue;
    }
    ++lps;
    const int sl = solver.extreme(-1.0, bottom, edges ? &fixed : nullptr, start_of(1, p));
    keep(1, p, sl);
    x_lo[p] = sl == 1 ? bottom : (sl == 0 ? inf : nan);
    if (edges && sl == 1) edge(p, -1.0, edges->lo_slope, edges->lo_from, edges->lo_to, edges->lo_label);
  }
  if (starts) starts->glpk_lps = solver.glpk;
  return lps;
}

}  // namespace pathpace
