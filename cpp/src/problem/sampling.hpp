#pragma once
// What every way of building a problem's rows shares: the path sampled at the grid (checked finite), and a
// constraint evaluated with its time recorded (SolverStats::time_constraints).

#include <chrono>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/path.hpp"
#include "pathpace/path_samples.hpp"

namespace pathpace::detail {

// x · 0 is 0 for every finite x and NaN for ±inf and NaN, so the sum is 0 exactly when all are finite.
// Four running sums so that the loop is not one chain of dependent additions (Eigen's allFinite() was
// the larger part of adding velocity or acceleration limits). With cap, +inf is first mapped to cap
// (allowed), NaN and -inf stay.
template <bool kAllowPlusInf, typename Matrix>
bool finite_entries(const Matrix& m) {
  const double* p = m.data();
  const Eigen::Index n = m.size();
  const double cap = std::numeric_limits<double>::max();
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  auto term = [cap](double x) {
    if (kAllowPlusInf) x = cap < x ? cap : x;
    return x * 0.0;
  };
  Eigen::Index i = 0;
  for (; i + 3 < n; i += 4)
    for (int j = 0; j < 4; ++j) s[j] += term(p[i + j]);
  for (; i < n; ++i) s[0] += term(p[i]);
  return s[0] + s[1] + s[2] + s[3] == 0.0;
}

// p, p', p'' at samples.s (the grid of a new problem, or one with a contact switch inserted), with the entry
// that is not finite named.
void sample_path(const Path& path, PathSamples& samples);

// Each constraint's rows at grid point k alone (one row each): `rows`' row k, or for a constraint whose rows
// are refined on demand (Constraint::refines) its exact() constraint evaluated at that point (what the rows
// bound from outside). For what must hold exactly at one point: feasible_set, the re-check of an infeasibility.
std::vector<ConstraintRows> exact_rows_at(const std::vector<std::shared_ptr<const Constraint>>& constraints,
                                          const std::vector<ConstraintRows>& rows, const PathSamples& samples,
                                          Eigen::Index k);

// A constraint's rows on `samples` with the time they took (summed into SolverStats::time_constraints): every
// evaluation that ends up in the problem's rows goes through here, so that no row keeps another's time.
ConstraintRows timed_evaluate(const Constraint& constraint, const PathSamples& samples);

}  // namespace pathpace::detail
