// TimeScalingProblem::solve with jerk limits: the problem without them (its timing is where the jerk rows are
// first linearised, and its T a lower bound of the continuous-time optimum), then solve/jerk_scp.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "base/validate.hpp"
#include "pathpace/time_scaling_problem.hpp"
#include "solve/jerk_scp.hpp"
#include "paths/third_derivatives.hpp"

namespace pathpace {

// A rest end's interval is one constant-jerk ramp (solve/jerk_scp.hpp), so its length fixes the ramp's: on a
// uniform grid a ramp much shorter than the interval (loose jerk limits) is stretched over it, and one much longer
// is resolved by intervals of s̈ linear in s, which lose part of the jerk. The grid therefore ends each rest
// interval where the ramp to the no-jerk optimum's s̈ there, at the largest jerk p' allows, ends:
// s_r = b³ / (6 j²) (s = j t³/6, s̈ = j t), dropping the grid points inside and those closer than a quarter
// interval beyond it.
Eigen::VectorXd TimeScalingProblem::jerk_grid(const Result& second_order) const {
  const Eigen::VectorXd& s = samples_.s;
  const Eigen::Index n = intervals();
  for (const auto& c : constraints_)
    if (c->per_grid_point()) return s;  // rows given per grid point: no other grid has them
  auto ramp = [&](Eigen::Index point, double b) {
    double j = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < samples_.dof(); ++i) {
      const double d = samples_.dq(point, i);
      if (d != 0) j = std::min(j, (d > 0 ? jerk_->jmax()[i] : -jerk_->jmin()[i]) / std::abs(d));
    }
    return b > 0 && std::isfinite(j) ? b * b * b / (6 * j * j) : 0.0;
  };
  const double length = s[n] - s[0];
  double head = sdot_begin_ == 0 ? ramp(0, second_order.sddot[0]) : 0.0;
  double tail = sdot_end_ == 0 ? ramp(n, -second_order.sddot[n - 1]) : 0.0;
  // A ramp within 1 % of the interval keeps the grid; at most a quarter of the path on each side, at least a
  // thousandth of the interval (a ramp shorter than that costs less than its rounding: loose or no jerk limits).
  const double ds0 = s[1] - s[0], dsn = s[n] - s[n - 1];
  if (sdot_begin_ == 0) head = std::max(head, 1e-3 * ds0);
  if (sdot_end_ == 0) tail = std::max(tail, 1e-3 * dsn);
  if (std::abs(head - ds0) < 1e-2 * ds0) head = 0;
  if (std::abs(tail - dsn) < 1e-2 * dsn) tail = 0;
  head = std::min(head, 0.25 * length), tail = std::min(tail, 0.25 * length);
  // A ramp that does not reach that s̈ (a short move, s̈ back to 0 before it) covers 1/6 of the acceleration
  // phase (s = j t³/6 up to t_1, s_1 = j t_1³/6 out of j t_1³ for the symmetric ramp up and down): at most 1/6 of
  // the stretch before the no-jerk s̈ first changes sign.
  Eigen::Index up = 0, down = n - 1;
  while (up < n - 1 && second_order.sddot[up] > 0) ++up;
  while (down > 0 && second_order.sddot[down] < 0) --down;
  head = std::min(head, (s[up] - s[0]) / 6), tail = std::min(tail, (s[n] - s[down + 1]) / 6);
  if (head == 0 && tail == 0) return s;
  std::vector<double> g{s[0]};
  if (head > 0) g.push_back(s[0] + head);
  const double lo = head > 0 ? s[0] + head + 0.25 * std::min(ds0, head) : s[0];
  const double hi = tail > 0 ? s[n] - tail - 0.25 * std::min(dsn, tail) : s[n];
  for (Eigen::Index k = 1; k < n; ++k)
    if (s[k] > lo && s[k] < hi) g.push_back(s[k]);
  if (tail > 0) g.push_back(s[n] - tail);
  g.push_back(s[n]);
  if (g.size() < 6) return s;  // keep N >= 4 and a linear interval between the ramps
  return Eigen::Map<const Eigen::VectorXd>(g.data(), static_cast<Eigen::Index>(g.size()));
}

Result TimeScalingProblem::solve_jerk(const SolverOptions& options, bool adapt_grid) const {
  if (options.guarantee != Guarantee::Grid)
    detail::fail("guarantee = 'continuous' is not implemented with jerk limits yet: use guarantee = 'grid' (the "
                 "limits then hold at the grid points)");
  const Eigen::Index n = intervals();
  if (n < 4)
    detail::fail("jerk limits need at least 4 grid intervals, the problem has " + std::to_string(n));
  // The second-order problem on the same rows, without the boundary s̈ rows (a relaxation of them): a start.
  // Rows refined on demand (Constraint::refines) are refined for it, and again for each jerk-limited timing.
  std::vector<ConstraintRows> refined;
  std::vector<RefineMemory> memory;
  if (refines()) refined = rows_;
  const std::vector<ConstraintRows>& rows = refines() ? refined : rows_;
  Result res = refines() ? solve_refined(refined, nullptr, options, memory) : solve_rows(rows_, nullptr, options);
  const double t2 = res.duration;
  if (!res.ok()) {
    res.message = "without jerk limits: " + res.message;
    return res;
  }
  // A rest inside the path (rows that force ṡ = 0 there: a contact phase's no-impact rule, or ṡ² <= 0) cannot be
  // reached with s̈ linear in s between grid points (θ then falls quadratically and the time to reach 0 is
  // infinite); only the ends have their constant-jerk ramps. Said at once, where the start LP and the rounds
  // took a minute to end in NUMERICAL_ERROR on the ladder.
  for (Eigen::Index k = 1; k < n; ++k)
    if (res.sdot[k] <= 0)
      detail::fail("jerk limits: the timing must stop (ṡ = 0) at grid index " + std::to_string(k) + ", s = " +
                   detail::fmt(samples_.s[k]) +
                   ", inside the path (a contact phase's no-impact rule, or a row that bounds ṡ² by 0); the jerk "
                   "solve takes rests at the path's ends only: split the path there, or relax that row (for "
                   "contact phases, impact_tolerance)");
  if (adapt_grid) {
    const Eigen::VectorXd grid = jerk_grid(res);
    if (grid.size() != samples_.s.size() || grid != samples_.s) {
      TimeScalingProblem adapted(path_, grid);
      for (const auto& c : constraints_) adapted.add_constraint(c);
      adapted.set_settings(settings());
      adapted.contact_drift_ = contact_drift_;
      adapted.jerk_ = jerk_;
      return adapted.solve_jerk(options, false);
    }
  }
  detail::JerkInput in;
  in.samples = &samples_;
  detail::third_derivatives(*path_, samples_.s, in.p3_left, in.p3_right);
  in.jmin = jerk_->jmin();
  in.jmax = jerk_->jmax();
  in.rows = &rows;
  in.sdot_begin = sdot_begin_;
  in.sdot_end = sdot_end_;
  in.zero_sddot_begin = zero_sddot_begin_;
  in.zero_sddot_end = zero_sddot_end_;
  in.theta_hint = res.sdot.array().square();
  in.max_iterations = options.max_iterations;
  in.primal_dual = options.method == Method::Auto;
  in.tolerance = options.tolerance;
  in.lp_tolerance = options.lp_feasibility_tolerance;
  in.time_limit = options.time_limit;
  detail::JerkOutput out;
  for (;;) {
    out = detail::solve_jerk(in);
    if (!refines() || out.theta.size() != samples_.s.size()) break;
    // Each constraint's rows where this timing (θ and s̈ at the grid points) lies beyond what they know; its
    // start (the second-order timing, feasible for the exact rows) stays feasible for the refined ones.
    int changed = 0, lps = 0;
    for (size_t i = 0; i < constraints_.size(); ++i) {
      if (!constraints_[i]->refines()) continue;
      const int before = memory[i].lp_solves;
      changed += constraints_[i]->refine(samples_, out.theta, &out.b, refined[i], memory[i]);
      lps += memory[i].lp_solves - before;
    }
    res.stats.projection_lp_solves += lps;
    if (changed == 0) break;
    ++res.stats.projection_rounds;
  }

  res.status = out.status;
  res.message = out.message;
  res.binding = BindingLabels(std::vector<std::string>(static_cast<size_t>(n)));
  res.stats.lp_solves += out.lp_solves;
  res.stats.jerk_iterations = out.structured ? out.newton_steps : out.iterations;
  res.stats.jerk_linearised_gap = out.gap;
  res.stats.gap = out.gap;
  res.stats.second_order_duration = t2;
  const bool timed = out.status == Status::Optimal || out.status == Status::IterationLimit || out.status == Status::TimeLimit;
  if (!timed) {
    res.sdot.resize(0), res.times.resize(0), res.sddot.resize(0);
    res.duration = std::nan("");
    return res;
  }
  res.sdot = out.theta.cwiseMax(0.0).cwiseSqrt();
  res.sddot_points = out.b;
  const Eigen::VectorXd dt = detail::jerk_interval_times(samples_.s, out.theta, out.b);
  res.times.resize(n + 1);
  res.sddot.resize(n);
  res.times[0] = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    res.times[k + 1] = res.times[k] + dt[k];
    res.sddot[k] = (res.sdot[k + 1] - res.sdot[k]) / dt[k];
  }
  res.duration = res.times[n];
  return res;
}

}  // namespace pathpace
