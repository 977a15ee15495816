#pragma once
// The pieces of a jerk-limited timing that both of its solvers use (solve/jerk_scp.hpp): the grid's shape, the
// exact time T(θ, b) and its 8-point Gauss-Legendre form with gradient and Hessian, the rows (per-point limits,
// consistency of θ and b, jerk rows before their linearisation) and the exact-consistency repair.
//
// Unknowns x = (θ_0 .. θ_n, b_0 .. b_n): θ = ṡ², b = s̈ at the grid points (docs/method.md "Jerk limits").

#include <chrono>
#include <vector>

#include <Eigen/Core>

#include "solve/jerk_scp.hpp"

namespace pathpace::detail {

/// Which ends are rest ends (base/jerk_interval.hpp), the grid's intervals.
struct JerkShape {
  Eigen::Index n = 0;  ///< intervals
  Eigen::VectorXd ds;
  bool rest0 = false, restN = false;
  bool rest_interval(Eigen::Index k) const { return (k == 0 && rest0) || (k == n - 1 && restN); }
  /// The grid point whose θ sets a rest interval's time (its moving end).
  Eigen::Index moving_end(Eigen::Index k) const { return k == 0 && rest0 ? 1 : n - 1; }
  Eigen::Index b_col(Eigen::Index k) const { return n + 1 + k; }
};

JerkShape jerk_shape(const Eigen::VectorXd& s, bool rest0, bool restN);

/// Σ coef·x[col] <= rhs (at most 6 terms), physical units.
struct JerkRow {
  int n = 0;
  int col[6];
  double val[6];
  double rhs = 0;
  void add(int c, double v) {
    for (int i = 0; i < n; ++i)
      if (col[i] == c) { val[i] += v; return; }
    col[n] = c, val[n] = v, ++n;
  }
  double dot(const Eigen::VectorXd& x) const {
    double s = 0;
    for (int i = 0; i < n; ++i) s += val[i] * x[col[i]];
    return s;
  }
};

/// A jerk limit at one grid point on one side, before linearisation: lin·x <= J/√θ_point.
struct JerkLimitRow {
  JerkRow lin;  ///< sign·(p' b' + 3 p'' b + p''' θ); rhs unused
  Eigen::Index point = 0;
  double J = 0;
  /// The row linearised at θ̄ (the tangent of J/√θ, which lies below it: an inner row, exact at θ̄).
  JerkRow linearised(double theta_bar) const;
  /// r, a linearised() of this row, linearised again at tb (θ̄ clamped as linearised() does) with root = √tb:
  /// only its θ coefficient and right-hand side depend on θ̄, and the rows of one grid point share the root.
  void relinearise(JerkRow& r, double tb, double root) const {
    // J/√θ >= J (3θ̄ - θ) / (2 θ̄^{3/2}): lin's θ coefficient plus the tangent's slope, 1.5 J / √θ̄ on the right.
    // jerk_limit_rows adds the θ column last; any other place is searched for.
    const int c = static_cast<int>(point);
    int i = r.n - 1, l = lin.n - 1;
    while (i >= 0 && r.col[i] != c) --i;
    while (l >= 0 && lin.col[l] != c) --l;
    if (i >= 0) r.val[i] = (l >= 0 ? lin.val[l] : 0.0) + J / (2 * tb * root);
    r.rhs = 1.5 * J / root;
  }
};

/// Exact time of the profile (+inf where θ reaches 0 inside an interval).
double jerk_total_time(const JerkShape& sh, const Eigen::VectorXd& x);

/// How many graded pieces the quadrature takes on an interval whose θ goes from theta0 to theta1, its least
/// theta_min: 1 if θ varies by at most 2, else 1 + ⌈log2(max θ / theta_min)⌉ (at most 40).
int jerk_quadrature_pieces(double theta0, double theta1, double theta_min);

/// The time by 8-point Gauss-Legendre quadrature of ∫ dσ/√θ(σ) on each linear-b interval (θ is affine in the
/// unknowns there, so this is convex; on graded pieces, jerk_quadrature_pieces), the rest intervals exactly; with its gradient and, if hess, the 3×3
/// Hessian block of each interval over (θ_k, b_k, b_{k+1}) (row-major, 9 per interval; the rest intervals' one
/// entry ∂²/∂θ² in [0]). +inf (nothing else set) where some quadrature node has θ <= 0.
double jerk_quadrature_time(const JerkShape& sh, const Eigen::VectorXd& x, Eigen::VectorXd* grad,
                            std::vector<double>* hess);

/// One row per interval: θ_{k+1} - θ_k - Δs_k (b_k + b_{k+1}) = 0 (rest intervals: θ_1 = 1.5 Δs b_1), as lhs <= 0.
std::vector<JerkRow> jerk_consistency_rows(const JerkShape& sh);

/// Every constraint row a θ_k + b b_k <= c of `in.rows` at each grid point (+inf rows dropped).
std::vector<JerkRow> jerk_point_rows(const JerkInput& in, const JerkShape& sh);

/// The jerk limits at each moving grid point, on each side, both signs.
std::vector<JerkLimitRow> jerk_limit_rows(const JerkInput& in, const JerkShape& sh);

/// The rows of `rows` on two unknowns (θ_k, b_k) of one grid point, less those that another row of the same
/// point and side dominates over the whole θ range [lo[θ_k], hi[θ_k]] by more than a relative 1e-9: a row
/// bounding b_k from above is kept where, somewhere in that range, it is within that margin of the least of
/// them (from below: of the largest). The feasible set is unchanged (the margin errs towards keeping); rows on
/// other unknowns are kept as they are. A grid point has a limit row per joint and sign, of which a few bound
/// the polygon: each row kept costs ~10 passes per interior-point iteration.
std::vector<JerkRow> jerk_undominated_rows(const std::vector<JerkRow>& rows, Eigen::Index nb, const Eigen::VectorXd& lo,
                                           const Eigen::VectorXd& hi);

/// The box [lo, hi] with each b_k's sides tightened to what the rows on (θ_k, b_k) imply over θ_k in
/// [lo[θ_k], hi[θ_k]]: a row bounding b_k from above by P + Q θ_k bounds it by the larger of its values at the
/// range's ends (from below: the smaller), widened by 1e-12 relative for rounding. Every point that meets the
/// rows and the box lies in it: a certificate's minimum over this box is still a lower bound, and much tighter
/// than over the box's 1e3 s_b sides (jerk_newton's lagrangian_bound).
void jerk_implied_box(const std::vector<JerkRow>& rows, Eigen::Index nb, Eigen::VectorXd& lo, Eigen::VectorXd& hi);

/// A problem's rows before linearisation (jerk_point_rows, jerk_limit_rows), built once per solve: the start,
/// the structured solve and the final check all read them.
struct JerkRowSet {
  std::vector<JerkRow> point;
  std::vector<JerkLimitRow> jerk;
};
JerkRowSet jerk_rows(const JerkInput& in, const JerkShape& sh);

/// Column bounds: the fixed end values, θ >= 0, the rest ends' jerk as a bound on θ at the moving end.
void jerk_column_bounds(const JerkInput& in, const JerkShape& sh, Eigen::VectorXd& lo, Eigen::VectorXd& hi);

/// Makes (θ, b) exactly consistent: θ by the forward recursion from b, the last free b absorbing the residual.
void jerk_make_consistent(const JerkShape& sh, Eigen::VectorXd& x, double theta_end, bool zero_b_end);

/// A strictly feasible start without an LP (rest to rest only): b at the grid points from the no-jerk optimum
/// (in.theta_hint), shifted by a constant so that θ by the recursion closes at the rest end, then scaled to 0.9
/// of the largest κ for which κ (θ, b) holds every row. False if that profile has θ <= 0 inside or a row
/// cannot be met by slowing.
bool jerk_scaled_start(const JerkInput& in, const JerkShape& sh, const JerkRowSet& rows, const Eigen::VectorXd& hi,
                       Eigen::VectorXd& x);

/// The structured solver (solve/jerk_newton.cpp): from the strictly feasible, consistent x, a log-barrier path
/// with banded Newton steps, the jerk rows re-linearised at each iterate, to a certified gap of in.tolerance on
/// the convex problem linearised at its answer (out.gap, out.newton_steps); first_gap sets the first barrier
/// parameter (the duality gap of the first centre, relative to T). x is then that answer, strictly feasible,
/// consistent to rounding. False, x unchanged, where it does not apply (an end not at rest: every fixed value
/// must be 0; x not strictly feasible), or it did not converge by `deadline` or in its step budget.
bool jerk_newton(const JerkInput& in, const JerkShape& sh, const JerkRowSet& rows, const Eigen::VectorXd& lo,
                 const Eigen::VectorXd& hi, const Eigen::VectorXd& box, double first_gap, Eigen::VectorXd& x,
                 JerkOutput& out, std::chrono::steady_clock::time_point deadline);

}  // namespace pathpace::detail
