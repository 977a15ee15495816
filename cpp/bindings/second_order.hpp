#pragma once
// SecondOrderConstraint from Python callables (bind_second_order.cpp), shared with the problem's
// add_torque_limits(inverse_dynamics=...) and add_second_order_constraint (bind_problem.cpp).
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "pathpace/constraints/second_order_constraint.hpp"

namespace pathpace::python {

namespace py = pybind11;

/// tau_min <= inverse_dynamics(q, qd, qdd) <= tau_max (SecondOrderConstraint::torque_limits).
std::shared_ptr<const SecondOrderConstraint> callback_torque_limits(py::handle inverse_dynamics, py::handle tau_min,
                                                                    py::handle tau_max, py::handle scale,
                                                                    py::handle margin, py::handle vectorized,
                                                                    const std::vector<std::string>& joint_names);

/// F(q) inverse_dynamics(q, qd, qdd) <= g(q); F, g callables of q or constant arrays.
std::shared_ptr<const SecondOrderConstraint> callback_second_order(py::handle inverse_dynamics, py::handle F,
                                                                   py::handle g, py::handle name, py::handle labels,
                                                                   py::handle family, py::handle vectorized);

}  // namespace pathpace::python
