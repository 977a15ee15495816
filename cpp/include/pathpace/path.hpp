#pragma once
/// @file path.hpp
/// The geometric path q = p(s), s in [s_begin, s_end], and its first two derivatives.

#include <Eigen/Core>

namespace pathpace {

class PiecewisePolynomialPath;

/// A geometric path in joint space. Implementations are immutable after construction and
/// safe to evaluate from several threads at once.
class Path {
 public:
  virtual ~Path() = default;

  /// Number of coordinates n of q.
  virtual int dof() const = 0;
  virtual double s_begin() const = 0;
  virtual double s_end() const = 0;

  /// Evaluates p(s), p'(s), p''(s) at one s. s outside [s_begin, s_end] is clamped.
  /// Each output must have size dof().
  virtual void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                        Eigen::Ref<Eigen::VectorXd> ddq) const = 0;

  /// Batch evaluation: row i of each matrix is p, p', p'' at s[i]. Shapes (len(s), dof()).
  /// The default calls the single-point evaluate; paths can do better.
  virtual void evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                Eigen::MatrixXd& ddq) const;

  /// The path as polynomial pieces when it is one (CubicSplinePath, SampledPath, ...), else nullptr. What needs
  /// the pieces asks this, never the concrete type: exact bounds between grid points (guarantee = continuous),
  /// breakpoints in the automatic grid, the exact tail of a restart.
  virtual const PiecewisePolynomialPath* polynomial() const { return nullptr; }

  /// p(s) at each s: shape (len(s), dof()).
  Eigen::MatrixXd q(const Eigen::Ref<const Eigen::VectorXd>& s) const;
  /// p'(s) at each s: shape (len(s), dof()).
  Eigen::MatrixXd dq(const Eigen::Ref<const Eigen::VectorXd>& s) const;
  /// p''(s) at each s: shape (len(s), dof()).
  Eigen::MatrixXd ddq(const Eigen::Ref<const Eigen::VectorXd>& s) const;
};

}  // namespace pathpace
