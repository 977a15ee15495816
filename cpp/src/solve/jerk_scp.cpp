#include "solve/jerk_scp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "base/jerk_interval.hpp"
#include "base/validate.hpp"
#include "lp/glpk_lp.hpp"

namespace pathpace::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The shape of the profile: which ends are rest ends (base/jerk_interval.hpp), the grid.
struct Shape {
  Eigen::Index n = 0;  // intervals
  Eigen::VectorXd ds;
  bool rest0 = false, restN = false;
  bool rest_interval(Eigen::Index k) const { return (k == 0 && rest0) || (k == n - 1 && restN); }
};

Shape make_shape(const Eigen::VectorXd& s) {
  Shape sh;
  sh.n = s.size() - 1;
  sh.ds = s.tail(sh.n) - s.head(sh.n);
  return sh;
}

// T and, if grad, ∂T/∂θ (first n+1) and ∂T/∂b (last n+1).
double total_time(const Shape& sh, const Eigen::VectorXd& x, Eigen::VectorXd* grad) {
  const Eigen::Index n = sh.n, nb = n + 1;
  if (grad) grad->setZero(2 * nb);
  double T = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double ds = sh.ds[k];
    if (sh.rest_interval(k)) {
      const Eigen::Index m = k == 0 && sh.rest0 ? 1 : n - 1;  // the interval's moving end
      const double th = x[m];
      if (!(th > 0)) return kInf;
      T += rest_interval_time(th, ds);
      if (grad) (*grad)[m] += -1.5 * ds / (th * std::sqrt(th));
      continue;
    }
    const double t = linear_b_time(x[k], x[nb + k], x[nb + k + 1], ds);
    if (!std::isfinite(t)) return kInf;
    T += t;
    if (grad) {
      double g[3];
      linear_b_time_gradient(x[k], x[nb + k], x[nb + k + 1], ds, g);
      (*grad)[k] += g[0];
      (*grad)[nb + k] += g[1];
      (*grad)[nb + k + 1] += g[2];
    }
  }
  return T;
}

// A row Σ coef·x[col] <= rhs in physical units.
struct Row {
  int n = 0;
  int col[6];
  double val[6];
  double rhs = 0;
  void add(int c, double v) {
    for (int i = 0; i < n; ++i)
      if (col[i] == c) { val[i] += v; return; }
    col[n] = c, val[n] = v, ++n;
  }
};

class JerkLp {
 public:
  JerkLp(const JerkInput& in, const Shape& sh, double s_theta, double s_b) : in_(in), sh_(sh), st_(s_theta), sb_(s_b) {
    nb_ = sh.n + 1;
  }

  // Builds the LP linearised at theta_bar; bounds lo/hi per column (physical units).
  bool build(const Eigen::VectorXd& theta_bar, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
    lp_.reset(static_cast<int>(2 * nb_));
    rows_ = 0;
    const Eigen::Index n = sh_.n;
    const PathSamples& smp = *in_.samples;
    // Consistency of each interval, as two rows.
    for (Eigen::Index k = 0; k < n; ++k) {
      Row r;
      const double ds = sh_.ds[k];
      if (k == 0 && sh_.rest0) {
        r.add(1, 1.0), r.add(bcol(1), -1.5 * ds);
      } else if (k == n - 1 && sh_.restN) {
        r.add(static_cast<int>(n - 1), 1.0), r.add(bcol(n - 1), 1.5 * ds);
      } else {
        r.add(static_cast<int>(k + 1), 1.0), r.add(static_cast<int>(k), -1.0), r.add(bcol(k), -ds), r.add(bcol(k + 1), -ds);
      }
      push(r);
      for (int i = 0; i < r.n; ++i) r.val[i] = -r.val[i];
      push(r);
    }
    // The constraints' rows at each grid point, with (x, u) = (θ_k, b_k).
    for (const ConstraintRows& cr : *in_.rows)
      for (Eigen::Index k = 0; k <= n; ++k)
        for (Eigen::Index j = 0; j < cr.rows(); ++j) {
          const double c = cr.c(k, j);
          if (!(c < kInf)) continue;
          Row r;
          if (cr.a(k, j) != 0) r.add(static_cast<int>(k), cr.a(k, j));
          if (cr.b(k, j) != 0) r.add(bcol(k), cr.b(k, j));
          r.rhs = c;
          push(r);
        }
    // Jerk rows at each grid point that moves, on each side (the interval's b').
    const Eigen::Index dof = smp.dof();
    for (Eigen::Index k = 0; k <= n; ++k) {
      if ((k == 0 && sh_.rest0) || (k == n && sh_.restN)) continue;
      const double tb = std::max(theta_bar[k], 1e-300);
      for (int side = 0; side < 2; ++side) {
        if ((side == 0 && k == 0) || (side == 1 && k == n)) continue;
        Row slope;  // b' on this side
        const Eigen::Index iv = side == 0 ? k - 1 : k;
        const double ds = sh_.ds[iv];
        if (iv == 0 && sh_.rest0) slope.add(bcol(1), 1.0 / (3 * ds));
        else if (iv == n - 1 && sh_.restN) slope.add(bcol(n - 1), -1.0 / (3 * ds));
        else slope.add(bcol(iv + 1), 1.0 / ds), slope.add(bcol(iv), -1.0 / ds);
        const Eigen::MatrixXd& p3 = side == 0 ? in_.p3_left : in_.p3_right;
        for (Eigen::Index j = 0; j < dof; ++j)
          for (int sign = 1; sign >= -1; sign -= 2) {
            const double J = sign > 0 ? in_.jmax[j] : -in_.jmin[j];
            if (!(J < kInf)) continue;
            Row r;
            for (int i = 0; i < slope.n; ++i) r.add(slope.col[i], sign * smp.dq(k, j) * slope.val[i]);
            r.add(bcol(k), sign * 3 * smp.ddq(k, j));
            // |g| <= J/√θ, inner by the tangent at θ̄: J/√θ >= J (3θ̄ - θ) / (2 θ̄^{3/2}).
            r.add(static_cast<int>(k), sign * p3(k, j) + J / (2 * tb * std::sqrt(tb)));
            r.rhs = 1.5 * J / std::sqrt(tb);
            push(r);
          }
      }
    }
    if (!lp_.load()) return false;
    for (Eigen::Index c = 0; c < 2 * nb_; ++c) {
      const double sc = scale(c);
      lp_.set_col_bounds(static_cast<int>(c), lo[c] / sc, hi[c] / sc);
    }
    return true;
  }

  // min cost·x (physical cost per column); x in physical units on success.
  GlpkLp::Outcome solve(const Eigen::VectorXd& cost, Eigen::VectorXd& x) {
    std::vector<double> c(static_cast<size_t>(2 * nb_));
    double big = 0;
    for (Eigen::Index i = 0; i < 2 * nb_; ++i) big = std::max(big, std::abs(cost[i] * scale(i)));
    if (!(big > 0)) big = 1;
    for (Eigen::Index i = 0; i < 2 * nb_; ++i) c[static_cast<size_t>(i)] = cost[i] * scale(i) / big;
    lp_.set_objective(c);
    const GlpkLp::Outcome out = lp_.solve(in_.lp_tolerance);
    if (out != GlpkLp::Outcome::Optimal) return out;
    std::vector<double> y;
    lp_.column_values(y);
    x.resize(2 * nb_);
    for (Eigen::Index i = 0; i < 2 * nb_; ++i) x[i] = y[static_cast<size_t>(i)] * scale(i);
    return out;
  }

 private:
  int bcol(Eigen::Index k) const { return static_cast<int>(nb_ + k); }
  double scale(Eigen::Index c) const { return c < nb_ ? st_ : sb_; }
  void push(const Row& r) {
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
    ++rows_;
  }
  const JerkInput& in_;
  const Shape& sh_;
  double st_, sb_;
  Eigen::Index nb_ = 0;
  GlpkLp lp_;
  int rows_ = 0;
  std::vector<int> idx_;
  std::vector<double> val_;
};

// Makes (θ, b) exactly consistent: θ by the forward recursion from the LP's b, the last free b absorbing the
// residual at the end (the LP holds the equalities to its tolerance only).
void make_consistent(const Shape& sh, Eigen::VectorXd& x, double theta_end, bool zero_b_end) {
  const Eigen::Index n = sh.n, nb = n + 1;
  Eigen::Index k = 0;
  if (sh.rest0) x[1] = 1.5 * sh.ds[0] * x[nb + 1], k = 1;
  const Eigen::Index stop = sh.restN ? n - 2 : n - 1;  // last interval of the recursion
  for (; k < stop; ++k) x[k + 1] = x[k] + sh.ds[k] * (x[nb + k] + x[nb + k + 1]);
  // Interval `stop` closes the chain.
  if (sh.restN) {
    // θ_{N-1} = θ_{N-2} + Δs (b_{N-2} + b_{N-1}) and θ_{N-1} = -1.5 Δs' b_{N-1}.
    const double d = sh.ds[stop], d2 = sh.ds[n - 1];
    x[nb + n - 1] = -(x[stop] + d * x[nb + stop]) / (d + 1.5 * d2);
    x[n - 1] = -1.5 * d2 * x[nb + n - 1];
    x[n] = 0;
  } else if (zero_b_end) {
    // b_N = 0: the last two intervals, θ_N = θ_{N-2} + Δs_{N-2} b_{N-2} + (Δs_{N-2} + Δs_{N-1}) b_{N-1}.
    const double d1 = sh.ds[n - 2], d2 = sh.ds[n - 1];
    x[nb + n] = 0;
    x[nb + n - 1] = (theta_end - x[n - 2] - d1 * x[nb + n - 2]) / (d1 + d2);
    x[n - 1] = x[n - 2] + d1 * (x[nb + n - 2] + x[nb + n - 1]);
    x[n] = theta_end;
  } else {
    x[n] = theta_end;
    x[nb + n] = (x[n] - x[stop]) / sh.ds[stop] - x[nb + stop];
  }
}

// Column bounds: the fixed ends, θ >= 0, and at a rest end the bound that the jerk of its interval (constant
// s⃛ = (2/9) θ^{3/2}/Δs², times p' there) puts on θ of the interval's moving end.
void column_bounds(const JerkInput& in, const Shape& sh, Eigen::VectorXd& lo, Eigen::VectorXd& hi) {
  const PathSamples& smp = *in.samples;
  const Eigen::Index n = sh.n, nb = n + 1;
  lo.resize(2 * nb), hi.resize(2 * nb);
  lo.head(nb).setZero();
  hi.head(nb).setConstant(kInf);
  lo.tail(nb).setConstant(-kInf);
  hi.tail(nb).setConstant(kInf);
  lo[0] = hi[0] = in.sdot_begin * in.sdot_begin;
  lo[n] = hi[n] = in.sdot_end * in.sdot_end;
  if (sh.rest0 || in.zero_sddot_begin) lo[nb] = hi[nb] = 0;
  if (sh.restN || in.zero_sddot_end) lo[nb + n] = hi[nb + n] = 0;
  auto rest_cap = [&](Eigen::Index point, Eigen::Index moving, double ds) {
    for (Eigen::Index j = 0; j < smp.dof(); ++j) {
      const double d = smp.dq(point, j);
      if (d == 0) continue;
      const double J = d > 0 ? in.jmax[j] : -in.jmin[j];
      if (J < kInf) hi[moving] = std::min(hi[moving], std::pow(4.5 * ds * ds * J / std::abs(d), 2.0 / 3.0));
    }
  };
  if (sh.rest0) rest_cap(0, 1, sh.ds[0]);
  if (sh.restN) rest_cap(n, n - 1, sh.ds[n - 1]);
}

// Start: the LP linearised at the second-order optimum (floored), maximising Σ w_k θ_k with the weights of
// ∂(Σ Δs/√θ)/∂θ there; its solution is feasible (inner rows) whatever the linearisation point. False (and `out`
// says why) if it fails.
bool start_point(const JerkInput& in, const Shape& sh, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
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
  const GlpkLp::Outcome o = lp.solve(cost, x);
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

}  // namespace

Eigen::VectorXd jerk_interval_times(const Eigen::VectorXd& s, const Eigen::VectorXd& theta, const Eigen::VectorXd& b) {
  Shape sh = make_shape(s);
  sh.rest0 = theta[0] == 0;
  sh.restN = theta[sh.n] == 0;
  Eigen::VectorXd out(sh.n);
  for (Eigen::Index k = 0; k < sh.n; ++k) {
    if (sh.rest_interval(k)) out[k] = rest_interval_time(theta[k == 0 && sh.rest0 ? 1 : sh.n - 1], sh.ds[k]);
    else out[k] = linear_b_time(theta[k], b[k], b[k + 1], sh.ds[k]);
  }
  return out;
}

JerkOutput solve_jerk(const JerkInput& in) {
  const auto t0 = std::chrono::steady_clock::now();
  JerkOutput out;
  const PathSamples& smp = *in.samples;
  Shape sh = make_shape(smp.s);
  sh.rest0 = in.sdot_begin == 0;
  sh.restN = in.sdot_end == 0;
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
  column_bounds(in, sh, lo, hi);

  JerkLp lp(in, sh, s_theta, s_b);
  auto fixed = [&](Eigen::Index c) { return lo[c] == hi[c]; };

  Eigen::VectorXd x;
  if (!start_point(in, sh, lo, hi, s_theta, s_b, lp, x, out)) return out;
  make_consistent(sh, x, thN, in.zero_sddot_end);
  double T = total_time(sh, x, nullptr);
  if (!std::isfinite(T)) {
    out.message = "jerk limits: the start has an interval where the speed reaches 0 (no finite time)";
    return out;
  }

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
    if (lp.build(at.head(nb), l, h) && lp.solve(gc, yc) == GlpkLp::Outcome::Optimal && yc.head(nb).maxCoeff() < 0.5 * cap)
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
    if (!lp.build(x.head(nb), l, h) || lp.solve(g, y) != GlpkLp::Outcome::Optimal) {
      out.status = Status::NumericalError;
      out.message = "jerk limits: a linearised LP failed";
      break;
    }
    make_consistent(sh, y, thN, in.zero_sddot_end);
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
    make_consistent(sh, x, thN, in.zero_sddot_end);
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
  out.theta = x.head(nb);
  out.b = x.tail(nb);
  out.duration = T;
  return out;
}

}  // namespace pathpace::detail
