// The continuous audit's contact part (see solve/auditor.hpp): a contact constraint's samples by slice LPs
// (ContactConstraint::slice), warm-started per interval across calls and rounds, and its cuts from the slices'
// edges.
#include "solve/auditor.hpp"

#include <algorithm>
#include <cmath>

namespace pathpace::detail {

// Constraint::slice at samples in intervals ks, each LP warm-started from its interval's last optimal
// bases (SliceStarts), which the LPs' own optima then replace; the LPs spent go to audit_.lps.
void Auditor::warm_slice(const Constraint& cc, size_t ci, const std::vector<Eigen::Index>& ks, const PathSamples& ps,
                         const Eigen::VectorXd& u, Eigen::VectorXd& lo, Eigen::VectorXd& hi, const Eigen::VectorXd* x,
                         SliceEdges* edges) {
  auto& bases = memory_.bases[ci];
  SliceStarts st;
  for (int end = 0; end < 2; ++end) {
    st.start[end].reserve(ks.size());
    for (Eigen::Index k : ks) st.start[end].push_back(bases[static_cast<size_t>(k)][static_cast<size_t>(end)]);
  }
  audit_.lps += cc.slice(ps, u, lo, hi, x, edges, &st);
  audit_.glpk_lps += st.glpk_lps;
  for (int end = 0; end < 2; ++end)
    for (size_t q = 0; q < ks.size() && q < st.found[end].size(); ++q)
      if (!st.found[end][q].empty()) bases[static_cast<size_t>(ks[q])][static_cast<size_t>(end)] = std::move(st.found[end][q]);
}
bool Auditor::covers(const AuditMemory::Slices& M, double x, double u) {
  if (!(M.hi_from <= u && u <= M.hi_to)) return false;
  return (!M.hi_capped && x > M.hi + M.hi_slope * (u - M.u)) || (M.lo_from <= u && u <= M.lo_to) || M.lo_skipped;
}

void Auditor::keep_slice(AuditMemory::Slices& M, double u, double lo, double hi, const SliceEdges& edges,
                         Eigen::Index e, double cap, bool lo_skipped) {
  M = AuditMemory::Slices();
  M.u = u;
  // Kept only for a slice whose ends are numbers (an empty slice or a failed LP is asked again).
  if (std::isnan(hi) || std::isnan(lo) || lo > hi) return;
  M.hi_capped = hi == kInf || hi >= cap * (1.0 - 1e-9);
  M.hi = hi;
  M.hi_slope = edges.hi_slope[e];
  M.hi_from = edges.hi_from[e];
  M.hi_to = edges.hi_to[e];
  M.lo_skipped = lo_skipped;
  if (lo > -kInf) {  // -inf: its LP was skipped (x above the top)
    M.lo = lo;
    M.lo_slope = edges.lo_slope[e];
    M.lo_from = edges.lo_from[e];
    M.lo_to = edges.lo_to[e];
  }
}

// A contact constraint's samples, all in one batch (one warm-started LP sequence): the Chebyshev points,
// the earlier cut points and the earlier peak search's points whose slices still cover the timing (the
// rest dropped) of every interval to audit, into (ks_, ls_, memo_of_), interval todo[t]'s from first[t]
// to first[t + 1]; f their violations.
void Auditor::contact_batch(const Constraint& cc, size_t ci, const std::vector<Eigen::Index>& todo,
                            std::vector<size_t>& first, std::vector<double>& f) {
  auto& memo = memory_.slices[ci];
  if (memo.size() != static_cast<size_t>(N_ * points_)) memo.assign(static_cast<size_t>(N_ * points_), {});
  auto& ends = memory_.grid_slices[ci];
  const bool at_ends = cc.refines();
  if (at_ends && ends.size() != static_cast<size_t>(2 * N_)) ends.assign(static_cast<size_t>(2 * N_), {});
  ks_.clear();
  ls_.clear();
  memo_of_.clear();
  far_ends_.assign(static_cast<size_t>(N_), 0);
  const ConstraintRows& grid = grid_rows_[ci];
  for (size_t t = 0; t < todo.size(); ++t) {
    const Eigen::Index k = todo[t];
    const size_t kk = static_cast<size_t>(k);
    first[t] = ks_.size();
    // The guess that the slices' bottoms are far from the timing in this interval: both grid points' exact
    // bottoms (their rows, no LP) are below it by more than kGuess of its size. Its samples' LPs then skip the
    // bottom; bottoms() checks the guess by the screen, and where it fails the interval is sampled again.
    if (!at_ends && !memory_.bottoms_near[ci][kk]) {
      constexpr double kGuess = 0.25;
      const double u = u_of(k);
      far_ends_[kk] = std::max(row_slice_bottom(grid, k, x_of(k, 0.0), u), row_slice_bottom(grid, k + 1, x_of(k, 1.0), u)) <= -kGuess;
    }
    auto add = [&](double l, AuditMemory::Slices* M) {
      ks_.push_back(k);
      ls_.push_back(l);
      memo_of_.push_back(M);
    };
    if (at_ends) {
      add(0.0, &ends[2 * kk]);
      add(1.0, &ends[2 * kk + 1]);
    }
    for (int m = 0; m < points_; ++m) add(lam_[static_cast<size_t>(m)], &memo[kk * static_cast<size_t>(points_) + static_cast<size_t>(m)]);
    for (AuditMemory::Point& pt : memory_.cut_points[ci][kk]) add(pt.lam, &pt.slice);
    auto& probes = memory_.probes[ci][kk];
    probes.erase(std::remove_if(probes.begin(), probes.end(),
                                [&](const AuditMemory::Point& pt) { return !covers(pt.slice, x_of(k, pt.lam), u_of(k)); }),
                 probes.end());
    for (AuditMemory::Point& pt : probes) add(pt.lam, &pt.slice);
  }
  first[todo.size()] = ks_.size();
  contact_samples(cc, ci, first, todo, f);
}

// A contact constraint's samples (ks_[i], ls_[i]) of the intervals todo[t] (samples first[t] ..
// first[t + 1]: `points` Chebyshev points, then cut points): a sample whose slice edges from an earlier
// round cover this u (SliceEdges: each end of the slice is exactly linear in u over its range) has its
// slice without an LP; every other sample gets its slice by LPs (the bottom's skipped where x is above
// the top), with its edges kept for the rounds after.
void Auditor::contact_samples(const Constraint& cc, size_t ci, const std::vector<size_t>& first,
                              const std::vector<Eigen::Index>& todo, std::vector<double>& f) {
  const std::vector<Eigen::Index>& kk = ks_;
  const std::vector<double>& ll = ls_;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double cap = cc.projection_cap();
  f.assign(kk.size(), nan);
  fbot_.assign(kk.size(), nan);
  std::vector<Eigen::Index> bk;
  std::vector<double> bl, bu, bx, bskip;
  std::vector<size_t> main_of;  // per sample asked: its index in kk
  for (size_t t = 0; t < todo.size(); ++t)
    for (size_t i = first[t]; i < first[t + 1]; ++i) {
      const Eigen::Index k = kk[i];
      const double u = u_of(k), x = x_of(k, ll[i]);
      const AuditMemory::Slices& M = *memo_of_[i];
      if (covers(M, x, u)) {
        const double hi = M.hi_capped ? kInf : M.hi + M.hi_slope * (u - M.u);
        const bool bottom = M.lo_from <= u && u <= M.lo_to;
        const double lo = bottom && x <= hi ? M.lo + M.lo_slope * (u - M.u) : -kInf;
        f[i] = slice_violation(x, lo, hi);
        // A bottom skipped below the top: unknown (NaN, Auditor::bottoms).
        fbot_[i] = !bottom && x <= hi ? nan : bottom_violation(x, lo, hi);
        ++audit_.reused;
        continue;
      }
      bk.push_back(k);
      bl.push_back(ll[i]);
      bu.push_back(u);
      bx.push_back(x);
      bskip.push_back(far_ends_[static_cast<size_t>(k)] ? kInf : x);
      main_of.push_back(i);
    }
  if (bk.empty()) return;
  const PathSamples ps = samples_at(bk, bl);
  Eigen::VectorXd lo, hi;
  SliceEdges edges;
  const Eigen::Index n = static_cast<Eigen::Index>(bu.size());
  const Eigen::VectorXd skip = Eigen::Map<const Eigen::VectorXd>(bskip.data(), n);
  warm_slice(cc, ci, bk, ps, Eigen::Map<const Eigen::VectorXd>(bu.data(), n), lo, hi, &skip, &edges);
  for (size_t q = 0; q < bk.size(); ++q) {
    const Eigen::Index e = static_cast<Eigen::Index>(q);
    const bool skipped = bskip[q] == kInf && !(bx[q] > hi[e]);  // the bottom guessed far, not solved
    f[main_of[q]] = slice_violation(bx[q], lo[e], hi[e]);
    fbot_[main_of[q]] = skipped ? nan : bottom_violation(bx[q], lo[e], hi[e]);
    keep_slice(*memo_of_[main_of[q]], bu[q], lo[e], hi[e], edges, e, cap, skipped);
  }
}
// A contact constraint's cuts at the peaks (ks_, ls_) of the brackets cuts[q]: the polygon's edge through
// the end of its slice that the timing's (x, u) is beyond (SliceEdges; the polygon lies on its side of
// that line, so the row is exact), one LP per end instead of a projection of the polygon. A slice that
// is empty there (u outside the polygon) or whose LP failed has no such edge: that point's polygon is
// projected, and its broken rows cut. Besides the peak, the top edges at kSpread points evenly between the
// interval's cuts (or ends) that flank the peak, broken or not (see kSpread).
void Auditor::contact_cuts(size_t ci, const std::vector<size_t>& cuts, const std::vector<Eigen::Index>& at,
                           const std::map<std::string, int>& named) {
  std::vector<Eigen::Index> ks;
  std::vector<char> spread;  // per point: 0 a peak, 1 a spread point
  for (size_t q = 0; q < cuts.size(); ++q) {
    ks.push_back(at[cuts[q]]);
    spread.push_back(0);
  }
  for (size_t q = 0; q < cuts.size(); ++q) {
    double a = 0.0, c = 1.0;
    for (double l : memory_.cut_at[ci][static_cast<size_t>(at[cuts[q]])]) {
      if (l < ls_[q]) a = std::max(a, l);
      if (l > ls_[q]) c = std::min(c, l);
    }
    for (int j = 1; j <= kSpread; ++j) {
      const double l = a + (c - a) * j / (kSpread + 1.0);
      if (std::abs(l - ls_[q]) < 1e-2 * (c - a)) continue;  // the peak's own
      ks.push_back(at[cuts[q]]);
      ls_.push_back(l);
      spread.push_back(1);
    }
  }
  const Constraint& cc = *constraints_[ci];
  // The bottom's LP only where it can cut: at a peak below its slice's top (above it, the bottom is below
  // too); a spread point cuts its top only (a bottom broken there is found by the next round's samples).
  Eigen::VectorXd u(static_cast<Eigen::Index>(ks.size())), skip(u.size()), lo, hi;
  for (size_t q = 0; q < ks.size(); ++q) {
    u[static_cast<Eigen::Index>(q)] = u_of(ks[q]);
    skip[static_cast<Eigen::Index>(q)] = spread[q] || !bottom_[static_cast<size_t>(ks[q])] ? kInf : x_of(ks[q], ls_[q]);
  }
  SliceEdges edges;
  edges.labels = true;
  warm_slice(cc, ci, ks, samples_at(ks, ls_), u, lo, hi, &skip, &edges);
  const double cap = cc.projection_cap();
  std::vector<Eigen::Index> pk;  // the points to project
  std::vector<double> pl;
  for (size_t q = 0; q < ks.size(); ++q) {
    const Eigen::Index k = ks[q], e = static_cast<Eigen::Index>(q);
    const double l = ls_[q], x = x_of(k, l), uq = u[e];
    if (!spread[q]) memory_.cut_points[ci][static_cast<size_t>(k)].push_back({l, {}, {}, {}, {}});
    if (std::isnan(lo[e]) || std::isnan(hi[e]) || lo[e] > hi[e]) {
      if (spread[q]) continue;
      pk.push_back(k);
      pl.push_back(l);
      continue;
    }
    // x <= hi + s (u' - u) and x >= lo + s' (u' - u), as rows a x + b u' <= c.
    if (hi[e] < cap * (1.0 - 1e-9) && (spread[q] || violation(1.0, 0.0, hi[e], 0.0, x, x, 0.0) > tolerance_))
      add_cut(ci, k, l, 1.0, -edges.hi_slope[e], hi[e] - edges.hi_slope[e] * uq, edges.hi_label[static_cast<size_t>(q)], named);
    if (violation(-1.0, 0.0, -lo[e], 0.0, x, x, 0.0) > tolerance_)
      add_cut(ci, k, l, -1.0, edges.lo_slope[e], edges.lo_slope[e] * uq - lo[e], edges.lo_label[static_cast<size_t>(q)], named);
  }
  if (pk.empty()) return;
  const ConstraintRows rr = cc.evaluate(samples_at(pk, pl));
  audit_.projections += static_cast<int>(pk.size());
  for (size_t q = 0; q < pk.size(); ++q) add_broken_rows(ci, rr, static_cast<Eigen::Index>(q), pk[q], pl[q], named);
}
}  // namespace pathpace::detail
