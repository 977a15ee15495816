#include "solve/jerk_row_groups.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace pathpace::detail {

namespace {

using Key = std::array<int, 3>;  // a row's columns, ascending, -1 after the used ones

bool key_less(const Key& a, const Key& b) {
  for (int i = 0; i < 3; ++i) {
    // -1 (unused) sorts last, so rows on fewer columns follow those on more
    const unsigned ua = static_cast<unsigned>(a[static_cast<size_t>(i)]);
    const unsigned ub = static_cast<unsigned>(b[static_cast<size_t>(i)]);
    if (ua != ub) return ua < ub;
  }
  return false;
}

}  // namespace

JerkRowGroups::JerkRowGroups(const std::vector<JerkRow>& point, const std::vector<JerkLimitRow>& jerk,
                             const std::vector<char>& free) {
  const std::size_t R = point.size() + jerk.size();
  for (std::vector<double>* v : {&v0_, &v1_, &v2_, &rhs_, &lin_theta_, &J_}) v->reserve(R);
  auto push = [&](double a0, double a1, double a2, double rhs, double lin_theta, double J) {
    v0_.push_back(a0), v1_.push_back(a1), v2_.push_back(a2), rhs_.push_back(rhs);
    lin_theta_.push_back(lin_theta), J_.push_back(J);
  };
  // The limit rows: bucketed by their first column (a counting sort: a grid point's rows come from several
  // constraints, so they are not adjacent in `point`), then by their whole column set within a bucket.
  std::vector<Key> keys(point.size());
  int columns = 0;
  for (std::size_t i = 0; i < point.size(); ++i) {
    const JerkRow& r = point[i];
    Key k{-1, -1, -1};
    const int used = std::min(r.n, 3);
    for (int j = 0; j < used; ++j) k[static_cast<size_t>(j)] = r.col[j];
    for (int a = 1; a < used; ++a)  // ascending (at most three)
      for (int b = a; b > 0 && k[static_cast<size_t>(b - 1)] > k[static_cast<size_t>(b)]; --b)
        std::swap(k[static_cast<size_t>(b - 1)], k[static_cast<size_t>(b)]);
    keys[i] = k;
    columns = std::max(columns, k[0] + 1);
  }
  std::vector<std::size_t> start(static_cast<size_t>(columns) + 1, 0), order(point.size());
  for (const Key& k : keys) ++start[static_cast<size_t>(k[0]) + 1];
  for (std::size_t c = 0; c < static_cast<size_t>(columns); ++c) start[c + 1] += start[c];
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < point.size(); ++i) order[next[static_cast<size_t>(keys[i][0])]++] = i;
  }
  for (std::size_t c = 0; c < static_cast<size_t>(columns); ++c)  // buckets are a few rows: insertion order kept
    std::stable_sort(order.begin() + static_cast<std::ptrdiff_t>(start[c]),
                     order.begin() + static_cast<std::ptrdiff_t>(start[c + 1]),
                     [&](std::size_t a, std::size_t b) { return key_less(keys[a], keys[b]); });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t ri = order[i];
    const Key& k = keys[ri];
    if (i == 0 || k != keys[order[i - 1]]) {
      Group g;
      for (int j = 0; j < 3; ++j) g.col[j] = k[static_cast<size_t>(j)];
      g.begin = g.end = size();
      groups_.push_back(g);
    }
    const JerkRow& r = point[ri];
    double a[3] = {0, 0, 0};
    for (int j = 0; j < r.n; ++j)
      for (int s = 0; s < 3; ++s)
        if (k[static_cast<size_t>(s)] == r.col[j]) a[s] += r.val[j];
    push(a[0], a[1], a[2], r.rhs, 0.0, 0.0);
    groups_.back().end = size();
  }
  // The jerk rows: jerk_limit_rows gives one grid point's side after another, so a group is a run of rows on
  // the same columns.
  for (const JerkLimitRow& jr : jerk) {
    const int theta = static_cast<int>(jr.point);
    Key k{-1, -1, -1};
    double a[2] = {0, 0}, lin_theta = 0;
    int used = 0;
    for (int j = 0; j < jr.lin.n; ++j) {
      const int c = jr.lin.col[j];
      if (c == theta) lin_theta += jr.lin.val[j];
      else if (free[static_cast<size_t>(c)] && used < 2) k[static_cast<size_t>(used++)] = c;
    }
    if (used == 2 && k[0] > k[1]) std::swap(k[0], k[1]);
    for (int j = 0; j < jr.lin.n; ++j)
      for (int s = 0; s < used; ++s)
        if (jr.lin.col[j] == k[static_cast<size_t>(s)]) a[s] += jr.lin.val[j];
    k[2] = free[static_cast<size_t>(theta)] ? theta : -1;
    const Group* last = groups_.empty() ? nullptr : &groups_.back();
    if (!last || last->point != jr.point || last->col[0] != k[0] || last->col[1] != k[1] || last->col[2] != k[2]) {
      Group g;
      for (int j = 0; j < 3; ++j) g.col[j] = k[static_cast<size_t>(j)];
      g.point = jr.point;
      g.begin = g.end = size();
      groups_.push_back(g);
    }
    push(a[0], a[1], 0.0, 0.0, lin_theta, jr.J);
    groups_.back().end = size();
  }
  relinearise(Eigen::VectorXd::Ones(static_cast<Eigen::Index>(free.size())));
}

void JerkRowGroups::relinearise(const Eigen::VectorXd& xbar) {
  // J/√θ >= J (3θ̄ - θ) / (2 θ̄^{3/2}): the θ coefficient gains the tangent's slope J / (2 θ̄^{3/2}), and
  // the right-hand side is 1.5 J / √θ̄ (JerkLimitRow::relinearise).
  for (const Group& g : groups_) {
    if (g.point < 0) continue;
    const double tb = std::max(xbar[g.point], 1e-300), root = std::sqrt(tb);
    const double slope = 1.0 / (2 * tb * root), level = 1.5 / root;
    for (std::size_t r = g.begin; r < g.end; ++r) {
      v2_[r] = lin_theta_[r] + J_[r] * slope;
      rhs_[r] = J_[r] * level;
    }
  }
}

bool JerkRowGroups::slacks(const Eigen::VectorXd& x, double* s) const {
  bool positive = true;
  for (const Group& g : groups_) {
    double x0, x1, x2;
    load(g, x, x0, x1, x2);
    for (std::size_t r = g.begin; r < g.end; ++r) {
      s[r] = rhs_[r] - (v0_[r] * x0 + v1_[r] * x1 + v2_[r] * x2);
      positive &= s[r] > 0;
    }
  }
  return positive;
}

void JerkRowGroups::products(const Eigen::VectorXd& d, double* out) const {
  for (const Group& g : groups_) {
    double d0, d1, d2;
    load(g, d, d0, d1, d2);
    for (std::size_t r = g.begin; r < g.end; ++r) out[r] = v0_[r] * d0 + v1_[r] * d1 + v2_[r] * d2;
  }
}

void JerkRowGroups::scatter(const double* w, Eigen::VectorXd& gr) const {
  for (const Group& g : groups_) {
    double s0 = 0, s1 = 0, s2 = 0;
    for (std::size_t r = g.begin; r < g.end; ++r) s0 += w[r] * v0_[r], s1 += w[r] * v1_[r], s2 += w[r] * v2_[r];
    if (g.col[0] >= 0) gr[g.col[0]] += s0;
    if (g.col[1] >= 0) gr[g.col[1]] += s1;
    if (g.col[2] >= 0) gr[g.col[2]] += s2;
  }
}

double JerkRowGroups::weighted_rhs(const double* w) const {
  double sum = 0;
  for (std::size_t r = 0; r < rhs_.size(); ++r) sum += w[r] * rhs_[r];
  return sum;
}

}  // namespace pathpace::detail
