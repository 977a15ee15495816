#include "pathpace/auto_grid.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/validate.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace {

Eigen::VectorXd auto_grid(const Path& path, double tolerance, int min_intervals, int max_intervals) {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    detail::fail("grid_tolerance = " + detail::fmt(tolerance) + " must be in (0, 1)");
  if (min_intervals < 1) detail::fail("min_intervals = " + std::to_string(min_intervals) + " must be >= 1");
  if (max_intervals < min_intervals)
    detail::fail("max_intervals = " + std::to_string(max_intervals) + " must be >= min_intervals = " +
                 std::to_string(min_intervals));
  const double a = path.s_begin(), b = path.s_end();
  const double eps = 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});

  std::vector<double> s(static_cast<size_t>(min_intervals) + 1);
  for (int i = 0; i <= min_intervals; ++i) s[static_cast<size_t>(i)] = a + (b - a) * i / min_intervals;
  s.back() = b;
  if (const PiecewisePolynomialPath* pp = path.polynomial())
    for (Eigen::Index i = 1; i + 1 < pp->breakpoints().size(); ++i) s.push_back(pp->breakpoints()[i]);
  std::sort(s.begin(), s.end());
  // Points closer than rounding would make intervals of zero width.
  s.erase(std::unique(s.begin(), s.end(), [eps](double x, double y) { return y - x <= eps; }), s.end());
  s.back() = b;

  // Scales over the whole path, from the starting grid and its midpoints.
  const Eigen::Index n = path.dof();
  Eigen::VectorXd probe(2 * static_cast<Eigen::Index>(s.size()) - 1);
  for (size_t i = 0; i < s.size(); ++i) {
    probe[2 * static_cast<Eigen::Index>(i)] = s[i];
    if (i + 1 < s.size()) probe[2 * static_cast<Eigen::Index>(i) + 1] = 0.5 * (s[i] + s[i + 1]);
  }
  Eigen::MatrixXd q, dq, ddq;
  path.evaluate(probe, q, dq, ddq);
  const double scale0 = (q.colwise().maxCoeff() - q.colwise().minCoeff()).maxCoeff();
  const double scale1 = dq.cwiseAbs().maxCoeff(), scale2 = ddq.cwiseAbs().maxCoeff();
  if (!std::isfinite(scale0) || !std::isfinite(scale1) || !std::isfinite(scale2))
    detail::fail("path is not finite on [" + detail::fmt(a) + ", " + detail::fmt(b) + "]: cannot choose a grid");
  const double tol0 = tolerance * scale0, tol1 = tolerance * scale1, tol2 = tolerance * scale2;

  // Halve failing intervals, one sweep per level; only new intervals need checking.
  std::vector<double> grid = s, next;
  std::vector<char> check(grid.size() - 1, 1), next_check;
  Eigen::MatrixXd qe, dqe, ddqe, qm, dqm, ddqm;
  Eigen::VectorXd ends(static_cast<Eigen::Index>(grid.size()));
  for (;;) {
    ends = Eigen::Map<const Eigen::VectorXd>(grid.data(), static_cast<Eigen::Index>(grid.size()));
    path.evaluate(ends, qe, dqe, ddqe);
    std::vector<size_t> idx;
    for (size_t i = 0; i + 1 < grid.size(); ++i)
      if (check[i]) idx.push_back(i);
    if (idx.empty()) break;
    Eigen::VectorXd mids(static_cast<Eigen::Index>(idx.size()));
    for (size_t m = 0; m < idx.size(); ++m) mids[static_cast<Eigen::Index>(m)] = 0.5 * (grid[idx[m]] + grid[idx[m] + 1]);
    path.evaluate(mids, qm, dqm, ddqm);
    std::vector<char> split(grid.size() - 1, 0);
    size_t n_split = 0;
    for (size_t m = 0; m < idx.size(); ++m) {
      const Eigen::Index i = static_cast<Eigen::Index>(idx[m]), r = static_cast<Eigen::Index>(m);
      // An interval narrower than rounding cannot be halved: accept it.
      if (grid[idx[m] + 1] - grid[idx[m]] <= 4 * eps) continue;
      bool bad = false;
      for (Eigen::Index j = 0; j < n && !bad; ++j) {
        bad = std::abs(qm(r, j) - 0.5 * (qe(i, j) + qe(i + 1, j))) > tol0 ||
              std::abs(dqm(r, j) - 0.5 * (dqe(i, j) + dqe(i + 1, j))) > tol1 ||
              std::abs(ddqm(r, j) - 0.5 * (ddqe(i, j) + ddqe(i + 1, j))) > tol2;
      }
      if (bad) {
        split[idx[m]] = 1;
        ++n_split;
      }
    }
    if (n_split == 0) break;
    if (grid.size() - 1 + n_split > static_cast<size_t>(max_intervals))
      detail::fail("grid = 'auto' needs more than max_intervals = " + std::to_string(max_intervals) +
                   " intervals for grid_tolerance = " + detail::fmt(tolerance) +
                   ": raise the tolerance or max_intervals, or give the grid");
    next.clear();
    next_check.clear();
    for (size_t i = 0; i + 1 < grid.size(); ++i) {
      next.push_back(grid[i]);
      if (split[i]) {
        next.push_back(0.5 * (grid[i] + grid[i + 1]));
        next_check.push_back(1);
        next_check.push_back(1);
      } else {
        next_check.push_back(0);
      }
    }
    next.push_back(grid.back());
    grid.swap(next);
    check.swap(next_check);
  }
  return Eigen::Map<const Eigen::VectorXd>(grid.data(), static_cast<Eigen::Index>(grid.size()));
}

}  // namespace pathpace
