#pragma once
// A primal simplex for the LP of one SLP window (sec. V.C) that uses the chain structure of eq. (26).
//
// Why. The first LP of a window is the Frank-Wolfe check at its greedy start, and on the arm corpus it nearly
// always certifies the window at once (with the step to its vertex): a GLPK call is mostly set-up and
// factorisation, while a primal simplex on the chain itself costs O(window) per pivot.
//
// The LP: minimise g·y over the window's rows and lo <= y <= hi (g = ∇T at the start θ). A basis is a set S of
// active constraints (rows, or a bound of a column), one per free column, nonsingular. Every row touches two
// neighbouring columns, so S can be matched to the columns (each constraint to a column it acts on), and in
// that order both B (constraints x columns) and its transpose are tridiagonal: the multipliers (Bᵀλ = -g) and
// an edge direction (B d = -e_p) cost one banded solve each. The matching is found earliest-deadline-first
// (a row of interval k can serve column k or k+1 only: an interval scheduling problem, where EDF finds a
// perfect matching whenever one exists). The greedy profile is a vertex (each free θ_j is at a bound or the
// top of a slice, where a row of interval j-1 or j is tight), so the simplex starts there; at the usual
// degenerate vertex (several rows tight at a point) a few pivots of length ~0 reach a dual feasible basis.
// Bland's rule (smallest index leaves, smallest index enters) rules out cycling; a pivot cap, a singular
// basis or an unbounded ray give up (the caller then runs GLPK).
//
// Nothing is trusted to the basis being optimal or to the simplex's arithmetic: with its multipliers clamped
// at 0, weak duality bounds the LP (as GlpkLp::lagrangian_bound does; d = g + Aᵀλ over the rows):
//     g·θ - min_{y in the window's set} g·y <= Σ_free j (d_j θ_j - min_{lo_j <= y_j <= hi_j} d_j y_j) + Σ_r λ_r (c_r - a_r·θ)
// at the start θ, valid for any λ >= 0. Returns that bound on the start's Frank-Wolfe gap (+inf if given up).

#include <algorithm>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "solve/reachability.hpp"

namespace pathpace::detail {

class ChainSimplex {
 public:
  /// The LP of window [a, a + m] of `chain` (its intervals' rows), lo <= θ <= hi on the window's points (local
  /// indices 0..m), columns first..last free (the others fixed at the start's values). Keeps references to
  /// chain, lo and hi.
  ChainSimplex(const Chain& chain, Eigen::Index a, Eigen::Index m, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
               Eigen::Index first, Eigen::Index last);

  /// From the vertex `theta` (θ_0..θ_m, feasible; each free point at a bound or where a row of an adjacent
  /// interval is tight, as the greedy profile is), minimises g·y by at most `max_pivots` pivots; returns the
  /// bound above on g·θ - min g·y (>= 0), or +inf if it gave up (no start basis, singular, pivot budget).
  /// warm: start from the basis the previous call ended with (optimal for its g) at its vertex(), which stays
  /// primal feasible for a new g (lo, hi and the rows are the same); `theta` is then any feasible point (the
  /// Frank-Wolfe iterate, on the segment to that vertex or at it): the bound is computed there, whatever
  /// vertex the simplex stands on.
  double gap(const Eigen::VectorXd& theta, const Eigen::VectorXd& g, int max_pivots, bool warm = false);

  /// The vertex the simplex ended at (after gap(): the LP's optimum if the bound is finite).
  const Eigen::VectorXd& vertex() const { return y_; }
  int pivots() const { return pivots_; }
  /// For tests, after a finite gap(g): whether the matching and B's coefficients that the pivots kept up
  /// incrementally are those computed from scratch for the final basis, and the multipliers solve Bᵀλ = -g
  /// (to 1e-12 of the terms' magnitude).
  bool fresh_state(const Eigen::VectorXd& g) const;

 private:
  struct Row {
    const Line* line;
    Eigen::Index k;  // interval (local): acts on columns k (α) and k + 1 (β)
  };
  // Constraint codes: >= 0 a row index; kHi / kLo the upper / lower bound of the column it is matched to.
  static constexpr int kHi = -1, kLo = -2;
  // start_basis's dynamic programme: a constraint that point i could take.
  struct Option {
    int code;      // kHi, kLo or a row index
    double cost;   // its relative slack at y_ (plus a tie-break: bounds, then earlier rows)
    double total;  // least total cost of points 0..i with this option at point i
    int prev;      // the option of point i - 1 on that least-cost path (index into opt_)
  };

  Eigen::Index col(std::size_t i) const { return first_ + static_cast<Eigen::Index>(i); }
  std::size_t local(Eigen::Index j) const { return static_cast<std::size_t>(j - first_); }
  bool free_col(Eigen::Index j) const { return j >= first_ && j <= last_; }
  // Point j's rows: interval j - 1's are [t0, t1), interval j's [t1, t2) (empty beyond the window's intervals).
  void point_rows(Eigen::Index j, std::size_t& t0, std::size_t& t1, std::size_t& t2) const {
    const std::size_t m = row_begin_.size() - 1, u = static_cast<std::size_t>(j);
    t0 = row_begin_[u > 0 ? u - 1 : 0];
    t1 = row_begin_[std::min(u, m)];
    t2 = row_begin_[std::min(u + 1, m)];
  }
  double coef(std::size_t owner, std::size_t i) const;
  bool start_basis();
  bool match();
  bool edf(std::size_t i0, std::size_t i_stop, std::vector<int>& mt, std::size_t& cl, std::size_t& cr) const;
  void coefs(std::size_t i0, std::size_t i1);
  void block(std::size_t i, std::size_t& bl, std::size_t& br) const;
  void fill(bool transpose, std::size_t i0, std::size_t i1);
  bool duals(const Eigen::VectorXd& g, std::size_t cl, std::size_t cr);
  bool step(std::size_t p, std::size_t& cl, std::size_t& cr);

  const Eigen::VectorXd &lo_, &hi_;
  Eigen::Index first_, last_;
  std::size_t n_;
  std::vector<Row> rows_;                 // the window's rows, by interval
  std::vector<std::size_t> row_begin_;    // interval k's rows: [row_begin_[k], row_begin_[k + 1])
  std::vector<char> in_basis_;           // per row: in S
  std::vector<Option> opt_;               // start_basis: the options of every point, point i's from opt_begin_[i]
  std::vector<std::size_t> opt_begin_;
  std::vector<int> bounds_, match_;  // bounds_[i]: kHi / kLo if column i's bound is in S, else 0
  std::vector<double> own_, left_, right_;  // per column: its constraint's coefficient on it, on column i-1, i+1
  std::vector<double> l_, d_, u_, u2_, rhs_, lambda_;
  std::vector<double> viol_;  // start_basis: each row's row_violation at y_
  Eigen::VectorXd y_;
  int pivots_ = 0;
  bool has_basis_ = false;
};

}  // namespace pathpace::detail
