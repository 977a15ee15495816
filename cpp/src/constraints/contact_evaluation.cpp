// ContactConstraint::evaluate: every grid point's polygon, projected from its LP (sec. IV.C).
#include "pathpace/constraints/contact_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

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
  if (!sub.refine_state.empty()) {
    out.refine_state.assign(static_cast<size_t>(samples.size()), nullptr);
    for (size_t i = 0; i < in.size(); ++i) out.refine_state[static_cast<size_t>(in[i])] = sub.refine_state[i];
  }
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

namespace {

// A grid point's projection, warm from the previous point's bases; once more from a cold start (a fresh basis)
// when it failed or ran out of LPs, keeping the larger result. Both runs' LPs are counted.
detail::Projection project_point(detail::PolytopeProjector& projector, const detail::PolytopeLp& lp,
                                 const ContactOptions& o, const std::vector<detail::Vertex>* focus, int& lps,
                                 LpCounts& by_cause, detail::ProjectionState* state = nullptr) {
  detail::Projection pr = projector.project(lp, 1e-9, o.max_lps, o.projection_tolerance, focus, state);
  lps += pr.lp_solves;
  by_cause += pr.by_cause;
  if (pr.outcome == detail::Projection::Outcome::Failed ||
      (pr.outcome == detail::Projection::Outcome::Polygon && !pr.complete)) {
    detail::Projection cold = detail::project_polytope(lp, 1e-9, o.max_lps, o.projection_tolerance, focus, state);
    lps += cold.lp_solves;
    by_cause.cold_retry += cold.lp_solves;
    if (cold.outcome != detail::Projection::Outcome::Failed &&
        (pr.outcome == detail::Projection::Outcome::Failed || cold.complete || cold.vertices.size() > pr.vertices.size()))
      pr = std::move(cold);
  }
  return pr;
}

// Whether `per_point` optimal bases of `lp` at each of `points` grid points fit the memory kept for
// project_on_demand's states (256 MB): beyond, the states keep no bases (or evaluate() none at all).
bool kept_bases_fit(Eigen::Index points, const detail::PolytopeLp& lp, int per_point) {
  constexpr double kBudget = 256.0 * (1 << 20);
  return static_cast<double>(points) * static_cast<double>(lp.A.rows() + lp.A.cols()) * per_point <= kBudget;
}

// A row's label at its occurrence at one grid point: one column per (label, occurrence) (see project()).
std::string occurrence_label(const std::string& label, int occurrence) {
  return occurrence == 0 ? label : label + " [polygon edge " + std::to_string(occurrence + 1) + " of this limit]";
}

}  // namespace

// A polygon's half-planes as rows, each named by what binds it; edges on the stand-in bounds (the stand-in
// the projection used: options_.cap, or larger where the shadow lies beyond it) are not limits.
void ContactConstraint::polygon_rows(const detail::Projection& pr, const std::vector<std::string>& what,
                                     std::vector<detail::Line>& out, std::vector<std::string>& names) const {
  for (size_t e = 0; e < pr.halfplanes.size(); ++e) {
    const detail::Line& h = pr.halfplanes[e];
    const double cap = pr.stand_in;
    const bool on_cap = (std::abs(h.b) < 1e-12 && h.a > 0 && std::abs(h.c - cap) <= 1e-6 * cap) ||
                        (std::abs(h.a) < 1e-12 && std::abs(std::abs(h.c) - cap) <= 1e-6 * cap);
    if (on_cap) continue;
    out.push_back(h);
    names.push_back(binding_label(reduced_, what, pr.binding[e]));
  }
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
  // On demand: three LPs per point, their support lines an outer polygon; refine() goes on from each point's
  // state (kept in the rows while it is small: three bases per point).
  const std::vector<detail::Vertex> no_focus;
  const std::vector<detail::Vertex>* focus = options_.project_on_demand ? &no_focus : nullptr;
  const bool keep = focus && kept_bases_fit(samples.size(), lp, 3);
  ConstraintRows r;
  if (keep) r.refine_state.resize(static_cast<size_t>(samples.size()));
  for (Eigen::Index p = 0; p < samples.size(); ++p) {
    lp_point(reduced_, samples.q.row(p).transpose(), a.row(p).transpose(), b.row(p).transpose(), c.row(p).transpose(), lp);
    detail::ProjectionState state;
    const detail::Projection pr =
        project_point(projector, lp, options_, focus, r.lp_solves, r.lp_by_cause, keep ? &state : nullptr);
    if (keep && state.resumable)
      r.refine_state[static_cast<size_t>(p)] = std::make_shared<const detail::ProjectionState>(std::move(state));
    if (pr.outcome != detail::Projection::Outcome::Polygon) {
      // Empty (confirmed in exact arithmetic), or no support point at all (the solver failed: reported
      // inexact, and solve() re-checks such a point before it calls it infeasible).
      empty_point[static_cast<size_t>(p)] = 1;
      if (pr.outcome == detail::Projection::Outcome::Failed) r.inexact_points.push_back(p);
    } else {
      if (!pr.complete) r.inexact_points.push_back(p);
      polygon_rows(pr, what, polys[static_cast<size_t>(p)], names[static_cast<size_t>(p)]);
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
        labels.push_back(occurrence_label(l, occurrence));
      }
      at[static_cast<size_t>(p)].push_back(it->second);
    }
  }
  // The last row marks grid points where no contact forces balance the robot: 0 <= -1 there.
  const Eigen::Index marker = static_cast<Eigen::Index>(labels.size());
  r.resize(samples.size(), marker + 1);  // a, b, c and labels only: inexact_points and lp_solves stay
  for (size_t j = 0; j < labels.size(); ++j) r.labels[j] = labels[j];
  r.labels[static_cast<size_t>(marker)] = kNoBalance;
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

std::shared_ptr<const Constraint> ContactConstraint::exact() const {
  if (!options_.project_on_demand) return nullptr;
  auto out = std::make_shared<ContactConstraint>(*this);
  out->options_.project_on_demand = false;
  return out;
}

namespace {

// Whether (x, u) needs the polygon at a point refined: beyond an edge of its inner polygon that is not
// certified (beyond a certified one it is infeasible, and the outer rows already exclude it).
bool beyond_uncertified(const Eigen::Matrix<double, Eigen::Dynamic, 4>& hull, double tolerance, double x, double u) {
  for (Eigen::Index e = 0; e < hull.rows(); ++e)
    if (hull(e, 3) == 0.0 && hull(e, 0) * x + hull(e, 1) * u > hull(e, 2) + tolerance) return true;
  return false;
}

// The grid points to refine, each with its new focus points added to memory.focus: every active point whose
// (θ_k, s̈), with either adjacent s̈ (or sddot[k]), lies beyond an edge of its inner polygon not yet certified,
// or that was not refined yet (evaluate() keeps no inner polygon). tolerance -1: an empty or failed polygon.
std::vector<Eigen::Index> points_to_refine(const Constraint& c, const PathSamples& samples, const Eigen::VectorXd& theta,
                                           const Eigen::VectorXd* sddot, RefineMemory& memory) {
  const Eigen::Index P = samples.size();
  std::vector<Eigen::Index> todo;
  for (Eigen::Index p = 0; p < P; ++p) {
    const size_t k = static_cast<size_t>(p);
    if (!c.active_at(samples.s[p]) || memory.tolerance[k] < 0.0) continue;
    bool need = false;
    for (int side = 0; side < 2; ++side) {
      const Eigen::Index i = p - 1 + side;  // the interval: p - 1 before, p after
      if (sddot ? side == 1 : i < 0 || i >= P - 1) continue;
      const double u = sddot ? (*sddot)[p] : (theta[i + 1] - theta[i]) / (2.0 * (samples.s[i + 1] - samples.s[i]));
      if (memory.hull[k].rows() == 0 || beyond_uncertified(memory.hull[k], memory.tolerance[k], theta[p], u)) {
        memory.focus[k].push_back({theta[p], u});
        need = true;
      }
    }
    if (need) todo.push_back(p);
  }
  return todo;
}

// A refined point's rows in a contact constraint's ConstraintRows: one column per (label, occurrence), as
// project() lays them out; a label not seen before gets a new column, inactive at every other point.
class PointRows {
 public:
  PointRows(ConstraintRows& rows, const std::string& prefix, std::string rest)
      : rows_(rows), prefix_(prefix), rest_(std::move(rest)) {
    for (size_t j = 0; j < rows.labels.size(); ++j) column_.emplace(rows.labels[j], static_cast<Eigen::Index>(j));
    marker_ = column_.at(prefix + ContactConstraint::kNoBalance);
  }
  // Point p's rows cleared (but the no-impact row at a phase's start), then marked empty, or these lines.
  void write(Eigen::Index p, const detail::Projection& pr, const std::vector<detail::Line>& lines,
             const std::vector<std::string>& names) {
    for (Eigen::Index j = 0; j < rows_.rows(); ++j) {
      if (!rest_.empty() && rows_.labels[static_cast<size_t>(j)] == rest_) continue;
      rows_.a(p, j) = 0.0;
      rows_.b(p, j) = 0.0;
      rows_.c(p, j) = std::numeric_limits<double>::infinity();
    }
    auto& inexact = rows_.inexact_points;
    const auto listed = std::find(inexact.begin(), inexact.end(), p);
    const bool exact = pr.outcome == detail::Projection::Outcome::Polygon && pr.complete;
    if (!exact && listed == inexact.end()) inexact.push_back(p);
    if (exact && listed != inexact.end()) inexact.erase(listed);
    if (pr.outcome != detail::Projection::Outcome::Polygon) {
      rows_.c(p, marker_) = -1.0;
      return;
    }
    std::map<std::string, int> seen;
    for (size_t j = 0; j < lines.size(); ++j) {
      const Eigen::Index col = column(prefix_ + occurrence_label(names[j], seen[names[j]]++));
      rows_.a(p, col) = lines[j].a;
      rows_.b(p, col) = lines[j].b;
      rows_.c(p, col) = lines[j].c;
    }
  }

 private:
  Eigen::Index column(const std::string& label) {
    auto it = column_.find(label);
    if (it != column_.end()) return it->second;
    const Eigen::Index n = rows_.rows(), P = rows_.a.rows();
    column_.emplace(label, n);
    rows_.labels.push_back(label);
    for (ConstraintRows::Matrix* m : {&rows_.a, &rows_.b, &rows_.c}) m->conservativeResize(P, n + 1);
    rows_.a.col(n).setZero();
    rows_.b.col(n).setZero();
    rows_.c.col(n).setConstant(std::numeric_limits<double>::infinity());
    return n;
  }
  ConstraintRows& rows_;
  const std::string& prefix_;
  const std::string rest_;
  std::map<std::string, Eigen::Index> column_;
  Eigen::Index marker_ = 0;
};

}  // namespace

// The rounds of project_on_demand (ContactOptions): each point to refine is projected again with all its
// focus points so far, from where its last projection stopped (ProjectionState), and its rows rewritten.
int ContactConstraint::refine(const PathSamples& samples, const Eigen::VectorXd& theta, const Eigen::VectorXd* sddot,
                              ConstraintRows& rows, RefineMemory& memory) const {
  if (!options_.project_on_demand) return 0;
  const size_t np = static_cast<size_t>(samples.size());
  if (memory.hull.size() != np) {
    memory.focus.assign(np, {});
    memory.hull.assign(np, {});
    memory.tolerance.assign(np, 0.0);
    memory.state.assign(np, nullptr);
  }
  const std::vector<Eigen::Index> todo = points_to_refine(*this, samples, theta, sddot, memory);
  if (todo.empty()) return 0;

  detail::PolytopeLp lp;
  lp_structure(reduced_, 0, lp);
  RobotWorkspace ws(*robot_);
  const Eigen::MatrixXd q = detail::gather_rows(samples.q, todo);
  Eigen::MatrixXd a, b, c;
  robot_->path_torque_coefficients_batch(ws, q, detail::gather_rows(samples.dq, todo),
                                         detail::gather_rows(samples.ddq, todo), a, b, c);
  detail::PolytopeProjector projector;
  const std::vector<std::string> what = binding_names(reduced_);
  const std::string prefix = options_.label.empty() ? std::string() : options_.label + ": ";
  PointRows out(rows, prefix, options_.rest_at_begin.empty() ? std::string() : prefix + options_.rest_at_begin);
  // Bases of about 16 support points per point (the refined polygons' size in bench/README.md) while they fit.
  const bool keep_bases = kept_bases_fit(samples.size(), lp, 16);
  std::vector<detail::Vertex> focus;
  std::vector<detail::Line> lines;
  std::vector<std::string> names;
  int changed = 0;
  for (size_t t = 0; t < todo.size(); ++t) {
    const Eigen::Index p = todo[t], ti = static_cast<Eigen::Index>(t);
    const size_t k = static_cast<size_t>(p);
    lp_point(reduced_, q.row(ti).transpose(), a.row(ti).transpose(), b.row(ti).transpose(), c.row(ti).transpose(), lp);
    focus.clear();
    for (const auto& f : memory.focus[k]) focus.push_back({f[0], f[1]});
    if (!memory.state[k]) {  // evaluate()'s state where it kept one, else a fresh start
      const bool from_rows = rows.refine_state.size() == np && rows.refine_state[k];
      auto st = from_rows ? std::make_shared<detail::ProjectionState>(
                                *static_cast<const detail::ProjectionState*>(rows.refine_state[k].get()))
                          : std::make_shared<detail::ProjectionState>();
      st->keep_bases = keep_bases;
      memory.state[k] = st;
    }
    const int lps_before = memory.lp_solves;
    const detail::Projection pr = project_point(projector, lp, options_, &focus, memory.lp_solves, memory.lp_by_cause,
                                                static_cast<detail::ProjectionState*>(memory.state[k].get()));
    // A point whose timing lies beyond a certified edge (by the solver's tolerance) needs no LP: unchanged.
    if (memory.lp_solves == lps_before) continue;
    ++changed;
    lines.clear();
    names.clear();
    if (pr.outcome == detail::Projection::Outcome::Polygon) polygon_rows(pr, what, lines, names);
    out.write(p, pr, lines, names);
    memory.tolerance[k] = pr.outcome == detail::Projection::Outcome::Polygon ? pr.tolerance : -1.0;
    auto& hull = memory.hull[k];
    hull.resize(static_cast<Eigen::Index>(pr.hull.size()), 4);
    for (size_t e = 0; e < pr.hull.size(); ++e)
      hull.row(static_cast<Eigen::Index>(e)) << pr.hull[e].a, pr.hull[e].b, pr.hull[e].c, pr.hull_certified[e] ? 1.0 : 0.0;
  }
  return changed;
}

}  // namespace pathpace
