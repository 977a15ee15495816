#pragma once
// A symmetric band matrix of half-bandwidth 4 and its LDLᵀ without pivoting: the KKT systems of the structured
// jerk solve (solve/jerk_newton.cpp), quasi-definite after a tiny regularisation (Vanderbei 1995), so the
// factorisation exists in any order.
//
// The loops are written for the fixed band (rows >= 4 have all their entries) with the pivots' reciprocals
// kept, so that a row's substitution is four independent products, not a chain of subtractions: the KKT system
// is solved six times per interior-point iteration (predictor and corrector, two refinements each).

#include <algorithm>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace pathpace::detail {

class BandLdlt {
 public:
  static constexpr Eigen::Index kBand = 4;

  explicit BandLdlt(Eigen::Index m)
      : m_(m), a_(static_cast<size_t>(m * kW)), f_(a_.size()), inv_d_(static_cast<size_t>(m)) {}
  Eigen::Index size() const { return m_; }
  void clear() { std::fill(a_.begin(), a_.end(), 0.0); }
  /// A(i, j) += v (and A(j, i)); |i - j| <= kBand.
  void add(Eigen::Index i, Eigen::Index j, double v) {
    if (i < j) std::swap(i, j);
    a_[idx(i, j)] += v;
  }
  double at(Eigen::Index i, Eigen::Index j) const {
    if (i < j) std::swap(i, j);
    return i - j > kBand ? 0.0 : a_[idx(i, j)];
  }
  /// This matrix := diag(scale) K diag(scale).
  void scaled(const BandLdlt& K, const Eigen::VectorXd& scale);
  /// Factors A + diag(reg); false if a pivot is not finite or zero.
  bool factor(const Eigen::VectorXd& reg);
  /// x := (A + diag(reg))⁻¹ x with the last factor().
  void solve(Eigen::VectorXd& x) const;
  /// y = A x (unregularised).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

 private:
  static constexpr Eigen::Index kW = kBand + 1;  // row i holds A(i, i - e), e = 0..kBand
  size_t idx(Eigen::Index i, Eigen::Index j) const { return static_cast<size_t>(i * kW + (i - j)); }
  Eigen::Index m_;
  std::vector<double> a_, f_, inv_d_;
};

}  // namespace pathpace::detail
