#pragma once
/// @file path_samples.hpp
/// The path evaluated at the grid points: computed once per problem, read by every constraint.

#include <Eigen/Core>

namespace pathpace {

// docstrings.txt @@ PathSamples
/// @brief The path at the grid points, as Constraint.evaluate reads it (read-only).
///
/// Computed once per problem, read by every constraint. Row k of q, dq, ddq belongs to s[k].
struct PathSamples {
  // docstrings.txt @@ PathSamples.s
  /// (N+1,): The grid s_0 < ... < s_N.
  Eigen::VectorXd s;
  // docstrings.txt @@ PathSamples.q
  /// (N+1, n): p at s.
  Eigen::MatrixXd q;
  // docstrings.txt @@ PathSamples.dq
  /// (N+1, n): p' at s.
  Eigen::MatrixXd dq;
  // docstrings.txt @@ PathSamples.ddq
  /// (N+1, n): p'' at s.
  Eigen::MatrixXd ddq;

  Eigen::Index size() const { return s.size(); }
  // docstrings.txt @@ PathSamples.dof
  /// n.
  Eigen::Index dof() const { return q.cols(); }
};

}  // namespace pathpace
