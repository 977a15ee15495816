#include "solve/binding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

namespace pathpace::detail {

BindingLabels binding_labels(const Chain& chain, const GridSets& sets, const Eigen::VectorXd& theta, double* violation,
                             double tolerance) {
  const Eigen::Index n = chain.intervals();
  std::vector<int> out(static_cast<size_t>(n), -1);
  // The row labels, shared by the intervals and with the grid's sets; copied only if an id outside them (e.g. a
  // box's side) needs a name too (a copy of every label per solve was about 0.5 % of a call at N = 100).
  std::shared_ptr<std::vector<std::string>> names;
  const int rows = sets.labels ? static_cast<int>(sets.labels->size()) : 0;
  std::vector<std::pair<int, int>> extra;  // (id, index into names)
  double worst = 0.0;                       // the rows' largest violation (with `violation`)
  for (Eigen::Index k = 0; k < n; ++k) {
    double best = std::numeric_limits<double>::infinity();
    int best_id = 0;
    bool found = false;
    auto consider = [&](double slack, double scale, int id) {
      const double sc = std::max(scale, 1e-300);
      // Most rows have plenty of slack: a row whose slack is beyond twice min(best, tolerance) relative
      // to its scale (far beyond rounding) can neither win nor be reported, so it is skipped before the
      // division. The labels are those of dividing every row.
      const double bound = std::min(best, tolerance);
      if (bound > 0.0 ? slack > 2.0 * bound * sc : slack > 0.0) return;
      const double rel = slack / sc;
      if (rel < best) {
        best = rel;
        best_id = id;
        found = true;
      }
    };
    for (const Line& r : chain.rows(k)) {
      const double lhs_k = r.a * theta[k], lhs_k1 = r.b * theta[k + 1];
      consider(r.c - lhs_k - lhs_k1, std::max({std::abs(r.c), std::abs(lhs_k) + std::abs(lhs_k1)}), r.id);
      if (violation) worst = raise_violation(worst, r, theta[k], theta[k + 1]);
    }
    // A speed bound at either end of the interval (eq. 16); the ends fixed by boundary speeds are not
    // constraints of the path, and a bound of "no limit" is none.
    for (Eigen::Index j : {k, k + 1}) {
      const int id = chain.x_hi_id[static_cast<size_t>(j)];
      if (id >= 0 && j > 0 && j < n) consider(chain.x_hi[j] - theta[j], std::abs(chain.x_hi[j]), id);
    }
    if (!(found && best <= tolerance)) continue;
    int index = best_id;
    if (best_id < 0 || best_id >= rows) {
      auto it = std::find_if(extra.begin(), extra.end(), [best_id](const auto& e) { return e.first == best_id; });
      if (it == extra.end()) {
        if (!names)
          names = sets.labels ? std::make_shared<std::vector<std::string>>(*sets.labels)
                              : std::make_shared<std::vector<std::string>>();
        names->push_back(sets.label(best_id));
        it = extra.insert(extra.end(), {best_id, static_cast<int>(names->size()) - 1});
      }
      index = it->second;
    }
    out[static_cast<size_t>(k)] = index;
  }
  if (violation) *violation = std::max(worst, bound_violation(chain, theta));
  if (names) return BindingLabels(std::move(out), std::move(names));
  return BindingLabels(std::move(out), sets.labels ? sets.labels : std::make_shared<const std::vector<std::string>>());
}

}  // namespace pathpace::detail
