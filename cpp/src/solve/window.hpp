#pragma once
// One SLP window of eq. (26)-(27) (solve/slp.hpp) and the three solvers that can take it; which one runs
// when is solve/window_policy.hpp's decision.

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "lp/glpk_lp.hpp"
#include "solve/barrier.hpp"
#include "solve/reachability.hpp"
#include "solve/slp.hpp"
#include "solve/window_policy.hpp"

namespace pathpace::detail {

/// A window's iterate and its certificate, as the solvers leave it.
struct WindowResult {
  SlpOutcome::Status status = SlpOutcome::Status::Converged;
  Eigen::VectorXd theta;  ///< θ_a .. θ_b
  double T = 0.0;         ///< Σ_{k in [a, b)} f_k at theta
  double gap = std::numeric_limits<double>::infinity();  ///< Frank-Wolfe gap of theta (absolute), if computed
  /// Best lower bound on the window's optimum: max over the Frank-Wolfe checks of T(θ) - gap(θ).
  double lower = -std::numeric_limits<double>::infinity();
  int iterations = 0, lp_solves = 0, newton_steps = 0;
};

/// One window's problem, fixed while it is solved: minimise Σ_{k in [a, a + m)} f_k over θ_a..θ_{a+m}
/// subject to the rows of those intervals and lo <= θ <= hi (local indices 0..m; a fixed end has lo = hi).
struct WindowData {
  const Chain& chain;
  Eigen::Index a = 0, m = 0;  ///< first point (in the chain), intervals
  Eigen::VectorXd ds, lo, hi;
  Eigen::Index first = 0, last = 0;  ///< the free points (the LP's columns), local
  int cols = 0;
  /// Of the start: the scale of the trust region and of the LP's column scaling, and the floor that keeps
  /// ∂T/∂θ finite at θ = 0 (see gradient()).
  double theta_max = 0.0, floor = 0.0;
  double rel_target = 0.0;  ///< the gap to reach, relative to the window's T
  const SlpLimits& limits;
};

/// ∂T/∂θ_j of eq. (27) on the window, with the floor of WindowData.
void gradient(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta, double floor, Eigen::VectorXd& g);
/// The exact minimiser of T on the segment θ + α d, α in [0, 1] (T is convex along it).
double line_search(const Eigen::VectorXd& ds, const Eigen::VectorXd& theta, const Eigen::VectorXd& d, double floor,
                   Eigen::VectorXd& tmp, Eigen::VectorXd& g);

/// Frank-Wolfe iterations whose LPs the chain simplex solves (policy.chain_frank_wolfe of them,
/// chain_pivot_budget pivots each); true if they certified the window. theta and out follow the iterate.
bool chain_simplex_window(const WindowData& w, const WindowPolicy& policy, const WindowProgress& progress,
                          Eigen::VectorXd& theta, WindowResult& out);

/// The rows of the window's intervals that can bind in its LPs (the others are implied by these and the
/// column bounds), in the barrier's form.
std::vector<WindowRow> window_rows(const WindowData& w);

/// The log barrier from theta (solve/barrier.hpp); true if it certified the window (then out holds its
/// result; otherwise only out.newton_steps changed).
bool barrier_attempt(const WindowData& w, const std::vector<WindowRow>& rows, const WindowPolicy& policy,
                     const Eigen::VectorXd& theta, WindowResult& out);

/// The paper's SLP (sec. V.C) on the window with GLPK: the LP is in θ itself (scaled), so its rows never
/// change; the trust region and the bounds are column bounds; each LP starts from the previous one's basis.
/// The first LP has no trust region: it is the Frank-Wolfe check, and at a start that is already optimal it
/// certifies it at once.
class GlpkSlp {
 public:
  /// Sets up the LP at the iterate theta (its scaling and start basis are theta's); see loaded().
  GlpkSlp(const WindowData& w, const std::vector<WindowRow>& rows, const Eigen::VectorXd& theta, GlpkLp& lp);
  /// False if GLPK refused the LP (then the window ends with LpFailed).
  bool loaded() const { return loaded_; }
  /// SLP iterations until out.iterations reaches `until`; true if the window ended (certified, or a
  /// status other than Converged set in out), false if `until` was reached.
  bool iterate(int until, Eigen::VectorXd& theta, WindowResult& out);

 private:
  struct LpRow {
    Eigen::Index k;  // interval (local)
    double alpha, beta, c;
    bool on_k, on_k1;  // coefficient on a column at point k / k+1
    int n;             // LP coefficients (1 or 2), normalised
    int col[2];
    double val[2], rhs;
  };
  void add_rows(const std::vector<WindowRow>& rows, const Eigen::VectorXd& theta);
  void start_basis(const Eigen::VectorXd& theta);
  bool take_row(Eigen::Index k, Eigen::Index j, const std::vector<char>& tight, const std::vector<size_t>& row_begin,
                std::vector<GlpkLp::Stat>& rs) const;
  SlpOutcome::Status solve_lp(double radius, const Eigen::VectorXd& theta, WindowResult& out);
  SlpOutcome::Status solve_and_add_broken_rows(WindowResult& out);
  bool one_iteration(Eigen::VectorXd& theta, WindowResult& out);

  const WindowData& w_;
  GlpkLp& lp_;
  bool loaded_ = false;
  Eigen::VectorXd sigma_;
  std::vector<LpRow> lp_rows_;  // the rows in the LP, in its order
  std::vector<LpRow> waiting_;  // the rows not (yet) in it
  std::vector<int> idx_;
  std::vector<double> val_, cost_, x_;
  double rho_ = 0.0;
  bool global_ = true;  // next LP without trust region (Frank-Wolfe)
  bool first_lp_ = true;
  Eigen::VectorXd g_, d_, tmp_, gtmp_;
};

}  // namespace pathpace::detail
