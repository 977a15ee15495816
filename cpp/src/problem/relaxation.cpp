// TimeScalingProblem::relaxation: how far each family of limits must widen for an infeasible problem to become
// feasible, by bisection on feasibility (reachability only, no SLP).
#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "solve/continuous.hpp"
#include "solve/grid_sets.hpp"
#include "solve/reachability.hpp"
#include "base/validate.hpp"

namespace pathpace {
namespace {

// The constraints' own rows at the grid points `kept` alone (no boundary or interval rows): a subset of the
// problem's rows there, so an empty set at one of them means the whole problem is infeasible. It costs
// |kept| / (N + 1) of a full evaluation: where a grid point's own set is empty, the relaxation brackets its
// scale on those points first and evaluates the whole problem once or twice, not at every bisection step.
bool points_nonempty(const std::vector<std::shared_ptr<const Constraint>>& constraints, const PathSamples& all,
                     const std::vector<Eigen::Index>& kept) {
  PathSamples sub;
  const Eigen::Index m = static_cast<Eigen::Index>(kept.size());
  sub.s.resize(m);
  sub.q.resize(m, all.dof());
  sub.dq.resize(m, all.dof());
  sub.ddq.resize(m, all.dof());
  for (Eigen::Index i = 0; i < m; ++i) {
    const Eigen::Index k = kept[static_cast<size_t>(i)];
    sub.s[i] = all.s[k];
    sub.q.row(i) = all.q.row(k);
    sub.dq.row(i) = all.dq.row(k);
    sub.ddq.row(i) = all.ddq.row(k);
  }
  std::vector<ConstraintRows> rows;
  rows.reserve(constraints.size());
  for (const auto& c : constraints)
    rows.push_back(c->per_grid_point() ? c->at_grid_points(kept)->evaluate(sub) : c->evaluate(sub));
  const detail::GridSets sets = detail::build_grid_sets(sub, rows, detail::problem_scale(sub.s, rows));
  for (const detail::PointSet& p : sets.points)
    if (p.empty) return false;
  return true;
}

// The problem's constraints with family f ("all": every family, one after the other) widened by `scale`; where
// rows is given, the widened constraints' rows replace the old ones in it.
std::vector<std::shared_ptr<const Constraint>> relaxed_constraints(
    const std::vector<std::shared_ptr<const Constraint>>& constraints, const std::string& f, double scale,
    const PathSamples& samples, std::vector<ConstraintRows>* rows) {
  std::vector<std::shared_ptr<const Constraint>> cons = constraints;
  for (size_t i = 0; i < constraints.size(); ++i) {
    std::shared_ptr<const Constraint> r;
    for (const std::string& fi : constraints[i]->families()) {
      if (f != "all" && fi != f) continue;
      if (auto next = (r ? r : constraints[i])->relaxed(fi, scale)) r = std::move(next);
    }
    if (r) {
      if (rows) (*rows)[i] = r->evaluate(samples);
      cons[i] = std::move(r);
    }
  }
  return cons;
}

using ScaleTest = std::function<bool(double)>;

// Bisection on log(scale) between an infeasible lo and a feasible hi (feasibility grows with the scale: each
// relaxed set contains the last). Returns the feasible end.
double bisect_scale(const ScaleTest& ok, double lo, double hi, double rel_tolerance) {
  while (hi > lo * (1.0 + rel_tolerance)) {
    const double mid = std::sqrt(lo * hi);
    (ok(mid) ? hi : lo) = mid;
  }
  return hi;
}

// From an infeasible lo, grow hi (x 4) until feasible, then bisect; inf if max_scale is infeasible.
double search_scale(const ScaleTest& ok, double lo, double hi, double max_scale, double rel_tolerance) {
  while (hi < max_scale && !ok(hi)) {
    lo = hi;
    hi = std::min(4.0 * hi, max_scale);
  }
  if (hi >= max_scale && !ok(max_scale)) return std::numeric_limits<double>::infinity();
  return bisect_scale(ok, lo, hi, rel_tolerance);
}

// Where some grid points' own sets are empty: infeasible on those points at a scale => infeasible there, so
// their bracket's upper end is the answer when the whole problem is feasible at it (its lower end, infeasible,
// is within tolerance). Otherwise the answer is usually just above: grow by (1 + tol), (1 + 4 tol), ... before
// bisecting on the whole problem.
double scale_from_empty_points(const ScaleTest& points_ok, const ScaleTest& ok, double max_scale,
                               double rel_tolerance) {
  double lo = search_scale(points_ok, 1.0, 2.0, max_scale, rel_tolerance);
  if (!std::isfinite(lo) || ok(lo)) return lo;
  for (double step = rel_tolerance;; step *= 4.0) {
    const double hi = std::min(lo * (1.0 + step), max_scale);
    if (ok(hi)) return bisect_scale(ok, lo, hi, rel_tolerance);
    if (hi >= max_scale) return std::numeric_limits<double>::infinity();
    lo = hi;
  }
}

}  // namespace

bool TimeScalingProblem::feasible_with(const std::vector<std::shared_ptr<const Constraint>>& constraints,
                                       std::vector<ConstraintRows> rows, Guarantee guarantee) const {
  detail::IntervalExtra extra;
  if (guarantee == Guarantee::Continuous)
    detail::add_kinematic_continuous_rows(*path_, samples_, constraints, rows, extra);
  add_boundary_rows(rows, extra);
  const detail::Scale scale = detail::problem_scale(samples_.s, rows);
  const detail::GridSets sets = detail::build_grid_sets(samples_, rows, scale);
  for (const detail::PointSet& p : sets.points)
    if (p.empty) return false;
  const detail::Chain chain = detail::build_chain(samples_.s, sets, &extra, scale);
  // Unbounded is not infeasible: some timing exists (and a relaxation cannot make it less bounded).
  const double th0 = sdot_begin_ * sdot_begin_ / scale.x_unit;
  detail::Reachability reach = detail::reachability(chain, th0, sdot_end_ * sdot_end_ / scale.x_unit);
  if (reach.outcome != detail::Reachability::Outcome::Feasible) return reach.outcome == detail::Reachability::Outcome::Unbounded;
  // As solve() judges it: a speed forced to zero on an interval means the path cannot be traversed.
  return detail::avoid_stopped_profile(chain, reach, th0, reach.theta);
}

std::map<std::string, double> TimeScalingProblem::relaxation(double max_scale, double rel_tolerance,
                                                             Guarantee guarantee) const {
  const Use use(*this, Use::Read, "relaxation");
  if (!(max_scale > 1.0) || !std::isfinite(max_scale))
    detail::fail("max_scale = " + detail::fmt(max_scale) + " must be > 1 and finite");
  if (!(rel_tolerance > 0.0 && rel_tolerance < 1.0))
    detail::fail("rel_tolerance = " + detail::fmt(rel_tolerance) + " must be in (0, 1)");
  if (refines()) {
    // Rows refined on demand bound their constraints from outside: the search needs the exact ones.
    TimeScalingProblem exact(path_, samples_.s);
    for (const auto& c : constraints_) {
      const std::shared_ptr<const Constraint> e = c->exact();
      exact.add_constraint(e ? e : c);
    }
    exact.set_settings(settings());
    return exact.relaxation(max_scale, rel_tolerance, guarantee);
  }
  std::vector<std::string> families;
  for (const auto& c : constraints_)
    for (const std::string& f : c->families())
      if (std::find(families.begin(), families.end(), f) == families.end()) families.push_back(f);
  if (families.size() >= 2) families.push_back("all");
  std::map<std::string, double> out;
  if (families.empty()) return out;
  if (feasible_with(constraints_, rows_, guarantee)) {
    for (const std::string& f : families) out[f] = 1.0;
    return out;
  }
  // The grid points whose own set is empty as posed (see points_nonempty).
  std::vector<Eigen::Index> empty;
  {
    const detail::GridSets sets = detail::build_grid_sets(samples_, rows_, detail::problem_scale(samples_.s, rows_));
    for (size_t k = 0; k < sets.points.size(); ++k)
      if (sets.points[k].empty) empty.push_back(static_cast<Eigen::Index>(k));
  }
  for (const std::string& f : families) {
    auto relaxed = [&](double scale, std::vector<ConstraintRows>* rows) {
      return relaxed_constraints(constraints_, f, scale, samples_, rows);
    };
    auto feasible = [&](double scale) {
      std::vector<ConstraintRows> rows = rows_;
      std::vector<std::shared_ptr<const Constraint>> cons = relaxed(scale, &rows);
      return feasible_with(cons, std::move(rows), guarantee);
    };
    auto points_feasible = [&](double scale) { return points_nonempty(relaxed(scale, nullptr), samples_, empty); };
    out[f] = empty.empty() ? search_scale(feasible, 1.0, 2.0, max_scale, rel_tolerance)
                           : scale_from_empty_points(points_feasible, feasible, max_scale, rel_tolerance);
  }
  return out;
}

std::string TimeScalingProblem::describe_relaxation(const std::map<std::string, double>& relaxation) {
  std::ostringstream os;
  std::vector<std::pair<double, std::string>> finite;
  for (const auto& [f, scale] : relaxation)
    if (std::isfinite(scale) && f != "all") finite.emplace_back(scale, f);
  std::sort(finite.begin(), finite.end());
  if (finite.empty()) {
    auto all = relaxation.find("all");
    if (all != relaxation.end() && std::isfinite(all->second))
      os << "feasible only with every family of limits x " << detail::fmt(std::ceil(all->second * 1e3) / 1e3);
    else if (relaxation.empty())
      os << "no constraint family can be relaxed to explain it";
    else
      os << "no single family of limits scaled up to x 1000 makes it feasible";
    return os.str();
  }
  // Four digits say enough, rounded up so that the printed scale is a feasible one.
  auto up4 = [](double v) {
    const double e = std::pow(10.0, std::floor(std::log10(v)) - 3);
    return detail::fmt(std::ceil(v / e) * e);
  };
  os << "feasible with ";
  for (size_t i = 0; i < finite.size(); ++i)
    os << (i ? " or " : "") << finite[i].second << " limits x " << up4(finite[i].first);
  return os.str();
}
}  // namespace pathpace
