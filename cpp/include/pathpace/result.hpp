#pragma once
/// @file result.hpp
/// What a solve returns: a status, the timing at the grid points and where a failure happened.

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pathpace/path.hpp"

namespace pathpace {

class Trajectory;
class RobotModel;
class ContactConstraint;

enum class Status {
  Optimal,         ///< the optimum of the discretised problem (eq. 26-27)
  Infeasible,      ///< no timing satisfies the constraints; see Result::infeasibility
  IterationLimit,  ///< SLP stopped at max_iterations; the timing is feasible but maybe not optimal
  NumericalError,  ///< the LP solver failed; the timing (if any) is the last feasible one
  Unbounded,       ///< nothing bounds the speed somewhere along the path (T would be 0)
};

const char* to_string(Status status);

/// Where and why a path cannot be timed.
struct Infeasibility {
  Eigen::Index grid_index = -1;                        ///< first grid index where it fails
  double s = std::numeric_limits<double>::quiet_NaN();  ///< s at that index
  std::vector<std::string> constraints;                 ///< the constraint rows that bind there
};

struct SolverStats {
  int slp_iterations = 0;
  int lp_solves = 0;
  bool greatest_element = false;  ///< the optimum is a max-closed set's greatest element (exact, no SLP)
  double gap = 0.0;               ///< certified bound on (T - T*) / T* (0 when exact)
  double average_halfplanes = 0;  ///< supporting half-planes per grid point after pruning
  double time_constraints = 0;    ///< seconds: path samples and constraint rows
  double time_feasible_sets = 0;  ///< seconds: polygons and pruning
  double time_reachability = 0;   ///< seconds: controllable sets and forward pass
  double time_slp = 0;            ///< seconds
  /// Contact polygons (sec. IV.C): computed when the contacts were added (add_constraint), reported here.
  double time_projection = 0;     ///< seconds, included in time_constraints
  int projection_lp_solves = 0;   ///< LPs of the projection
  int inexact_points = 0;         ///< grid points whose polygon is only an inner approximation (see FeasibleSet::exact)
};

class Result {
 public:
  Status status = Status::NumericalError;
  std::string message;
  double duration = std::numeric_limits<double>::quiet_NaN();  ///< T
  Eigen::VectorXd s;      ///< grid s_0..s_N
  Eigen::VectorXd sdot;   ///< ṡ_k (N+1)
  Eigen::VectorXd times;  ///< t_k (N+1), t_0 = 0
  Eigen::VectorXd sddot;  ///< s̈ on interval k (N)
  Infeasibility infeasibility;
  SolverStats stats;
  std::shared_ptr<const Path> path;
  std::shared_ptr<const RobotModel> robot;  ///< from the problem's torque limits or contacts, if any
  std::shared_ptr<const ContactConstraint> contacts;  ///< the problem's contact constraint, if any

  /// True for Optimal (and for IterationLimit, whose timing is feasible).
  bool ok() const { return status == Status::Optimal || status == Status::IterationLimit; }
  /// The timed trajectory; throws pathpace::Error if there is no timing (e.g. infeasible).
  Trajectory trajectory() const;
};

}  // namespace pathpace
