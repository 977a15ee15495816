#include "solve/brent.hpp"

#include <algorithm>
#include <cmath>

namespace pathpace::detail {

namespace {

const double kGolden = 0.5 * (std::sqrt(5.0) - 1.0);

// The next point of a bracket that is not done: parabolic through (a, b, c) when b is the best and the
// step is less than half the one before last and stays inside, else golden towards the larger side.
double next_point(PeakBracket& c) {
  const double g = kGolden;
  const double tol = 1e-9 + 1e-7 * (c.c - c.a);
  double next;
  bool parabolic = false;
  if (c.fb >= c.fa && c.fb >= c.fc) {
    const double p = (c.b - c.a) * (c.fb - c.fc), q = (c.b - c.c) * (c.fb - c.fa);
    const double den = 2.0 * (p - q);
    if (den != 0.0) {
      const double d = -((c.b - c.a) * p - (c.b - c.c) * q) / den;
      if (std::abs(d) < 0.5 * std::abs(c.step_before) && c.b + d > c.a + tol && c.b + d < c.c - tol) {
        next = std::abs(d) < tol ? c.b + (d < 0 ? -tol : tol) : c.b + d;
        parabolic = true;
      }
    }
    if (!parabolic) next = c.b - c.a > c.c - c.b ? c.b - (1.0 - g) * (c.b - c.a) : c.b + (1.0 - g) * (c.c - c.b);
  } else if (c.fa >= c.fc) {  // f falls from a: the peak is nearer a
    next = c.a + (1.0 - g) * (c.b - c.a);
  } else {
    next = c.c - (1.0 - g) * (c.c - c.b);
  }
  c.step_before = c.step;
  c.step = next - c.b;
  if (!parabolic) c.step_before = c.c - c.a;  // a golden step re-opens the safeguard
  return next;
}

// The bracket with f(x) = fx: x becomes b if it is the best, else the end on its side.
void shrink(PeakBracket& c, double x, double fx) {
  if (fx >= c.fb) {
    if (x < c.b) {
      c.c = c.b;
      c.fc = c.fb;
    } else {
      c.a = c.b;
      c.fa = c.fb;
    }
    c.b = x;
    c.fb = fx;
  } else if (x < c.b) {
    c.a = x;
    c.fa = fx;
  } else {
    c.c = x;
    c.fc = fx;
  }
}

}  // namespace

double PeakBracket::best() const { return std::max({fa, fb, fc}); }

double PeakBracket::at() const { return fb >= fa && fb >= fc ? b : (fa >= fc ? a : c); }

PeakBracket golden_bracket(double a, double fa, double c, double fc) {
  PeakBracket p;
  p.a = a;
  p.c = c;
  p.fa = fa;
  p.fc = fc;
  p.b = fc > fa ? a + kGolden * (c - a) : c - kGolden * (c - a);
  p.step = p.step_before = c - a;
  return p;
}

void maximize_batch(std::vector<PeakBracket>& brackets, const BatchFunction& f, const BracketSettled& settled,
                    int max_steps) {
  std::vector<std::size_t> active;
  std::vector<double> x, fx;
  for (std::size_t i = 0; i < brackets.size(); ++i) {
    active.push_back(i);
    x.push_back(brackets[i].b);
  }
  if (active.empty()) return;
  f(active, x, fx);
  for (std::size_t q = 0; q < active.size(); ++q) brackets[active[q]].fb = fx[q];
  for (int it = 0; it < max_steps; ++it) {
    active.clear();
    x.clear();
    for (std::size_t i = 0; i < brackets.size(); ++i) {
      PeakBracket& c = brackets[i];
      if (c.done) continue;
      if (c.c - c.a <= 1e-7 || !std::isfinite(c.fb) || settled(i, c)) {
        c.done = true;
        continue;
      }
      active.push_back(i);
      x.push_back(next_point(c));
    }
    if (active.empty()) break;
    f(active, x, fx);
    for (std::size_t q = 0; q < active.size(); ++q) shrink(brackets[active[q]], x[q], fx[q]);
  }
}

}  // namespace pathpace::detail
