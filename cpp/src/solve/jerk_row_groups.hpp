#pragma once
// The inequality rows of the structured jerk solve (solve/jerk_newton.cpp), stored by the unknowns they read.
//
// Every row reads at most three unknowns, and many rows read the same three: a grid point's limit rows read
// (θ_k, b_k), its jerk rows on one side (b_{k∓1}, b_k, θ_k) (solve/jerk_rows.hpp). Rows on the same unknowns
// form a group, stored contiguously column by column, so a pass over the rows (slacks, a·d, Σ w a, the Hessian
// Σ w a aᵀ) loads the group's unknowns once, sums its entries in registers, and runs over plain arrays without a
// branch per entry. An interior-point iteration makes about ten such passes over ~40 rows per grid point; stored
// row by row (JerkRow, with its column search) they were most of its time.
//
// A jerk group's θ column is slot 2; its θ coefficient and right-hand side are the tangent of J/√θ at the point
// of linearisation (JerkLimitRow::relinearise), written by relinearise().

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "solve/jerk_rows.hpp"

namespace pathpace::detail {

class JerkRowGroups {
 public:
  struct Group {
    int col[3] = {-1, -1, -1};  ///< the unknowns read; -1: an unused slot (its coefficients are 0)
    Eigen::Index point = -1;    ///< a jerk group's grid point (θ_point in slot 2); -1 for limit rows
    std::size_t begin = 0, end = 0;
  };

  /// `point`: limit rows on free unknowns only (fixed ones moved to the right-hand side); `jerk`: the jerk rows,
  /// whose terms on unknowns that are not `free` are dropped (the caller's fixed values are 0). The jerk rows are
  /// linearised at θ = 1 until relinearise() is called.
  JerkRowGroups(const std::vector<JerkRow>& point, const std::vector<JerkLimitRow>& jerk,
                const std::vector<char>& free);

  std::size_t size() const { return rhs_.size(); }
  const std::vector<Group>& groups() const { return groups_; }

  /// The jerk rows linearised at x̄ (θ̄ floored at 1e-300, as JerkLimitRow::linearised).
  void relinearise(const Eigen::VectorXd& xbar);
  /// s_r = rhs_r - a_r·x; whether every s_r > 0 (false if one is NaN).
  bool slacks(const Eigen::VectorXd& x, double* s) const;
  /// out_r = a_r·d.
  void products(const Eigen::VectorXd& d, double* out) const;
  /// g += Σ_r w_r a_r.
  void scatter(const double* w, Eigen::VectorXd& g) const;
  /// Σ_r w_r rhs_r.
  double weighted_rhs(const double* w) const;
  /// add(c_i, c_j, Σ_r w_r a_ri a_rj) for each pair of a group's used slots, i >= j (each pair once per group).
  template <class Add>
  void hessian(const double* w, Add&& add) const {
    for (const Group& g : groups_) {
      double h00 = 0, h10 = 0, h11 = 0, h20 = 0, h21 = 0, h22 = 0;
      for (std::size_t r = g.begin; r < g.end; ++r) {
        const double a0 = v0_[r], a1 = v1_[r], a2 = v2_[r], wr = w[r];
        const double w0 = wr * a0, w1 = wr * a1, w2 = wr * a2;
        h00 += w0 * a0, h10 += w1 * a0, h11 += w1 * a1;
        h20 += w2 * a0, h21 += w2 * a1, h22 += w2 * a2;
      }
      const double h[6] = {h00, h10, h11, h20, h21, h22};
      int at = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j <= i; ++j, ++at)
          if (g.col[i] >= 0 && g.col[j] >= 0) add(g.col[i], g.col[j], h[at]);
    }
  }

 private:
  void load(const Group& g, const Eigen::VectorXd& x, double& x0, double& x1, double& x2) const {
    x0 = g.col[0] >= 0 ? x[g.col[0]] : 0.0;
    x1 = g.col[1] >= 0 ? x[g.col[1]] : 0.0;
    x2 = g.col[2] >= 0 ? x[g.col[2]] : 0.0;
  }
  std::vector<Group> groups_;
  std::vector<double> v0_, v1_, v2_, rhs_;
  std::vector<double> lin_theta_, J_;  ///< per row: a jerk row's θ coefficient before the tangent's, and its J
};

}  // namespace pathpace::detail
