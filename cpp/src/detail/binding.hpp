#pragma once
// Which constraint binds on each interval of a timed profile (Result::binding).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "detail/grid_sets.hpp"
#include "detail/reachability.hpp"
#include "pathpace/binding_labels.hpp"

namespace pathpace::detail {

/// Per interval k, the label of the row of eq. (26) (or the bound on θ at either end) with the least
/// slack relative to its terms at θ, if that slack is below `tolerance`; "" otherwise.
BindingLabels binding_labels(const Chain& chain, const GridSets& sets, const Eigen::VectorXd& theta,
                             double tolerance = 1e-6);

}  // namespace pathpace::detail
