#pragma once
/// @file sampled_path.hpp
/// A path known only at samples: q, q', q'' given at each s (e.g. from another planner).

#include <Eigen/Core>

#include "pathpace/path.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace {

// docstrings.txt @@ SampledPath
/// @brief A path known at samples: q, q', q'' given at each s (e.g. from another planner).
///
/// Between samples, the quintic Hermite interpolant: C², and exact at every sample, so a grid on the
/// samples sees exactly the data given and a trajectory evaluated in between is smooth.
class SampledPath : public PiecewisePolynomialPath {
 public:
  // docstrings.txt @@ SampledPath.__init__
  /// @param s (m,): Strictly increasing, m >= 2.
  /// @param q,dq,ddq (m, n): p, p', p'' at the samples.
  SampledPath(const Eigen::VectorXd& s, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq);

  const Eigen::VectorXd& samples() const { return breakpoints(); }

 private:
  static PiecewisePolynomialPath build(const Eigen::VectorXd& s, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                       const Eigen::MatrixXd& ddq);
};

}  // namespace pathpace
