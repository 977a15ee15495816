#pragma once
// SolverOptions checked once, where they enter TimeScalingProblem::solve: every field, whatever the
// guarantee, so that no stage below re-checks one (they rely on these ranges).

#include "pathpace/solver_options.hpp"

namespace pathpace::detail {

/// Throws InvalidInput naming the first field out of its range ("<field> = <value> must be ...").
void validate(const SolverOptions& options);

}  // namespace pathpace::detail
