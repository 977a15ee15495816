#include "solve/barrier.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solve/slp.hpp"  // duration(): T of eq. (27)

namespace pathpace::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A row with the fixed points' terms moved to the right-hand side: a0 θ_k + a1 θ_{k+1} <= c.
struct Row {
  Eigen::Index k;
  double a0, a1, c;
};

// s_r = c - a0 θ_k - a1 θ_{k+1}: the row's slack at θ.
double slack(const Row& r, const Eigen::VectorXd& theta) { return r.c - r.a0 * theta[r.k] - r.a1 * theta[r.k + 1]; }

struct Problem {
  const Eigen::VectorXd& ds;
  std::vector<Row> rows;
  Eigen::VectorXd lo, hi;
  std::vector<char> free;
  Eigen::Index m;  // intervals
};

// ∇T over the free points (0 at fixed ones). With r = √θ and S = r_k + r_{k+1}, f_k = 2Δs_k / S and
// ∂f_k/∂θ_k = -Δs_k / (S² r_k).
void gradient_T(const Problem& p, const Eigen::VectorXd& theta, Eigen::VectorXd& g) {
  g.setZero(p.m + 1);
  for (Eigen::Index k = 0; k < p.m; ++k) {
    const double r0 = std::sqrt(theta[k]), r1 = std::sqrt(theta[k + 1]), S = r0 + r1;
    const double q = p.ds[k] / (S * S);
    if (p.free[static_cast<size_t>(k)]) g[k] -= q / r0;
    if (p.free[static_cast<size_t>(k + 1)]) g[k + 1] -= q / r1;
  }
}

// Slope of the barrier function φ = t T - Σ log s_r - Σ log(θ - lo) - Σ log(hi - θ) along d at θ + α d.
double slope(const Problem& p, const Eigen::VectorXd& theta, const Eigen::VectorXd& d, double alpha, double t,
             Eigen::VectorXd& tmp, Eigen::VectorXd& g) {
  tmp = theta + alpha * d;
  gradient_T(p, tmp, g);
  double out = t * g.dot(d);
  for (const Row& r : p.rows) {
    const double ad = r.a0 * d[r.k] + r.a1 * d[r.k + 1];
    const double s = slack(r, tmp);
    out += ad / s;
  }
  for (Eigen::Index j = 0; j <= p.m; ++j) {
    if (!p.free[static_cast<size_t>(j)]) continue;
    out -= d[j] / (tmp[j] - p.lo[j]);
    if (p.hi[j] < kInf) out += d[j] / (p.hi[j] - tmp[j]);
  }
  return out;
}

bool strictly_feasible(const Problem& p, const Eigen::VectorXd& theta) {
  for (Eigen::Index j = 0; j <= p.m; ++j)
    if (p.free[static_cast<size_t>(j)] && !(theta[j] > p.lo[j] && theta[j] < p.hi[j])) return false;
  for (const Row& r : p.rows)
    if (!(slack(r, theta) > 0.0)) return false;
  return true;
}

// The window's problem with its fixed points (lo_j == hi_j) set in theta and their terms moved to the rows'
// right-hand sides; n_free counts the others.
Problem fixed_points_out(const Eigen::VectorXd& ds, const std::vector<WindowRow>& rows, const Eigen::VectorXd& lo_in,
                         const Eigen::VectorXd& hi_in, Eigen::VectorXd& theta, Eigen::Index& n_free) {
  const Eigen::Index m = ds.size();
  Problem p{ds, {}, lo_in.cwiseMax(0.0), hi_in, std::vector<char>(static_cast<size_t>(m) + 1, 0), m};
  n_free = 0;
  for (Eigen::Index j = 0; j <= m; ++j) {
    if (p.hi[j] > p.lo[j]) {
      p.free[static_cast<size_t>(j)] = 1;
      ++n_free;
    } else {
      theta[j] = p.hi[j];
    }
  }
  if (n_free == 0) return p;
  p.rows.reserve(rows.size());
  for (const WindowRow& w : rows) {
    Row r{w.k, w.alpha, w.beta, w.c};
    if (!p.free[static_cast<size_t>(w.k)]) {
      r.c -= w.alpha * theta[w.k];
      r.a0 = 0.0;
    }
    if (!p.free[static_cast<size_t>(w.k + 1)]) {
      r.c -= w.beta * theta[w.k + 1];
      r.a1 = 0.0;
    }
    if (r.a0 != 0.0 || r.a1 != 0.0) p.rows.push_back(r);
  }
  return p;
}

// A strictly feasible start between the feasible `start` and lo, in theta: every row satisfied at `start` and
// at lo (the rest state, or a slower one) is satisfied strictly in between, unless it is tight at both. 1 % of
// the way in, not less: from smaller slacks of the tight rows the damped Newton steps of the first centring
// crawl along the boundary. False if none of the tries is strictly feasible.
bool strict_start(const Problem& p, const Eigen::VectorXd& start, Eigen::VectorXd& theta) {
  const double start_max = std::max(start.maxCoeff(), 1e-300);
  for (double lambda : {1.0 - 1e-2, 0.9, 0.5}) {
    for (Eigen::Index j = 0; j <= p.m; ++j) {
      if (!p.free[static_cast<size_t>(j)]) continue;
      double v = p.lo[j] + lambda * (start[j] - p.lo[j]);
      if (!(v > p.lo[j])) v = p.lo[j] + (1.0 - lambda) * std::min(p.hi[j] - p.lo[j], start_max);
      theta[j] = v;
    }
    if (strictly_feasible(p, theta)) return true;
  }
  return false;
}

// The starting t: the one whose centring direction is shortest at the start, t = -∇T·∇b / |∇T|² (b the
// barrier terms), kept between a gap of T (n_ineq / t at the centre) and the target gap. gT is ∇T at theta.
double initial_t(const Problem& p, const Eigen::VectorXd& theta, double T, double n_ineq, double abs_target,
                 Eigen::VectorXd& gT) {
  gradient_T(p, theta, gT);
  Eigen::VectorXd gb = Eigen::VectorXd::Zero(p.m + 1);
  for (const Row& r : p.rows) {
    const double wi = 1.0 / slack(r, theta);
    gb[r.k] += wi * r.a0;
    gb[r.k + 1] += wi * r.a1;
  }
  for (Eigen::Index j = 0; j <= p.m; ++j) {
    if (!p.free[static_cast<size_t>(j)]) continue;
    gb[j] -= 1.0 / (theta[j] - p.lo[j]);
    if (p.hi[j] < kInf) gb[j] += 1.0 / (p.hi[j] - theta[j]);
  }
  const double t_lo = n_ineq / std::max(T, 1e-300), t_hi = n_ineq / std::max(abs_target, 1e-300);
  const double tt = -gT.dot(gb) / std::max(gT.squaredNorm(), 1e-300);
  return std::clamp(std::isfinite(tt) ? tt : t_lo, t_lo, t_hi);
}

// Scratch of the Newton steps (sized once).
struct Newton {
  Eigen::VectorXd gT, g, hd, ho, d, tmp, gtmp, cp, dp;
  explicit Newton(Eigen::Index m) : g(m + 1), hd(m + 1), ho(m + 1), d(m + 1), cp(m + 1), dp(m + 1) {}
};

// The Newton step d of φ = t T + barrier at theta (gT = ∇T there): its gradient and tridiagonal Hessian, then
// H d = -g by the Thomas algorithm on the diagonally scaled (SPD, unit-diagonal) matrix. False if the
// elimination breaks down (H not numerically positive definite).
bool newton_step(const Problem& p, const Eigen::VectorXd& theta, double t, Newton& nw) {
  const Eigen::Index m = p.m;
  const Eigen::VectorXd& ds = p.ds;
  Eigen::VectorXd &g = nw.g, &hd = nw.hd, &ho = nw.ho, &d = nw.d, &cp = nw.cp, &dp = nw.dp;
  hd.setZero();
  ho.setZero();
  gradient_T(p, theta, nw.gT);
  g = t * nw.gT;
  for (Eigen::Index k = 0; k < m; ++k) {
    const bool f0 = p.free[static_cast<size_t>(k)], f1 = p.free[static_cast<size_t>(k + 1)];
    if (!f0 && !f1) continue;
    const double r0 = std::sqrt(theta[k]), r1 = std::sqrt(theta[k + 1]), S = r0 + r1;
    const double D = ds[k], S2 = S * S, S3 = S2 * S;
    if (f0) hd[k] += t * (D / (S3 * r0 * r0) + D / (2.0 * S2 * r0 * r0 * r0));
    if (f1) hd[k + 1] += t * (D / (S3 * r1 * r1) + D / (2.0 * S2 * r1 * r1 * r1));
    if (f0 && f1) ho[k] += t * D / (S3 * r0 * r1);
  }
  for (size_t i = 0; i < p.rows.size(); ++i) {
    const Row& r = p.rows[i];
    const double s = slack(r, theta);
    const double wi = 1.0 / s;
    g[r.k] += wi * r.a0;
    g[r.k + 1] += wi * r.a1;
    hd[r.k] += wi * wi * r.a0 * r.a0;
    hd[r.k + 1] += wi * wi * r.a1 * r.a1;
    ho[r.k] += wi * wi * r.a0 * r.a1;
  }
  for (Eigen::Index j = 0; j <= m; ++j) {
    if (!p.free[static_cast<size_t>(j)]) {
      hd[j] = 1.0;  // g_j = 0 and no off-diagonal term here (rows and T carry none on fixed points): d_j = 0
      continue;
    }
    const double d1 = 1.0 / (theta[j] - p.lo[j]);
    g[j] -= d1;
    hd[j] += d1 * d1;
    if (p.hi[j] < kInf) {
      const double d2 = 1.0 / (p.hi[j] - theta[j]);
      g[j] += d2;
      hd[j] += d2 * d2;
    }
  }
  for (Eigen::Index j = 0; j <= m; ++j) hd[j] = 1.0 / std::sqrt(hd[j]);  // now D^{-1/2}
  double prev_c = 0.0, prev_d = 0.0;
  for (Eigen::Index j = 0; j <= m; ++j) {
    const double off_left = j > 0 ? ho[j - 1] * hd[j - 1] * hd[j] : 0.0;
    const double off_right = j < m ? ho[j] * hd[j] * hd[j + 1] : 0.0;
    const double denom = 1.0 - off_left * prev_c;
    if (!(denom > 0.0)) return false;
    cp[j] = off_right / denom;
    dp[j] = (-g[j] * hd[j] - off_left * prev_d) / denom;
    prev_c = cp[j];
    prev_d = dp[j];
  }
  for (Eigen::Index j = m; j >= 0; --j) {
    if (j < m) dp[j] -= cp[j] * dp[j + 1];
    d[j] = dp[j] * hd[j];
  }
  return true;
}

// The step along d (Newton decrement² dec2): the largest that keeps every slack positive (times 0.99), then a
// line search on φ' along d, which is increasing (φ convex) with φ'(0) = -dec2 < 0: α is accepted if φ'(α) <= 0,
// else regula falsi (Illinois) for its root on [0, α] gives the left end, where φ' <= 0. Close to the centre
// (dec2 < 0.1) the full step is taken as it is: there φ'(1) is a sum of terms of size t|∇T||d| that cancel to
// ~dec2², below their rounding, and a line search would only stall Newton's convergence.
double step_length(const Problem& p, const Eigen::VectorXd& theta, double t, double dec2, Newton& nw) {
  const Eigen::VectorXd& d = nw.d;
  double amax = kInf;
  for (const Row& r : p.rows) {
    const double ad = r.a0 * d[r.k] + r.a1 * d[r.k + 1];
    if (ad > 0.0) amax = std::min(amax, slack(r, theta) / ad);
  }
  for (Eigen::Index j = 0; j <= p.m; ++j) {
    if (!p.free[static_cast<size_t>(j)]) continue;
    if (d[j] < 0.0) amax = std::min(amax, (theta[j] - p.lo[j]) / -d[j]);
    if (d[j] > 0.0 && p.hi[j] < kInf) amax = std::min(amax, (p.hi[j] - theta[j]) / d[j]);
  }
  double alpha = std::min(1.0, 0.99 * amax);
  double fr = dec2 < 0.1 ? -1.0 : slope(p, theta, d, alpha, t, nw.tmp, nw.gtmp);
  if (fr > 0.0) {
    double l = 0.0, fl = -dec2, r = alpha;
    int side = 0;
    for (int it = 0; it < 30 && r - l > 1e-3 * r; ++it) {
      const double x = (l * fr - r * fl) / (fr - fl);
      const double fx = slope(p, theta, d, x, t, nw.tmp, nw.gtmp);
      if (fx > 0.0) {
        r = x;
        fr = fx;
        if (side == -1) fl *= 0.5;
        side = -1;
      } else {
        l = x;
        fl = fx;
        if (side == 1) fr *= 0.5;
        side = 1;
      }
    }
    alpha = l > 0.0 ? l : 0.5 * r;
  }
  return alpha;
}

// Near the central path: a lower bound on the window's optimum from multipliers of the rows (see the header).
// λ_r = 1 / (t s_r) is exact only at the centre; its error grows with the centring residual in the directions
// where the barrier is steep (tight rows), which dec2 weighs by their tiny inverse curvature. With the Newton
// step d at this θ (d_current: no step taken since it was computed), λ_r = (1 + a_r·d / s_r) / (t s_r) is the
// multiplier after the step to first order, and cancels that residual (clipped at 0: any λ >= 0 gives a valid
// bound). gT is ∇T at theta.
double multiplier_bound(const Problem& p, const Eigen::VectorXd& theta, double T, double t, const Eigen::VectorXd& gT,
                        const Eigen::VectorXd& d, bool d_current) {
  Eigen::VectorXd coef = gT;
  double lower = T;
  for (size_t i = 0; i < p.rows.size(); ++i) {
    const Row& r = p.rows[i];
    const double s = slack(r, theta);
    const double ad = d_current ? r.a0 * d[r.k] + r.a1 * d[r.k + 1] : 0.0;
    const double lam = std::max(0.0, 1.0 + ad / s) / (t * s);
    coef[r.k] += lam * r.a0;
    coef[r.k + 1] += lam * r.a1;
    lower -= lam * r.c;
  }
  for (Eigen::Index j = 0; j <= p.m; ++j) {
    if (!p.free[static_cast<size_t>(j)]) continue;
    lower -= gT[j] * theta[j];
    if (coef[j] >= 0.0) lower += coef[j] * p.lo[j];
    else if (p.hi[j] < kInf) lower += coef[j] * p.hi[j];
    else lower = -kInf;
  }
  return lower;
}

}  // namespace

BarrierResult barrier_window(const Eigen::VectorXd& ds, const std::vector<WindowRow>& rows, const Eigen::VectorXd& lo_in,
                             const Eigen::VectorXd& hi_in, const Eigen::VectorXd& start, double abs_target, int max_steps,
                             std::chrono::steady_clock::time_point deadline) {
  BarrierResult out;
  const Eigen::Index m = ds.size();
  Eigen::VectorXd theta = start;
  Eigen::Index n_free = 0;
  const Problem p = fixed_points_out(ds, rows, lo_in, hi_in, theta, n_free);
  if (n_free == 0 || !strict_start(p, start, theta)) return out;

  const double n_ineq = static_cast<double>(p.rows.size()) + static_cast<double>(2 * n_free);
  double T = duration(ds, theta);
  Newton nw(m);
  double t = initial_t(p, theta, T, n_ineq, abs_target, nw.gT);
  // t grows by μ after each centring; at the final t the centring is tightened to a Newton decrement of
  // dec_final, where the bound is within a few per cent of n_ineq / t.
  const double mu = 30.0;
  const double dec_final = 1e-8;
  const double t_final = n_ineq / (0.5 * abs_target);
  int since_update = 0;
  for (out.newton_steps = 0; out.newton_steps < max_steps; ++out.newton_steps) {
    if ((out.newton_steps & 15) == 15 && std::chrono::steady_clock::now() >= deadline) return out;
    if (!newton_step(p, theta, t, nw)) return out;
    const double dec2 = -nw.g.dot(nw.d);
    if (!(dec2 >= 0.0) || !std::isfinite(dec2)) return out;
    const bool final_t = t >= t_final;  // (not n_ineq / t <= ...: t = t_final must count, after rounding)
    if (!(final_t && dec2 <= dec_final)) {
      const double alpha = step_length(p, theta, t, dec2, nw);
      Eigen::VectorXd next = theta + alpha * nw.d;
      if (!strictly_feasible(p, next)) return out;
      theta = next;
      T = duration(ds, theta);
      ++since_update;
    }
    // Between updates of t, centring to dec2 <= 0.5 is enough (the next t moves the centre anyway). The
    // bound is taken only once n_ineq / t is below the target, after centring tightly: its error grows
    // with the residual of the centring conditions, which Newton's quadratic convergence removes in a
    // step or two.
    if (dec2 > (final_t ? dec_final : 0.5) && since_update < 50) continue;
    if (!final_t) {
      t = std::min(t * mu, t_final);
      since_update = 0;
      continue;
    }
    const bool d_current = final_t && dec2 <= dec_final;
    if (!d_current) gradient_T(p, theta, nw.gT);  // θ moved since this iteration's gradient
    out.lower = std::max(out.lower, multiplier_bound(p, theta, T, t, nw.gT, nw.d, d_current));
    if (T - out.lower <= abs_target) {
      out.ok = true;
      out.theta = theta;
      out.T = T;
      out.lower = std::min(out.lower, T);
      ++out.newton_steps;
      return out;
    }
    if (dec2 <= dec_final) {
      t *= 4.0;  // centred, yet the bound is not there: ask for less gap
      since_update = 0;
    }
  }
  return out;
}

}  // namespace pathpace::detail
