#include "solve/jerk_scp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "base/jerk_interval.hpp"
#include "base/validate.hpp"
#include "lp/glpk_lp.hpp"
#include "solve/jerk_rows.hpp"

namespace pathpace::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The exact T and its gradient (8-point Gauss-Legendre, base/jerk_interval.hpp) for the GLPK rounds.
double total_time(const JerkShape& sh, const Eigen::VectorXd& x, Eigen::VectorXd* grad) {
  if (grad) jerk_quadrature_time(sh, x, grad, nullptr);
  return jerk_total_time(sh, x);
}

// One GLPK LP of the rows linearised at θ̄ (the start, and the fallback rounds).
class JerkLp {
 public:
  JerkLp(const JerkShape& sh, const JerkRowSet& rows, double s_theta, double s_b)
      : sh_(sh), st_(s_theta), sb_(s_b), nb_(sh.n + 1), fixed_(jerk_consistency_rows(sh)), point_(rows.point),
        jerk_(rows.jerk) {}

  // Builds the LP linearised at theta_bar; bounds lo/hi per column (physical units).
  bool build(const Eigen::VectorXd& theta_bar, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
    lp_.reset(static_cast<int>(2 * nb_));
    for (JerkRow r : fixed_) {  // equalities as two rows
      push(r);
      for (int i = 0; i < r.n; ++i) r.val[i] = -r.val[i];
      push(r);
    }
    for (const JerkRow& r : point_) push(r);
    for (const JerkLimitRow& r : jerk_) push(r.linearised(theta_bar[r.point]));
    if (!lp_.load()) return false;
    for (Eigen::Index c = 0; c < 2 * nb_; ++c) {
      const double sc = scale(c);
      lp_.set_col_bounds(static_cast<int>(c), lo[c] / sc, hi[c] / sc);
    }
    return true;
  }

  // min cost·x (physical cost per column); x in physical units on success.
  GlpkLp::Outcome solve(const Eigen::VectorXd& cost, double tol, Eigen::VectorXd& x) {
    std::vector<double> c(static_cast<size_t>(2 * nb_));
    double big = 0;
    for (Eigen::Index i = 0; i < 2 * nb_; ++i) big = std::max(big, std::abs(cost[i] * scale(i)));
    if (!(big > 0)) big = 1;
    for (Eigen::Index i = 0; i < 2 * nb_; ++i) c[static_cast<size_t>(i)] = cost[i] * scale(i) / big;
    lp_.set_objective(c);
    const GlpkLp::Outcome out = lp_.solve(tol);
    if (out != GlpkLp::Outcome::Optimal) return out;
    std::vector<double> y;
    lp_.column_values(y);
    x.resize(2 * nb_);
    for (Eigen::Index i = 0; i < 2 * nb_; ++i) x[i] = y[static_cast<size_t>(i)] * scale(i);
    return out;
  }

 private:
  double scale(Eigen::Index c) const { return c < nb_ ? st_ : sb_; }
  void push(const JerkRow& r) {  // GLPK's tolerances are absolute: columns scaled, each row to unit size
    idx_.clear(), val_.clear();
    double size = std::abs(r.rhs);
    for (int i = 0; i < r.n; ++i)
      if (r.val[i] != 0) {
        idx_.push_back(r.col[i]);
        val_.push_back(r.val[i] * scale(r.col[i]));
        size = std::max(size, std::abs(val_.back()));
      }
    if (idx_.empty()) return;
    if (!(size > 0)) size = 1;
    for (double& v : val_) v /= size;
    lp_.add_row_upper(idx_, val_, r.rhs / size);
  }
  const JerkShape& sh_;
  double st_, sb_;
  Eigen::Index nb_ = 0;
  std::vector<JerkRow> fixed_;
  const std::vector<JerkRow>& point_;
  const std::vector<JerkLimitRow>& jerk_;
  GlpkLp lp_;
  std::vector<int> idx_;
  std::vector<double> val_;
};

// Start: the LP linearised at the second-order optimum (floored), maximising Σ w_k θ_k with the weights of
// ∂(Σ Δs/√θ)/∂θ there; its solution is feasible (inner rows) whatever the linearisation point. False (and `out`
// says why) if it fails.
bool start_point(const JerkInput& in, const JerkShape& sh, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                 double s_theta, double s_b, JerkLp& lp, Eigen::VectorXd& x, JerkOutput& out) {
  const Eigen::Index n = sh.n, nb = n + 1;
  const Eigen::VectorXd bar = in.theta_hint.cwiseMax(1e-6 * s_theta);
  Eigen::VectorXd l = lo, h = hi, cost = Eigen::VectorXd::Zero(2 * nb);
  for (Eigen::Index k = 0; k <= n; ++k) {
    if (lo[k] != hi[k]) h[k] = std::min(h[k], 3 * bar[k]);
    const double w = 0.5 * ((k > 0 ? sh.ds[k - 1] : 0) + (k < n ? sh.ds[k] : 0));
    cost[k] = -w / (bar[k] * std::sqrt(bar[k]));
  }
  for (Eigen::Index k = 0; k <= n; ++k)
    if (lo[nb + k] != hi[nb + k]) l[nb + k] = std::max(l[nb + k], -1e3 * s_b), h[nb + k] = std::min(h[nb + k], 1e3 * s_b);
  if (!lp.build(bar, l, h)) {
    out.message = "jerk limits: the LP could not be loaded";
    return false;
  }
  ++out.lp_solves;
  const GlpkLp::Outcome o = lp.solve(cost, in.lp_tolerance, x);
  if (o == GlpkLp::Outcome::Infeasible) {
    out.status = Status::Infeasible;
    out.message = "jerk limits: no timing found whose jerk, linearised at the timing without jerk limits, holds "
                  "with the other constraints at the grid points (an inner approximation: the problem may still "
                  "be feasible)";
    return false;
  }
  if (o != GlpkLp::Outcome::Optimal) {
    out.message = "jerk limits: the start LP failed";
    return false;
  }
  return true;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The fallback where jerk_newton does not apply (an end not at rest) or fails: rounds of one GLPK LP each,
// linearised at x, minimising ∇T·y in a trust region, then a line search on T.
void glpk_rounds(const JerkInput& in, const JerkShape& sh, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                 double s_theta, double s_b, JerkLp& lp, Eigen::VectorXd& x, double& T, JerkOutput& out,
                 std::chrono::steady_clock::time_point t0) {
  const Eigen::Index n = sh.n, nb = n + 1;
  const double thN = in.sdot_end * in.sdot_end;
  auto fixed = [&](Eigen::Index c) { return lo[c] == hi[c]; };
  // Rounds: linearise at x, minimise ∇T·y in a trust region, line search on T (x + α (y - x) stays feasible:
  // both ends satisfy the convex linearised rows, which are inner ones).
  double rho = 0.5;
  bool certified = false;  // out.gap is that of the current x
  Eigen::VectorXd g, y;
  // Certificate: the LP of the linearisation at x without a trust region. T is convex and the linearised rows
  // form a convex set C containing x, so min_C T >= T(x) + min_C ∇T·(y - x): the gap bound is -min ∇T·(y - x).
  auto certify = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd gc, yc;
    total_time(sh, at, &gc);
    Eigen::VectorXd l = lo, h = hi;
    const double cap = 1e6 * s_theta;
    for (Eigen::Index k = 0; k <= n; ++k) h[k] = std::min(h[k], cap);  // hit only if nothing bounds θ
    ++out.lp_solves;
    out.gap = kInf;
    if (lp.build(at.head(nb), l, h) && lp.solve(gc, in.lp_tolerance, yc) == GlpkLp::Outcome::Optimal && yc.head(nb).maxCoeff() < 0.5 * cap)
      out.gap = std::max(0.0, -gc.dot(yc - at)) / total_time(sh, at, nullptr);
    return out.gap;
  };
  out.status = Status::IterationLimit;
  for (int it = 0;; ++it) {
    if (it >= in.max_iterations) {
      out.message = "jerk limits: max_iterations linearisation rounds reached";
      break;
    }
    if (seconds_since(t0) > in.time_limit) {
      out.status = Status::TimeLimit;
      out.message = "jerk limits: time_limit reached";
      break;
    }
    total_time(sh, x, &g);
    const double tmax = x.head(nb).maxCoeff();
    Eigen::VectorXd l = lo, h = hi;
    for (Eigen::Index k = 0; k <= n; ++k) {
      if (!fixed(k)) {
        const double r = rho * std::max(x[k], 1e-3 * tmax);
        l[k] = std::max(l[k], x[k] - r), h[k] = std::min(h[k], x[k] + r);
      }
      if (!fixed(nb + k)) {
        const double r = rho * (std::abs(x[nb + k]) + s_b);
        l[nb + k] = std::max(l[nb + k], x[nb + k] - r), h[nb + k] = std::min(h[nb + k], x[nb + k] + r);
      }
    }
    ++out.iterations;
    ++out.lp_solves;
    if (!lp.build(x.head(nb), l, h) || lp.solve(g, in.lp_tolerance, y) != GlpkLp::Outcome::Optimal) {
      out.status = Status::NumericalError;
      out.message = "jerk limits: a linearised LP failed";
      break;
    }
    jerk_make_consistent(sh, y, thN, in.zero_sddot_end);
    const Eigen::VectorXd d = y - x;
    const double pred = -g.dot(d);
    if (pred <= 0.1 * in.tolerance * T) {
      // Converged within the trust region: done if the certificate agrees, else widen the region and go on.
      certified = true;
      if (certify(x) <= in.tolerance || rho >= 1e3) break;
      rho = std::min(16 * rho, 1e3);
      continue;
    }
    double alpha = 1, Tn = kInf;
    for (int ls = 0; ls < 30; ++ls, alpha *= 0.5) {
      Tn = total_time(sh, x + alpha * d, nullptr);
      if (Tn <= T - 1e-4 * alpha * pred) break;
    }
    if (!(Tn <= T - 1e-4 * alpha * pred)) {
      rho *= 0.25;
      if (rho < 1e-12) break;
      continue;
    }
    x += alpha * d;
    certified = false;
    jerk_make_consistent(sh, x, thN, in.zero_sddot_end);
    T = total_time(sh, x, nullptr);
    rho = alpha == 1 ? std::min(2 * rho, 1e3) : std::max(alpha, 0.1) * rho;
  }

  if (out.status != Status::NumericalError) {
    if (!certified) certify(x);
    if (!std::isfinite(out.gap)) {
      if (out.message.empty()) out.message = "jerk limits: the certificate LP failed (no gap bound)";
    } else if (out.status == Status::IterationLimit && out.gap <= in.tolerance) {
      out.status = Status::Optimal;
      out.message.clear();
    } else if (out.status == Status::IterationLimit && out.message.empty()) {
      out.message = "jerk limits: the rounds stopped with a gap of " + fmt(out.gap) +
                    " to the linearised problem (above tolerance)";
    }
  }
}

// The worst violation of the grid rows at x, relative to each row's size: the limits (rows and bounds) and the
// exact jerk rows |p' b' + 3 p'' b + p''' θ| <= J/√θ.
double grid_violation(const JerkRowSet& rows, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                      const Eigen::VectorXd& x) {
  double worst = 0;
  for (const JerkRow& r : rows.point) {
    double size = std::abs(r.rhs);
    for (int i = 0; i < r.n; ++i) size = std::max(size, std::abs(r.val[i] * x[r.col[i]]));
    if (size > 0) worst = std::max(worst, (r.dot(x) - r.rhs) / size);
  }
  for (const JerkLimitRow& r : rows.jerk) {
    const double cap = r.J / std::sqrt(std::max(x[r.point], 0.0));
    worst = std::max(worst, (r.lin.dot(x) - cap) / cap);
  }
  for (Eigen::Index c = 0; c < x.size(); ++c) {
    if (hi[c] < kInf && x[c] > hi[c]) worst = std::max(worst, (x[c] - hi[c]) / std::max(std::abs(hi[c]), 1e-300));
    if (lo[c] > -kInf && x[c] < lo[c]) worst = std::max(worst, (lo[c] - x[c]) / std::max(std::abs(lo[c]), std::abs(x[c])));
  }
  return worst;
}

// The answer at x: its grid violation, θ, b and exact T.
JerkOutput& finish(const JerkShape& sh, const JerkRowSet& rows, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                   const Eigen::VectorXd& x, JerkOutput& out) {
  const Eigen::Index nb = sh.n + 1;
  out.grid_violation = grid_violation(rows, lo, hi, x);
  out.theta = x.head(nb);
  out.b = x.tail(nb);
  out.duration = jerk_total_time(sh, x);
  return out;
}

// The structured solve's answer: made exactly consistent; the iterate is strictly feasible and the repair moves
// it by rounding, so a row violated by more than 1e-10 of its size steps back by slowing (θ, b) -> κ (θ, b)
// (rest to rest: every fixed value is 0).
JerkOutput& finish_structured(const JerkInput& in, const JerkShape& sh, const JerkRowSet& rows,
                              const Eigen::VectorXd& lo,
                              const Eigen::VectorXd& hi, Eigen::VectorXd& x, JerkOutput& out) {
  out.structured = true;
  out.status = out.gap <= in.tolerance ? Status::Optimal : Status::IterationLimit;
  out.message = out.status == Status::Optimal ? "" : "jerk limits: the interior point stalled with a certified gap of " +
                                                         fmt(out.gap) + " to the linearised problem (tolerance " +
                                                         fmt(in.tolerance) + ")";
  jerk_make_consistent(sh, x, in.sdot_end * in.sdot_end, in.zero_sddot_end);
  for (int back = 0; back < 8; ++back) {
    const double v = grid_violation(rows, lo, hi, x);
    if (v <= 1e-10) break;
    x *= 1 - 2 * v;
  }
  return finish(sh, rows, lo, hi, x, out);
}

}  // namespace

Eigen::VectorXd jerk_interval_times(const Eigen::VectorXd& s, const Eigen::VectorXd& theta, const Eigen::VectorXd& b) {
  const JerkShape sh = jerk_shape(s, theta[0] == 0, theta[s.size() - 1] == 0);
  Eigen::VectorXd out(sh.n);
  for (Eigen::Index k = 0; k < sh.n; ++k) {
    if (sh.rest_interval(k)) out[k] = rest_interval_time(theta[sh.moving_end(k)], sh.ds[k]);
    else out[k] = linear_b_time(theta[k], b[k], b[k + 1], sh.ds[k]);
  }
  return out;
}

JerkOutput solve_jerk(const JerkInput& in) {
  const auto t0 = std::chrono::steady_clock::now();
  JerkOutput out;
  const PathSamples& smp = *in.samples;
  const JerkShape sh = jerk_shape(smp.s, in.sdot_begin == 0, in.sdot_end == 0);
  const Eigen::Index n = sh.n, nb = n + 1;
  const double th0 = in.sdot_begin * in.sdot_begin, thN = in.sdot_end * in.sdot_end;

  // Scales: GLPK's tolerances are absolute in the variables it is given.
  const double s_theta = std::max(in.theta_hint.maxCoeff(), std::max(th0, thN));
  double s_b = 0;
  for (Eigen::Index k = 0; k < n; ++k)
    s_b = std::max(s_b, std::abs(in.theta_hint[k + 1] - in.theta_hint[k]) / (2 * sh.ds[k]));
  s_b = std::max(s_b, s_theta / (smp.s[n] - smp.s[0]));
  if (!(s_theta > 0) || !std::isfinite(s_theta)) {
    out.message = "jerk limits: the second-order timing has no speed to start from";
    return out;
  }

  Eigen::VectorXd lo, hi;
  jerk_column_bounds(in, sh, lo, hi);
  // The box in which the structured solve's certificate holds (every unknown bounded; far from any optimum).
  Eigen::VectorXd box(2 * nb);
  box.head(nb).setConstant(1e6 * s_theta);
  box.tail(nb).setConstant(1e3 * s_b);
  const auto deadline = t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(in.time_limit));
  // Rest to rest: the structured solve from the scaled start (no LP).
  Eigen::VectorXd x;
  const JerkRowSet rows = jerk_rows(in, sh);
  if (jerk_scaled_start(in, sh, rows, hi, x) && jerk_newton(in, sh, rows, lo, hi, box, 1.0, x, out, deadline))
    return finish_structured(in, sh, rows, lo, hi, x, out);

  JerkLp lp(sh, rows, s_theta, s_b);
  if (!start_point(in, sh, lo, hi, s_theta, s_b, lp, x, out)) return out;
  jerk_make_consistent(sh, x, thN, in.zero_sddot_end);
  double T = total_time(sh, x, nullptr);
  if (!std::isfinite(T)) {
    out.message = "jerk limits: the start has an interval where the speed reaches 0 (no finite time)";
    return out;
  }
  // The start LP's x, slowed by 1 % to be strictly inside (rest to rest), then the structured solve; else the
  // GLPK rounds.
  Eigen::VectorXd xs = 0.99 * x;
  if (jerk_newton(in, sh, rows, lo, hi, box, 0.1, xs, out, deadline))
    return finish_structured(in, sh, rows, lo, hi, xs, out);
  glpk_rounds(in, sh, lo, hi, s_theta, s_b, lp, x, T, out, t0);
  return finish(sh, rows, lo, hi, x, out);
}

}  // namespace pathpace::detail
