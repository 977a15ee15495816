#include "solve/continuous.hpp"
#include "solve/auditor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "geometry/interval_bounds.hpp"
#include "solve/brent.hpp"
#include "base/validate.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"

namespace pathpace::detail {

namespace {

int total_rows(const std::vector<ConstraintRows>& rows) {
  int n = 0;
  for (const ConstraintRows& r : rows) n += static_cast<int>(r.rows());
  return n;
}

}  // namespace

void add_kinematic_continuous_rows(const Path& path, const PathSamples& samples,
                                   const std::vector<std::shared_ptr<const Constraint>>& constraints,
                                   std::vector<ConstraintRows>& rows, IntervalExtra& extra) {
  const Eigen::Index N = samples.size() - 1, n = samples.dof();
  extra.rows.resize(static_cast<size_t>(N));
  // A constraint's own speed bounds for between grid points (Constraint::speed_bounds_between_grid_points):
  // rows x <= bound, named after its first row.
  const size_t own_rows = rows.size();  // rows[ci] are constraints[ci]'s (the loop appends after them)
  for (size_t ci = 0; ci < constraints.size(); ++ci) {
    const Eigen::VectorXd bound =
        constraints[ci]->speed_bounds_between_grid_points(samples, ci < own_rows ? rows[ci] : ConstraintRows{});
    if (bound.size() == 0) continue;
    if (bound.size() != N + 1)
      fail(constraints[ci]->name() + ": speed_bounds_between_grid_points gave " + std::to_string(bound.size()) +
           " bounds for " + std::to_string(N + 1) + " grid points");
    ConstraintRows cr;
    cr.resize(samples.size(), 1);
    const std::string own = ci < own_rows && rows[ci].rows() > 0 ? rows[ci].labels[0] : constraints[ci]->name();
    cr.labels[0] = own + " (between grid points)";
    for (Eigen::Index k = 0; k <= N; ++k) {
      if (!(bound[k] >= 0.0))
        fail(constraints[ci]->name() + ": speed_bounds_between_grid_points gave " + fmt(bound[k]) +
             " at grid point " + std::to_string(k) + ", expected a number >= 0 (+inf: none)");
      if (bound[k] < std::numeric_limits<double>::infinity()) {
        cr.a(k, 0) = 1.0;
        cr.c(k, 0) = bound[k];
      }
    }
    rows.push_back(std::move(cr));
  }
  bool any = false;
  for (const auto& c : constraints) any = any || c->joint_rate_limits().order != 0;
  if (!any) return;
  const PiecewisePolynomialPath* pp = path.polynomial();
  if (!pp)
    fail("guarantee = 'continuous' bounds velocity and acceleration between grid points on piecewise-polynomial "
         "paths (CubicSplinePath, PiecewisePolynomialPath, SampledPath, scipy and toppra splines through as_path); "
         "this path has no polynomial pieces (a callback path: sample it into a SampledPath)");
  const IntervalRows ir = interval_rows(*pp, samples.s);
  const double inf = std::numeric_limits<double>::infinity();
  const size_t own = rows.size();  // rows[i] are constraints[i]'s grid rows (for their labels)
  for (size_t ci = 0; ci < constraints.size(); ++ci) {
    const std::shared_ptr<const Constraint>& c = constraints[ci];
    const JointRateLimits limits = c->joint_rate_limits();
    if (limits.order == 1) {
      // One bound per grid point for all joints (each joint's own would do too, but the polygon keeps only
      // the smallest bound on x alone anyway).
      ConstraintRows cr;
      cr.resize(samples.size(), 1);
      cr.labels[0] = "velocity (between grid points)";
      const Eigen::VectorXd bound = continuous_speed_bounds(*pp, samples.s, ir, samples.dq, limits.lo, limits.hi);
      for (Eigen::Index k = 0; k <= N; ++k)
        if (bound[k] < inf) {
          cr.a(k, 0) = 1.0;
          cr.c(k, 0) = bound[k];
        }
      rows.push_back(std::move(cr));
    } else if (limits.order == 2) {
      const int id0 = total_rows(rows);
      ConstraintRows cr;  // labels only: its rows are inactive at the grid points, they act on intervals
      cr.resize(samples.size(), 2 * n);
      // The grid rows' own labels (joint names where the problem has them), "between grid points".
      const bool named = ci < own && rows[ci].labels.size() == static_cast<size_t>(2 * n);
      for (size_t l = 0; l < static_cast<size_t>(2 * n); ++l)
        cr.labels[l] = (named ? rows[ci].labels[l]
                              : "acceleration joint " + std::to_string(l / 2) + (l % 2 ? " lower" : " upper")) +
                       " (between grid points)";
      rows.push_back(std::move(cr));
      for (Eigen::Index k = 0; k < N; ++k) {
        auto& out = extra.rows[static_cast<size_t>(k)];
        for (size_t i = ir.offset[static_cast<size_t>(k)]; i < ir.offset[static_cast<size_t>(k) + 1]; ++i) {
          const int j = ir.joint[i];
          if (std::isfinite(limits.hi[j])) out.push_back({ir.A[i], ir.B[i], limits.hi[j], id0 + 2 * j});
          if (std::isfinite(limits.lo[j])) out.push_back({-ir.A[i], -ir.B[i], -limits.lo[j], id0 + 2 * j + 1});
        }
      }
    }
  }
}

double violation(double a, double b, double c, double lam, double t0, double t1, double u) {
  if (c == std::numeric_limits<double>::infinity()) return -std::numeric_limits<double>::infinity();
  const double ax = a * ((1.0 - lam) * t0 + lam * t1), bu = b * u;
  return (ax + bu - c) / std::max({std::abs(c), std::abs(ax) + std::abs(bu), 1e-300});
}

double slice_violation(double x, double lo, double hi) {
  if (std::isnan(lo) || std::isnan(hi) || lo > hi) return 1.0;
  const double over = std::max(x - hi, lo - x);
  if (over == -std::numeric_limits<double>::infinity()) return over;
  return over / std::max({std::abs(x), std::isfinite(hi) ? std::abs(hi) : 0.0, 1e-300});
}

double bottom_violation(double x, double lo, double hi) {
  if (std::isnan(lo) || std::isnan(hi) || lo > hi) return 1.0;
  const double end = lo == -std::numeric_limits<double>::infinity() ? hi : lo;
  if (!std::isfinite(end)) return -std::numeric_limits<double>::infinity();
  return (end - x) / std::max({std::abs(x), std::isfinite(hi) ? std::abs(hi) : 0.0, 1e-300});
}

namespace {

// An upper bound of v on [la, lb] from its end values, if v'' >= -K there: the chord plus K τ (h - τ) / 2.
double bump_bound(double la, double va, double lb, double vb, double K) {
  const double h = lb - la, slope = (vb - va) / h;
  const double tau = K > 0.0 ? std::clamp(0.5 * h + slope / K, 0.0, h) : (slope > 0.0 ? h : 0.0);
  return va + slope * tau + 0.5 * K * tau * (h - tau);
}

// The slice at u of row r's polygon: [lo, hi], or u_broken where a row on u alone excludes this u.
void row_slice(const ConstraintRows& rows, Eigen::Index r, double u, double& lo, double& hi, bool& u_broken) {
  const double inf = std::numeric_limits<double>::infinity();
  lo = -inf;
  hi = inf;
  u_broken = false;
  for (Eigen::Index j = 0; j < rows.rows(); ++j) {
    const double a = rows.a(r, j), c = rows.c(r, j), rest = c - rows.b(r, j) * u;
    if (c == inf) continue;
    if (a > 0.0) hi = std::min(hi, rest / a);
    else if (a < 0.0) lo = std::max(lo, rest / a);
    else if (rest < 0.0) u_broken = true;  // a row on u alone that this u breaks
  }
}

// bottom_violation of a row slice (row_slice's lo, hi, u_broken): 1 where a row on u alone breaks u.
double slice_bottom(double x, double lo, double hi, bool u_broken) { return u_broken ? 1.0 : bottom_violation(x, lo, hi); }

// slice_violation from a polygon's rows (row r of `rows`): the slice at u is where every row a x + b u <= c holds.
// The slice measures x's distance relative to x's own size, which at rest is rounding over rounding: a
// timing that leaves rest on the polygon's top edge (x = 0, the top at -1.9e-14 for its u) read as a full
// violation that no cut could remove (audit_worst = 1 on a G1 lean that met every limit). Where the slice
// says broken (rarely: a second pass, not a division per row at every sample), the rows' own measure
// (violation(), relative to each row's terms) decides, if smaller.
// [lo, hi] and u_broken: row r's slice at u (row_slice).
double row_slice_violation(const ConstraintRows& rows, Eigen::Index r, double x, double u, double lo, double hi,
                           bool u_broken) {
  const double inf = std::numeric_limits<double>::infinity();
  const double by_slice = u_broken ? 1.0 : slice_violation(x, lo, hi);
  if (!(by_slice > 0.0)) return by_slice;
  double by_rows = -inf;
  for (Eigen::Index j = 0; j < rows.rows(); ++j)
    if (rows.c(r, j) != inf) by_rows = std::max(by_rows, violation(rows.a(r, j), rows.b(r, j), rows.c(r, j), 0.0, x, x, u));
  return std::min(by_slice, by_rows);
}

}  // namespace

double row_slice_bottom(const ConstraintRows& rows, Eigen::Index r, double x, double u) {
  double lo, hi;
  bool u_broken;
  row_slice(rows, r, u, lo, hi, u_broken);
  return slice_bottom(x, lo, hi, u_broken);
}

namespace {

// v'' from three samples.
double second_difference(double la, double va, double lb, double vb, double lc, double vc) {
  return 2.0 * ((vc - vb) / (lc - lb) - (vb - va) / (lb - la)) / (lc - la);
}

}  // namespace

Audit Auditor::run() {
  std::vector<size_t> which;
  for (size_t i = 0; i < constraints_.size(); ++i)
    if (constraints_[i]->joint_rate_limits().order == 0) which.push_back(i);
  if (which.empty() || points_ < 1) return audit_;
  // Coarse pass at Chebyshev points of each interval: dense near the ends, where a row that is tight at
  // the grid point with a slope into the interval peaks.
  lam_.resize(static_cast<size_t>(points_));
  for (int m = 0; m < points_; ++m) lam_[static_cast<size_t>(m)] = 0.5 * (1.0 - std::cos(M_PI * (m + 1.0) / (points_ + 1.0)));
  audit_.worst = -kInf;
  size_memory();
  for (size_t ci : which) audit_constraint(ci);
  if (!std::isfinite(audit_.worst)) audit_.worst = 0.0;
  return audit_;
}

void Auditor::size_memory() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const size_t n = constraints_.size();
  if (memory_.theta0.size() != n) {
    memory_.theta0.assign(n, std::vector<double>(static_cast<size_t>(N_), nan));
    memory_.theta1 = memory_.theta0;
    memory_.worst = memory_.theta0;
  }
  if (memory_.coarse.size() != n) {
    memory_.coarse.assign(n, ConstraintRows());
    memory_.cut_points.assign(n, std::vector<std::vector<AuditMemory::Point>>(static_cast<size_t>(N_)));
  }
  if (memory_.cut_at.size() != n) memory_.cut_at.assign(n, std::vector<std::vector<double>>(static_cast<size_t>(N_)));
  if (memory_.slices.size() != n) memory_.slices.assign(n, {});
  if (memory_.grid_slices.size() != n) memory_.grid_slices.assign(n, {});
  if (memory_.probes.size() != n) memory_.probes.assign(n, std::vector<std::vector<AuditMemory::Point>>(static_cast<size_t>(N_)));
  if (memory_.curvature.size() != n) memory_.curvature.assign(n, std::vector<double>(static_cast<size_t>(N_), 0.0));
  if (memory_.bottoms_near.size() != n) memory_.bottoms_near.assign(n, std::vector<char>(static_cast<size_t>(N_), 0));
  if (memory_.bases.size() != n) memory_.bases.assign(n, std::vector<std::array<std::vector<signed char>, 2>>(static_cast<size_t>(N_)));
}

// Per interval and constraint, the violation at λ is the largest relative violation over the
// constraint's rows there (a contact polygon's rows differ from one point to the next, so rows are not
// followed one by one); its peak is found, and every row broken at the peak becomes a cut.
void Auditor::audit_constraint(size_t ci) {
  const Constraint* contact = constraints_[ci]->projected() ? constraints_[ci].get() : nullptr;
  if (!contact) coarse_rows(ci);
  const std::vector<Eigen::Index> todo = intervals_to_audit(ci);
  std::vector<double> fc;
  std::vector<size_t> first(todo.size() + 1, 0);
  if (contact) contact_batch(*contact, ci, todo, first, fc);
  sample_intervals(ci, contact, todo, first, fc);
  path_curvature(ci, todo);
  if (contact) {
    // Intervals whose samples skipped their bottoms (contact_batch's guess from the grid points) where the
    // screen finds the bottom near after all: sampled again with bottoms (the other samples' slices are
    // kept, so only those LPs are solved again).
    const std::vector<Eigen::Index> redo = bottoms(todo);
    if (!redo.empty()) {
      for (Eigen::Index k : redo) forget_skipped_bottoms(ci, k);
      const int reused = audit_.reused;  // this round's own slices: not reuse across rounds
      contact_batch(*contact, ci, todo, first, fc);
      audit_.reused = reused;
      sample_intervals(ci, contact, todo, first, fc);
      path_curvature(ci, todo);
      bottoms(todo);
    }
  }
  std::vector<PeakBracket> cand;
  std::vector<Eigen::Index> at;    // per bracket: its interval
  std::vector<double> curvature;   // and that interval's curvature bound
  brackets(todo, cand, at, curvature);
  if (cand.empty()) return;
  std::vector<std::pair<double, double>> span;  // per bracket: its samples, before the search narrows it
  for (const PeakBracket& c : cand) span.emplace_back(c.a, c.c);
  // The peak between two samples (solve/brent.hpp), every bracket's evaluations in one batch per step. A
  // bracket is settled early when the bound of bump_bound, from its three points, shows no violation.
  maximize_batch(
      cand,
      [&](const std::vector<size_t>& which, const std::vector<double>& xs, std::vector<double>& f) {
        ks_.clear();
        for (size_t i : which) ks_.push_back(at[i]);
        violations(ci, contact, ks_, xs, f);
      },
      [&](size_t i, const PeakBracket& c) {
        // A bracket already broken is cut anyway: narrowed to half its span, not to its peak (the spread
        // cuts of contact_cuts cover the rest of it).
        if (c.best() > tolerance_ && c.c - c.a < 0.5 * (span[i].second - span[i].first)) return true;
        if (!std::isfinite(c.fa) || !std::isfinite(c.fc)) return false;
        const double K =
            std::max(K_of(at[i], curvature[i]), 4.0 * std::max(0.0, -second_difference(c.a, c.fa, c.b, c.fb, c.c, c.fc)));
        return c.best() <= tolerance_ && bump_bound(c.a, c.fa, c.b, c.fb, K) <= tolerance_ &&
               bump_bound(c.b, c.fb, c.c, c.fc, K) <= tolerance_;
      });
  const int before = audit_.cuts;
  cut(ci, cand, at);
  // Only in a round that cut: the loop ends at a round without cuts, and the timing then meets every limit.
  if (contact && audit_.cuts > before) tight_cuts(ci, todo);
}

// See the header. A Chebyshev point's slice top is an edge of the polygon there, kept with its LP's
// sensitivity (AuditMemory::Slices): a supporting line, so the row is exact wherever the slice was solved,
// and it costs no LP.
void Auditor::tight_cuts(size_t ci, const std::vector<Eigen::Index>& todo) {
  const std::map<std::string, int> unnamed;  // labelled as the constraint's first row, as a cut with no name
  const std::vector<AuditMemory::Slices>& memo = memory_.slices[ci];
  for (Eigen::Index k : todo) {
    const double u = u_of(k);
    std::vector<double>& cut_at = memory_.cut_at[ci][static_cast<size_t>(k)];
    for (int m = 0; m < points_; ++m) {
      const AuditMemory::Slices& M = memo[static_cast<size_t>(k) * static_cast<size_t>(points_) + static_cast<size_t>(m)];
      const double l = lam_[static_cast<size_t>(m)];
      if (M.hi_capped || !(M.hi_from <= M.hi_to) || std::find(cut_at.begin(), cut_at.end(), l) != cut_at.end()) continue;
      const double x = x_of(k, l), hi = M.hi + M.hi_slope * (u - M.u);
      if ((x - hi) / std::max(std::abs(x), std::abs(hi)) < -kTight) continue;
      add_cut(ci, k, l, 1.0, -M.hi_slope, M.hi - M.hi_slope * M.u, std::string(), unnamed);
    }
  }
}

PathSamples Auditor::samples_at(const std::vector<Eigen::Index>& ks, const std::vector<double>& ls) const {
  PathSamples ps;
  ps.s.resize(static_cast<Eigen::Index>(ks.size()));
  for (size_t i = 0; i < ks.size(); ++i) ps.s[static_cast<Eigen::Index>(i)] = s_[ks[i]] + (s_[ks[i] + 1] - s_[ks[i]]) * ls[i];
  path_.evaluate(ps.s, ps.q, ps.dq, ps.ddq);
  return ps;
}

double Auditor::worst_row(const ConstraintRows& rr, Eigen::Index r, double l, Eigen::Index k) const {
  double w = -kInf;
  for (Eigen::Index j = 0; j < rr.rows(); ++j)
    w = std::max(w, violation(rr.a(r, j), rr.b(r, j), rr.c(r, j), l, theta_[k], theta_[k + 1], u_of(k)));
  return w;
}

// The violation at (interval kk[i], λ ll[i]) under θ. A contact constraint is asked only whether the
// timing's own point (x(λ), u) lies in its polygon there (the polygon's slice at u: two LPs, one where x
// is above the slice's top, no projection); its violation is x's relative distance beyond the slice.
// Any other constraint gives its rows (cheap: no LPs).
void Auditor::violations(size_t ci, const Constraint* contact, const std::vector<Eigen::Index>& kk,
                         const std::vector<double>& ll, std::vector<double>& f) {
  f.resize(kk.size());
  if (kk.empty()) return;
  const PathSamples ps = samples_at(kk, ll);
  if (contact) {
    Eigen::VectorXd u(static_cast<Eigen::Index>(kk.size())), x(u.size()), skip(u.size()), lo, hi;
    for (size_t i = 0; i < kk.size(); ++i) {
      u[static_cast<Eigen::Index>(i)] = u_of(kk[i]);
      x[static_cast<Eigen::Index>(i)] = x_of(kk[i], ll[i]);
      skip[static_cast<Eigen::Index>(i)] = bottom_[static_cast<size_t>(kk[i])] ? x[static_cast<Eigen::Index>(i)] : kInf;
    }
    SliceEdges edges;
    warm_slice(*contact, ci, kk, ps, u, lo, hi, &skip, &edges);
    const double cap = contact->projection_cap();
    for (size_t i = 0; i < kk.size(); ++i) {
      const Eigen::Index e = static_cast<Eigen::Index>(i);
      f[i] = slice_violation(x[e], lo[e], hi[e]);
      auto& probes = memory_.probes[ci][static_cast<size_t>(kk[i])];
      if (probes.size() >= AuditMemory::kProbes) probes.erase(probes.begin());
      probes.push_back({ll[i], {}, {}, {}, {}});
      keep_slice(probes.back().slice, u[e], lo[e], hi[e], edges, e, cap, skip[e] == kInf && !(x[e] > hi[e]));
    }
    return;
  }
  const ConstraintRows rr = constraints_[ci]->evaluate(ps);
  for (size_t i = 0; i < kk.size(); ++i) f[i] = worst_row(rr, static_cast<Eigen::Index>(i), ll[i], kk[i]);
}

// The rows at the Chebyshev points do not depend on the timing: evaluated once per solve (not for a
// contact constraint, whose polygons are not projected there).
void Auditor::coarse_rows(size_t ci) {
  if (memory_.coarse[ci].a.rows() == N_ * points_) return;
  ks_.clear();
  ls_.clear();
  for (Eigen::Index k = 0; k < N_; ++k)
    for (int m = 0; m < points_; ++m) {
      ks_.push_back(k);
      ls_.push_back(lam_[static_cast<size_t>(m)]);
    }
  memory_.coarse[ci] = constraints_[ci]->evaluate(samples_at(ks_, ls_));
}

// The intervals to audit: those whose speeds differ from the ones they were audited at (the same speeds
// have the same violation, counted from the memory).
std::vector<Eigen::Index> Auditor::intervals_to_audit(size_t ci) {
  const auto& t0 = memory_.theta0[ci];
  const auto& t1 = memory_.theta1[ci];
  std::vector<Eigen::Index> todo;
  for (Eigen::Index k = 0; k < N_; ++k) {
    const size_t kk = static_cast<size_t>(k);
    if (t0[kk] == theta_[k] && t1[kk] == theta_[k + 1]) {
      audit_.worst = std::max(audit_.worst, memory_.worst[ci][kk]);
      continue;
    }
    todo.push_back(k);
  }
  return todo;
}


// Each interval's samples: both grid points (the grid's own rows), the Chebyshev points, and the points
// where the interval was cut before (the timing is tight there, and a violation next to one would lie
// between the Chebyshev points); sorted and merged into Ls_, Vs_, their worst kept in the memory.
void Auditor::sample_intervals(size_t ci, const Constraint* contact, const std::vector<Eigen::Index>& todo,
                               const std::vector<size_t>& first, const std::vector<double>& fc) {
  const ConstraintRows& cr = memory_.coarse[ci];
  const ConstraintRows& grid = grid_rows_[ci];
  std::vector<std::array<double, 3>> sample;  // (λ, violation, bottom_violation) of one interval
  Ls_.assign(todo.size(), {});
  Vs_.assign(todo.size(), {});
  Bs_.assign(todo.size(), {});
  for (size_t t = 0; t < todo.size(); ++t) {
    const Eigen::Index k = todo[t];
    const size_t kk = static_cast<size_t>(k);
    sample.clear();
    if (contact) {
      // At the grid points the polygon is known (its exact rows): the slice by arithmetic, no LP; rows refined
      // on demand bound it from outside only, and their grid points are in the batch (contact_batch).
      if (!contact->refines())
        for (int end = 0; end < 2; ++end) {  // each grid point's slice once, for both measures
          const double x = x_of(k, end), u = u_of(k);
          double lo, hi;
          bool u_broken;
          row_slice(grid, k + end, u, lo, hi, u_broken);
          sample.push_back({static_cast<double>(end), row_slice_violation(grid, k + end, x, u, lo, hi, u_broken),
                            slice_bottom(x, lo, hi, u_broken)});
        }
      for (size_t i = first[t]; i < first[t + 1]; ++i) sample.push_back({ls_[i], fc[i], fbot_[i]});
    } else {
      sample.push_back({0.0, worst_row(grid, k, 0.0, k), 0.0});
      sample.push_back({1.0, worst_row(grid, k + 1, 1.0, k), 0.0});
      for (int m = 0; m < points_; ++m)
        sample.push_back({lam_[static_cast<size_t>(m)], worst_row(cr, k * points_ + m, lam_[static_cast<size_t>(m)], k), 0.0});
      for (const AuditMemory::Point& pt : memory_.cut_points[ci][kk]) {
        double w = -kInf;
        for (Eigen::Index j = 0; j < pt.a.size(); ++j)
          w = std::max(w, violation(pt.a[j], pt.b[j], pt.c[j], pt.lam, theta_[k], theta_[k + 1], u_of(k)));
        sample.push_back({pt.lam, w, 0.0});
      }
    }
    std::sort(sample.begin(), sample.end());
    std::vector<double>& L = Ls_[t];
    std::vector<double>& V = Vs_[t];
    std::vector<double>& B = Bs_[t];
    for (const auto& [l, v, b] : sample) {
      if (!L.empty() && l - L.back() <= 1e-6) {
        V.back() = std::max(V.back(), v);
        B.back() = std::fmax(B.back(), b);  // NaN (unknown) only where neither is known
        continue;
      }
      L.push_back(l);
      V.push_back(v);
      B.push_back(b);
    }
    double worst = -kInf;
    for (double v : V) worst = std::max(worst, v);
    memory_.theta0[ci][kk] = theta_[k];
    memory_.theta1[ci][kk] = theta_[k + 1];
    memory_.worst[ci][kk] = worst;
    audit_.worst = std::max(audit_.worst, worst);
  }
}

// Between two samples the violation v(λ) exceeds their chord only where it is concave, by at most
// K τ (h - τ) / 2 where v'' >= -K. K is not known in closed form (a polygon's edges move with s), so the
// screen assumes (docs/method.md, "Limits between grid points") that v's concavity in s is at most 4
// times the larger of two curvatures that the second divided differences of the samples show: the
// largest near the limit anywhere on the path in this round (every sample of the triple at v >= -1e-2),
// and the largest in the interval itself (in λ: that times Δs_k², K_of). Path-wide near the limit, so
// that an interval whose samples happen to lie on a line (a rounding-level change of its polygons can
// make them so) does not switch its screen off; not path-wide far from it, where v, a distance relative
// to x's size, bends with that size (an interval leaving rest, whose slice top is many times x, would
// keep the whole path's tight brackets from the screen). An interval's own curvature is the largest of
// this and every earlier round of the solve: a later round may have no triple near its limit while the
// interval's samples have come to lie on a line (the coarse rod of test_continuous, 1-2 samples per
// interval; docs/method.md). Fills curvature_[t] per interval todo[t].
void Auditor::path_curvature(size_t ci, const std::vector<Eigen::Index>& todo) {
  constexpr double kNear = 1e-2;
  double near = 0.0;
  curvature_.assign(todo.size(), 0.0);
  for (size_t t = 0; t < todo.size(); ++t) {
    const std::vector<double>& L = Ls_[t];
    const std::vector<double>& V = Vs_[t];
    const double h = s_[todo[t] + 1] - s_[todo[t]];
    for (size_t j = 1; j + 1 < L.size(); ++j) {
      if (!std::isfinite(V[j - 1]) || !std::isfinite(V[j]) || !std::isfinite(V[j + 1])) continue;
      // Samples closer than 1 % of the interval amplify the rows' rounding into a curvature.
      if (L[j] - L[j - 1] < 0.01 || L[j + 1] - L[j] < 0.01) continue;
      const double cv = -second_difference(L[j - 1], V[j - 1], L[j], V[j], L[j + 1], V[j + 1]) / (h * h);
      curvature_[t] = std::max(curvature_[t], cv);
      if (std::min({V[j - 1], V[j], V[j + 1]}) >= -kNear) near = std::max(near, cv);
    }
  }
  for (size_t t = 0; t < todo.size(); ++t) {
    double& own = memory_.curvature[ci][static_cast<size_t>(todo[t])];  // the interval's largest of every round
    own = std::max(own, curvature_[t]);
    curvature_[t] = std::max(own, near);
  }
}

// Whether each interval's slices need their bottoms: a peak search's samples and its peak cut solve the
// slice's bottom (a second LP) only in an interval whose bottom could come near the timing. Its bottom's
// violation at the interval's samples (both grid points, the Chebyshev points, the cut points), under the
// screen's concavity bound (bump_bound, the interval's K), stays below -kFar between every two of them:
// the bottom is far from the timing there (kFar is path_curvature's "near the limit", so that the
// concavity that the combined samples show, which a far bottom's own does not shape, still applies).
std::vector<Eigen::Index> Auditor::bottoms(const std::vector<Eigen::Index>& todo) {
  constexpr double kFar = 1e-2;
  bottom_.assign(static_cast<size_t>(N_), 1);
  std::vector<Eigen::Index> redo;
  for (size_t t = 0; t < todo.size(); ++t) {
    std::vector<double>& L = Ls_[t];
    std::vector<double>& V = Vs_[t];
    std::vector<double>& B = Bs_[t];
    const double K = K_of(todo[t], curvature_[t]);
    bool far = true;
    size_t i = 0;  // the last sample whose bottom is known
    while (far && i < B.size() && std::isnan(B[i])) ++i;
    for (size_t j = i + 1; far && j < L.size(); ++j) {
      if (std::isnan(B[j])) continue;
      far = bump_bound(L[i], std::max(B[i], -1.0), L[j], std::max(B[j], -1.0), K) <= -kFar;
      i = j;
    }
    bottom_[static_cast<size_t>(todo[t])] = far ? 0 : 1;
    if (far) continue;
    // Samples whose bottom was skipped say the top's violation only: not samples here (the caller samples
    // the interval again with their bottoms).
    size_t w = 0;
    for (size_t j = 0; j < L.size(); ++j)
      if (!std::isnan(B[j])) {
        L[w] = L[j];
        V[w] = V[j];
        B[w++] = B[j];
      }
    if (w < L.size()) redo.push_back(todo[t]);
    L.resize(w);
    V.resize(w);
    B.resize(w);
  }
  return redo;
}

// Interval k's kept slices whose bottom was skipped: forgotten (their LPs solved again, bottoms too), and
// the interval not guessed far again in this solve.
void Auditor::forget_skipped_bottoms(size_t ci, Eigen::Index k) {
  const size_t kk = static_cast<size_t>(k);
  memory_.bottoms_near[ci][kk] = 1;
  for (int m = 0; m < points_; ++m) {
    AuditMemory::Slices& M = memory_.slices[ci][kk * static_cast<size_t>(points_) + static_cast<size_t>(m)];
    if (M.lo_skipped) M = AuditMemory::Slices();
  }
  for (AuditMemory::Point& pt : memory_.cut_points[ci][kk])
    if (pt.slice.lo_skipped) pt.slice = AuditMemory::Slices();
  auto& probes = memory_.probes[ci][kk];
  probes.erase(std::remove_if(probes.begin(), probes.end(), [](const AuditMemory::Point& pt) { return pt.slice.lo_skipped; }),
               probes.end());
}

// A bracket between every two neighbouring samples whose bump bound does not clear the tolerance; at[i]
// its interval.
void Auditor::brackets(const std::vector<Eigen::Index>& todo, std::vector<PeakBracket>& cand, std::vector<Eigen::Index>& at,
                       std::vector<double>& curvature) const {
  for (size_t t = 0; t < todo.size(); ++t) {
    const Eigen::Index k = todo[t];
    const std::vector<double>& L = Ls_[t];
    const std::vector<double>& V = Vs_[t];
    const double K = K_of(k, curvature_[t]);
    for (size_t i = 0; i + 1 < L.size(); ++i) {
      const double va = V[i], vb = V[i + 1];
      if (va == -kInf && vb == -kInf) continue;
      if (std::isfinite(va) && std::isfinite(vb) && bump_bound(L[i], va, L[i + 1], vb, K) <= tolerance_) continue;
      cand.push_back(golden_bracket(L[i], va, L[i + 1], vb));
      at.push_back(k);
      curvature.push_back(curvature_[t]);
    }
  }
}

// One cut per interval and round, at its largest violation: every row broken at the peak, as a row of the
// interval (exact, see the header), labelled as the problem's own row of that name (the constraint's
// first row if it has none). A contact constraint's cut is the polygon's edge there, with kSpread more
// (contact_cuts); other constraints' rows are cheap to evaluate, and one row per round keeps the rows of
// an interval from crowding near-parallel.
void Auditor::cut(size_t ci, const std::vector<PeakBracket>& cand, const std::vector<Eigen::Index>& at) {
  ks_.clear();
  ls_.clear();
  std::vector<size_t> cuts;
  std::map<Eigen::Index, size_t> best_of;
  for (size_t i = 0; i < cand.size(); ++i) {
    auto it = best_of.emplace(at[i], i).first;
    if (cand[i].best() > cand[it->second].best()) it->second = i;
  }
  for (size_t i = 0; i < cand.size(); ++i) {
    const double best = cand[i].best();
    double& remembered = memory_.worst[ci][static_cast<size_t>(at[i])];
    audit_.worst = std::max(audit_.worst, best);
    remembered = std::max(remembered, best);
    if (best_of[at[i]] != i) continue;
    if (best > tolerance_) {
      cuts.push_back(i);
      ks_.push_back(at[i]);
      ls_.push_back(cand[i].at());
    }
  }
  if (cuts.empty()) return;
  std::map<std::string, int> named;
  const ConstraintRows& grid = grid_rows_[ci];
  for (size_t j = 0; j < grid.labels.size(); ++j) named.emplace(grid.labels[j], static_cast<int>(j));
  if (constraints_[ci]->projected()) {
    contact_cuts(ci, cuts, at, named);
    return;
  }
  const ConstraintRows rr = constraints_[ci]->evaluate(samples_at(ks_, ls_));
  for (size_t q = 0; q < cuts.size(); ++q) {
    const Eigen::Index k = at[cuts[q]], r = static_cast<Eigen::Index>(q);
    memory_.cut_points[ci][static_cast<size_t>(k)].push_back({ls_[q], rr.a.row(r).transpose(), rr.b.row(r).transpose(), rr.c.row(r).transpose(), {}});
    add_broken_rows(ci, rr, r, k, ls_[q], named);
  }
}

// Row a x + b u <= c at λ l of interval k as a row of the interval (see the header), named as the
// problem's row `label` (the constraint's first row if it has none).
void Auditor::add_cut(size_t ci, Eigen::Index k, double l, double a, double b, double c, const std::string& label,
                      const std::map<std::string, int>& named) {
  const double h = s_[k + 1] - s_[k];
  const auto id = named.find(label);
  extra_.rows[static_cast<size_t>(k)].push_back(
      {a * (1.0 - l) - b / (2.0 * h), a * l + b / (2.0 * h), c, row_offset_[ci] + (id == named.end() ? 0 : id->second)});
  memory_.cut_at[ci][static_cast<size_t>(k)].push_back(l);
  ++audit_.cuts;
}

// Every row of rr's sample r (at λ l of interval k) that the timing breaks there, as a cut.
void Auditor::add_broken_rows(size_t ci, const ConstraintRows& rr, Eigen::Index r, Eigen::Index k, double l,
                              const std::map<std::string, int>& named) {
  for (Eigen::Index j = 0; j < rr.rows(); ++j)
    if (violation(rr.a(r, j), rr.b(r, j), rr.c(r, j), l, theta_[k], theta_[k + 1], u_of(k)) > tolerance_)
      add_cut(ci, k, l, rr.a(r, j), rr.b(r, j), rr.c(r, j), rr.labels[static_cast<size_t>(j)], named);
}



Audit audit_and_cut(const Path& path, const Eigen::VectorXd& s, const Eigen::VectorXd& theta,
                    const std::vector<std::shared_ptr<const Constraint>>& constraints,
                    const std::vector<ConstraintRows>& grid_rows, const std::vector<int>& row_offset, int points,
                    double tolerance, IntervalExtra& extra, AuditMemory& memory) {
  return Auditor(path, s, theta, constraints, grid_rows, row_offset, points, tolerance, extra, memory).run();
}

}  // namespace pathpace::detail
