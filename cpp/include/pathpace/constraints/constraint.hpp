#pragma once
/// @file constraint.hpp
/// A constraint on the timing, written at each grid point as half-planes a·x + b·u <= c in
/// x = ṡ² and u = s̈ (the paper's eq. 9).

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/path_samples.hpp"

namespace pathpace {

/// LPs of contact projections (sec. IV.C) by cause: the initial directions (a triangle), edge LPs that
/// found a new vertex (or failed), edge LPs that certified an edge, feasibility LPs that grew the stand-in
/// bounds, and every LP of a grid point projected once more from a cold start.
struct LpCounts {
  int initial = 0, vertex = 0, certificate = 0, cap_growth = 0, cold_retry = 0;
  LpCounts& operator+=(const LpCounts& o) {
    initial += o.initial, vertex += o.vertex, certificate += o.certificate, cap_growth += o.cap_growth;
    cold_retry += o.cold_retry;
    return *this;
  }
};

/// Half-planes of one constraint at every grid point. Row j at grid point k reads
///   a(k, j)·x + b(k, j)·u <= c(k, j).
/// A row with c = +inf is inactive at that grid point (a limit that is absent, or padding when the
/// number of half-planes varies along the path). labels[j] names row j for infeasibility reports,
/// e.g. "acceleration joint 3 upper".
struct ConstraintRows {
  /// Row-major: the r rows of one grid point are contiguous, as the per-point polygons read them.
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Matrix a;  ///< (N+1, r)
  Matrix b;  ///< (N+1, r)
  Matrix c;  ///< (N+1, r)
  std::vector<std::string> labels;  ///< r names
  /// Grid points where the rows are only an inner approximation of the constraint (a projection whose
  /// LP failed or ran out of budget, sec. IV.C); empty when they are exact.
  std::vector<Eigen::Index> inexact_points;
  /// True when no entry can be bad by construction (a and b finite, c a number or +inf), as in the
  /// library's velocity and acceleration limits, built from finite samples and validated limits: the
  /// problem then skips its scan of the entries (~1.5 % of a solve at N = 1000). A constraint of your own
  /// leaves it false, and its rows are checked; one that edits the rows another's evaluate() returned
  /// (a subclass of VelocityLimits, say) must set it false again.
  bool valid_by_construction = false;
  int lp_solves = 0;     ///< LPs spent computing the rows (projections)
  LpCounts lp_by_cause;  ///< the same LPs by cause (contact projections)
  double seconds = 0.0;  ///< time spent computing them (set by TimeScalingProblem::add_constraint)

  void resize(Eigen::Index points, Eigen::Index rows) {
    a.setZero(points, rows);
    b.setZero(points, rows);
    c.setConstant(points, rows, std::numeric_limits<double>::infinity());
    labels.assign(static_cast<size_t>(rows), std::string());
  }
  /// Sizes the arrays without initialising a, b, c (for constraints that write every entry).
  void allocate(Eigen::Index points, Eigen::Index rows) {
    a.resize(points, rows);
    b.resize(points, rows);
    c.resize(points, rows);
    labels.assign(static_cast<size_t>(rows), std::string());
  }
  Eigen::Index rows() const { return a.cols(); }
};

/// Interface of every constraint. Implementations are immutable after construction, so one instance
/// can serve several problems and threads; evaluate() keeps its scratch space local.
class Constraint {
 public:
  virtual ~Constraint() = default;

  /// A short name for messages, e.g. "velocity limits".
  virtual std::string name() const = 0;

  /// The half-planes at every grid point of `samples`. Throws InvalidInput when the constraint does
  /// not fit the path (e.g. a dimension mismatch), naming what does not fit.
  virtual ConstraintRows evaluate(const PathSamples& samples) const = 0;

  /// The family of limits a uniform relaxation scales when an infeasible problem is explained
  /// ("velocity", "acceleration", "torque", ...; see TimeScalingProblem::relaxation). Empty: the
  /// constraint is not relaxed.
  virtual std::string family() const { return {}; }

  /// The same constraint with its limit intervals widened by `scale` >= 1 about zero (a bound l <= 0
  /// becomes scale·l, a bound l > 0 becomes l / scale, likewise for upper bounds), so that the
  /// feasible set grows monotonically with the scale; nullptr if the constraint has no such scale.
  virtual std::shared_ptr<const Constraint> relaxed(double /*scale*/) const { return nullptr; }

  /// Every family this constraint takes part in (a contact constraint holds torque limits and friction).
  virtual std::vector<std::string> families() const {
    std::string f = family();
    return f.empty() ? std::vector<std::string>() : std::vector<std::string>{f};
  }
  /// The constraint with only `family`'s limits widened by `scale`; nullptr if it has no such family.
  virtual std::shared_ptr<const Constraint> relaxed(const std::string& family, double scale) const {
    return family == this->family() ? relaxed(scale) : nullptr;
  }
};

/// A limit interval [lo, hi] widened by scale >= 1 about zero (see Constraint::relaxed).
inline double widen_lower(double lo, double scale) { return lo <= 0.0 ? lo * scale : lo / scale; }
inline double widen_upper(double hi, double scale) { return hi >= 0.0 ? hi * scale : hi / scale; }

}  // namespace pathpace
