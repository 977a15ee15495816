#pragma once
/// @file sampled_path.hpp
/// A path known only at samples: q, q', q'' given at each s (e.g. from another planner).

#include <Eigen/Core>

#include "pathpace/path.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace {

/// Between samples, the quintic Hermite interpolant: it reproduces the given q, q', q'' exactly at every
/// sample and is C2, so a grid on the samples sees exactly the data given and a trajectory evaluated
/// in between is smooth.
class SampledPath : public PiecewisePolynomialPath {
 public:
  /// s (m >= 2, strictly increasing); q, dq, ddq of shape (m, n).
  SampledPath(const Eigen::VectorXd& s, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq);

  const Eigen::VectorXd& samples() const { return breakpoints(); }

 private:
  static PiecewisePolynomialPath build(const Eigen::VectorXd& s, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                       const Eigen::MatrixXd& ddq);
};

}  // namespace pathpace
