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
class SampledPath : public Path {
 public:
  /// s (m >= 2, strictly increasing); q, dq, ddq of shape (m, n).
  SampledPath(const Eigen::VectorXd& s, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq, const Eigen::MatrixXd& ddq);

  int dof() const override { return pieces_.dof(); }
  double s_begin() const override { return pieces_.s_begin(); }
  double s_end() const override { return pieces_.s_end(); }
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override {
    pieces_.evaluate(s, q, dq, ddq);
  }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                Eigen::MatrixXd& ddq) const override {
    pieces_.evaluate(s, q, dq, ddq);
  }

  const Eigen::VectorXd& samples() const { return pieces_.breakpoints(); }

 private:
  static PiecewisePolynomialPath build(const Eigen::VectorXd& s, const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                       const Eigen::MatrixXd& ddq);
  PiecewisePolynomialPath pieces_;
};

}  // namespace pathpace
