#pragma once
// The tail [s0, s_end] of a path, for TimeScalingProblem::restarted: the same p(s) on a shorter domain.

#include <algorithm>
#include <memory>

#include "pathpace/path.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace::detail {

class SubPath final : public Path {
 public:
  SubPath(std::shared_ptr<const Path> parent, double s0) : parent_(std::move(parent)), s0_(s0) {}
  int dof() const override { return parent_->dof(); }
  double s_begin() const override { return s0_; }
  double s_end() const override { return parent_->s_end(); }
  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override {
    parent_->evaluate(std::max(s, s0_), q, dq, ddq);  // clamped like every path (the parent clamps the end)
  }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                Eigen::MatrixXd& ddq) const override {
    parent_->evaluate(s.cwiseMax(s0_), q, dq, ddq);  // the parent's batch evaluation, if it has a fast one
  }
  const std::shared_ptr<const Path>& parent() const { return parent_; }

 private:
  std::shared_ptr<const Path> parent_;
  double s0_;
};

/// The tail [s0, s_end] of a piecewise-polynomial path as one: the piece containing s0 re-expanded about
/// s0 (Taylor shift of its coefficients), the later pieces as they are. Keeps what needs polynomial
/// pieces (guarantee = continuous) working on restarts.
inline std::shared_ptr<const PiecewisePolynomialPath> polynomial_tail(const PiecewisePolynomialPath& p, double s0) {
  const Eigen::VectorXd& bp = p.breakpoints();
  const Eigen::Index i0 = p.piece(s0), M = bp.size() - 1;
  Eigen::VectorXd b(M - i0 + 1);
  b[0] = s0;
  b.tail(M - i0) = bp.tail(M - i0);
  std::vector<Eigen::MatrixXd> c(p.coefficients().begin() + i0, p.coefficients().end());
  const Eigen::MatrixXd old = c[0];
  const Eigen::Index D = old.rows() - 1;
  const double x0 = s0 - bp[i0];
  for (Eigen::Index m = 0; m <= D; ++m) {
    // c'_m = Σ_{i>=m} c_i C(i, m) x0^(i-m), by Horner in x0.
    Eigen::RowVectorXd v = Eigen::RowVectorXd::Zero(old.cols());
    for (Eigen::Index i = D; i >= m; --i) {
      double binom = 1.0;
      for (Eigen::Index r = 0; r < m; ++r) binom = binom * static_cast<double>(i - r) / static_cast<double>(r + 1);
      v = v * x0 + binom * old.row(i);
    }
    c[0].row(m) = v;
  }
  return std::make_shared<PiecewisePolynomialPath>(std::move(b), std::move(c));
}

/// The tail [s0, s_end] of any path (s0 in [s_begin, s_end)): the path itself at s0 = s_begin, polynomial
/// pieces again for a polynomial path, otherwise a SubPath evaluating the parent.
inline std::shared_ptr<const Path> path_tail(std::shared_ptr<const Path> path, double s0) {
  if (s0 == path->s_begin()) return path;
  if (const PiecewisePolynomialPath* pp = path->polynomial()) return polynomial_tail(*pp, s0);
  return std::make_shared<SubPath>(std::move(path), s0);
}

}  // namespace pathpace::detail
