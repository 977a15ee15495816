#pragma once
// p''' of a path of polynomial pieces, for jerk limits (TimeScalingProblem::add_jerk_limits) and the jerk of a
// trajectory: the paths' own derivative, kept beside them.

#include <Eigen/Core>

#include "pathpace/path.hpp"

namespace pathpace::detail {

/// p''' at each s from the left and from the right piece of the path's polynomial() (they differ at a
/// breakpoint); InvalidInput naming the path kinds that have pieces when it has none.
void third_derivatives(const Path& path, const Eigen::VectorXd& s, Eigen::MatrixXd& left, Eigen::MatrixXd& right);

}  // namespace pathpace::detail
