// Paths: the abstract Path and the three concrete ones.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/auto_grid.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"
#include "pathpace/sampled_path.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

// p, p' or p'' at scalar or array s: a scalar gives shape (n,), an array (m, n).
py::object eval(const Path& p, py::handle s, int which) { return evaluate_at(p, s, to_path_parameters(s, "s"), which); }

SplineBoundary parse_boundary(const std::string& b) {
  if (b == "not-a-knot") return SplineBoundary::NotAKnot;
  if (b == "natural") return SplineBoundary::Natural;
  if (b == "clamped") return SplineBoundary::Clamped;
  throw InvalidInput("boundary = '" + b + "' must be one of 'not-a-knot', 'natural', 'clamped'");
}

const char* boundary_name(SplineBoundary b) {
  switch (b) {
    case SplineBoundary::NotAKnot: return "not-a-knot";
    case SplineBoundary::Natural: return "natural";
    case SplineBoundary::Clamped: return "clamped";
  }
  return "not-a-knot";
}

// Pickle state of a piecewise polynomial: (breakpoints, coefficients (pieces, degree + 1, n)).
py::tuple polynomial_state(const PiecewisePolynomialPath& p) {
  const auto& c = p.coefficients();
  const py::ssize_t pieces = static_cast<py::ssize_t>(c.size()), rows = c.empty() ? 0 : c[0].rows(),
                    cols = c.empty() ? 0 : c[0].cols();
  py::array_t<double> out({pieces, rows, cols});
  auto o = out.mutable_unchecked<3>();
  for (py::ssize_t i = 0; i < pieces; ++i)
    for (py::ssize_t j = 0; j < rows; ++j)
      for (py::ssize_t k = 0; k < cols; ++k) o(i, j, k) = c[static_cast<size_t>(i)](j, k);
  return py::make_tuple(p.breakpoints(), out);
}

std::vector<Eigen::MatrixXd> polynomial_pieces(py::handle coefficients) {
  auto c = as_float_array(coefficients, "coefficients");
  if (c.ndim() != 3) throw InvalidInput("coefficients has shape " + shape_str(c) + ", expected (pieces, degree + 1, n)");
  std::vector<Eigen::MatrixXd> pieces;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  for (py::ssize_t i = 0; i < c.shape(0); ++i)
    pieces.emplace_back(Eigen::Map<const RowMajor>(c.data() + i * c.shape(1) * c.shape(2), c.shape(1), c.shape(2)));
  return pieces;
}

void bind_path(py::module_& m) {
  py::class_<Path, std::shared_ptr<Path>>(m, "Path", doc::Path)
      .def_property_readonly("dof", &Path::dof, doc::Path_dof)
      .def_property_readonly("s_begin", &Path::s_begin, doc::Path_s_begin)
      .def_property_readonly("s_end", &Path::s_end, doc::Path_s_end)
      .def("q", [](const Path& p, py::handle s) { return eval(p, s, 0); }, "s"_a, doc::Path_q)
      .def("dq", [](const Path& p, py::handle s) { return eval(p, s, 1); }, "s"_a, doc::Path_dq)
      .def("ddq", [](const Path& p, py::handle s) { return eval(p, s, 2); }, "s"_a, doc::Path_ddq)
      .def("evaluate", [](const Path& p, py::handle s) {
        return py::make_tuple(eval(p, s, 0), eval(p, s, 1), eval(p, s, 2));
      }, "s"_a, doc::Path_evaluate);
}

void bind_piecewise_polynomial_path(py::module_& m) {
  py::class_<PiecewisePolynomialPath, Path, std::shared_ptr<PiecewisePolynomialPath>>(m, "PiecewisePolynomialPath",
                                                                                      doc::PiecewisePolynomialPath)
      .def(py::init([](py::handle breakpoints, py::handle coefficients) {
             Eigen::VectorXd b = to_vector(breakpoints, "breakpoints");
             return std::make_shared<PiecewisePolynomialPath>(std::move(b), polynomial_pieces(coefficients));
           }),
           "breakpoints"_a, "coefficients"_a)
      .def_property_readonly("breakpoints", &PiecewisePolynomialPath::breakpoints, doc::PiecewisePolynomialPath_breakpoints)
      .def(py::pickle([](const PiecewisePolynomialPath& p) { return polynomial_state(p); },
                      [](const py::tuple& t) {
                        check_state(t, 2, "PiecewisePolynomialPath");
                        return std::make_shared<PiecewisePolynomialPath>(to_vector(t[0], "breakpoints"),
                                                                         polynomial_pieces(t[1]));
                      }))
      .def("__repr__", [](const PiecewisePolynomialPath& p) {
        return "<PiecewisePolynomialPath pieces=" + std::to_string(p.coefficients().size()) + " dof=" + std::to_string(p.dof()) + ">";
      });
}

void bind_cubic_spline_path(py::module_& m) {
  py::class_<CubicSplinePath, PiecewisePolynomialPath, std::shared_ptr<CubicSplinePath>>(m, "CubicSplinePath", doc::CubicSplinePath)
      .def(py::init([](py::handle waypoints, py::object knots, py::handle boundary, py::handle start_derivative,
                       py::handle end_derivative, py::handle s_begin_arg, py::handle s_end_arg) {
             const Eigen::MatrixXd w = to_matrix(waypoints, "waypoints");
             const SplineBoundary b = parse_boundary(to_string_arg(boundary, "boundary"));
             const double s_begin = to_double(s_begin_arg, "s_begin"), s_end = to_double(s_end_arg, "s_end");
             const Eigen::VectorXd d0 = optional_vector(start_derivative, "start_derivative");
             const Eigen::VectorXd d1 = optional_vector(end_derivative, "end_derivative");
             if (py::isinstance<py::str>(knots)) {
               const std::string k = knots.cast<std::string>();
               KnotSpacing spacing;
               if (k == "uniform") spacing = KnotSpacing::Uniform;
               else if (k == "chord") spacing = KnotSpacing::ChordLength;
               else throw InvalidInput("knots = '" + k + "' must be 'uniform', 'chord' or an array of s");
               return std::make_shared<CubicSplinePath>(w, spacing, b, s_begin, s_end, d0, d1);
             }
             if (knots.is_none()) type_error("knots", "'uniform', 'chord' or an array of s", knots);
             return std::make_shared<CubicSplinePath>(w, to_vector(knots, "knots"), b, d0, d1);
           }),
           "waypoints"_a, "knots"_a = "uniform", "boundary"_a = "not-a-knot", "start_derivative"_a = py::none(),
           "end_derivative"_a = py::none(), "s_begin"_a = 0.0, "s_end"_a = 1.0)
      .def_property_readonly("knots", &CubicSplinePath::knots, doc::CubicSplinePath_knots)
      .def_property_readonly("waypoints", &CubicSplinePath::waypoints, doc::CubicSplinePath_waypoints)
      .def_property_readonly("boundary", [](const CubicSplinePath& p) { return boundary_name(p.boundary()); },
                             doc::CubicSplinePath_boundary)
      .def_property_readonly("start_derivative", [](const CubicSplinePath& p) -> py::object {
        return p.start_derivative().size() ? py::cast(p.start_derivative()) : py::object(py::none());
      }, doc::CubicSplinePath_start_derivative)
      .def_property_readonly("end_derivative", [](const CubicSplinePath& p) -> py::object {
        return p.end_derivative().size() ? py::cast(p.end_derivative()) : py::object(py::none());
      }, doc::CubicSplinePath_end_derivative)
      // Rebuilt from its constructor arguments (waypoints, knots, boundary, end slopes): the same
      // deterministic computation gives the same coefficients.
      .def(py::pickle([](const CubicSplinePath& p) {
                        return py::make_tuple(p.waypoints(), p.knots(), boundary_name(p.boundary()),
                                              p.start_derivative(), p.end_derivative());
                      },
                      [](const py::tuple& t) {
                        check_state(t, 5, "CubicSplinePath");
                        const SplineBoundary b = parse_boundary(t[2].cast<std::string>());
                        Eigen::VectorXd d0 = to_vector(t[3], "start_derivative"), d1 = to_vector(t[4], "end_derivative");
                        return std::make_shared<CubicSplinePath>(to_matrix(t[0], "waypoints"), to_vector(t[1], "knots"), b,
                                                                 d0, d1);
                      }))
      .def("__repr__", [](const CubicSplinePath& p) {
        return "<CubicSplinePath waypoints=" + std::to_string(p.waypoints().rows()) + " dof=" + std::to_string(p.dof()) + ">";
      });
}

void bind_sampled_path(py::module_& m) {
  py::class_<SampledPath, PiecewisePolynomialPath, std::shared_ptr<SampledPath>>(m, "SampledPath", doc::SampledPath)
      .def(py::init([](py::handle s, py::handle q, py::handle dq, py::handle ddq) {
             return std::make_shared<SampledPath>(to_vector(s, "s"), to_matrix(q, "q", true), to_matrix(dq, "dq", true),
                                                  to_matrix(ddq, "ddq", true));
           }),
           "s"_a, "q"_a, "dq"_a, "ddq"_a)
      .def_property_readonly("samples", &SampledPath::samples, doc::SampledPath_samples)
      // Rebuilt from (s, q, q', q'') at its samples; the quintic Hermite pieces reproduce them exactly.
      .def(py::pickle([](const SampledPath& p) {
                        Eigen::MatrixXd q, dq, ddq;
                        p.evaluate(p.samples(), q, dq, ddq);
                        return py::make_tuple(p.samples(), q, dq, ddq);
                      },
                      [](const py::tuple& t) {
                        check_state(t, 4, "SampledPath");
                        return std::make_shared<SampledPath>(to_vector(t[0], "s"), to_matrix(t[1], "q"),
                                                             to_matrix(t[2], "dq"), to_matrix(t[3], "ddq"));
                      }))
      .def("__repr__", [](const SampledPath& p) {
        return "<SampledPath samples=" + std::to_string(p.samples().size()) + " dof=" + std::to_string(p.dof()) + ">";
      });
}

}  // namespace

void bind_paths(py::module_& m) {
  bind_path(m);
  bind_piecewise_polynomial_path(m);
  bind_cubic_spline_path(m);
  bind_sampled_path(m);
  m.def("auto_grid", [](py::handle path_arg, py::handle tolerance, py::handle min_intervals, py::handle max_intervals) {
    const auto path = to_object<Path>(path_arg, "path", "Path");
    const double tol = to_double(tolerance, "tolerance");
    const int lo = to_int32(min_intervals, "min_intervals"), hi = to_int32(max_intervals, "max_intervals");
    py::gil_scoped_release release;
    return auto_grid(*path, tol, lo, hi);
  }, "path"_a, "tolerance"_a = 1e-3, "min_intervals"_a = 16, "max_intervals"_a = 1000000, doc::auto_grid);
}

}  // namespace pathpace::python
