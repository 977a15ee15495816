// The structured solver of the jerk-limited timing (solve/jerk_scp.hpp, jerk_newton): a primal log-barrier
// method whose Newton steps solve a banded KKT system, the jerk rows re-linearised at every iterate.
//
// Why it converges, and stays feasible. φ_t(x) = t T(x) - Σ log s_r(x) - Σ log(bounds) with the true slacks s_r
// is the barrier function of the non-convex problem. Replacing each jerk slack J/√θ - g by its tangent in θ at
// x̄ gives φ_t^x̄ >= φ_t (the tangent lies below J/√θ, so the slack is smaller and -log larger), equal at x̄ with
// the same gradient: a convex majoriser. Each step is one damped Newton step on φ_t^x̄, so φ_t decreases
// (majorise-minimise) and every iterate is strictly feasible for the true rows. The same x̄ is then a centre of
// φ_t^x̄ when it is one of φ_t: at the end the multipliers certify the convex problem linearised there.
//
// Why it is O(N) per step. Unknowns ordered θ_0, b_0, ν_0, θ_1, b_1, ν_1, ... (ν_k the multiplier of interval k's
// consistency θ_{k+1} = θ_k + Δs_k (b_k + b_{k+1})): T couples (θ_k, b_k, b_{k+1}), a jerk row (b_{k±1}, b_k, θ_k),
// a limit row (θ_k, b_k): the KKT matrix has half-bandwidth 4. It is quasi-definite after a tiny regularisation
// (H + δI, -δI), so an LDLᵀ without pivoting exists (Vanderbei 1995); two steps of iterative refinement against
// the unregularised matrix remove δ's error.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lp/band_ldlt.hpp"
#include "solve/jerk_row_groups.hpp"
#include "solve/jerk_rows.hpp"

namespace pathpace::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
struct Problem {
  const JerkShape& sh;
  Eigen::VectorXd lo, hi;
  std::vector<char> free;
  std::vector<JerkRow> point, consistency;
  const std::vector<JerkLimitRow>& jerk;
  Eigen::Index nb = 0;
  Eigen::VectorXd cert_lo, cert_hi;  // the certificate's box: lo, hi with b's sides as the rows imply
  // KKT position of column c (θ_k -> 3k, b_k -> 3k + 1) and of interval k's multiplier.
  Eigen::Index pos(Eigen::Index c) const { return c < nb ? 3 * c : 3 * (c - nb) + 1; }
  Eigen::Index nu_pos(Eigen::Index k) const { return 3 * k + 2; }
  double n_ineq(std::size_t rows) const {
    double m = static_cast<double>(rows);
    for (Eigen::Index c = 0; c < 2 * nb; ++c)
      if (free[static_cast<size_t>(c)]) m += (lo[c] > -kInf) + (hi[c] < kInf);
    return m;
  }
};

// Whether x is strictly inside every row (slacks into s) and bound.
bool strictly_inside(const Problem& p, const JerkRowGroups& rows, const Eigen::VectorXd& x, std::vector<double>& s) {
  for (Eigen::Index c = 0; c < 2 * p.nb; ++c)
    if (p.free[static_cast<size_t>(c)] && !(x[c] > p.lo[c] && x[c] < p.hi[c])) return false;
  s.resize(rows.size());
  return rows.slacks(x, s.data());
}

// Σ log s over positive s as the log of their product, one log per 8 factors: the product's exponent is taken
// out (frexp) after every 8, so that it neither overflows nor underflows for factors within 1e±38 of one, and a
// factor outside that, which the product could lose, takes its own log. The barrier's line search evaluates
// ~10^4-10^5 slacks per trial; a log per slack was the largest part of a Newton step. The product's relative
// rounding (one ulp per factor) is of the order of a plain sum of the logs' own.
class LogSum {
 public:
  void add(double s) {
    if (!(s > 1e-38 && s < 1e38)) {
      sum_ += std::log(s);
      return;
    }
    product_ *= s;
    if (++count_ == 8) flush();
  }
  double value() {
    flush();
    return sum_ + std::log(product_) + exponent_ * M_LN2;
  }

 private:
  void flush() {
    int e = 0;
    product_ = std::frexp(product_, &e);
    exponent_ += e;
    count_ = 0;
  }
  double product_ = 1.0, sum_ = 0.0;
  long exponent_ = 0;
  int count_ = 0;
};

// φ at x for the rows as given (+inf outside).
double barrier_value(const Problem& p, const JerkRowGroups& rows, const Eigen::VectorXd& x, double t,
                     std::vector<double>& slack) {
  const double T = jerk_quadrature_time(p.sh, x, nullptr, nullptr);
  if (!std::isfinite(T)) return kInf;
  LogSum logs;
  slack.resize(rows.size());
  rows.slacks(x, slack.data());
  for (double s : slack) {
    if (!(s > 0)) return kInf;
    logs.add(s);
  }
  for (Eigen::Index c = 0; c < 2 * p.nb; ++c) {
    if (!p.free[static_cast<size_t>(c)]) continue;
    if (p.lo[c] > -kInf) {
      if (!(x[c] > p.lo[c])) return kInf;
      logs.add(x[c] - p.lo[c]);
    }
    if (p.hi[c] < kInf) {
      if (!(x[c] < p.hi[c])) return kInf;
      logs.add(p.hi[c] - x[c]);
    }
  }
  return t * T - logs.value();
}

struct Step {
  explicit Step(Eigen::Index m) : Ks(m) {}
  Eigen::VectorXd gT, d, nu;  // ∇T at x̄, the Newton step, the consistency multipliers (of φ / t)
  double dec2 = 0;            // Newton decrement², -∇φ·d
  // Scratch reused over the steps: ∇²T's blocks, the rows' 1 / slack, their multipliers, per-row weights and
  // products.
  std::vector<double> hT;
  std::vector<double> inv_slack, lam, weight, scratch;
  Eigen::VectorXd scale;      // the KKT matrix's symmetric scaling (solve_kkt)
  Eigen::VectorXd kkt_b, kkt_y, kkt_r;  // solve_kkt's scratch
  Eigen::VectorXd reg, g;                // newton_step's: the regularisation (the same at every step), ∇φ
  BandLdlt Ks;
};

// The primal-dual method's terms in place of the barrier's (primal_dual): per row the Hessian weight λ_r / s_r
// (the barrier's 1 / s_r²) and the gradient's γ_r / s_r (the barrier's 1 / s_r), and the same per bound.
struct PdTerms {
  std::vector<double> hess_row, grad_row;  // grad_row: γ_r / s_r, the row's weight in the gradient
  bool rows_in_gradient = true;            // false: every γ_r = 0 (the predictor), no pass over the rows
  Eigen::VectorXd hess_lo, hess_hi, grad_lo, grad_hi;
};

// ∇φ at x̄: t ∇T plus each row's and bound's γ / slack along its normal (γ = 1: the barrier's, whose row weights
// are the rows' 1 / slack; pd's are pd->grad_row).
void kkt_gradient(const Problem& p, const JerkRowGroups& rows, const Eigen::VectorXd& x, double t,
                  const std::vector<double>& inv, const PdTerms* pd, const Eigen::VectorXd& gT, Eigen::VectorXd& g) {
  g = t * gT;
  if (!pd) rows.scatter(inv.data(), g);
  else if (pd->rows_in_gradient) rows.scatter(pd->grad_row.data(), g);
  for (Eigen::Index c = 0; c < 2 * p.nb; ++c) {
    if (!p.free[static_cast<size_t>(c)]) {
      g[c] = 0;
      continue;
    }
    if (p.lo[c] > -kInf) g[c] -= (pd ? pd->grad_lo[c] : 1.0) / (x[c] - p.lo[c]);
    if (p.hi[c] < kInf) g[c] += (pd ? pd->grad_hi[c] : 1.0) / (p.hi[c] - x[c]);
  }
}

// The KKT system's solution for the gradient g with the factorisation of newton_step: st.d, st.nu (of φ / t), dec2.
bool solve_kkt(const Problem& p, const Eigen::VectorXd& g, double t, Step& st) {
  const Eigen::Index nb = p.nb, nx = 2 * nb, m = 3 * nb - 1;
  Eigen::VectorXd &b = st.kkt_b, &y = st.kkt_y, &r = st.kkt_r;
  b.setZero(m);
  for (Eigen::Index c = 0; c < nx; ++c) b[p.pos(c)] = -g[c] * st.scale[p.pos(c)];
  const BandLdlt& Ks = st.Ks;
  y = b;
  Ks.solve(y);
  for (int it = 0; it < 2; ++it) {  // iterative refinement against the unregularised Â
    Ks.multiply(y, r);
    r = b - r;
    Ks.solve(r);
    y += r;
  }
  y.array() *= st.scale.array();
  st.d.resize(nx);
  for (Eigen::Index c = 0; c < nx; ++c) st.d[c] = p.free[static_cast<size_t>(c)] ? y[p.pos(c)] : 0.0;
  st.nu.resize(p.sh.n);
  for (Eigen::Index k = 0; k < p.sh.n; ++k) st.nu[k] = y[p.nu_pos(k)] / t;
  st.dec2 = -g.dot(st.d);
  return std::isfinite(st.dec2);
}

// The Newton step of φ_t^x̄ at x̄ subject to the consistency rows (with `pd`, the primal-dual system of the same
// shape). False if the factorisation fails.
bool newton_step(const Problem& p, const JerkRowGroups& rows, const Eigen::VectorXd& x, double t, BandLdlt& K,
                 Step& st, const PdTerms* pd = nullptr) {
  const Eigen::Index nb = p.nb, nx = 2 * nb, m = 3 * nb - 1;
  std::vector<double>& hT = st.hT;
  jerk_quadrature_time(p.sh, x, &st.gT, &hT);
  K.clear();
  auto is_free = [&](Eigen::Index c) { return p.free[static_cast<size_t>(c)] != 0; };
  auto addH = [&](Eigen::Index c1, Eigen::Index c2, double v) {
    if (is_free(c1) && is_free(c2)) K.add(p.pos(c1), p.pos(c2), v);
  };
  // t ∇²T (each pair once: the block is symmetric, add() stores the lower triangle).
  for (Eigen::Index k = 0; k < p.sh.n; ++k) {
    const double* h = hT.data() + 9 * k;
    if (p.sh.rest_interval(k)) {
      const Eigen::Index c = p.sh.moving_end(k);
      addH(c, c, t * h[0]);
      continue;
    }
    const Eigen::Index c[3] = {k, nb + k, nb + k + 1};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b <= a; ++b) addH(c[a], c[b], t * h[3 * a + b]);
  }
  // The barrier's row weights: 1 / slack in a pass of its own (each a division whose latency the assembly
  // would wait for row by row), and its square. The primal-dual method brings its own (pd).
  std::vector<double>& inv = st.inv_slack;
  if (!pd) {
    inv.resize(rows.size());
    rows.slacks(x, inv.data());
    for (double& v : inv) v = 1.0 / v;
    st.weight.resize(rows.size());
    for (size_t k = 0; k < inv.size(); ++k) st.weight[k] = inv[k] * inv[k];
  }
  rows.hessian(pd ? pd->hess_row.data() : st.weight.data(),
               [&](int c1, int c2, double v) { K.add(p.pos(c1), p.pos(c2), v); });
  for (Eigen::Index c = 0; c < nx; ++c) {
    if (!is_free(c)) {
      K.add(p.pos(c), p.pos(c), 1.0);
      continue;
    }
    if (p.lo[c] > -kInf) {
      const double w = 1.0 / (x[c] - p.lo[c]);
      K.add(p.pos(c), p.pos(c), pd ? pd->hess_lo[c] : w * w);
    }
    if (p.hi[c] < kInf) {
      const double w = 1.0 / (p.hi[c] - x[c]);
      K.add(p.pos(c), p.pos(c), pd ? pd->hess_hi[c] : w * w);
    }
  }
  // Consistency rows (E d = 0: x̄ is consistent), symmetric scaling: primal by 1/√H_ii, rows to unit norm.
  Eigen::VectorXd& scale = st.scale;
  scale.resize(m);
  for (Eigen::Index c = 0; c < nx; ++c) scale[p.pos(c)] = 1.0 / std::sqrt(std::max(K.at(p.pos(c), p.pos(c)), 1e-300));
  for (Eigen::Index k = 0; k < p.sh.n; ++k) {
    const JerkRow& e = p.consistency[static_cast<size_t>(k)];
    double nrm = 0;
    for (int i = 0; i < e.n; ++i)
      if (is_free(e.col[i])) nrm += std::pow(e.val[i] * scale[p.pos(e.col[i])], 2);
    scale[p.nu_pos(k)] = nrm > 0 ? 1.0 / std::sqrt(nrm) : 1.0;
    for (int i = 0; i < e.n; ++i)
      if (is_free(e.col[i])) K.add(p.nu_pos(k), p.pos(e.col[i]), e.val[i]);
    if (!(nrm > 0)) K.add(p.nu_pos(k), p.nu_pos(k), 1.0);
  }
  // Scale in place: Â = S A S.
  BandLdlt& Ks = st.Ks;
  Ks.scaled(K, scale);
  if (st.reg.size() != m) {  // quasi-definite: +δ on the primal diagonal, -δ on the multipliers'
    st.reg.resize(m);
    for (Eigen::Index c = 0; c < nx; ++c) st.reg[p.pos(c)] = 1e-11;
    for (Eigen::Index k = 0; k < p.sh.n; ++k) st.reg[p.nu_pos(k)] = -1e-11;
  }
  if (!Ks.factor(st.reg)) return false;
  kkt_gradient(p, rows, x, t, inv, pd, st.gT, st.g);
  return solve_kkt(p, st.g, t, st);
}

// The largest step along d keeping every slack and bound positive.
double max_step(const Problem& p, const JerkRowGroups& rows, const Eigen::VectorXd& x, const Eigen::VectorXd& d,
                Step& st) {
  double amax = kInf;
  std::vector<double>&s = st.scratch, &ad = st.weight;
  s.resize(rows.size()), ad.resize(rows.size());
  rows.slacks(x, s.data());
  rows.products(d, ad.data());
  for (size_t k = 0; k < s.size(); ++k)
    if (ad[k] > 0) amax = std::min(amax, s[k] / ad[k]);
  for (Eigen::Index c = 0; c < 2 * p.nb; ++c) {
    if (!p.free[static_cast<size_t>(c)]) continue;
    if (d[c] < 0 && p.lo[c] > -kInf) amax = std::min(amax, (x[c] - p.lo[c]) / -d[c]);
    if (d[c] > 0 && p.hi[c] < kInf) amax = std::min(amax, (p.hi[c] - x[c]) / d[c]);
  }
  return amax;
}

// Lower bound on min T over the problem linearised at x (convex), from multipliers λ_r >= 0 of its rows and ν of
// its consistency rows: T(y) >= T(x) + ∇T·(y - x) >= T(x) - ∇T·x - λ·c + Σ_j min_{lo_j <= y_j <= hi_j} coef_j y_j,
// coef = ∇T + Σ λ_r a_r + Eᵀν (weak duality: any λ >= 0 and ν give a bound, the closer to optimal the tighter).
double lagrangian_bound(const Problem& p, const JerkRowGroups& rows, const Eigen::VectorXd& x, double T,
                        const Eigen::VectorXd& gT, const Eigen::VectorXd& nu, const std::vector<double>& lam) {
  Eigen::VectorXd coef = gT;
  double lower = T - gT.dot(x) - rows.weighted_rhs(lam.data());
  rows.scatter(lam.data(), coef);
  for (Eigen::Index k = 0; k < p.sh.n; ++k) {
    const JerkRow& e = p.consistency[static_cast<size_t>(k)];
    for (int i = 0; i < e.n; ++i) coef[e.col[i]] += nu[k] * e.val[i];
  }
  for (Eigen::Index c = 0; c < 2 * p.nb; ++c) {
    const bool f = p.free[static_cast<size_t>(c)] != 0;
    const double lo = f ? p.cert_lo[c] : x[c], hi = f ? p.cert_hi[c] : x[c];
    if (coef[c] > 0) lower += coef[c] * lo;
    else if (coef[c] < 0) lower += coef[c] * hi;
    if (!std::isfinite(lower)) return -kInf;
  }
  return lower;
}

// The barrier's bound: λ_r = (1 + a_r·d / s_r) / (t s_r) (the barrier's multiplier after the step d, to first
// order; solve/barrier.hpp), clipped at 0.
double multiplier_bound(const Problem& p, const JerkRowGroups& rows, const Eigen::VectorXd& x, double T,
                        double t, Step& st) {
  std::vector<double>&lam = st.lam, &ad = st.scratch;
  lam.resize(rows.size()), ad.resize(rows.size());
  rows.slacks(x, lam.data());
  rows.products(st.d, ad.data());
  for (size_t k = 0; k < lam.size(); ++k) {
    const double s = lam[k];
    lam[k] = std::max(0.0, 1.0 + ad[k] / s) / (t * s);
  }
  return lagrangian_bound(p, rows, x, T, st.gT, st.nu, lam);
}

// The primal-dual interior-point method (Mehrotra's predictor-corrector), tried before the barrier path: on the
// same banded KKT matrix, with the rows' Hessian weights λ_r / s_r of its own multipliers λ instead of the
// barrier's 1 / (t s_r²), it follows the central path without the barrier's inner centring (the barrier took
// 70-90 damped steps at N = 1000, 10-14 after each of its 20x increases of t). Feasible: x stays strictly inside
// the rows linearised at it (fraction to the boundary), so inside the true rows, and the jerk rows are
// linearised again at each iterate (their slacks only grow: the tangent lies below J/√θ). Its answer is certified
// like the barrier's, by weak duality with its own λ and ν (lagrangian_bound); where it does not certify within
// its iterations, or a step fails, the barrier path runs from the same start. True: x certified to `tolerance`.
// An iteration's stages (predictor, centring, corrector, certificate, step) share a dozen per-row and per-bound
// vectors that a split would pass around, hence
// long function: one iteration of the method, its stages in order.
bool primal_dual(const Problem& p, JerkRowGroups& rows, Eigen::VectorXd& x, double T, double tolerance,
                 JerkOutput& out, std::chrono::steady_clock::time_point deadline, Eigen::VectorXd& best,
                 double& best_gap) {
  const Eigen::Index nb = p.nb, nx = 2 * nb;
  const size_t R = rows.size();
  BandLdlt K(3 * nb - 1);
  Step st(3 * nb - 1);
  PdTerms pd;
  pd.hess_row.resize(R), pd.grad_row.resize(R);
  for (Eigen::VectorXd* v : {&pd.hess_lo, &pd.hess_hi, &pd.grad_lo, &pd.grad_hi}) v->setZero(nx);
  // Slacks (rows, then each finite bound of a free unknown) and their multipliers; g_lo, g_hi 0 where no bound.
  std::vector<double> s(R), lam(R), ds(R), dlam(R), ds_aff(R), dlam_aff(R), lam_full(R), s_next(R);
  std::vector<double> inv_s(R), inv_lam(R);  // 1 / s and 1 / λ at the iterate: the ratio tests multiply
  // The per-row vectors as arrays: each pass is packet operations, its sums and maxima tree reductions (a running
  // scalar sum or maximum waits on every step).
  auto A = [](std::vector<double>& v) {
    return Eigen::Map<Eigen::ArrayXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  };
  auto S = A(s), L = A(lam);
  Eigen::VectorXd glo = Eigen::VectorXd::Zero(nx), ghi = glo, zlo = glo, zhi = glo, zlo_aff = glo, zhi_aff = glo;
  auto has_lo = [&](Eigen::Index c) { return p.free[static_cast<size_t>(c)] && p.lo[c] > -kInf; };
  auto has_hi = [&](Eigen::Index c) { return p.free[static_cast<size_t>(c)] && p.hi[c] < kInf; };
  auto bound_slacks = [&]() {
    for (Eigen::Index c = 0; c < nx; ++c) {
      if (has_lo(c)) glo[c] = x[c] - p.lo[c];
      if (has_hi(c)) ghi[c] = p.hi[c] - x[c];
    }
  };
  rows.slacks(x, s.data());
  bound_slacks();
  double m = static_cast<double>(R);
  for (Eigen::Index c = 0; c < nx; ++c) m += has_lo(c) + has_hi(c);
  const double mu0 = T / m;  // the barrier's first centre: a duality gap of T
  const double mu_floor = 0.1 * tolerance * T / m;  // a tenth of the gap the tolerance allows
  L = mu0 / S;
  for (Eigen::Index c = 0; c < nx; ++c) {
    if (has_lo(c)) zlo[c] = mu0 / glo[c];
    if (has_hi(c)) zhi[c] = mu0 / ghi[c];
  }
  // The multipliers' step for the primal step dx from the complementarity rows λ ds + s dλ = γ - λ s (ds = -a·dx;
  // pd.grad_row = γ / s, 0 for the predictor), and the largest primal and dual steps keeping s, λ > 0.
  auto directions = [&](const Eigen::VectorXd& dx, std::vector<double>& dsv, std::vector<double>& dl,
                        Eigen::VectorXd& dzlo, Eigen::VectorXd& dzhi, double& ap, double& ad) {
    rows.products(dx, dsv.data());
    auto d = A(dsv), l = A(dl);
    d = -d;
    if (pd.rows_in_gradient) l = A(pd.grad_row) - L - L * d * A(inv_s);
    else l = -L - L * d * A(inv_s);
    // The largest -ds / s and -dλ / λ.
    const double rp = R ? std::max(0.0, (-d * A(inv_s)).maxCoeff()) : 0.0;
    const double rd = R ? std::max(0.0, (-l * A(inv_lam)).maxCoeff()) : 0.0;
    ap = rp > 0 ? 1.0 / rp : kInf;
    ad = rd > 0 ? 1.0 / rd : kInf;
    for (Eigen::Index c = 0; c < nx; ++c) {
      if (has_lo(c)) {
        dzlo[c] = (pd.grad_lo[c] - zlo[c] * glo[c] - zlo[c] * dx[c]) / glo[c];
        if (dx[c] < 0) ap = std::min(ap, -glo[c] / dx[c]);
        if (dzlo[c] < 0) ad = std::min(ad, -zlo[c] / dzlo[c]);
      }
      if (has_hi(c)) {
        dzhi[c] = (pd.grad_hi[c] - zhi[c] * ghi[c] + zhi[c] * dx[c]) / ghi[c];
        if (dx[c] > 0) ap = std::min(ap, ghi[c] / dx[c]);
        if (dzhi[c] < 0) ad = std::min(ad, -zhi[c] / dzhi[c]);
      }
    }
  };
  // The bounds' part of Σ (s + ap ds)(λ + ad dλ).
  auto bound_gap = [&](double ap, double ad, const Eigen::VectorXd& dx, const Eigen::VectorXd& dzlo,
                       const Eigen::VectorXd& dzhi) {
    double sum = 0;
    for (Eigen::Index c = 0; c < nx; ++c) {
      if (has_lo(c)) sum += (glo[c] + ap * dx[c]) * (zlo[c] + ad * dzlo[c]);
      if (has_hi(c)) sum += (ghi[c] - ap * dx[c]) * (zhi[c] + ad * dzhi[c]);
    }
    return sum;
  };
  const int max_iterations = 100;
  int short_steps = 0;  // consecutive iterations whose primal or dual step was below 0.05
  int stale = 0;        // consecutive certificates that did not improve on the best by 1 %
  Eigen::VectorXd dx_aff, g, dzlo(nx), dzhi(nx), next;
  for (int it = 0; it < max_iterations; ++it) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    // The predictor: γ = 0. The rows' reciprocals, Hessian weights λ / s and Σ s λ in one pass.
    A(inv_lam) = 1.0 / (S * L);  // one division: 1 / (s λ) gives both reciprocals
    A(inv_s) = L * A(inv_lam);
    A(inv_lam) *= S;
    A(pd.hess_row) = L * A(inv_s);
    const double row_gap = (S * L).sum();
    pd.rows_in_gradient = false;
    for (Eigen::Index c = 0; c < nx; ++c) {
      pd.hess_lo[c] = has_lo(c) ? zlo[c] / glo[c] : 0.0;
      pd.hess_hi[c] = has_hi(c) ? zhi[c] / ghi[c] : 0.0;
      pd.grad_lo[c] = pd.grad_hi[c] = 0.0;
    }
    if (!newton_step(p, rows, x, 1.0, K, st, &pd)) return false;
    ++out.newton_steps;
    dx_aff = st.d;
    double ap = 0, ad = 0;
    directions(dx_aff, ds_aff, dlam_aff, zlo_aff, zhi_aff, ap, ad);
    const double mu = (row_gap + bound_gap(0, 0, dx_aff, zlo_aff, zhi_aff)) / m;
    const double apa = std::min(1.0, ap), ada = std::min(1.0, ad);
    const double mu_aff =
        (((S + apa * A(ds_aff)) * (L + ada * A(dlam_aff))).sum() + bound_gap(apa, ada, dx_aff, zlo_aff, zhi_aff)) /
        m;
    // The centring target σμ, not below mu_floor: a duality gap far below the tolerance's only makes the
    // active rows' λ/s huge and the KKT solves inexact (seen: the bound closing to 1e-5, then lost).
    const double sigma = std::pow(std::min(1.0, mu_aff / mu), 3);
    const double target = std::max(sigma * mu, mu_floor);
    // The corrector: γ = the target less the predictor's second-order term, on the same factorisation.
    A(pd.grad_row) = (target - A(ds_aff) * A(dlam_aff)) * A(inv_s);
    pd.rows_in_gradient = true;
    for (Eigen::Index c = 0; c < nx; ++c) {
      if (has_lo(c)) pd.grad_lo[c] = target - dx_aff[c] * zlo_aff[c];
      if (has_hi(c)) pd.grad_hi[c] = target + dx_aff[c] * zhi_aff[c];
    }
    kkt_gradient(p, rows, x, 1.0, st.inv_slack, &pd, st.gT, g);
    if (!solve_kkt(p, g, 1.0, st)) return false;
    const Eigen::VectorXd dx = st.d;
    directions(dx, ds, dlam, dzlo, dzhi, ap, ad);
    // The certificate at x, as the barrier's: the multipliers after the full step (λ + dλ, clipped at 0) and the
    // step's ν satisfy ∇T(x) + ∇²T dx + Aᵀλ + Eᵀν = 0, so the bound is tight as dx vanishes. The bound's gap
    // T - lower is at least Σ λ_r s_r (lagrangian_bound's minimum over the box is at most its value at x, and
    // E x = 0): the whole bound is taken only where that sum leaves it a chance.
    A(lam_full) = (L + A(dlam)).max(0.0);
    const double full_gap = (A(lam_full) * S).sum();
    if (full_gap <= 2 * tolerance * T) {
      const double lower = lagrangian_bound(p, rows, x, T, st.gT, st.nu, lam_full);
      out.gap = std::max(0.0, T - lower) / T;
      if (T - lower <= tolerance * T) return true;
      // The best certified iterate so far; eight certificates in a row without 1 % progress is a stall (the
      // KKT systems lose the last digits on grids whose intervals span decades: seen at 1.2e-7 against 1e-7).
      if (out.gap < 0.99 * best_gap) best_gap = out.gap, best = x, stale = 0;
      else if (++stale == 8) return false;
    } else {
      out.gap = full_gap / T;  // a lower bound of the certificate's gap here
    }
    ap = std::min(1.0, 0.995 * ap), ad = std::min(1.0, 0.995 * ad);
    // Back from a step whose θ reaches 0 between grid points (T infinite; the rows hold only at the grid points).
    double T_next = kInf;
    for (int back = 0;; ++back) {
      next = x + ap * dx;
      rows.relinearise(next);
      T_next = strictly_inside(p, rows, next, s_next) ? jerk_quadrature_time(p.sh, next, nullptr, nullptr) : kInf;
      if (std::isfinite(T_next) || back == 30) break;
      ap *= 0.5;
    }
    if (!std::isfinite(T_next)) return false;
    x = next;
    T = T_next;
    L += ad * A(dlam);
    zlo += ad * dzlo, zhi += ad * dzhi;
    S = A(s_next);  // the rows' slacks at the new x, linearised there
    bound_slacks();
    // Three short steps in a row: the iterate has left the central path (a few rows' slacks change by orders of
    // magnitude per step, near a rest end or on a grid whose intervals differ a thousandfold). The multipliers
    // are set back to the centre of this x, λ s = μ for every row and bound: any λ > 0 is a valid dual start, and
    // the certificate uses only the step's own. Giving up there instead (to the barrier path, 400 steps) cost
    // 5-6 s on random non-uniform grids of 400 points where this takes 30-50 iterations (bench/README.md).
    short_steps = ap < 0.05 || ad < 0.05 ? short_steps + 1 : 0;
    if (short_steps == 3) {
      const double mc = ((S * L).sum() + bound_gap(0, 0, dx, zlo, zhi)) / m;
      L = mc / S;
      for (Eigen::Index c = 0; c < nx; ++c) {
        if (has_lo(c)) zlo[c] = mc / glo[c];
        if (has_hi(c)) zhi[c] = mc / ghi[c];
      }
      short_steps = 0;
    }
  }
  return false;
}

}  // namespace

bool jerk_scaled_start(const JerkInput& in, const JerkShape& sh, const JerkRowSet& rows, const Eigen::VectorXd& hi,
                       Eigen::VectorXd& x) {
  const Eigen::Index n = sh.n, nb = n + 1;
  if (!sh.rest0 || !sh.restN || n < 4) return false;
  // b at the grid points: the mean of the no-jerk optimum's s̈ on the two sides.
  const Eigen::VectorXd& th = in.theta_hint;
  Eigen::VectorXd u(n), b = Eigen::VectorXd::Zero(nb), w = Eigen::VectorXd::Zero(nb);
  for (Eigen::Index k = 0; k < n; ++k) u[k] = (th[k + 1] - th[k]) / (2 * sh.ds[k]);
  for (Eigen::Index k = 1; k < n; ++k) b[k] = 0.5 * (u[k - 1] + u[k]), w[k] = 1;
  // θ by the recursion from b; F(b) = θ_{N-1} + 1.5 Δs_{N-1} b_{N-1} is the residual of the last (rest)
  // interval, linear in b: the shift b + α·1 closes it.
  auto closure = [&](const Eigen::VectorXd& bb, Eigen::VectorXd* theta) {
    double t = 1.5 * sh.ds[0] * bb[1];
    if (theta) theta->setZero(nb), (*theta)[1] = t;
    for (Eigen::Index k = 1; k < n - 1; ++k) {
      t += sh.ds[k] * (bb[k] + bb[k + 1]);
      if (theta) (*theta)[k + 1] = t;
    }
    return t + 1.5 * sh.ds[n - 1] * bb[n - 1];
  };
  const double fw = closure(w, nullptr);
  if (!(fw > 0)) return false;
  b -= (closure(b, nullptr) / fw) * w;
  Eigen::VectorXd theta;
  closure(b, &theta);
  x.resize(2 * nb);
  x.head(nb) = theta;
  x.tail(nb) = b;
  for (Eigen::Index k = 1; k < n; ++k)
    if (!(theta[k] > 0)) return false;
  if (!std::isfinite(jerk_quadrature_time(sh, x, nullptr, nullptr))) return false;
  // The κ for which κ x holds every row: the limits scale by κ, the jerk rows' left side by κ and their right
  // side J/√θ by 1/√κ. A row with a negative right-hand side that x meets by a negative left side (a contact
  // polygon need not contain (θ, s̈) = 0) bounds κ from below.
  double kappa = kInf, kappa_lo = 0.0;
  for (const JerkRow& r : rows.point) {
    const double l = r.dot(x);
    if (l > 0) kappa = std::min(kappa, r.rhs / l);
    else if (l < 0 && r.rhs < 0) kappa_lo = std::max(kappa_lo, r.rhs / l);
    else if (l == 0 && !(r.rhs >= 0)) return false;  // l = 0: e.g. a row of a rest end's fixed zeros
  }
  for (const JerkLimitRow& r : rows.jerk) {
    const double g = r.lin.dot(x);
    if (g > 0) kappa = std::min(kappa, std::pow(r.J / (g * std::sqrt(x[r.point])), 2.0 / 3.0));
  }
  for (Eigen::Index k = 0; k < nb; ++k)
    if (x[k] > 0 && hi[k] < kInf) kappa = std::min(kappa, hi[k] / x[k]);
  if (!(kappa > 0) || !std::isfinite(kappa)) return false;
  // 0.9 of the largest, or halfway into the range where a lower bound leaves less room.
  const double k = 0.9 * kappa > kappa_lo * 1.01 ? 0.9 * kappa : 0.5 * (kappa_lo + kappa);
  if (!(k > kappa_lo * (1 + 1e-9) && k < kappa)) return false;
  x *= k;
  return true;
}

bool jerk_newton(const JerkInput& in, const JerkShape& sh, const JerkRowSet& set, const Eigen::VectorXd& lo,
                 const Eigen::VectorXd& hi, const Eigen::VectorXd& box, double first_gap, Eigen::VectorXd& x,
                 JerkOutput& out, std::chrono::steady_clock::time_point deadline) {
  const Eigen::Index nb = sh.n + 1, nx = 2 * nb;
  Problem p{sh, lo, hi, std::vector<char>(static_cast<size_t>(nx), 0), {}, jerk_consistency_rows(sh),
            set.jerk, nb, {}, {}};
  // Rows of one free unknown are bounds; the box (certificate: every unknown bounded) stays far from the optimum.
  for (Eigen::Index c = 0; c < nx; ++c) {
    p.free[static_cast<size_t>(c)] = lo[c] < hi[c];
    if (p.free[static_cast<size_t>(c)]) p.lo[c] = std::max(p.lo[c], -box[c]), p.hi[c] = std::min(p.hi[c], box[c]);
  }
  for (const JerkRow& row : set.point) {
    JerkRow r;  // the fixed unknowns' terms moved to the right-hand side
    r.rhs = row.rhs;
    for (int i = 0; i < row.n; ++i) {
      if (p.free[static_cast<size_t>(row.col[i])]) r.add(row.col[i], row.val[i]);
      else r.rhs -= row.val[i] * x[row.col[i]];
    }
    if (r.n == 0) continue;  // a constant row: grid_violation checks it
    if (r.n == 1) {
      const int c = r.col[0];
      if (r.val[0] > 0) p.hi[c] = std::min(p.hi[c], r.rhs / r.val[0]);
      else p.lo[c] = std::max(p.lo[c], r.rhs / r.val[0]);
    } else {
      p.point.push_back(r);
    }
  }
  // x must be strictly feasible; every fixed value 0 (rest to rest: the starts are slowed by scaling).
  for (Eigen::Index c = 0; c < nx; ++c)
    if (!p.free[static_cast<size_t>(c)] && lo[c] != 0) return false;
  p.cert_lo = p.lo, p.cert_hi = p.hi;
  jerk_implied_box(p.point, nb, p.cert_lo, p.cert_hi);
  p.point = jerk_undominated_rows(p.point, nb, p.lo, p.hi);
  JerkRowGroups rows(p.point, p.jerk, p.free);
  std::vector<double> slack;
  Eigen::VectorXd xs = x;
  rows.relinearise(xs);
  if (!strictly_inside(p, rows, xs, slack)) return false;

  const double n_ineq = p.n_ineq(rows.size());
  double T = jerk_quadrature_time(sh, xs, nullptr, nullptr);
  if (!std::isfinite(T)) return false;
  const double t_final = n_ineq / (0.25 * in.tolerance * T);  // T here is the start's, above the answer's
  int pd_steps = 0;  // the primal-dual method's iterations (counted in newton_steps with the barrier's)
  if (in.primal_dual) {
    Eigen::VectorXd xp = xs;
    Eigen::VectorXd best;
    double best_gap = kInf;
    if (primal_dual(p, rows, xp, T, in.tolerance, out, deadline, best, best_gap)) {
      x = xp;
      return true;
    }
    // Stalled within ten times the tolerance: its best iterate, ITERATION_LIMIT with that certified gap
    // (finish_structured), where the barrier path's 400 steps and then the GLPK rounds took minutes at N = 2000.
    if (best_gap <= 10 * in.tolerance) {
      x = best;
      out.gap = best_gap;
      return true;
    }
    pd_steps = out.newton_steps;  // the barrier's first step re-linearises `rows` at xs
  }
  BandLdlt K(3 * nb - 1);
  Step st(3 * nb - 1);
  double t = n_ineq / (first_gap * T);
  const int max_steps = 400;
  int since = 0;
  Eigen::VectorXd x0 = x, next(nx);
  x = xs;
  for (out.newton_steps = 0; out.newton_steps < max_steps; ++out.newton_steps) {
    if ((out.newton_steps & 7) == 7 && std::chrono::steady_clock::now() >= deadline) break;
    rows.relinearise(x);
    if (!newton_step(p, rows, x, t, K, st)) break;
    const bool final_t = t >= t_final;
    // At the final t and near its centre the bound is taken at every step (O(rows)): it certifies as soon as
    // the centring residual allows.
    if (final_t && st.dec2 <= 1e-2) {
      const double lower = multiplier_bound(p, rows, x, T, t, st);
      out.gap = std::max(0.0, T - lower) / T;
      if (T - lower <= in.tolerance * T) {
        out.newton_steps += 1 + pd_steps;
        return true;
      }
      if (st.dec2 <= 1e-9) {  // centred, yet the bound is not there: ask for less gap
        t *= 4;
        continue;
      }
    }
    double alpha = std::min(1.0, 0.99 * max_step(p, rows, x, st.d, st));
    if (st.dec2 >= 0.1) {
      const double phi0 = barrier_value(p, rows, x, t, slack);
      for (int ls = 0; ls < 60; ++ls, alpha *= 0.5)
        if (barrier_value(p, rows, x + alpha * st.d, t, slack) <= phi0 - 0.25 * alpha * st.dec2) break;
    }
    next = x + alpha * st.d;
    rows.relinearise(next);
    bool centred = st.dec2 <= 0.5;
    const double T_next =
        strictly_inside(p, rows, next, slack) ? jerk_quadrature_time(sh, next, nullptr, nullptr) : kInf;
    if (!std::isfinite(T_next)) {
      if (st.dec2 > 1e-3) break;
      centred = true;  // rounding at a tiny decrement: stay, as if centred
      if (final_t) t *= 4;
    } else {
      x = next;
      T = T_next;
    }
    ++since;
    if (!final_t && (centred || since >= 50)) {
      t = std::min(t * 20, t_final);
      since = 0;
    }
  }
  x = x0;
  return false;
}

}  // namespace pathpace::detail
