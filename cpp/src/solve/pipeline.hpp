#pragma once
// One solve of eq. (26)-(27) on given rows, as stages that each take the previous one's output (sec. V):
//   rows -> grid sets (the feasible polygon per grid point, sec. IV) -> reachability (controllable sets, the
//   greedy profile, and the relaxation's bracket) -> certify (SLP windows, or the proof without them) ->
//   assemble (ṡ, s̈, t).
// A stage that finds no timing says why in a Stop; problem/solve.cpp turns it into the Result's status and
// message (with the relaxation and contact re-check that need the problem itself).

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/binding_labels.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/result.hpp"
#include "pathpace/solver_options.hpp"
#include "solve/grid_sets.hpp"
#include "solve/line_reachability.hpp"
#include "solve/reachability.hpp"

namespace pathpace::detail {

/// A stage's verdict that ends the solve without a timing: the status, the grid index it is about, the rows
/// that bind there (GridSets label ids) and why, in words.
struct Stop {
  Status status = Status::Infeasible;
  Eigen::Index k = 0;
  std::vector<int> ids;
  std::string why;
};

/// The solve's clock: when it started and when its budget (SolverOptions::time_limit) runs out.
struct Budget {
  std::chrono::steady_clock::time_point started, deadline;
  double time_limit = 0.0;  ///< seconds, for the messages
  static Budget from(double time_limit);
};

/// Stage 1: the feasible polygon of every grid point, in the units where the speeds are ~1 (Scale).
struct SetsStage {
  Scale scale;
  GridSets sets;
  double seconds = 0.0;
  std::optional<Stop> stop;  ///< an empty polygon, or a boundary speed beyond its end point's bound
};
/// `scale`: these units instead of problem_scale's of `rows` (rows refined between solves keep one scale, so
/// that the parts of the timing their refinement does not touch stay the same to the bit).
SetsStage grid_sets_stage(const PathSamples& samples, const std::vector<ConstraintRows>& rows, double sdot_begin,
                          double sdot_end, const Scale* scale = nullptr);

/// Stage 2: the chain of interval rows, the reachability analysis and, with Method::Auto and coupling rows,
/// the relaxation's bracket (see SolverOptions' Method::Auto); theta is the profile to certify.
struct ReachStage {
  Chain chain;
  double th0 = 0.0, thN = 0.0;  ///< boundary θ in the chain's units
  Eigen::VectorXd theta;
  /// The relaxed analysis (when have_full); on the heap because `reach` may point into it (Reachability::base).
  std::unique_ptr<Reachability> relaxed;
  Reachability reach;
  /// The full analysis by lines when it stands in for `reach` (which then holds nothing): its greedy profile
  /// starts the SLP's windows and its capped pass repairs their result (see line_stage in pipeline.cpp).
  std::unique_ptr<LineAnalysis> lines;
  bool have_full = false;  ///< the relaxed and full analyses both ran and ended feasible
  bool proven = false;     ///< theta is the optimum, or within the tolerance of it, without SLP
  bool exact = false;      ///< theta (proven) already meets the grid points' rows to rounding (line_stage)
  double T_relaxed = 0.0;  ///< T(θ') when have_full (a lower bound on T*), else NaN
  double gap = 0.0;        ///< the bracket's certified gap, when proven by it
  double seconds = 0.0;
  std::optional<Stop> stop;  ///< infeasible, unbounded, or a speed forced to zero on an interval
};
/// Throws InvalidInput for a stationary stretch of path that nothing bounds (crossed in zero time).
ReachStage reachability_stage(const PathSamples& samples, const SetsStage& sets, const IntervalExtra* extra,
                              double sdot_begin, double sdot_end, const SolverOptions& options);

/// Stage 3: the certified timing: by SLP on windows unless stage 2 proved it, then checked in the grid
/// points' own terms (eq. 26) and made exactly feasible.
struct Certified {
  Status status = Status::Optimal;
  std::string message;
  Eigen::VectorXd theta;  ///< in the chain's units
  BindingLabels binding;
  double gap = 0.0;
  bool greatest_element = false;
  int slp_iterations = 0, lp_solves = 0, windows = 0, window_points = 0, newton_steps = 0;
  double seconds = 0.0;  ///< in SLP
};
Certified certify_stage(const PathSamples& samples, const SetsStage& sets, const ReachStage& reach,
                        const SolverOptions& options, const Budget& budget);

/// Stage 4: ṡ, s̈ and t of the certified θ (eq. 24-25) into `res`.
void assemble(const Eigen::VectorXd& s, const Scale& scale, Eigen::VectorXd theta, Result& res);

}  // namespace pathpace::detail
