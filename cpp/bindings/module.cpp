// PYBIND11_MODULE(_core): the only place the Python module is assembled.
// Each bind_*.cpp binds one area; numpy in and out, the GIL released around long calls.
#include <pybind11/pybind11.h>

#include <cstdlib>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "docstrings.hpp"
#include "pathpace/errors.hpp"

namespace py = pybind11;

namespace pathpace::python {
// In this order: a class is bound before the signatures that name it (pybind11 writes its Python name).
void bind_paths(py::module_& m);
void bind_constraint_base(py::module_& m);  // Constraint, PathSamples, ConstraintRows: before any derived constraint
void bind_constraints(py::module_& m);
void bind_robot(py::module_& m);
void bind_torque_limits(py::module_& m);  // bind_constraints.cpp
void bind_second_order(py::module_& m);
void bind_contacts(py::module_& m);
void bind_trajectory(py::module_& m);
void bind_result(py::module_& m);
void bind_problem(py::module_& m);

namespace {

// Every problem and solve allocates and frees a few hundred kB to a few MB of arrays (samples, rows,
// per-interval polygons). glibc hands freed memory at the top of the heap back to the OS as soon as
// more than 128 kB is free there, so the next solve page-faults all of it in again, a large part of a
// fast solve's time (bench/README.md). The Python module therefore asks
// glibc to keep up to 64 MiB of freed heap in the process and to serve allocations below 8 MiB from
// the heap. This is process-wide (it helps every library in the process alike); set
// PATHPACE_NO_MALLOC_TUNING=1 in the environment before importing pathpace to keep glibc's defaults.
bool tune_malloc() {
#if defined(__GLIBC__)
  const char* off = std::getenv("PATHPACE_NO_MALLOC_TUNING");
  if (off && *off && std::string(off) != "0") return false;
  return mallopt(M_MMAP_THRESHOLD, 8 << 20) == 1 && mallopt(M_TRIM_THRESHOLD, 64 << 20) == 1 &&
         mallopt(M_TOP_PAD, 8 << 20) == 1;
#else
  return false;
#endif
}

}  // namespace
}  // namespace pathpace::python

PYBIND11_MODULE(_core, m) {
  m.doc() = "pathpace C++ core: time-optimal path parameterization";
  // Translators are tried newest first, so the base class is registered before the derived one.
  // InvalidInputError derives from both pathpace.Error and ValueError, so ordinary Python code that
  // catches bad arguments (ValueError) works, as does code that catches everything from pathpace.
  auto error = py::register_exception<pathpace::Error>(m, "Error", PyExc_RuntimeError);
  auto invalid = py::register_exception<pathpace::InvalidInput>(m, "InvalidInputError",
                                                                py::make_tuple(error, py::handle(PyExc_ValueError)));
  // Exception types are made by register_exception, which takes no docstring.
  error.attr("__doc__") = pathpace::python::doc::Error;
  invalid.attr("__doc__") = pathpace::python::doc::InvalidInputError;
  pathpace::python::bind_paths(m);
  pathpace::python::bind_constraint_base(m);
  pathpace::python::bind_constraints(m);
  pathpace::python::bind_robot(m);
  pathpace::python::bind_torque_limits(m);
  pathpace::python::bind_second_order(m);
  pathpace::python::bind_contacts(m);
  pathpace::python::bind_trajectory(m);
  pathpace::python::bind_result(m);
  pathpace::python::bind_problem(m);
  m.attr("malloc_tuned") = pathpace::python::tune_malloc();
}
