#pragma once
/// @file piecewise_polynomial_path.hpp
/// A path given as polynomial pieces between breakpoints.

#include <vector>

#include <Eigen/Core>

#include "pathpace/path.hpp"

namespace pathpace {

// docstrings.txt @@ PiecewisePolynomialPath
/// @brief Polynomial pieces between breakpoints.
///
/// On [b_i, b_{i+1}], p(s) = Σ_j coefficients[i, j, :] (s - b_i)**j (lowest degree first). The domain
/// is [breakpoints[0], breakpoints[M]]; s outside it is clamped.
class PiecewisePolynomialPath : public Path {
 public:
  // docstrings.txt @@ PiecewisePolynomialPath.__init__
  /// @param breakpoints (M+1,): Strictly increasing.
  /// @param coefficients M matrices of shape (degree + 1, n), all alike: coefficients[i](j, :) multiplies
  ///   (s - breakpoints[i])^j on piece i.
  PiecewisePolynomialPath(Eigen::VectorXd breakpoints, std::vector<Eigen::MatrixXd> coefficients);

  int dof() const override { return dof_; }
  double s_begin() const override { return breakpoints_[0]; }
  double s_end() const override { return breakpoints_[breakpoints_.size() - 1]; }
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override;
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                Eigen::MatrixXd& ddq) const override;
  const PiecewisePolynomialPath* polynomial() const override { return this; }

  const Eigen::VectorXd& breakpoints() const { return breakpoints_; }
  const std::vector<Eigen::MatrixXd>& coefficients() const { return coefficients_; }
  /// Index i of the piece containing s (clamped), by binary search.
  Eigen::Index piece(double s) const;

 private:
  Eigen::VectorXd breakpoints_;
  std::vector<Eigen::MatrixXd> coefficients_;
  int dof_ = 0;
};

}  // namespace pathpace
