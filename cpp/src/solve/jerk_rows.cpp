#include "solve/jerk_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/jerk_interval.hpp"

namespace pathpace::detail {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

JerkShape jerk_shape(const Eigen::VectorXd& s, bool rest0, bool restN) {
  JerkShape sh;
  sh.n = s.size() - 1;
  sh.ds = s.tail(sh.n) - s.head(sh.n);
  sh.rest0 = rest0;
  sh.restN = restN;
  return sh;
}

JerkRow JerkLimitRow::linearised(double theta_bar) const {
  const double tb = std::max(theta_bar, 1e-300);
  JerkRow r = lin;
  r.add(static_cast<int>(point), 0.0);  // the θ column, if lin has none
  relinearise(r, tb, std::sqrt(tb));
  return r;
}

double jerk_total_time(const JerkShape& sh, const Eigen::VectorXd& x) {
  const Eigen::Index n = sh.n, nb = n + 1;
  double T = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (sh.rest_interval(k)) {
      const double th = x[sh.moving_end(k)];
      if (!(th > 0)) return kInf;
      T += rest_interval_time(th, sh.ds[k]);
      continue;
    }
    const double t = linear_b_time(x[k], x[nb + k], x[nb + k + 1], sh.ds[k]);
    if (!std::isfinite(t)) return kInf;
    T += t;
  }
  return T;
}

int jerk_quadrature_pieces(double theta0, double theta1, double theta_min) {
  const double ratio = std::max(theta0, theta1) / theta_min;
  return ratio <= 2 ? 1 : std::min(40, 1 + static_cast<int>(std::ceil(std::log2(ratio))));
}

double jerk_quadrature_time(const JerkShape& sh, const Eigen::VectorXd& x, Eigen::VectorXd* grad,
                            std::vector<double>* hess) {
  const Eigen::Index n = sh.n, nb = n + 1;
  if (grad) grad->setZero(2 * nb);
  if (hess) hess->assign(static_cast<size_t>(9 * n), 0.0);
  double T = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double ds = sh.ds[k];
    double* h = hess ? hess->data() + 9 * k : nullptr;
    if (sh.rest_interval(k)) {
      const Eigen::Index m = sh.moving_end(k);
      const double th = x[m];
      if (!(th > 0)) return kInf;
      const double r = std::sqrt(th);
      T += rest_interval_time(th, ds);
      if (grad) (*grad)[m] += -1.5 * ds / (th * r);
      if (h) h[0] = 2.25 * ds / (th * th * r);
      continue;
    }
    // θ(σ) = θ_k + 2 b_k σ + (b_{k+1} - b_k) σ²/Δs = v·(1, 2σ - σ²/Δs, σ²/Δs): T_k = ∫ θ^{-1/2}.
    const double t0 = x[k], b0 = x[nb + k], b1 = x[nb + k + 1];
    double tk = 0, g[3] = {0, 0, 0};
    // Pieces graded geometrically towards the end of smaller θ, halving, until θ varies by at most ~2 on each:
    // 8-point Gauss-Legendre on one piece of an interval whose θ falls 28-fold loses 2.4e-4 of its time, on
    // the graded pieces ~1e-12 (next to a rest ramp, θ at the ramp's end can be that small).
    const double th_end = t0 + ds * (b0 + b1), th_min = linear_b_min_theta(t0, b0, b1, ds);
    if (!(th_min > 0)) return kInf;
    const int pieces = jerk_quadrature_pieces(t0, th_end, th_min);
    const bool towards_end = th_end < t0;
    for (int piece = 0; piece < pieces; ++piece) {
      // Piece `piece` of the graded split, as [u0, u1] in units of ds measured from the small end.
      const double u1 = piece == 0 ? 1.0 : std::ldexp(1.0, -piece), u0 = piece == pieces - 1 ? 0.0 : 0.5 * u1;
      for (int i = 0; i < 8; ++i) {
        const double u = u0 + (u1 - u0) * gl8_nodes()[i];
        const double sg = (towards_end ? 1.0 - u : u) * ds, q = sg * sg / ds;
        const double dv[3] = {1.0, 2 * sg - q, q};
        const double th = t0 + b0 * dv[1] + b1 * dv[2];
        if (!(th > 0)) return kInf;
        // One division and one root per node: 1/θ, and θ^(-1/2) as its root.
        const double w = gl8_weights()[i] * (u1 - u0) * ds, inv = 1.0 / th, f = w * std::sqrt(inv);
        tk += f;
        const double f1 = -0.5 * f * inv;
        for (int a = 0; a < 3; ++a) g[a] += f1 * dv[a];
        if (h) {
          const double f2 = 0.75 * f * inv * inv;
          for (int a = 0; a < 3; ++a)
            for (int c = 0; c <= a; ++c) h[3 * a + c] += f2 * dv[a] * dv[c];
        }
      }
    }
    if (h)  // the upper triangle from the lower
      for (int a = 0; a < 3; ++a)
        for (int c = a + 1; c < 3; ++c) h[3 * a + c] = h[3 * c + a];
    T += tk;
    if (grad) {
      (*grad)[k] += g[0];
      (*grad)[nb + k] += g[1];
      (*grad)[nb + k + 1] += g[2];
    }
  }
  return T;
}

std::vector<JerkRow> jerk_consistency_rows(const JerkShape& sh) {
  std::vector<JerkRow> out;
  const Eigen::Index n = sh.n;
  out.reserve(static_cast<size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    JerkRow r;
    const double ds = sh.ds[k];
    if (k == 0 && sh.rest0) {
      r.add(1, 1.0), r.add(static_cast<int>(sh.b_col(1)), -1.5 * ds);
    } else if (k == n - 1 && sh.restN) {
      r.add(static_cast<int>(n - 1), 1.0), r.add(static_cast<int>(sh.b_col(n - 1)), 1.5 * ds);
    } else {
      r.add(static_cast<int>(k + 1), 1.0), r.add(static_cast<int>(k), -1.0);
      r.add(static_cast<int>(sh.b_col(k)), -ds), r.add(static_cast<int>(sh.b_col(k + 1)), -ds);
    }
    out.push_back(r);
  }
  return out;
}

std::vector<JerkRow> jerk_point_rows(const JerkInput& in, const JerkShape& sh) {
  std::vector<JerkRow> out;
  size_t count = 0;
  for (const ConstraintRows& cr : *in.rows) count += static_cast<size_t>(cr.rows() * (sh.n + 1));
  out.reserve(count);
  for (const ConstraintRows& cr : *in.rows)
    for (Eigen::Index k = 0; k <= sh.n; ++k)
      for (Eigen::Index j = 0; j < cr.rows(); ++j) {
        const double c = cr.c(k, j);
        if (!(c < kInf)) continue;
        JerkRow r;
        if (cr.a(k, j) != 0) r.add(static_cast<int>(k), cr.a(k, j));
        if (cr.b(k, j) != 0) r.add(static_cast<int>(sh.b_col(k)), cr.b(k, j));
        r.rhs = c;
        if (r.n > 0) out.push_back(r);
      }
  return out;
}

std::vector<JerkLimitRow> jerk_limit_rows(const JerkInput& in, const JerkShape& sh) {
  std::vector<JerkLimitRow> out;
  const PathSamples& smp = *in.samples;
  const Eigen::Index n = sh.n, dof = smp.dof();
  out.reserve(static_cast<size_t>(4 * dof * (n + 1)));
  for (Eigen::Index k = 0; k <= n; ++k) {
    if ((k == 0 && sh.rest0) || (k == n && sh.restN)) continue;
    for (int side = 0; side < 2; ++side) {
      if ((side == 0 && k == 0) || (side == 1 && k == n)) continue;
      JerkRow slope;  // b' on this side
      const Eigen::Index iv = side == 0 ? k - 1 : k;
      const double ds = sh.ds[iv];
      const int bl = static_cast<int>(sh.b_col(iv)), br = static_cast<int>(sh.b_col(iv + 1));
      if (iv == 0 && sh.rest0) slope.add(br, 1.0 / (3 * ds));
      else if (iv == n - 1 && sh.restN) slope.add(bl, -1.0 / (3 * ds));
      else slope.add(br, 1.0 / ds), slope.add(bl, -1.0 / ds);
      const Eigen::MatrixXd& p3 = side == 0 ? in.p3_left : in.p3_right;
      for (Eigen::Index j = 0; j < dof; ++j)
        for (int sign = 1; sign >= -1; sign -= 2) {
          const double J = sign > 0 ? in.jmax[j] : -in.jmin[j];
          if (!(J < kInf)) continue;
          JerkLimitRow r;
          for (int i = 0; i < slope.n; ++i) r.lin.add(slope.col[i], sign * smp.dq(k, j) * slope.val[i]);
          r.lin.add(static_cast<int>(sh.b_col(k)), sign * 3 * smp.ddq(k, j));
          r.lin.add(static_cast<int>(k), sign * p3(k, j));
          r.point = k;
          r.J = J;
          out.push_back(r);
        }
    }
  }
  return out;
}

namespace {

// A row α θ_k + β b_k <= c of one grid point k (two columns, θ_k and b_k): false for any other row.
bool point_row(const JerkRow& r, Eigen::Index nb, int& k, double& alpha, double& beta) {
  if (r.n != 2) return false;
  const int t = std::min(r.col[0], r.col[1]), b = std::max(r.col[0], r.col[1]);
  if (t >= nb || b != t + nb) return false;
  k = t;
  alpha = r.col[0] == t ? r.val[0] : r.val[1], beta = r.col[0] == b ? r.val[0] : r.val[1];
  return true;
}

}  // namespace

std::vector<JerkRow> jerk_undominated_rows(const std::vector<JerkRow>& rows, Eigen::Index nb, const Eigen::VectorXd& lo,
                                           const Eigen::VectorXd& hi) {
  // b_k <= P + Q θ_k (β > 0) or b_k >= P + Q θ_k (β < 0) for a row α θ_k + β b_k <= c: P = c / β, Q = -α / β.
  struct Bound {
    double P, Q;
    std::size_t row;
  };
  std::vector<std::vector<Bound>> upper(static_cast<size_t>(nb)), lower(static_cast<size_t>(nb));
  std::vector<char> keep(rows.size(), 1);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const JerkRow& r = rows[i];
    int t = 0;
    double alpha = 0, beta = 0;
    if (!point_row(r, nb, t, alpha, beta)) continue;
    if (!(beta != 0) || !std::isfinite(alpha / beta) || !std::isfinite(r.rhs / beta)) continue;
    (beta > 0 ? upper : lower)[static_cast<size_t>(t)].push_back({r.rhs / beta, -alpha / beta, i});
  }
  for (Eigen::Index k = 0; k < nb; ++k) {
    const double L = lo[k], H = hi[k];
    if (!(std::isfinite(L) && std::isfinite(H) && L <= H)) continue;
    const double span = std::max(std::abs(L), std::abs(H));
    for (int side = 0; side < 2; ++side) {
      // Lower bounds are upper ones of -b: the same test with P, Q negated.
      const std::vector<Bound>& set = (side == 0 ? upper : lower)[static_cast<size_t>(k)];
      const double sg = side == 0 ? 1.0 : -1.0;
      for (const Bound& bi : set) {
        double from = L, to = H;  // where bi is within the margin of every other row's bound
        for (const Bound& bj : set) {
          if (&bj == &bi) continue;
          const double dq = sg * (bi.Q - bj.Q);
          const double room = sg * (bj.P - bi.P) + 1e-9 * (std::abs(bi.P) + std::abs(bj.P) +
                                                           (std::abs(bi.Q) + std::abs(bj.Q)) * span);
          if (dq > 0) to = std::min(to, room / dq);
          else if (dq < 0) from = std::max(from, room / dq);
          else if (room < 0) from = kInf;
        }
        if (!(from <= to)) keep[bi.row] = 0;
      }
    }
  }
  std::vector<JerkRow> out;
  out.reserve(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (keep[i]) out.push_back(rows[i]);
  return out;
}

void jerk_implied_box(const std::vector<JerkRow>& rows, Eigen::Index nb, Eigen::VectorXd& lo, Eigen::VectorXd& hi) {
  const Eigen::VectorXd theta_lo = lo.head(nb), theta_hi = hi.head(nb);
  for (const JerkRow& r : rows) {
    int t = 0;
    double alpha = 0, beta = 0;
    if (!point_row(r, nb, t, alpha, beta)) continue;
    const Eigen::Index b = nb + t;
    const double L = theta_lo[t], H = theta_hi[t];
    if (!(beta != 0) || !std::isfinite(L) || !std::isfinite(H)) continue;
    // b_k = (c - α θ_k) / β at the range's ends.
    const double at_L = (r.rhs - alpha * L) / beta, at_H = (r.rhs - alpha * H) / beta;
    if (!std::isfinite(at_L) || !std::isfinite(at_H)) continue;
    if (beta > 0) {
      const double v = std::max(at_L, at_H);
      hi[b] = std::min(hi[b], v + 1e-12 * (std::abs(at_L) + std::abs(at_H)));
    } else {
      const double v = std::min(at_L, at_H);
      lo[b] = std::max(lo[b], v - 1e-12 * (std::abs(at_L) + std::abs(at_H)));
    }
  }
}

JerkRowSet jerk_rows(const JerkInput& in, const JerkShape& sh) {
  return {jerk_point_rows(in, sh), jerk_limit_rows(in, sh)};
}

// Column bounds: the fixed ends, θ >= 0, and at a rest end the bound that the jerk of its interval (constant
// s⃛ = (2/9) θ^{3/2}/Δs², times p' there) puts on θ of the interval's moving end.
void jerk_column_bounds(const JerkInput& in, const JerkShape& sh, Eigen::VectorXd& lo, Eigen::VectorXd& hi) {
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

// Makes (θ, b) exactly consistent: θ by the forward recursion from the LP's b, the last free b absorbing the
// residual at the end (the LP holds the equalities to its tolerance only).
void jerk_make_consistent(const JerkShape& sh, Eigen::VectorXd& x, double theta_end, bool zero_b_end) {
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

}  // namespace pathpace::detail
