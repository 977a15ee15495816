// The continuous audit's stages (solve/continuous.hpp, audit_and_cut), shared by continuous.cpp (the
// samples, the screen, the peaks, the cuts) and audit_contacts.cpp (a contact constraint's slice LPs there).
// Private to solve/.
#pragma once

#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "solve/brent.hpp"
#include "solve/continuous.hpp"

namespace pathpace::detail {

// Relative violation of row (a, b, c) at λ on an interval with θ_k = t0, θ_{k+1} = t1, u = (t1 - t0)/(2Δs).
double violation(double a, double b, double c, double lam, double t0, double t1, double u);
// A contact constraint's violation at one point: x beyond the polygon's slice [lo, hi] at the timing's u,
// relative to x's own size (as a row's violation is relative to its terms); an empty slice (no x at
// all fits this u) or a failed LP counts as a full violation, which the cut's projection then settles.
double slice_violation(double x, double lo, double hi);
// The bottom's part of slice_violation, (lo - x) / max(|x|, |hi|): where the bottom's LP was skipped above
// the top (lo = -inf), (hi - x) / ..., which is larger (x >= lo, the bottom cannot be broken there); an
// empty slice or a failed LP 1.
double bottom_violation(double x, double lo, double hi);
// bottom_violation of grid point r's polygon (its rows) at (x, u).
double row_slice_bottom(const ConstraintRows& rows, Eigen::Index r, double x, double u);

// Contact cuts per interval and round besides its peak's (contact_cuts). Between two cuts at which the
// timing is tight, x(λ) is the chord of the limit, so the violation is about K d² / 8 for cuts d apart (K
// the limit's convexity in λ), and its peak lies near their middle, not where the final timing touches the
// limit. Rows at kSpread more points spread evenly between the cuts that flank the peak divide that gap by
// kSpread + 1 each round, the violation by about (kSpread + 1)². Spread over the peak's bracket (its
// samples: narrower than the cuts around it where earlier peak searches left samples) the touching point
// was seen to move out of it, which halved the gap per round instead (bench/README.md, issue 27).
constexpr int kSpread = 7;

// Tight cuts (Auditor::tight_cuts): after a round's cuts, every Chebyshev point of an audited interval
// where the timing is within kTight of its slice's top (relative to x's size, as a violation is) gets
// that top's edge as a row too. The cuts move the timing, and it comes to push on its limit beside them:
// an interval tight but unbroken at its samples broke between them in the next round, its neighbour in
// the one after (romeo-squat off1.5 of issue 27's corpus: intervals 48 and 50 cut in round 1, 49 and 51
// broken in rounds 2 and 3). kTight is path_curvature's "near the limit".
constexpr double kTight = 1e-2;

// One audit_and_cut call: the data its stages share. Per constraint (audit_constraint): the intervals
// whose speeds changed, their samples (contact slices in one batch), the path-wide concavity bound, the
// brackets it does not clear, their peaks (maximize_batch), and the cuts there.
class Auditor {
 public:
  Auditor(const Path& path, const Eigen::VectorXd& s, const Eigen::VectorXd& theta,
          const std::vector<std::shared_ptr<const Constraint>>& constraints, const std::vector<ConstraintRows>& grid_rows,
          const std::vector<int>& row_offset, int points, double tolerance, IntervalExtra& extra, AuditMemory& memory)
      : path_(path), s_(s), theta_(theta), constraints_(constraints), grid_rows_(grid_rows), row_offset_(row_offset),
        points_(points), tolerance_(tolerance), extra_(extra), memory_(memory), N_(s.size() - 1) {}
  Audit run();

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  void size_memory();
  void audit_constraint(size_t ci);
  PathSamples samples_at(const std::vector<Eigen::Index>& ks, const std::vector<double>& ls) const;
  double u_of(Eigen::Index k) const { return (theta_[k + 1] - theta_[k]) / (2.0 * (s_[k + 1] - s_[k])); }
  double x_of(Eigen::Index k, double l) const { return (1.0 - l) * theta_[k] + l * theta_[k + 1]; }
  double worst_row(const ConstraintRows& rr, Eigen::Index r, double l, Eigen::Index k) const;
  void violations(size_t ci, const Constraint* contact, const std::vector<Eigen::Index>& kk,
                  const std::vector<double>& ll, std::vector<double>& f);
  void coarse_rows(size_t ci);
  std::vector<Eigen::Index> intervals_to_audit(size_t ci);
  void contact_batch(const Constraint& cc, size_t ci, const std::vector<Eigen::Index>& todo, std::vector<size_t>& first,
                     std::vector<double>& f);
  // Whether a kept slice gives the violation at (x, u) without an LP: u within its top's range, and x
  // above the top or u within its bottom's range too, or its bottom skipped (then the top's alone).
  static bool covers(const AuditMemory::Slices& M, double x, double u);
  // M from a slice solved at u (lo, hi its ends, edges' row e their edges).
  static void keep_slice(AuditMemory::Slices& M, double u, double lo, double hi, const SliceEdges& edges,
                         Eigen::Index e, double cap, bool lo_skipped = false);
  void warm_slice(const Constraint& cc, size_t ci, const std::vector<Eigen::Index>& ks, const PathSamples& ps,
                  const Eigen::VectorXd& u, Eigen::VectorXd& lo, Eigen::VectorXd& hi, const Eigen::VectorXd* x,
                  SliceEdges* edges);
  void contact_samples(const Constraint& cc, size_t ci, const std::vector<size_t>& first,
                       const std::vector<Eigen::Index>& todo, std::vector<double>& f);
  void sample_intervals(size_t ci, const Constraint* contact, const std::vector<Eigen::Index>& todo,
                        const std::vector<size_t>& first, const std::vector<double>& fc);
  void path_curvature(size_t ci, const std::vector<Eigen::Index>& todo);
  std::vector<Eigen::Index> bottoms(const std::vector<Eigen::Index>& todo);
  void forget_skipped_bottoms(size_t ci, Eigen::Index k);
  double K_of(Eigen::Index k, double curvature) const {
    const double h = s_[k + 1] - s_[k];
    return 4.0 * curvature * h * h;
  }
  void brackets(const std::vector<Eigen::Index>& todo, std::vector<PeakBracket>& cand, std::vector<Eigen::Index>& at,
                std::vector<double>& curvature) const;
  void cut(size_t ci, const std::vector<PeakBracket>& cand, const std::vector<Eigen::Index>& at);
  void tight_cuts(size_t ci, const std::vector<Eigen::Index>& todo);  // see kTight
  void contact_cuts(size_t ci, const std::vector<size_t>& cuts, const std::vector<Eigen::Index>& at,
                    const std::map<std::string, int>& named);
  void add_cut(size_t ci, Eigen::Index k, double l, double a, double b, double c, const std::string& label,
               const std::map<std::string, int>& named);
  void add_broken_rows(size_t ci, const ConstraintRows& rr, Eigen::Index r, Eigen::Index k, double l,
                       const std::map<std::string, int>& named);

  const Path& path_;
  const Eigen::VectorXd& s_;
  const Eigen::VectorXd& theta_;
  const std::vector<std::shared_ptr<const Constraint>>& constraints_;
  const std::vector<ConstraintRows>& grid_rows_;
  const std::vector<int>& row_offset_;
  const int points_;
  const double tolerance_;
  IntervalExtra& extra_;
  AuditMemory& memory_;
  const Eigen::Index N_;
  Audit audit_;
  std::vector<double> lam_;            // the Chebyshev points in λ
  std::vector<Eigen::Index> ks_;       // a batch of samples: interval ks_[i] at λ ls_[i]
  std::vector<double> ls_;
  std::vector<AuditMemory::Slices*> memo_of_;  // contact_batch's samples: each one's kept slice
  std::vector<std::vector<double>> Ls_, Vs_;  // [interval to audit]: its samples, sorted and merged
  std::vector<double> curvature_;             // [interval to audit]: its bound on -v''(s) (path_curvature)
  std::vector<double> fbot_;                  // contact_samples' samples: bottom_violation of each
  std::vector<std::vector<double>> Bs_;       // [interval to audit]: bottom_violation at Ls_ (contact only)
  std::vector<char> bottom_;                  // [interval]: whether its slices' bottoms are solved (bottoms())
  std::vector<char> far_ends_;                // [interval]: its samples' LPs skip the bottom (contact_batch)
};

}  // namespace pathpace::detail
