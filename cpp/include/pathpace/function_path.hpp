#pragma once
/// @file function_path.hpp
/// A path from your own function of s: p, p', p'' on a vector of s (the C++ twin of Python's
/// pathpace.paths.CallbackPath).

#include <functional>

#include <Eigen/Core>

#include "pathpace/path.hpp"

namespace pathpace {

/// @brief A path whose p(s), p'(s), p''(s) come from a std::function on a vector of s: a path of another
/// library or an analytic curve, without sampling it first.
///
/// The function is called once per batch of s (the problem's grid, a trajectory's samples), with every s
/// clamped to [s_begin, s_end], and must fill q, dq, ddq with shape (len(s), dof). What it returns is
/// checked on every call: a wrong shape or a non-finite entry is an InvalidInput naming the entry and s.
/// It is called from the solver's threads, several at once: it must be safe to call concurrently (a pure
/// function of s is). The path has no polynomial pieces (polynomial() is nullptr), so
/// `guarantee = continuous` needs a PiecewisePolynomialPath or SampledPath instead.
class FunctionPath : public Path {
 public:
  /// Fills q, dq, ddq (the function resizes them) with p, p', p'' at each s: row i is s[i].
  using Function = std::function<void(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q,
                                      Eigen::MatrixXd& dq, Eigen::MatrixXd& ddq)>;

  /// @param function p, p', p'' on a vector of s (non-empty).
  /// @param dof Number of coordinates n (>= 1).
  /// @param s_begin,s_end The domain, finite with s_begin < s_end.
  /// @throws InvalidInput An empty function, dof < 1, or a bad domain.
  FunctionPath(Function function, int dof, double s_begin = 0.0, double s_end = 1.0);

  int dof() const override { return dof_; }
  double s_begin() const override { return s_begin_; }
  double s_end() const override { return s_end_; }
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override;
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                Eigen::MatrixXd& ddq) const override;

  /// The function given.
  const Function& function() const { return function_; }

 private:
  Function function_;
  int dof_;
  double s_begin_, s_end_;
};

}  // namespace pathpace
