#pragma once
/// @file linear_constraint.hpp
/// Any constraint linear in (x, u) given per grid point: lo <= A·x + B·u + C <= hi.

#include <string>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"

namespace pathpace {

// docstrings.txt @@ LinearConstraint
/// @brief lo <= A·x + B·u + C <= hi at every grid point (x = ṡ², u = s̈).
///
/// Given on the problem's grid: row k holds the r coefficients at s_k. This is how torques from any
/// dynamics source and user-defined Cartesian limits enter. lo may be -inf and hi +inf (one-sided); lo ==
/// hi makes an equality.
class LinearConstraint : public Constraint {
 public:
  // docstrings.txt @@ LinearConstraint.__init__
  /// @param A,B,C,lo,hi (N+1, r): Row k holds the coefficients at grid point s_k; lo may be -inf and hi +inf.
  /// @param label Names the rows in infeasibility reports.
  LinearConstraint(Eigen::MatrixXd A, Eigen::MatrixXd B, Eigen::MatrixXd C, Eigen::MatrixXd lo,
                   Eigen::MatrixXd hi, std::string label = "linear");

  std::string name() const override { return label_; }
  /// Throws InvalidInput if the arrays do not have N+1 rows for the samples' grid.
  ConstraintRows evaluate(const PathSamples& samples) const override;
  /// Given per grid point: no value between grid points (Constraint::per_grid_point).
  bool per_grid_point() const override { return true; }
  /// The rows of the grid points `kept`, in that order.
  std::shared_ptr<const Constraint> at_grid_points(const std::vector<Eigen::Index>& kept) const override;

  const Eigen::MatrixXd& A() const { return A_; }
  const Eigen::MatrixXd& B() const { return B_; }
  const Eigen::MatrixXd& C() const { return C_; }
  const Eigen::MatrixXd& lo() const { return lo_; }
  const Eigen::MatrixXd& hi() const { return hi_; }
  const std::string& label() const { return label_; }

 private:
  Eigen::MatrixXd A_, B_, C_, lo_, hi_;
  std::string label_;
};

}  // namespace pathpace
