// PYBIND11_MODULE(_core): the only place the Python module is assembled.
// Each bind_*.cpp binds one area; numpy in and out, the GIL released around long calls.
#include <pybind11/pybind11.h>

#include "pathpace/errors.hpp"

namespace py = pybind11;

namespace pathpace::python {
void bind_paths(py::module_& m);
void bind_constraints(py::module_& m);  // the Constraint base: before any derived constraint
void bind_robot(py::module_& m);
void bind_problem(py::module_& m);
}  // namespace pathpace::python

PYBIND11_MODULE(_core, m) {
  m.doc() = "pathpace C++ core: time-optimal path parameterization";
  // Translators are tried newest first, so the base class is registered before the derived one.
  // InvalidInputError derives from both pathpace.Error and ValueError, so ordinary Python code that
  // catches bad arguments (ValueError) works, as does code that catches everything from pathpace.
  auto error = py::register_exception<pathpace::Error>(m, "Error", PyExc_RuntimeError);
  py::register_exception<pathpace::InvalidInput>(m, "InvalidInputError",
                                                 py::make_tuple(error, py::handle(PyExc_ValueError)));
  pathpace::python::bind_paths(m);
  pathpace::python::bind_constraints(m);
  pathpace::python::bind_robot(m);
  pathpace::python::bind_problem(m);
}
