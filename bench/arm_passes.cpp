// Issue 25, a measured floor for the arm case: the relaxed and the full reachability analysis of velocity +
// acceleration limits (rest to rest) without polygons. Not the library: a standalone prototype that
// bench/arm_passes.py builds, feeds and checks against pathpace (same grid, same p', p'').
//
// On interval k (x = θ_k, y = θ_{k+1}, h = 1 / (2Δs_k)) every row of eq. (26) bounds y by a line in x:
// a joint's rows ±(p'' θ + p' s̈) <= A at s_k (forward) and at s_{k+1} (backward), with s̈ = (y - x) h, read
// α x + β y <= c, give y <= (c - α x) / β for β > 0 and y >= (c - α x) / β for β < 0; K_{k+1} adds y's box. So
// the interval's set is {Lo(x) <= y <= Hi(x)}: Hi the minimum of lines (concave), Lo the maximum (convex), and
// K_k = {x : g(x) = Hi(x) - Lo(x) >= 0} an interval. Its top is the largest root of the concave piecewise-
// linear g, found by Newton's method from x_hi with g's left derivative: from the right of the root each step
// lands in [root, x) and, once the two active lines are those at the root, on it (1.6 evaluations of g per
// interval on the arm corpus). The greedy pass takes y = Hi(θ_k). The relaxation drops the rows with α > 0
// and β > 0 (the only ones that break max-closure, as pathpace's Chain does): its greedy profile θ' is a lower
// bound on T*, the full one's θ an upper bound (the bracket of pathpace's reachability stage).
//
// Not done here (pathpace does it): units (Scale), K_k's bottom (0 from rest), pruned rows, the emptiness and
// unboundedness reports, the exact-feasibility step, the windows where the bracket is not tight.
//
// Input (binary, native endianness): int32 N, n; double s[N+1], dq[(N+1) n], ddq[(N+1) n] (row-major by
// grid point), v[n], A[n]. Output: T(θ') and T(θ) of the relaxed and the full pass.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

struct Ln {
  double P, Q;  // y = P + Q x
};

struct Data {
  int N = 0, n = 0;
  std::vector<double> s, dq, ddq, v, A;
};

// Both analyses in one backward pass over the intervals: each interval's lines are made once, the coupling
// rows' after the others, so that the relaxed analysis reads a prefix (as pathpace's Chain::relaxed_rows).
// Out of line so that callgrind counts it alone (bench/arm_passes.py --callgrind).
struct Analysis {
  std::vector<double> k_hi, theta;
  double T = 0.0;
};

// Newton on g = min U - max L from x (see the file's comment); U's last line and L's last are K_{k+1}'s sides.
// Returns K_k's top, or NaN if g < 0 on all of [0, x].
inline double top_of_k(const Ln* U, int mu, const Ln* L, int ml, double x) {
  for (int it = 0; it < 64; ++it) {
    int iu = 0, il = 0;
    double vu = U[0].P + U[0].Q * x, vl = L[0].P + L[0].Q * x;
    // Ties: the line active just left of x (g's left derivative).
    for (int t = 1; t < mu; ++t) {
      const double v = U[t].P + U[t].Q * x;
      if (v < vu || (v == vu && U[t].Q > U[iu].Q)) vu = v, iu = t;
    }
    for (int t = 1; t < ml; ++t) {
      const double v = L[t].P + L[t].Q * x;
      if (v > vl || (v == vl && L[t].Q < L[il].Q)) vl = v, il = t;
    }
    if (vu - vl >= -1e-15 * std::max(std::abs(vu), 1.0)) break;
    const double slope = U[iu].Q - L[il].Q;
    if (!(slope < 0.0)) return NAN;  // g < 0 and not decreasing at x: g < 0 on all of [0, x]
    const double next = (L[il].P - U[iu].P) / slope;
    if (!(next < x)) break;
    x = next;
  }
  return std::max(0.0, x);
}

// The greedy pass: θ_{k+1} = Hi_k(θ_k) (the top of the slice; θ_k in K_k keeps it >= Lo_k(θ_k)).
inline void greedy(const Data& d, const std::vector<Ln>& up, const std::vector<int>& off, const std::vector<int>& cnt,
                   Analysis& a) {
  a.theta.assign(static_cast<size_t>(d.N) + 1, 0.0);
  a.T = 0.0;
  for (int k = 0; k < d.N; ++k) {
    const Ln* U = up.data() + off[k];
    const double x = a.theta[k];
    double y = U[0].P + U[0].Q * x;
    for (int t = 1; t < cnt[k]; ++t) y = std::min(y, U[t].P + U[t].Q * x);
    a.theta[k + 1] = std::max(0.0, y);
    a.T += 2.0 * (d.s[k + 1] - d.s[k]) / (std::sqrt(a.theta[k]) + std::sqrt(a.theta[k + 1]));
  }
}

__attribute__((noinline)) bool analyses(const Data& d, Analysis& relaxed, Analysis& full) {
  const int N = d.N, n = d.n;
  std::vector<double> x_hi(N + 1);
  for (int k = 0; k <= N; ++k) {
    double x = 1e300;
    for (int j = 0; j < n; ++j) {
      const double p = d.dq[k * n + j];
      if (p != 0.0) x = std::min(x, d.v[j] * d.v[j] / (p * p));
    }
    x_hi[k] = x;
  }
  relaxed.k_hi.assign(N + 1, 0.0);
  full.k_hi.assign(N + 1, 0.0);
  // Interval k's upper lines: the relaxed analysis's [off_r[k], off_r[k] + cnt_r[k]) (its K_{k+1} side last),
  // the full one's [off_f[k], ...) (the same lines, its own K_{k+1} side, then the coupling rows). Lower lines
  // (no coupling row bounds y from below) are shared, each analysis appending its own K_{k+1} side.
  const size_t per = 2 * static_cast<size_t>(n) + 2;
  std::vector<Ln> up(static_cast<size_t>(N) * 2 * (per + n)), lo(static_cast<size_t>(N) * per), coupled(2 * n);
  std::vector<int> off_r(N), cnt_r(N), off_f(N), cnt_f(N);
  int nu = 0;
  for (int k = N - 1; k >= 0; --k) {
    const double h = 1.0 / (2.0 * (d.s[k + 1] - d.s[k]));
    Ln* L = lo.data() + static_cast<size_t>(k) * per;
    int ml = 0, nc = 0;
    const int u0 = nu;
    double xb = x_hi[k];
    auto add = [&](double al, double be, double c) {
      if (be > 0.0) (al > 0.0 ? coupled[nc++] : up[nu++]) = {c / be, -al / be};
      else if (be < 0.0) L[ml++] = {c / be, -al / be};
      else if (al > 0.0) xb = std::min(xb, c / al);
    };
    for (int j = 0; j < n; ++j) {
      const double a0 = d.ddq[k * n + j], b0 = d.dq[k * n + j];
      const double a1 = d.ddq[(k + 1) * n + j], b1 = d.dq[(k + 1) * n + j], A = d.A[j];
      add(a0 - b0 * h, b0 * h, A);  // at s_k: a θ_k + b (θ_{k+1} - θ_k) h <= A, and its negative
      add(-a0 + b0 * h, -b0 * h, A);
      add(-b1 * h, a1 + b1 * h, A);  // at s_{k+1}: a θ_{k+1} + b (θ_{k+1} - θ_k) h <= A, and its negative
      add(b1 * h, -a1 - b1 * h, A);
    }
    const int mr = nu - u0;
    // The relaxed block: its lines, its K_{k+1}; then the full block: a copy with the full K_{k+1} and the coupling rows.
    up[nu++] = {relaxed.k_hi[k + 1], 0.0};
    const int f0 = nu;
    std::copy(up.begin() + u0, up.begin() + u0 + mr, up.begin() + nu);
    nu += mr;
    up[nu++] = {full.k_hi[k + 1], 0.0};
    for (int t = 0; t < nc; ++t) up[nu++] = coupled[t];
    L[ml] = {0.0, 0.0};  // K_{k+1}'s bottom: 0 from rest, both analyses
    off_r[k] = u0;
    cnt_r[k] = mr + 1;
    off_f[k] = f0;
    cnt_f[k] = nu - f0;
    relaxed.k_hi[k] = top_of_k(up.data() + u0, mr + 1, L, ml + 1, xb);
    full.k_hi[k] = top_of_k(up.data() + f0, nu - f0, L, ml + 1, xb);
    if (std::isnan(relaxed.k_hi[k]) || std::isnan(full.k_hi[k])) {
      std::fprintf(stderr, "no speed at grid point %d reaches the end\n", k);
      return false;
    }
  }
  greedy(d, up, off_r, cnt_r, relaxed);
  greedy(d, up, off_f, cnt_f, full);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  FILE* f = std::fopen(argv[1], "rb");
  if (!f) return 2;
  Data d;
  if (std::fread(&d.N, 4, 1, f) != 1 || std::fread(&d.n, 4, 1, f) != 1) return 2;
  auto read = [&](std::vector<double>& x, size_t m) {
    x.resize(m);
    if (std::fread(x.data(), 8, m, f) != m) std::exit(2);
  };
  const size_t pts = static_cast<size_t>(d.N) + 1, n = static_cast<size_t>(d.n);
  read(d.s, pts);
  read(d.dq, pts * n);
  read(d.ddq, pts * n);
  read(d.v, n);
  read(d.A, n);
  std::fclose(f);
  Analysis relaxed, full;
  if (!analyses(d, relaxed, full)) return 1;
  std::printf("%.17g %.17g\n", relaxed.T, full.T);
  return 0;
}
