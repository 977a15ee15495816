#include "problem/sampling.hpp"

#include <algorithm>
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

std::vector<ConstraintRows> exact_rows_at(const std::vector<std::shared_ptr<const Constraint>>& constraints,
                                          const std::vector<ConstraintRows>& rows, const PathSamples& samples,
                                          Eigen::Index k) {
  PathSamples one;
  one.s = samples.s.segment(k, 1);
  one.q = samples.q.row(k);
  one.dq = samples.dq.row(k);
  one.ddq = samples.ddq.row(k);
  std::vector<ConstraintRows> out;
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::shared_ptr<const Constraint> e = i < constraints.size() ? constraints[i]->exact() : nullptr;
    if (e) {
      out.push_back(e->evaluate(one));
      continue;
    }
    // Row k alone (not a copy of every grid point's rows: feasible_set asks point by point).
    ConstraintRows r;
    r.a = rows[i].a.row(k);
    r.b = rows[i].b.row(k);
    r.c = rows[i].c.row(k);
    r.labels = rows[i].labels;
    const bool inexact =
        std::find(rows[i].inexact_points.begin(), rows[i].inexact_points.end(), k) != rows[i].inexact_points.end();
    r.inexact_points.assign(inexact ? 1 : 0, 0);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace pathpace::detail
