#pragma once
/// @file path_samples.hpp
/// The path evaluated at the grid points: computed once per problem, read by every constraint.

#include <Eigen/Core>

namespace pathpace {

/// p, p', p'' at the grid s_0 < ... < s_N. Row k of q, dq, ddq belongs to s[k]; shapes (N+1, n).
struct PathSamples {
  Eigen::VectorXd s;
  Eigen::MatrixXd q;
  Eigen::MatrixXd dq;
  Eigen::MatrixXd ddq;

  Eigen::Index size() const { return s.size(); }
  Eigen::Index dof() const { return q.cols(); }
};

}  // namespace pathpace
