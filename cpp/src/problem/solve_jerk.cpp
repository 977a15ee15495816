// TimeScalingProblem::solve with jerk limits: the problem without them (its timing is where the jerk rows are
// first linearised, and its T a lower bound of the continuous-time optimum), then solve/jerk_scp.hpp.
#include <cmath>

#include "base/validate.hpp"
#include "pathpace/time_scaling_problem.hpp"
#include "solve/jerk_scp.hpp"

namespace pathpace {

Result TimeScalingProblem::solve_jerk(const SolverOptions& options) const {
  if (options.guarantee != Guarantee::Grid)
    detail::fail("guarantee = 'continuous' is not implemented with jerk limits yet: use guarantee = 'grid' (the "
                 "limits then hold at the grid points)");
  const Eigen::Index n = intervals();
  if (n < 4)
    detail::fail("jerk limits need at least 4 grid intervals, the problem has " + std::to_string(n));
  // The second-order problem on the same rows, without the boundary s̈ rows (a relaxation of them): a start.
  Result res = solve_rows(rows_, nullptr, options);
  const double t2 = res.duration;
  if (!res.ok()) {
    res.message = "without jerk limits: " + res.message;
    return res;
  }
  detail::JerkInput in;
  in.samples = &samples_;
  JerkLimits::third_derivatives(*path_, samples_.s, in.p3_left, in.p3_right);
  in.jmin = jerk_->jmin();
  in.jmax = jerk_->jmax();
  in.rows = &rows_;
  in.sdot_begin = sdot_begin_;
  in.sdot_end = sdot_end_;
  in.zero_sddot_begin = zero_sddot_begin_;
  in.zero_sddot_end = zero_sddot_end_;
  in.theta_hint = res.sdot.array().square();
  in.max_iterations = options.max_iterations;
  in.tolerance = options.tolerance;
  in.lp_tolerance = options.lp_feasibility_tolerance;
  in.time_limit = options.time_limit;
  const detail::JerkOutput out = detail::solve_jerk(in);

  res.status = out.status;
  res.message = out.message;
  res.binding = BindingLabels(std::vector<std::string>(static_cast<size_t>(n)));
  res.stats.lp_solves += out.lp_solves;
  res.stats.jerk_iterations = out.iterations;
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
