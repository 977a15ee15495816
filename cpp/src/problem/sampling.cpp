#include "problem/sampling.hpp"

#include <cmath>
#include <string>

#include "base/clock.hpp"
#include "base/validate.hpp"

namespace pathpace::detail {

void sample_path(const Path& path, PathSamples& samples) {
  path.evaluate(samples.s, samples.q, samples.dq, samples.ddq);
  if (finite_entries<false>(samples.q) && finite_entries<false>(samples.dq) && finite_entries<false>(samples.ddq))
    return;  // the element-wise loop below only names the entry that is not
  for (Eigen::Index k = 0; k < samples.size(); ++k)
    for (Eigen::Index j = 0; j < samples.dof(); ++j)
      if (!std::isfinite(samples.q(k, j)) || !std::isfinite(samples.dq(k, j)) || !std::isfinite(samples.ddq(k, j)))
        detail::fail("path is not finite at grid[" + std::to_string(k) + "] = " + detail::fmt(samples.s[k]) +
                     " (coordinate " + std::to_string(j) + ")");
}

ConstraintRows timed_evaluate(const Constraint& constraint, const PathSamples& samples) {
  const auto t0 = std::chrono::steady_clock::now();
  ConstraintRows rows = constraint.evaluate(samples);
  rows.seconds = seconds_since(t0);
  return rows;
}

}  // namespace pathpace::detail
