#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace pathpace::python {
void bind_paths(py::module_& m) { (void)m; }
}  // namespace pathpace::python
