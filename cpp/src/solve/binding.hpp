#pragma once
// Which constraint binds on each interval of a timed profile (Result::binding).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "solve/grid_sets.hpp"
#include "solve/reachability.hpp"
#include "pathpace/binding_labels.hpp"

namespace pathpace::detail {

/// Per interval k, the label of the row of eq. (26) (or the bound on θ at either end) with the least
/// slack relative to its terms at θ, if that slack is below `tolerance`; "" otherwise.
/// With `violation`: also the largest violation of any row of the chain or of the bounds x_lo <= θ <= x_hi,
/// each relative to max(1, |c|, |α θ_k|, |β θ_{k+1}|) (raise_violation, bound_violation), from the same pass
/// over the rows (after SLP both are needed, and a second pass over every row would cost as much again).
BindingLabels binding_labels(const Chain& chain, const GridSets& sets, const Eigen::VectorXd& theta,
                             double* violation = nullptr, double tolerance = 1e-6);

}  // namespace pathpace::detail
