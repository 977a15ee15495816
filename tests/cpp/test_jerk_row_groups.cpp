// The grouped rows of the structured jerk solve (solve/jerk_row_groups.hpp) against the same rows one by one
// (JerkRow, JerkLimitRow::linearised): seeded rows of a chain of grid points, the limit rows of each point given
// constraint by constraint (so one point's rows are far apart in the input), jerk rows on both sides, rows next
// to a rest end (two unknowns), and terms on fixed unknowns that the groups drop. The groups store the rows in
// their own order, so every comparison is of an order-free quantity: the sorted slacks, and Σ f(s_r) a_r and
// Σ f(s_r) a_r a_rᵀ with weights that are functions of each row's slack.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

#include "solve/jerk_row_groups.hpp"

using namespace pathpace::detail;

namespace {

struct RowCase {
  int n = 0;  // intervals; unknowns θ_0..θ_n, b_0..b_n
  std::vector<JerkRow> point;
  std::vector<JerkLimitRow> jerk;
  std::vector<char> free;
  Eigen::VectorXd x, xbar;
};

RowCase row_case(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> U(-1.0, 1.0), P(0.5, 2.0);
  RowCase c;
  c.n = n;
  const int nb = n + 1;
  c.free.assign(static_cast<size_t>(2 * nb), 1);
  c.free[0] = c.free[static_cast<size_t>(n)] = 0;                            // θ at the rest ends
  c.free[static_cast<size_t>(nb)] = c.free[static_cast<size_t>(nb + n)] = 0;  // b at the rest ends
  c.x = Eigen::VectorXd::Zero(2 * nb);
  c.xbar = c.x;
  for (int k = 1; k < n; ++k) c.x[k] = P(rng), c.xbar[k] = P(rng), c.x[nb + k] = U(rng), c.xbar[nb + k] = U(rng);
  // Three "constraints", each a row on (θ_k, b_k) at every inner point: rows of a point are far apart.
  for (int family = 0; family < 3; ++family)
    for (int k = 1; k < n; ++k) {
      JerkRow r;
      r.add(k, U(rng));
      r.add(nb + k, U(rng));
      r.rhs = 10 + U(rng);
      c.point.push_back(r);
    }
  // Jerk rows at each inner point, both sides, several joints and both signs; b_0 and b_n are fixed (dropped).
  for (int k = 1; k < n; ++k)
    for (int side = 0; side < 2; ++side) {
      const int other = side == 0 ? k - 1 : k + 1;
      for (int j = 0; j < 3; ++j)
        for (int sign = 1; sign >= -1; sign -= 2) {
          JerkLimitRow r;
          r.lin.add(nb + other, sign * U(rng));
          r.lin.add(nb + k, sign * U(rng));
          r.lin.add(k, sign * U(rng));
          r.point = k;
          r.J = 20 * P(rng);
          c.jerk.push_back(r);
        }
    }
  return c;
}

}  // namespace

TEST(JerkRowGroups, AreTheRowsOneByOneInAnyOrder) {
  std::mt19937 rng(11);
  for (int n : {4, 5, 9, 30}) {
    RowCase c = row_case(rng, n);
    JerkRowGroups groups(c.point, c.jerk, c.free);
    ASSERT_EQ(groups.size(), c.point.size() + c.jerk.size());
    groups.relinearise(c.xbar);
    // The same rows one by one, linearised at x̄, with the fixed unknowns' terms dropped (their values are 0).
    std::vector<JerkRow> plain = c.point;
    for (const JerkLimitRow& r : c.jerk) plain.push_back(r.linearised(c.xbar[r.point]));
    std::vector<double> want(plain.size()), got(groups.size()), prod(groups.size());
    for (size_t i = 0; i < plain.size(); ++i) want[i] = plain[i].rhs - plain[i].dot(c.x);
    groups.slacks(c.x, got.data());
    std::vector<double> ws = want, gs = got;
    std::sort(ws.begin(), ws.end());
    std::sort(gs.begin(), gs.end());
    for (size_t i = 0; i < ws.size(); ++i) EXPECT_NEAR(gs[i], ws[i], 1e-12 * (1 + std::abs(ws[i]))) << n << " " << i;
    // a·d = slack(0) - slack(d) for the same rows, in the groups' order.
    std::vector<double> at_zero(groups.size());
    groups.products(c.x, prod.data());
    groups.slacks(Eigen::VectorXd::Zero(c.x.size()), at_zero.data());
    for (size_t i = 0; i < prod.size(); ++i) EXPECT_NEAR(prod[i], at_zero[i] - got[i], 1e-12 * (1 + std::abs(prod[i])));
    // Σ f(s) a and Σ f(s) a aᵀ with f(s) = 1 / s² (the barrier's Hessian weight), and Σ f(s) rhs.
    const Eigen::Index nx = c.x.size();
    Eigen::VectorXd g_want = Eigen::VectorXd::Zero(nx), g_got = g_want;
    Eigen::MatrixXd H_want = Eigen::MatrixXd::Zero(nx, nx), H_got = H_want;
    double rhs_want = 0;
    for (size_t i = 0; i < plain.size(); ++i) {
      const double w = 1 / (want[i] * want[i]);
      rhs_want += w * plain[i].rhs;
      for (int a = 0; a < plain[i].n; ++a) {
        if (!c.free[static_cast<size_t>(plain[i].col[a])]) continue;
        g_want[plain[i].col[a]] += w * plain[i].val[a];
        for (int b = 0; b < plain[i].n; ++b)
          if (c.free[static_cast<size_t>(plain[i].col[b])])
            H_want(plain[i].col[a], plain[i].col[b]) += w * plain[i].val[a] * plain[i].val[b];
      }
    }
    std::vector<double> w(groups.size());
    for (size_t i = 0; i < w.size(); ++i) w[i] = 1 / (got[i] * got[i]);
    groups.scatter(w.data(), g_got);
    groups.hessian(w.data(), [&](int i, int j, double v) {  // each pair of a group once
      H_got(i, j) += v;
      if (i != j) H_got(j, i) += v;
    });
    EXPECT_LE((g_got - g_want).lpNorm<Eigen::Infinity>(), 1e-11 * (1 + g_want.lpNorm<Eigen::Infinity>())) << n;
    EXPECT_LE((H_got - H_want).lpNorm<Eigen::Infinity>(), 1e-11 * (1 + H_want.lpNorm<Eigen::Infinity>())) << n;
    EXPECT_NEAR(groups.weighted_rhs(w.data()), rhs_want, 1e-11 * std::abs(rhs_want)) << n;
    // Rows of one point on the same unknowns share a group: one per point and family-free column set, plus
    // one per point and side for the jerk rows.
    EXPECT_EQ(groups.groups().size(), static_cast<size_t>(3 * (n - 1)));
    for (const JerkRowGroups::Group& g : groups.groups())
      for (int s = 0; s < 3; ++s) EXPECT_TRUE(g.col[s] < 0 || c.free[static_cast<size_t>(g.col[s])]);
  }
}

namespace {

// Seeded limit rows ±(α θ_k + β b_k) <= c, seven joints and both signs per grid point k in [first, last], as the
// acceleration limits give them; θ_k's upper side hi[k] drawn. β is drawn in [-1, 1], or away from 0 with
// beta_min > 0.
std::vector<JerkRow> seeded_limit_rows(std::mt19937& rng, Eigen::Index nb, Eigen::Index first, Eigen::Index last,
                                       double beta_min, Eigen::VectorXd& hi) {
  std::uniform_real_distribution<double> U(-1.0, 1.0), P(0.2, 3.0);
  std::vector<JerkRow> rows;
  for (Eigen::Index k = first; k <= last; ++k) {
    hi[k] = P(rng);
    for (int j = 0; j < 7; ++j)
      for (int sign = 1; sign >= -1; sign -= 2) {
        JerkRow r;
        const double alpha = U(rng), beta = beta_min > 0 ? beta_min + std::abs(U(rng)) : U(rng);
        r.add(static_cast<int>(k), sign * alpha);
        r.add(static_cast<int>(nb + k), sign * beta);
        r.rhs = P(rng);
        rows.push_back(r);
      }
  }
  return rows;
}

}  // namespace

// jerk_undominated_rows (solve/jerk_rows.hpp): seeded limit rows α θ_k + β b_k <= c at a few grid points, plus a
// row on other unknowns; a random (θ, b) in the θ range that meets the rows kept meets every row, and a row that
// is the binding one somewhere in the range is kept.
TEST(JerkUndominatedRows, KeepTheFeasibleSetAndEveryBindingRow) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const Eigen::Index nb = 6;
  for (int rep = 0; rep < 20; ++rep) {
    Eigen::VectorXd lo = Eigen::VectorXd::Zero(2 * nb), hi = Eigen::VectorXd::Constant(2 * nb, 1e300);
    std::vector<JerkRow> rows = seeded_limit_rows(rng, nb, 1, nb - 2, 0.0, hi);
    JerkRow other;  // a row on two grid points' unknowns: kept as it is
    other.add(1, 1.0), other.add(static_cast<int>(nb + 2), 1.0), other.rhs = 5;
    rows.push_back(other);
    const std::vector<JerkRow> kept = jerk_undominated_rows(rows, nb, lo, hi);
    EXPECT_LT(kept.size(), rows.size());
    EXPECT_EQ(kept.back().rhs, 5.0);
    auto worst = [](const std::vector<JerkRow>& rs, const Eigen::VectorXd& x) {
      double w = -1e300;
      for (const JerkRow& r : rs) w = std::max(w, r.dot(x) - r.rhs);
      return w;
    };
    // The same set: a point the kept rows admit, every row admits.
    int inside = 0;
    for (int t = 0; t < 4000; ++t) {
      Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * nb);
      for (Eigen::Index k = 1; k < nb - 1; ++k) x[k] = hi[k] * (0.5 + 0.5 * U(rng)), x[nb + k] = 0.5 * U(rng);
      if (worst(kept, x) <= 0) {
        ++inside;
        EXPECT_LE(worst(rows, x), 1e-12) << rep << " " << t;
      }
    }
    EXPECT_GT(inside, 20);  // the samples reach the set
    // Every row that is the least upper (largest lower) bound of b_k at some θ_k in the range is kept.
    auto is_kept = [&](const JerkRow& r) {
      for (const JerkRow& q : kept)
        if (q.rhs == r.rhs && q.val[0] == r.val[0] && q.val[1] == r.val[1]) return true;
      return false;
    };
    for (Eigen::Index k = 1; k < nb - 1; ++k)
      for (int t = 0; t <= 200; ++t) {
        const double th = hi[k] * t / 200.0;
        const JerkRow *up = nullptr, *down = nullptr;
        double u = 1e300, d = -1e300;
        for (const JerkRow& r : rows) {
          if (r.n != 2 || r.col[0] != k) continue;
          const double bound = (r.rhs - r.val[0] * th) / r.val[1];
          if (r.val[1] > 0 && bound < u) u = bound, up = &r;
          if (r.val[1] < 0 && bound > d) d = bound, down = &r;
        }
        ASSERT_TRUE(up && down);
        EXPECT_TRUE(is_kept(*up)) << rep << " " << k << " " << th;
        EXPECT_TRUE(is_kept(*down)) << rep << " " << k << " " << th;
      }
  }
}

// jerk_implied_box: every (θ_k, b_k) that meets the rows with θ_k in its range has b_k inside the tightened box
// (an outer bound: each row's own extreme over the θ range, not the polygon's), and the box is tightened (from
// ±1e3 to the rows' scale).
TEST(JerkImpliedBox, HoldsEveryPointTheRowsAdmitAndIsTightened) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const Eigen::Index nb = 5;
  for (int rep = 0; rep < 20; ++rep) {
    Eigen::VectorXd lo = Eigen::VectorXd::Constant(2 * nb, -1e3), hi = Eigen::VectorXd::Constant(2 * nb, 1e3);
    lo.head(nb).setZero();
    const std::vector<JerkRow> rows = seeded_limit_rows(rng, nb, 0, nb - 1, 0.1, hi);
    Eigen::VectorXd blo = lo, bhi = hi;
    jerk_implied_box(rows, nb, blo, bhi);
    for (Eigen::Index k = 0; k < nb; ++k) {
      EXPECT_EQ(blo[k], lo[k]);  // θ's sides as they were
      EXPECT_EQ(bhi[k], hi[k]);
      ASSERT_LT(bhi[nb + k] - blo[nb + k], 100.0);  // tightened from ±1e3
      int inside = 0;
      for (int t = 0; t < 20000; ++t) {
        Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * nb);
        x[k] = hi[k] * (0.5 + 0.5 * U(rng));
        x[nb + k] = blo[nb + k] - 1 + (bhi[nb + k] - blo[nb + k] + 2) * (0.5 + 0.5 * U(rng));
        bool ok = true;
        for (const JerkRow& r : rows)
          if ((r.col[0] == k) && r.dot(x) > r.rhs) ok = false;
        if (!ok) continue;
        ++inside;
        EXPECT_GE(x[nb + k], blo[nb + k]) << rep << " " << k;
        EXPECT_LE(x[nb + k], bhi[nb + k]) << rep << " " << k;
      }
      ASSERT_GT(inside, 50) << rep << " " << k;
    }
  }
}
