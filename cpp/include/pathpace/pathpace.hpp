#pragma once
/// @file pathpace.hpp
/// Umbrella header: everything a user of pathpace needs.

#include "pathpace/constraints/acceleration_limits.hpp"
#include "pathpace/constraints/constraint.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/contact.hpp"
#include "pathpace/constraints/linear_constraint.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/constraints/velocity_limits.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/feasible_set.hpp"
#include "pathpace/path.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"
#include "pathpace/result.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/robot_workspace.hpp"
#include "pathpace/sampled_path.hpp"
#include "pathpace/solver_options.hpp"
#include "pathpace/time_scaling_problem.hpp"
#include "pathpace/trajectory.hpp"
