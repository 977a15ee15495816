// TimeScalingProblem::relaxation: how far each family of limits must widen for an infeasible problem to become
// feasible, by bisection on feasibility (reachability only, no SLP).
#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "solve/continuous.hpp"
#include "solve/grid_sets.hpp"
#include "solve/reachability.hpp"
#include "base/validate.hpp"

namespace pathpace {

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
  for (const std::string& f : families) {
    auto feasible = [&](double scale) {
      std::vector<ConstraintRows> rows = rows_;
      std::vector<std::shared_ptr<const Constraint>> cons = constraints_;
      for (size_t i = 0; i < constraints_.size(); ++i) {
        // "all": every family of the constraint at once (relaxed one after the other).
        std::shared_ptr<const Constraint> r;
        for (const std::string& fi : constraints_[i]->families()) {
          if (f != "all" && fi != f) continue;
          if (auto next = (r ? r : constraints_[i])->relaxed(fi, scale)) r = std::move(next);
        }
        if (r) {
          rows[i] = r->evaluate(samples_);
          cons[i] = std::move(r);
        }
      }
      return feasible_with(cons, std::move(rows), guarantee);
    };
    // Feasibility grows with the scale (each relaxed set contains the last): double until feasible,
    // then bisect on log(scale).
    double lo = 1.0, hi = 2.0;
    while (hi < max_scale && !feasible(hi)) {
      lo = hi;
      hi = std::min(4.0 * hi, max_scale);
    }
    if (hi >= max_scale && !feasible(max_scale)) {
      out[f] = std::numeric_limits<double>::infinity();
      continue;
    }
    while (hi > lo * (1.0 + rel_tolerance)) {
      const double mid = std::sqrt(lo * hi);
      (feasible(mid) ? hi : lo) = mid;
    }
    out[f] = hi;
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
