#pragma once
/// @file time_scaling_problem.hpp
/// The time-scaling problem: a path, a grid, constraints and boundary speeds (sec. V).

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "pathpace/constraints/constraint.hpp"
#include "pathpace/feasible_set.hpp"
#include "pathpace/path.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/result.hpp"
#include "pathpace/solver_options.hpp"

namespace pathpace {

/// Minimise T = Σ 2Δs_k / (ṡ_k + ṡ_{k+1}) (eq. 25, 27) over the speeds at the grid points subject to
/// every constraint's half-planes at every grid point, on both sides of each grid point (eq. 26:
/// s̈ of interval k at s_k and of interval k-1 at s_k).
///
/// Adding constraints mutates the problem; solve() and feasible_set() are const and keep their scratch
/// space local, so one problem may be solved from several threads once it is built.
class TimeScalingProblem {
 public:
  /// N uniform intervals over [s_begin, s_end] of the path (N >= 1).
  TimeScalingProblem(std::shared_ptr<const Path> path, int intervals);
  /// A strictly increasing grid; its ends must be the path's s_begin and s_end (to 1e-12 relative).
  TimeScalingProblem(std::shared_ptr<const Path> path, Eigen::VectorXd grid);

  /// See VelocityLimits.
  void add_velocity_limits(const Eigen::VectorXd& vmin, const Eigen::VectorXd& vmax);
  /// See AccelerationLimits.
  void add_acceleration_limits(const Eigen::VectorXd& amin, const Eigen::VectorXd& amax);
  /// lo <= A·x + B·u + C <= hi at each grid point; arrays of shape (N+1, r). See LinearConstraint.
  void add_linear_constraint(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                             const Eigen::MatrixXd& lo, const Eigen::MatrixXd& hi,
                             const std::string& label = "linear");
  /// Any constraint; its rows are evaluated now, so errors surface here.
  void add_constraint(std::shared_ptr<const Constraint> constraint);

  /// ṡ at s_begin and s_end (default 0, rest to rest). Must be >= 0 and finite.
  void set_boundary_speeds(double sdot_begin, double sdot_end);
  /// The boundary speeds from joint velocities q̇ at s_begin and s_end (rad/s or m/s): q̇ = p'(s) ṡ
  /// (eq. 10), so q̇ must be a non-negative multiple of the path tangent p'; ṡ = p'·q̇ / |p'|². Throws
  /// InvalidInput naming the joint where q̇ is not parallel to p' (relative tolerance `tolerance`).
  void set_boundary_velocities(const Eigen::VectorXd& qd_begin, const Eigen::VectorXd& qd_end,
                               double tolerance = 1e-6);
  double sdot_begin() const { return sdot_begin_; }
  double sdot_end() const { return sdot_end_; }

  const std::shared_ptr<const Path>& path() const { return path_; }
  const Eigen::VectorXd& grid() const { return samples_.s; }
  Eigen::Index intervals() const { return samples_.s.size() - 1; }
  const PathSamples& samples() const { return samples_; }
  const std::vector<std::shared_ptr<const Constraint>>& constraints() const { return constraints_; }

  /// The pruned feasible polygon at grid index k (0 <= k <= N).
  FeasibleSet feasible_set(Eigen::Index k) const;

  Result solve(const SolverOptions& options = SolverOptions()) const;

 private:
  void init_samples();
  std::shared_ptr<const Path> path_;
  PathSamples samples_;
  std::vector<std::shared_ptr<const Constraint>> constraints_;
  std::vector<ConstraintRows> rows_;
  double sdot_begin_ = 0.0, sdot_end_ = 0.0;
};

}  // namespace pathpace
