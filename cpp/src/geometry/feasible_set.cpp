#include "pathpace/feasible_set.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pathpace/errors.hpp"

namespace pathpace {

bool FeasibleSet::contains(double x, double u, double tol) const {
  if (!(tol >= 0.0) || !std::isfinite(tol)) throw InvalidInput("tol = " + std::to_string(tol) + " must be >= 0 and finite");
  // NaN compares false with every bound below (and inf times a zero coefficient is NaN), so it would
  // pass them all: the set holds finite points only.
  if (empty || !std::isfinite(x) || !std::isfinite(u)) return false;
  const double sx = std::max(1.0, std::abs(x));
  if (x < x_min - tol * sx || x > x_max + tol * sx) return false;
  for (Eigen::Index i = 0; i < halfplanes.rows(); ++i) {
    const double ax = halfplanes(i, 0) * x, bu = halfplanes(i, 1) * u, c = halfplanes(i, 2);
    if (ax + bu - c > tol * std::max({1.0, std::abs(ax), std::abs(bu), std::abs(c)})) return false;
  }
  return true;
}

}  // namespace pathpace
