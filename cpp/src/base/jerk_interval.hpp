#pragma once
// One grid interval of a jerk-limited timing (TimeScalingProblem::add_jerk_limits, docs/method.md "Jerk limits").
//
// s̈ = b(s) is linear in s on the interval, b(s_k + σ) = b_k + c σ with c = (b_{k+1} - b_k)/Δs, so θ = ṡ² is
// quadratic in σ, θ(σ) = θ_k + 2 b_k σ + c σ², and σ(τ) solves the linear ODE σ'' = b_k + c σ with σ(0) = 0,
// σ'(0) = ṡ_k: σ = b_k C1(τ) + ṡ_k S1(τ) with S1 = sinh(√c τ)/√c, C1 = (cosh(√c τ) - 1)/c (cos/sin for c < 0,
// a series where c τ² is small, which is also the c = 0 case σ = ṡ_k τ + b_k τ²/2).
//
// A rest end (ṡ = 0 at s_begin or s_end) instead has a constant s⃛ = j on its interval: s = j τ³/6 from the
// rest point, so θ = θ_1 (σ/Δs)^{4/3}, s̈ = b_1 (σ/Δs)^{1/3} with b_1 = 2 θ_1 / (3 Δs), time 3 Δs/√θ_1 and
// j = (2/9) θ_1^{3/2} / Δs². (A b linear in s cannot start from rest with s̈ = 0: θ ∝ σ² takes forever.)

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathpace::detail {

struct IntervalMotion {
  double sigma, sdot, sddot;  // σ = s - s_k, ṡ, s̈
};

// (C0, S1, C1) at τ for the ODE above: C0 = cosh(√c τ), S1 = sinh(√c τ)/√c, C1 = (C0 - 1)/c.
inline void jerk_basis(double c, double tau, double& c0, double& s1, double& c1) {
  const double z = c * tau * tau;
  if (std::abs(z) < 1e-2) {
    // Taylor series; the first omitted term is below z^5 / 10! < 3e-17 relative.
    c0 = 1 + z * (1.0 / 2 + z * (1.0 / 24 + z * (1.0 / 720 + z * (1.0 / 40320 + z / 3628800))));
    s1 = tau * (1 + z * (1.0 / 6 + z * (1.0 / 120 + z * (1.0 / 5040 + z / 362880))));
    c1 = tau * tau * (1.0 / 2 + z * (1.0 / 24 + z * (1.0 / 720 + z * (1.0 / 40320 + z / 3628800))));
  } else if (c > 0) {
    const double w = std::sqrt(c);
    c0 = std::cosh(w * tau);
    s1 = std::sinh(w * tau) / w;
    c1 = (c0 - 1) / c;
  } else {
    const double w = std::sqrt(-c);
    c0 = std::cos(w * tau);
    s1 = std::sin(w * tau) / w;
    c1 = 2 * std::sin(0.5 * w * tau) * std::sin(0.5 * w * tau) / (-c);
  }
}

// The motion τ after the start of a linear-b interval.
inline IntervalMotion linear_b_motion(double sdot0, double b0, double c, double tau) {
  double c0, s1, c1;
  jerk_basis(c, tau, c0, s1, c1);
  const double sigma = b0 * c1 + sdot0 * s1;
  return {sigma, b0 * s1 + sdot0 * c0, b0 + c * sigma};
}

// The smallest θ on [0, ds] of θ(σ) = θ0 + 2 b0 σ + c σ².
inline double linear_b_min_theta(double theta0, double b0, double b1, double ds) {
  const double c = (b1 - b0) / ds;
  double m = std::min(theta0, theta0 + ds * (b0 + b1));
  if (c > 0 && b0 < 0 && -b0 < c * ds) m = std::min(m, theta0 - b0 * b0 / c);
  return m;
}

// The time of a linear-b interval (+inf where θ reaches 0 on it): Newton on σ(τ) = ds, safeguarded by bisection.
inline double linear_b_time(double theta0, double b0, double b1, double ds) {
  if (!(linear_b_min_theta(theta0, b0, b1, ds) > 0)) return std::numeric_limits<double>::infinity();
  const double c = (b1 - b0) / ds, v0 = std::sqrt(theta0), v1 = std::sqrt(theta0 + ds * (b0 + b1));
  double tau = 2 * ds / (v0 + v1);  // exact for c = 0
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 100; ++it) {
    const IntervalMotion m = linear_b_motion(v0, b0, c, tau);
    const double f = m.sigma - ds;
    if (f < 0) lo = tau; else hi = tau;
    if (std::abs(f) <= 4e-16 * ds) break;
    double next = m.sdot > 0 ? tau - f / m.sdot : std::numeric_limits<double>::quiet_NaN();
    if (!(next > lo && next < hi)) next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2 * tau;
    if (next == tau) break;
    tau = next;
  }
  return tau;
}

// Gauss-Legendre nodes and weights on [0, 1] (8 points): for the time ∫ dσ/√θ and its derivatives, smooth
// where θ > 0 (solve/jerk_rows.hpp).
inline const double* gl8_nodes() {
  static const double x[8] = {0.019855071751231856, 0.10166676129318664, 0.2372337950418355, 0.4082826787521751,
                              0.5917173212478249,   0.7627662049581645,  0.8983332387068134, 0.9801449282487681};
  return x;
}
inline const double* gl8_weights() {
  static const double w[8] = {0.05061426814518813, 0.11119051722668724, 0.15685332293894364, 0.18134189168918100,
                              0.18134189168918100, 0.15685332293894364, 0.11119051722668724, 0.05061426814518813};
  return w;
}

// Rest-end interval (see above): time, and j = s⃛ on it, from θ at its moving end.
inline double rest_interval_time(double theta1, double ds) { return 3 * ds / std::sqrt(theta1); }
inline double rest_interval_jerk(double theta1, double ds) { return (2.0 / 9.0) * theta1 * std::sqrt(theta1) / (ds * ds); }

}  // namespace pathpace::detail
