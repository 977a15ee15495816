// TimeScalingProblem::restarted: the problem from (s0, ṡ0) onward, on the grid points after s0 (online re-timing).
#include "pathpace/time_scaling_problem.hpp"

#include <algorithm>
#include <cmath>

#include "paths/sub_path.hpp"
#include "base/validate.hpp"

namespace pathpace {

TimeScalingProblem TimeScalingProblem::restarted(double s0, double sdot0) const {
  const Use use(*this, Use::Read, "restarted");
  if (jerk_)
    detail::fail("restarted: not implemented with jerk limits yet (the running trajectory's s̈ at s0 would have to "
                 "be a boundary state)");
  const Eigen::Index n = intervals();
  const double a = samples_.s[0], b = samples_.s[n];
  if (!std::isfinite(s0) || s0 < a || s0 >= b)
    detail::fail("s0 = " + detail::fmt(s0) + " must be in [s_begin, s_end) = [" + detail::fmt(a) + ", " +
                 detail::fmt(b) + ")");
  if (!std::isfinite(sdot0) || sdot0 < 0.0) detail::fail("sdot0 = " + detail::fmt(sdot0) + " must be >= 0 and finite");
  // The new grid and, for each of its points, the old grid index (-1: s0 is not an old grid point).
  const Eigen::Index k0 = static_cast<Eigen::Index>(std::upper_bound(samples_.s.data(), samples_.s.data() + n + 1, s0) -
                                                    samples_.s.data()) - 1;
  std::vector<double> g{s0};
  std::vector<Eigen::Index> kept{samples_.s[k0] == s0 ? k0 : -1};
  for (Eigen::Index k = k0 + 1; k <= n; ++k) {
    // A grid point a hair beyond s0 would make an interval of width ~0 (a wasted, ill-conditioned row
    // pair); the end point always stays.
    if (k < n && samples_.s[k] - s0 <= 1e-9 * (samples_.s[k] - samples_.s[k - 1])) continue;
    g.push_back(samples_.s[k]);
    kept.push_back(k);
  }
  std::shared_ptr<const Path> tail = s0 == a ? path_ : detail::path_tail(path_, s0);
  TimeScalingProblem p(std::move(tail), Eigen::Map<const Eigen::VectorXd>(g.data(), static_cast<Eigen::Index>(g.size())));
  for (const auto& c : constraints_) {
    if (!c->per_grid_point()) {
      p.add_constraint(c);
      continue;
    }
    // Rows given per grid point have no value between grid points (they may come from any dynamics).
    if (kept[0] < 0) {
      const Eigen::Index near = k0 < n && samples_.s[k0 + 1] - s0 < s0 - samples_.s[k0] ? k0 + 1 : k0;
      detail::fail("restarted: s0 = " + detail::fmt(s0) + " is not a grid point (nearest: grid[" + std::to_string(near) +
                   "] = " + detail::fmt(samples_.s[near]) + ") and constraint '" + c->name() +
                   "' is given per grid point (no value between grid points): restart at a grid point");
    }
    p.add_constraint(c->at_grid_points(kept));
  }
  ProblemSettings s = settings();
  s.sdot_begin = sdot0;
  if (s0 != a) s.zero_sddot_begin = false;  // a running trajectory's s̈ at s0 is free
  p.set_settings(s);
  return p;
}

}  // namespace pathpace
