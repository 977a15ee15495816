#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "solve/brent.hpp"

using pathpace::detail::golden_bracket;
using pathpace::detail::maximize_batch;
using pathpace::detail::PeakBracket;

namespace {

// Brackets [a, c] of the functions fns, one batch per step; returns how many batches were asked for.
int run(const std::vector<std::function<double(double)>>& fns, std::vector<PeakBracket>& br,
        const pathpace::detail::BracketSettled& settled, std::vector<int>* evaluations = nullptr) {
  int batches = 0;
  if (evaluations) evaluations->assign(fns.size(), 0);
  maximize_batch(
      br,
      [&](const std::vector<std::size_t>& which, const std::vector<double>& xs, std::vector<double>& fs) {
        ++batches;
        fs.resize(which.size());
        for (std::size_t q = 0; q < which.size(); ++q) {
          EXPECT_GT(xs[q], br[which[q]].a);  // every point asked lies strictly inside its bracket
          EXPECT_LT(xs[q], br[which[q]].c);
          fs[q] = fns[which[q]](xs[q]);
          if (evaluations) ++(*evaluations)[which[q]];
        }
      },
      settled);
  return batches;
}

std::vector<PeakBracket> brackets(const std::vector<std::function<double(double)>>& fns, double a, double c) {
  std::vector<PeakBracket> br;
  for (const auto& f : fns) br.push_back(golden_bracket(a, f(a), c, f(c)));
  return br;
}

}  // namespace

TEST(Brent, FindsTheKnownMaximaOfSmoothKinkedAndMonotoneFunctionsInOneBatchPerStep) {
  // Maxima: 2 at 0.3 (a parabola), 1 at 0.5 (sin πx), 1 at 0.8 (a narrow Gaussian), 0 at 0.7 (a kink,
  // where parabolas do not apply: golden steps), 1 at the bracket's end 1 (increasing).
  const std::vector<std::function<double(double)>> fns = {
      [](double x) { return 2.0 - (x - 0.3) * (x - 0.3); },
      [](double x) { return std::sin(M_PI * x); },
      [](double x) { return std::exp(-(x - 0.8) * (x - 0.8) / 0.01); },
      [](double x) { return -std::abs(x - 0.7); },
      [](double x) { return x; }};
  const double peak[] = {0.3, 0.5, 0.8, 0.7, 1.0}, value[] = {2.0, 1.0, 1.0, 0.0, 1.0};
  std::vector<PeakBracket> br = brackets(fns, 0.0, 1.0);
  const int batches = run(fns, br, [](std::size_t, const PeakBracket&) { return false; });
  EXPECT_LE(batches, 31);
  for (std::size_t i = 0; i < fns.size(); ++i) {
    EXPECT_NEAR(br[i].at(), peak[i], 1e-5) << i;
    // Near a smooth peak the value errs by the square of the location's error; at the kink, by as much.
    EXPECT_NEAR(br[i].best(), value[i], i == 3 ? 1e-5 : 1e-9) << i;
    EXPECT_GE(br[i].best(), fns[i](br[i].at()));  // best() is a value found, at at()
    EXPECT_LE(br[i].best(), fns[i](br[i].at()));
  }
  // The smooth peaks converge (parabolic steps): a bracket below 1e-7, well before the step budget.
  for (std::size_t i = 0; i < 3; ++i) EXPECT_TRUE(br[i].done && br[i].c - br[i].a <= 1e-7) << i;
}

TEST(Brent, SettledBracketsAreNotEvaluatedAgainAndTheOthersGoOn) {
  const std::vector<std::function<double(double)>> fns = {[](double x) { return 2.0 - (x - 0.3) * (x - 0.3); },
                                                           [](double x) { return std::sin(M_PI * x); }};
  std::vector<PeakBracket> br = brackets(fns, 0.0, 1.0);
  std::vector<int> evaluations;
  run(fns, br, [](std::size_t i, const PeakBracket&) { return i == 0; }, &evaluations);
  EXPECT_EQ(evaluations[0], 1);  // the first batch only
  EXPECT_GT(evaluations[1], 3);
  EXPECT_TRUE(br[0].done);
  EXPECT_NEAR(br[1].at(), 0.5, 1e-5);
}

TEST(Brent, ABracketWhoseValueIsNotFiniteStopsAndAnEmptyBatchAsksNothing) {
  const std::vector<std::function<double(double)>> fns = {[](double) { return -INFINITY; }};
  std::vector<PeakBracket> br = brackets(fns, 0.0, 1.0);
  std::vector<int> evaluations;
  run(fns, br, [](std::size_t, const PeakBracket&) { return false; }, &evaluations);
  EXPECT_EQ(evaluations[0], 1);
  EXPECT_TRUE(br[0].done);
  std::vector<PeakBracket> none;
  EXPECT_EQ(run({}, none, [](std::size_t, const PeakBracket&) { return false; }), 0);
}
