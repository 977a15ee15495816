// What binds at an optimum of eq. (19), as a Projection::binding code: one rule for GLPK's optima and the
// dense simplex's. Private to lp/.
#pragma once

#include <cmath>

#include <glpk.h>

#include "lp/projection.hpp"

namespace pathpace::detail {

// The inequality row (its dual per unit of its normalised row: row_norm) or the bound of a column from
// `first_column` on with the largest dual; kBindingUnknown: none. stat(k) and dual(k) are variable k's
// status and reduced cost in GLPK's numbering, 0-based: row i's auxiliary at i, column j at rows + j.
template <class Stat, class Dual>
int binding_rule(const PolytopeLp& in, const double* row_norm, int first_column, Stat stat, Dual dual) {
  const int rows = static_cast<int>(in.A.rows()), cols = static_cast<int>(in.A.cols());
  int code = kBindingUnknown;
  double best = 0.0;
  for (int i = 0; i < rows; ++i) {
    const int st = stat(i);
    // An equality (e.g. Newton's law on an unactuated base) is structure, not a limit one could relax.
    if (st == GLP_BS || st == GLP_NS || in.row_lo[i] == in.row_hi[i]) continue;
    const double w = std::abs(dual(i)) * row_norm[i];
    if (w > best) best = w, code = 2 * i + (st == GLP_NU ? 1 : 0);
  }
  for (int j = first_column; j < cols; ++j) {
    if (stat(rows + j) == GLP_BS) continue;
    const double w = std::abs(dual(rows + j));
    if (w > best) best = w, code = -(j + 1);
  }
  return code;
}

}  // namespace pathpace::detail
