#pragma once
// Maximisation of many one-dimensional functions at once, each on its own bracket: Brent's method
// (successive parabolic interpolation through the best point and its two neighbours, golden-section
// steps where a parabola does not apply or does not shrink the bracket fast enough; R. P. Brent,
// "Algorithms for Minimization without Derivatives", 1973, ch. 5), every step's evaluations of all the
// brackets in one batch (the continuous audit's contact slices are one warm-started LP sequence).

#include <cstddef>
#include <functional>
#include <vector>

namespace pathpace::detail {

/// A bracket a < b < c of a maximum, b the best interior point so far, f* the values there.
struct PeakBracket {
  double a = 0.0, b = 0.0, c = 0.0, fa = 0.0, fb = 0.0, fc = 0.0;
  double step = 0.0, step_before = 0.0;  // the last two steps (Brent's safeguard on parabolic steps)
  bool done = false;
  /// The largest value found, and where.
  double best() const;
  double at() const;
};

/// The bracket [a, c] with end values fa, fc, its interior point the golden section nearer the larger
/// end (fb is left for maximize_batch's first evaluation).
PeakBracket golden_bracket(double a, double fa, double c, double fc);

/// f(which, xs, fs): fs[q] = the value of bracket which[q]'s function at xs[q], for every q (one batch).
using BatchFunction =
    std::function<void(const std::vector<std::size_t>& which, const std::vector<double>& xs, std::vector<double>& fs)>;
/// settled(i, bracket): bracket i needs no further narrowing (the caller's own bound shows it).
using BracketSettled = std::function<bool(std::size_t i, const PeakBracket& bracket)>;

/// Narrows every bracket until it is shorter than 1e-7, its best value is not finite, `settled` says so,
/// or after max_steps batches (besides the first, which evaluates every b).
void maximize_batch(std::vector<PeakBracket>& brackets, const BatchFunction& f, const BracketSettled& settled,
                    int max_steps = 30);

}  // namespace pathpace::detail
