#pragma once
// Reachability analysis on the chain of intervals (sec. V with the rows of eq. 26).
//
// On interval k the unknowns are θ_k and θ_{k+1}; s̈ = (θ_{k+1} - θ_k) / (2Δs_k) is constant, and it must
// satisfy the half-planes of grid point k (forward rows) and of grid point k+1 (backward rows). Both
// become rows α θ_k + β θ_{k+1} <= c. Backward controllable intervals K_k (all θ_k from which s_N can be
// reached) come from one exact 2-D LP per interval; a forward greedy pass inside them yields a feasible θ.

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "solve/grid_sets.hpp"
#include "geometry/polygon2d.hpp"

namespace pathpace::detail {

/// On interval k a row reads α θ_k + β θ_{k+1} <= c, stored as a Line {a = α, b = β, c, id}. Each
/// interval's rows come in one block, the rows with α > 0 and β > 0 (the only kind that breaks
/// max-closure, "coupled") at its end, so that the relaxed analysis reads a prefix of the block.
struct Chain {
  Eigen::VectorXd ds;                 // Δs_k, N
  std::vector<Line> row_data;         // all intervals' rows, interval k at [offset[k], offset[k+1])
  std::vector<std::size_t> row_offset;
  std::vector<std::size_t> coupled_offset;  // interval k's coupled rows: [coupled_offset[k], offset[k+1])
  Eigen::Index intervals() const { return ds.size(); }
  View<Line> rows(Eigen::Index k) const {
    const std::size_t o = row_offset[static_cast<std::size_t>(k)];
    return {row_data.data() + o, row_offset[static_cast<std::size_t>(k) + 1] - o};
  }
  View<Line> relaxed_rows(Eigen::Index k) const {
    const std::size_t o = row_offset[static_cast<std::size_t>(k)];
    return {row_data.data() + o, coupled_offset[static_cast<std::size_t>(k)] - o};
  }
  View<Line> coupled_rows(Eigen::Index k) const {
    const std::size_t o = coupled_offset[static_cast<std::size_t>(k)];
    return {row_data.data() + o, row_offset[static_cast<std::size_t>(k) + 1] - o};
  }
  Eigen::VectorXd x_lo, x_hi;                  // per grid point bounds on θ_k
  double cap = kInfinityCap;                   // the box standing in for "no limit" (Scale::cap)
  std::vector<int> x_lo_id, x_hi_id;
  /// True if no row has α > 0 and β > 0: then the feasible set of θ is closed under the componentwise
  /// max (for α, β of opposite signs or either <= 0, max(θ, θ') satisfies every row that θ and θ' do),
  /// so it has a greatest element, which the greedy forward pass finds and which minimises T.
  bool lattice = true;
};

/// Rows of single intervals beyond the grid points' (guarantee = continuous: bounds that hold between
/// grid points), rows[k] for interval k, in chain form α θ_k + β θ_{k+1} <= c with label ids.
struct IntervalExtra {
  std::vector<std::vector<Line>> rows;
};

/// The chain in the units of `scale` (those `sets` were built in): Δs̃ = Δs / s_unit, θ̃ = θ / x_unit.
Chain build_chain(const Eigen::VectorXd& s, const GridSets& sets, const IntervalExtra* extra = nullptr,
                  const Scale& scale = {});

/// True for a row with α > 0 and β > 0 (beyond rounding): the only kind that breaks max-closure.
bool couples_positively(double alpha, double beta);
inline bool couples_positively(const Line& r) { return couples_positively(r.a, r.b); }


/// Violation of α x + β y <= c at (x, y), relative to max(1, |c|, |α x|, |β y|) (<= 0 when it holds).
double row_violation(const Line& r, double x, double y);

/// Interval k's polygon in (θ_k, θ_{k+1}): the box cut by its rows, in one envelope pass when that applies
/// (see Polygon2d::build), else row by row (which also names the rows of an empty set).
void interval_polygon(Polygon2d& poly, double x_lo, double x_hi, double y_lo, double y_hi, View<Line> rows);

/// Largest violation of the positively coupling rows by θ, relative to max(1, |c|, |α θ_k|, |β θ_{k+1}|).
double coupled_violation(const Chain& chain, const Eigen::VectorXd& theta);

/// max(worst, row_violation(r, x, y)) for worst >= 0: a row that holds (α x + β y - c <= 0) cannot raise it,
/// so the scale (and its division) is computed only for a violated row.
inline double raise_violation(double worst, const Line& r, double x, double y) {
  const double ax = r.a * x, by = r.b * y, d = ax + by - r.c;
  if (!(d > 0.0)) return worst;
  return std::max(worst, d / std::max({1.0, std::abs(r.c), std::abs(ax), std::abs(by)}));
}

/// Largest violation of the bounds x_lo <= θ <= x_hi by θ, relative to max(1, |bound|) (in the solve's units,
/// where 1 is a typical ṡ²). With the rows' (binding_labels' `violation`): how far θ is from feasible.
double bound_violation(const Chain& chain, const Eigen::VectorXd& theta);

/// Largest violation of the grid points' own rows a x + b u <= c (eq. 26, both adjacent s̈ at each point) by
/// θ, relative to max(1, |c|, |a θ_k|, |b u|, and |b| times the s̈ that θ's rounding resolves): the user's terms (a joint's q̈ against its limit), where the
/// chain's rows, which carry b / (2Δs) in both coefficients, would measure against terms N times larger
/// and hide an s̈ that breaks its limit on a fine grid. x_lo/x_hi as bound_violation does.
double grid_violation(const Chain& chain, const GridSets& sets, const Eigen::VectorXd& theta, Eigen::Index* where);

/// The last exact-feasibility step: where θ (from rest to rest) breaks a grid point's row by more than
/// `target` but by rounding only (<= 1e-6, relative), θ scaled down by 1 / (1 + 4 v), up to three times
/// doubling the shrink, until it meets every row to `target` (rows with c > 0, as speed and acceleration
/// limits have, hold with room at a lower speed). Returns grid_violation of the θ it leaves and sets
/// *T_increase to the relative growth of T (added to the certified gap); θ is unchanged when the step does
/// not help.
double exact_feasibility_step(const Chain& chain, const GridSets& sets, Eigen::VectorXd& theta, Eigen::Index* where,
                              double* T_increase, double target = 1e-9);

struct Reachability {
  enum class Outcome { Feasible, Infeasible, Unbounded };
  Outcome outcome = Outcome::Feasible;
  Eigen::VectorXd k_lo, k_hi;  // controllable intervals
  // Interval k's polygon in (θ_k, θ_{k+1}) with θ_{k+1} ∈ K_{k+1}: vertices [start[k], start[k] + size[k])
  // (stored in the order the backward pass builds them, interval N-1 first).
  std::vector<Vertex> vertices;
  std::vector<Line> edges;     // edges[start[k] + j] runs from vertex j - 1 to vertex j (Polygon2d's order)
  std::vector<size_t> start, size;
  // reachability_pair: where the full analysis's polygon equals the relaxed one's (in_base[k]), it is
  // read from `base` (the relaxed analysis, which must outlive this one) instead of stored twice.
  const Reachability* base = nullptr;
  std::vector<char> in_base;
  Eigen::VectorXd theta;       // greedy forward profile (when feasible)
  bool theta_is_greedy = false;  // theta is the greedy profile itself (forward_pass may then reuse it)
  Eigen::Index failed_index = -1;
  std::vector<int> binding;    // row ids (labels) that bind where it fails
  std::string reason;
};

/// Controllable sets and the greedy forward profile for θ_0 = theta_begin, θ_N = theta_end; on failure
/// the first grid index that fails and the rows that bind there.
Reachability reachability(const Chain& chain, double theta_begin, double theta_end);

/// The relaxed analysis (without the positively coupling rows: its feasible set is max-closed, so its
/// greedy profile θ' is its greatest element and T(θ') <= T*; if θ' also satisfies the dropped rows it is
/// the optimum of the full problem) and the full analysis together. Their backward passes usually meet the
/// same box (K_{k+1} alike) and then share the polygon of the rows both have, the full one adding only
/// the coupling rows, which rarely cut. Returns false, with nothing reliable in the outputs, if either
/// analysis does not end feasible: call reachability() for the report then. `full` reads polygons from
/// `relaxed` afterwards (Reachability::base): keep `relaxed` alive as long as `full` is used.
bool reachability_pair(const Chain& chain, double theta_begin, double theta_end, Reachability& relaxed,
                       Reachability& full);

/// The greedy forward pass below caps: θ_{k+1} = cap_{k+1} clamped into the slice of interval k's
/// polygon at θ_k. With caps = nullptr this is the greedy maximum; with caps = an SLP iterate it repairs
/// the iterate's LP-tolerance infeasibility. Each θ_{k+1} is read off an edge between two polygon
/// vertices, so (θ_k, θ_{k+1}) is a convex combination of points that satisfy every row to rounding:
/// no row with a small coefficient can amplify an error along the chain.
Eigen::VectorXd forward_pass(const Reachability& reach, double theta_begin, const Eigen::VectorXd* caps);

/// True if some interval has θ_k = θ_{k+1} = 0: it would be crossed in infinite time (eq. 25).
bool has_stopped_interval(const Eigen::VectorXd& theta);

/// A feasible profile that stops on no interval if any feasible profile does not, for a start when the
/// greedy one stops somewhere. Where the rows couple θ_k and θ_{k+1} positively (Chain::lattice false)
/// the greedy maximum can walk into a trap: θ_k at the top of K_k may leave only θ_{k+1} = 0, and the
/// next interval then only θ_{k+2} = 0 (on a coarse grid the greedy profile can stop where a small
/// constant θ is feasible). Taking θ_{k+1} in the middle of each slice instead keeps every
/// θ_{k+1} strictly inside K_{k+1} (the slice at a point strictly inside K_k has positive length when the
/// polygon has positive area), so it stops nowhere; its average with the greedy profile is feasible (the
/// feasible set is convex) and stops nowhere either.
Eigen::VectorXd unstopped_profile(const Reachability& reach, double theta_begin);

/// A greedy profile that stops on an interval is the answer only if it is the greatest element of a
/// max-closed feasible set (chain.lattice: then every feasible profile stops there); otherwise it may have
/// walked into a trap of the coupling rows, and the profile that does not stop (detail::unstopped_profile)
/// replaces it, in theta and reach.theta, when there is one. Returns whether theta moves on every interval.
bool avoid_stopped_profile(const Chain& chain, Reachability& reach, double th0, Eigen::VectorXd& theta);



}  // namespace pathpace::detail
