#pragma once
/// @file constraint.hpp
/// A constraint on the timing, written at each grid point as half-planes a·x + b·u <= c in
/// x = ṡ² and u = s̈ (the paper's eq. 9).

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/path_samples.hpp"

namespace pathpace {

class RobotModel;
struct Result;

/// LPs of contact projections (sec. IV.C) by cause: the initial directions (a triangle), edge LPs that
/// found a new vertex (or failed), edge LPs that certified an edge, feasibility LPs that grew the stand-in
/// bounds, and every LP of a grid point projected once more from a cold start.
/// Beside them (not LPs of their own): edges certified by an endpoint's basis without an LP (ranged), LPs
/// solved by the dense simplex and those it gave back to GLPK (dense, dense_fallback), and the simplex
/// iterations of all of them (pivots). The dense simplex's fallbacks by cause: its pivot cap, a step
/// bounded only by pivots below its tolerance, an unbounded ray, a singular refactorisation, a failed
/// certificate (they add up to dense_fallback).
struct LpCounts {
  int initial = 0, vertex = 0, certificate = 0, cap_growth = 0, cold_retry = 0;
  int ranged = 0, dense = 0, dense_fallback = 0, pivots = 0;
  int fallback_cap = 0, fallback_small_pivot = 0, fallback_unbounded = 0, fallback_singular = 0;
  int fallback_certificate = 0;
  LpCounts& operator+=(const LpCounts& o) {
    initial += o.initial, vertex += o.vertex, certificate += o.certificate, cap_growth += o.cap_growth;
    cold_retry += o.cold_retry;
    ranged += o.ranged, dense += o.dense, dense_fallback += o.dense_fallback, pivots += o.pivots;
    fallback_cap += o.fallback_cap, fallback_small_pivot += o.fallback_small_pivot;
    fallback_unbounded += o.fallback_unbounded, fallback_singular += o.fallback_singular;
    fallback_certificate += o.fallback_certificate;
    return *this;
  }
};

// docstrings.txt @@ ConstraintRows
/// @brief Half-planes a·x + b·u <= c (x = ṡ², u = s̈) at every grid point: what Constraint.evaluate returns.
///
/// Row j at grid point k reads a(k, j)·x + b(k, j)·u <= c(k, j). A row with c = +inf is inactive at that
/// grid point (a limit that is absent, or padding when the number of half-planes varies along the path).
/// labels[j] names row j for infeasibility reports, e.g. "acceleration joint 3 upper".
struct ConstraintRows {
  /// Row-major: the r rows of one grid point are contiguous, as the per-point polygons read them.
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // docstrings.txt @@ ConstraintRows.a
  /// (N+1, r): Coefficients of x.
  Matrix a;
  // docstrings.txt @@ ConstraintRows.b
  /// (N+1, r): Coefficients of u.
  Matrix b;
  // docstrings.txt @@ ConstraintRows.c
  /// (N+1, r): Right-hand sides; +inf: inactive.
  Matrix c;
  // docstrings.txt @@ ConstraintRows.labels
  /// r names, one per row.
  std::vector<std::string> labels;
  /// Grid points where the rows are only an inner approximation of the constraint (a projection whose
  /// LP failed or ran out of budget, sec. IV.C); empty when they are exact.
  std::vector<Eigen::Index> inexact_points;
  /// True when no entry can be bad by construction (a and b finite, c a number or +inf), as in the
  /// library's velocity and acceleration limits, built from finite samples and validated limits: the
  /// problem then skips its scan of the entries (a cost on the order of the rows' own). A constraint of your own
  /// leaves it false, and its rows are checked; one that edits the rows another's evaluate() returned
  /// (a subclass of VelocityLimits, say) must set it false again.
  bool valid_by_construction = false;
  /// A refines() constraint's own state at each grid point after evaluate(), where its refine() goes on from
  /// (meaningful only to that constraint; empty for any other, or where it kept none).
  std::vector<std::shared_ptr<const void>> refine_state;
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
  // docstrings.txt @@ ConstraintRows.rows
  /// r.
  Eigen::Index rows() const { return a.cols(); }
};

/// Joint limits that a constraint bounds between grid points by construction under guarantee = continuous
/// (docs/method.md): order 1 bounds q̇ = p' ṡ, order 2 bounds q̈ = p' s̈ + p'' ṡ², both per joint in [lo, hi];
/// order 0 (none) leaves the constraint to the audit, which samples its rows between grid points.
struct JointRateLimits {
  int order = 0;
  Eigen::VectorXd lo, hi;
};

/// An exact check of one grid point on a constraint's full polytope (Constraint::check_point): feasible and
/// rest_feasible ((x, u) = (0, 0)) are 1 yes, 0 no (confirmed in exact arithmetic), -1 unknown (the solver
/// failed, or the constraint has no such check).
struct PointCheck {
  int feasible = -1;
  int rest_feasible = -1;
};

/// The edges of a projected constraint's polygon at the ends of its slices (Constraint::slice): per sample
/// p, x_hi(t) = x_hi[p] + hi_slope[p] (t - u[p]) exactly for every s̈ t in [hi_from[p], hi_to[p]] (the
/// end's LP keeps its optimal basis there), and x_hi(t) <= that line for every t (x_hi is concave in t);
/// likewise x_lo with >= (convex). from = to = u[p] where that end is not known (no LP, or an empty
/// slice). With `labels` asked, *_label[p] names what binds each end, as the constraint's rows are named.
struct SliceEdges {
  bool labels = false;
  Eigen::VectorXd lo_slope, lo_from, lo_to, hi_slope, hi_from, hi_to;
  std::vector<std::string> lo_label, hi_label;
};

/// Warm starts of a projected constraint's slice LPs across calls (Constraint::slice): per sample p and end
/// (0 the top, 1 the bottom), start[end][p] (in, if sized to the samples) is an optimal basis that an earlier
/// call found at a nearby sample, empty for none, and found[end][p] (out) the optimal basis of this one's LP,
/// empty where that end had no LP or the LP failed. A basis is the constraint's own code, meaningful only to
/// the constraint that wrote it; a start that does not fit is ignored. glpk_lps (out): how many of the
/// call's LPs the general solver answered (a first sample, or one the warm-started simplex gave up on).
struct SliceStarts {
  std::vector<std::vector<signed char>> start[2], found[2];
  int glpk_lps = 0;
};

/// What a constraint whose rows are refined on demand (Constraint::refine) keeps between the rounds of one
/// solve, per grid point: its own code, meaningful only to the constraint that wrote it.
struct RefineMemory {
  /// [grid point]: the (x, u) points of earlier timings the rows were refined towards.
  std::vector<std::vector<std::array<double, 2>>> focus;
  /// [grid point]: the inner polygon's edges, rows (a, b, c, certified: 1 or 0); none: not refined yet.
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 4>> hull;
  /// [grid point]: the distance beyond an uncertified edge that still counts as inside.
  std::vector<double> tolerance;
  /// [grid point]: whatever else the constraint keeps there (a contact polygon: where its expansion stopped).
  std::vector<std::shared_ptr<void>> state;
  int lp_solves = 0;     ///< their LPs
  LpCounts lp_by_cause;  ///< the same LPs by cause
};

// docstrings.txt @@ Constraint
/// @brief Base of all constraints: half-planes a·x + b·u <= c per grid point, x = ṡ², u = s̈ (eq. 9).
///
/// Implementations are immutable after construction, so one instance can serve several problems and
/// threads; evaluate keeps its scratch space local.
///
/// Besides its rows, a constraint tells the problem what the problem needs to know of it through the hooks
/// below (merging, renaming, grid changes, the continuous guarantee, what a Result shows). Their defaults fit
/// a constraint whose rows are a function of the path at s alone, which is all a new family has to be; the
/// problem never asks for a concrete type (docs/architecture.md: where a new constraint family goes).
class Constraint {
 public:
  virtual ~Constraint() = default;

  // docstrings.txt @@ Constraint.name
  /// A short name for messages and infeasibility reports, e.g. "velocity limits".
  virtual std::string name() const = 0;

  // docstrings.txt @@ Constraint.evaluate
  /// @brief The rows at every grid point of samples.
  ///
  /// @param samples The path at the grid points.
  /// @return The half-planes.
  /// @throws InvalidInput When the constraint does not fit the path (e.g. a dimension mismatch), naming what does not
  ///   fit.
  virtual ConstraintRows evaluate(const PathSamples& samples) const = 0;

  // docstrings.txt @@ Constraint.family
  /// @brief The family of limits relaxation() scales ("velocity", "acceleration", "torque", ...); "" for none.
  ///
  /// Used when an infeasible problem is explained (see TimeScalingProblem.relaxation); a constraint of no
  /// family is not relaxed.
  virtual std::string family() const { return {}; }

  // docstrings.txt @@ Constraint.relaxed
  /// @brief The constraint with its limits widened by scale >= 1 about zero, or None (C++: nullptr) if it has no
  /// such scale.
  ///
  /// A bound l <= 0 becomes scale·l, a bound l > 0 becomes l / scale, likewise for upper bounds, so that the
  /// feasible set grows monotonically with the scale.
  ///
  /// @param scale >= 1; the feasible set must grow with it.
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

  // ---- hooks: what the problem asks of a constraint

  /// The robot whose dynamics the rows use, or nullptr. A problem without joint names takes the robot's
  /// when it has one joint per path coordinate.
  virtual std::shared_ptr<const RobotModel> robot() const { return nullptr; }

  /// True if this constraint can hold `other`'s limits in its own projection, as a contact constraint
  /// holds its robot's torque limits (eq. 17-18: alone, torque limits would demand τ = 0 of an unactuated
  /// base that only contact forces hold). The problem then keeps absorb(other) in place of both.
  virtual bool can_absorb(const Constraint& /*other*/) const { return false; }
  /// This constraint with `other`'s limits joined (only called when can_absorb(other)).
  virtual std::shared_ptr<const Constraint> absorb(const Constraint& other) const;

  // docstrings.txt @@ Constraint.with_joint_names
  /// @brief The constraint labelled with the problem's joint names, or None (C++: nullptr) if its labels do not
  /// come from them.
  ///
  /// For one that takes its labels from them and has none yet (limits added before set_joint_names). Only
  /// its labels may differ: the problem keeps its rows.
  ///
  /// @param names One per path coordinate.
  virtual std::shared_ptr<const Constraint> with_joint_names(const std::vector<std::string>& /*names*/) const {
    return nullptr;
  }

  // docstrings.txt @@ Constraint.per_grid_point
  /// @brief True if the rows are data given per grid point, with no value between grid points (LinearConstraint):
  /// the grid then gains no point (contact switches) and a restart begins at a grid point.
  virtual bool per_grid_point() const { return false; }
  // docstrings.txt @@ Constraint.at_grid_points
  /// @brief A per_grid_point() constraint's rows at the old grid points `kept` (the new grid of a restart).
  ///
  /// Any other constraint is evaluated again on the new grid and is never asked.
  ///
  /// @param kept Old grid indices, in order, each >= 0.
  virtual std::shared_ptr<const Constraint> at_grid_points(const std::vector<Eigen::Index>& kept) const;

  /// The joint limits guarantee = continuous bounds between grid points by construction (JointRateLimits).
  virtual JointRateLimits joint_rate_limits() const { return {}; }

  /// For guarantee = continuous: upper bounds on x = ṡ² at the grid points of `samples` (N+1 entries, +inf
  /// where none; `rows` are this constraint's rows there, as evaluate() gave them, empty if the problem has
  /// none) under which this constraint's rows also hold between grid points, up to a model error of
  /// the constraint's choosing; empty (the default) for none. The problem adds them as rows x <= bound, and
  /// still audits the constraint (joint_rate_limits order 0), so the bounds need not be rigorous: they spare
  /// the audit its rounds of cuts where the rows bind along a stretch (FrameLimits' speed rows).
  virtual Eigen::VectorXd speed_bounds_between_grid_points(const PathSamples& /*samples*/,
                                                           const ConstraintRows& /*rows*/) const {
    return {};
  }

  /// True if the rows are a projection of a polytope in more variables (contact forces, sec. IV.C). Its
  /// evaluation time counts as projection time, an infeasibility at a point is re-checked on the full
  /// polytope (check_point), and guarantee = continuous audits it by slices of the polytope (slice).
  virtual bool projected() const { return false; }
  /// False where the constraint does not hold (a contact phase outside its stretch of s).
  virtual bool active_at(double /*s*/) const { return true; }
  /// One LP on the full polytope at grid point k of `samples`, intersected with `extra` half-planes
  /// a x + b u <= c (rows [a, b, c]: the other constraints there), before an infeasibility is reported.
  virtual PointCheck check_point(const PathSamples& /*samples*/, Eigen::Index /*k*/,
                                 const Eigen::Matrix<double, Eigen::Dynamic, 3>& /*extra*/) const {
    return {};
  }
  /// For a projected() constraint: per sample p, the smallest and largest x with (x, u[p]) feasible at
  /// samples.s[p], without projecting; returns the LPs spent (see ContactConstraint::slice). With `x`
  /// (one per sample), x_lo[p] is left at -inf, without its LP, where x[p] > x_hi[p]: x's distance
  /// beyond the slice is then x[p] - x_hi[p], whatever x_lo[p] is. With `edges`, also the polygon's
  /// edges through the slice's ends (SliceEdges); with `starts`, its LPs' warm starts (SliceStarts).
  virtual int slice(const PathSamples& samples, const Eigen::VectorXd& u, Eigen::VectorXd& x_lo,
                    Eigen::VectorXd& x_hi, const Eigen::VectorXd* x = nullptr, SliceEdges* edges = nullptr,
                    SliceStarts* starts = nullptr) const;
  /// For a projected() constraint: the stand-in bound on x where nothing else bounds it (its polygons are
  /// cut there; slice reports +inf instead).
  virtual double projection_cap() const { return std::numeric_limits<double>::infinity(); }
  /// True if the rows bound the constraint from outside only, until refine() tightens them where a timing
  /// needs it (ContactOptions::project_on_demand): the problem's solve then refines them round by round.
  virtual bool refines() const { return false; }
  /// For a refines() constraint: tightens `rows` (as evaluate() or an earlier call left them) at every grid
  /// point where the timing θ (ṡ² at the grid points) is not known to satisfy the constraint, with both
  /// adjacent s̈ there (constant on each interval, eq. 24), or with `sddot` (s̈ at the grid points, a
  /// jerk-limited timing) that one. Returns the number of grid points changed (0: the timing satisfies the
  /// constraint at every grid point).
  virtual int refine(const PathSamples& /*samples*/, const Eigen::VectorXd& /*theta*/, const Eigen::VectorXd* /*sddot*/,
                     ConstraintRows& /*rows*/, RefineMemory& /*memory*/) const {
    return 0;
  }
  /// For a refines() constraint: the same constraint with exact rows at every grid point (what
  /// TimeScalingProblem::relaxation needs); nullptr for any other.
  virtual std::shared_ptr<const Constraint> exact() const { return nullptr; }

  /// Fills what a Result shows of this constraint (Result::robot, tau_min/tau_max, contacts, contact_phases).
  /// The problem calls it for its constraints in order; `torque_rank` records who set tau_min/tau_max: 2 a
  /// constraint's own torque limits, 1 limits held besides others (a contact constraint's), 0 nobody. Own
  /// limits are shown over held ones, and the last of a rank wins.
  virtual void report(Result& /*result*/, int& /*torque_rank*/) const {}
};

/// A limit interval [lo, hi] widened by scale >= 1 about zero (see Constraint::relaxed).
inline double widen_lower(double lo, double scale) { return lo <= 0.0 ? lo * scale : lo / scale; }
inline double widen_upper(double hi, double scale) { return hi >= 0.0 ? hi * scale : hi / scale; }

}  // namespace pathpace
