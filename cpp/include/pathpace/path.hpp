#pragma once
/// @file path.hpp
/// The geometric path q = p(s), s in [s_begin, s_end], and its first two derivatives.

#include <Eigen/Core>

namespace pathpace {

class PiecewisePolynomialPath;

// docstrings.txt @@ Path
/// @brief A geometric path q = p(s) for s in [s_begin, s_end] (abstract).
///
/// Joint coordinates q are in rad (revolute) or m (prismatic); s is dimensionless, so p' = dq/ds and
/// p'' = d²q/ds² are in rad (or m) per unit s. Implementations are immutable after construction and safe
/// to evaluate from several threads at once. `path(s, order)` evaluates it as toppra's interpolators do.
class Path {
 public:
  virtual ~Path() = default;

  // docstrings.txt @@ Path.dof
  /// Number of coordinates n of q.
  virtual int dof() const = 0;
  // docstrings.txt @@ Path.s_begin
  /// First value of s.
  virtual double s_begin() const = 0;
  // docstrings.txt @@ Path.s_end
  /// Last value of s.
  virtual double s_end() const = 0;

  // docstrings.txt @@ Path.evaluate
  /// @brief (p(s), p'(s), p''(s)) at once; shapes as in `q`.
  ///
  /// Into q, dq, ddq at one s (each of size dof()); s outside [s_begin, s_end] is clamped. The overload for
  /// a vector s fills matrices of shape (len(s), dof()).
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

  // docstrings.txt @@ Path.q
  /// @brief p(s).
  ///
  /// @param s (m,): Path parameter, clamped to [s_begin, s_end].
  /// @return (len(s), dof()): row i is p(s[i]).
  Eigen::MatrixXd q(const Eigen::Ref<const Eigen::VectorXd>& s) const;
  // docstrings.txt @@ Path.dq
  /// @brief p'(s) = dq/ds: (n,) for a scalar s, (m, n) for an array.
  ///
  /// @return (len(s), dof()): row i is p'(s[i]).
  Eigen::MatrixXd dq(const Eigen::Ref<const Eigen::VectorXd>& s) const;
  // docstrings.txt @@ Path.ddq
  /// @brief p''(s) = d²q/ds²: (n,) for a scalar s, (m, n) for an array.
  ///
  /// @return (len(s), dof()): row i is p''(s[i]).
  Eigen::MatrixXd ddq(const Eigen::Ref<const Eigen::VectorXd>& s) const;
};

}  // namespace pathpace
