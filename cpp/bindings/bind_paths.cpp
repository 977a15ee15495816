// Paths: the abstract Path and the three concrete ones.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"
#include "pathpace/sampled_path.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

// p, p' or p'' at scalar or array s: a scalar gives shape (n,), an array (m, n).
py::object eval(const Path& p, py::handle s, int which) {
  const Eigen::VectorXd sv = to_vector(s, "s");
  for (Eigen::Index i = 0; i < sv.size(); ++i)
    if (std::isnan(sv[i])) throw InvalidInput("s[" + std::to_string(i) + "] = nan must be a number");
  Eigen::MatrixXd q, dq, ddq;
  {
    py::gil_scoped_release release;
    p.evaluate(sv, q, dq, ddq);
  }
  const Eigen::MatrixXd& out = which == 0 ? q : (which == 1 ? dq : ddq);
  if (is_scalar(s)) return py::cast(Eigen::VectorXd(out.row(0).transpose()));
  return py::cast(out);
}

SplineBoundary parse_boundary(const std::string& b) {
  if (b == "not-a-knot") return SplineBoundary::NotAKnot;
  if (b == "natural") return SplineBoundary::Natural;
  if (b == "clamped") return SplineBoundary::Clamped;
  throw InvalidInput("boundary = '" + b + "' must be one of 'not-a-knot', 'natural', 'clamped'");
}

Eigen::VectorXd optional_vector(py::handle h, const char* name) {
  return h.is_none() ? Eigen::VectorXd() : to_vector(h, name);
}

}  // namespace

void bind_paths(py::module_& m) {
  py::class_<Path, std::shared_ptr<Path>>(m, "Path", "A geometric path q = p(s), s in [s_begin, s_end].")
      .def_property_readonly("dof", &Path::dof)
      .def_property_readonly("s_begin", &Path::s_begin)
      .def_property_readonly("s_end", &Path::s_end)
      .def("q", [](const Path& p, py::handle s) { return eval(p, s, 0); }, "s"_a, "p(s): (n,) for scalar s, (m, n) for an array")
      .def("dq", [](const Path& p, py::handle s) { return eval(p, s, 1); }, "s"_a, "p'(s)")
      .def("ddq", [](const Path& p, py::handle s) { return eval(p, s, 2); }, "s"_a, "p''(s)")
      .def("evaluate", [](const Path& p, py::handle s) {
        return py::make_tuple(eval(p, s, 0), eval(p, s, 1), eval(p, s, 2));
      }, "s"_a, "(p, p', p'') at s");

  py::class_<PiecewisePolynomialPath, Path, std::shared_ptr<PiecewisePolynomialPath>>(m, "PiecewisePolynomialPath")
      .def(py::init([](py::handle breakpoints, py::handle coefficients) {
             Eigen::VectorXd b = to_vector(breakpoints, "breakpoints");
             auto c = as_float_array(coefficients, "coefficients");
             if (c.ndim() != 3)
               throw InvalidInput("coefficients has shape " + shape_str(c) + ", expected (pieces, degree + 1, n)");
             std::vector<Eigen::MatrixXd> pieces;
             using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
             for (py::ssize_t i = 0; i < c.shape(0); ++i)
               pieces.emplace_back(Eigen::Map<const RowMajor>(c.data() + i * c.shape(1) * c.shape(2), c.shape(1), c.shape(2)));
             return std::make_shared<PiecewisePolynomialPath>(std::move(b), std::move(pieces));
           }),
           "breakpoints"_a, "coefficients"_a,
           "coefficients[i, j, :] multiplies (s - breakpoints[i])**j on piece i")
      .def_property_readonly("breakpoints", &PiecewisePolynomialPath::breakpoints)
      .def("__repr__", [](const PiecewisePolynomialPath& p) {
        return "<PiecewisePolynomialPath pieces=" + std::to_string(p.coefficients().size()) + " dof=" + std::to_string(p.dof()) + ">";
      });

  py::class_<CubicSplinePath, PiecewisePolynomialPath, std::shared_ptr<CubicSplinePath>>(m, "CubicSplinePath")
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
           "end_derivative"_a = py::none(), "s_begin"_a = 0.0, "s_end"_a = 1.0,
           "Cubic spline through waypoints (K, n); boundary as scipy's CubicSpline bc_type.")
      .def_property_readonly("knots", &CubicSplinePath::knots)
      .def_property_readonly("waypoints", &CubicSplinePath::waypoints)
      .def("__repr__", [](const CubicSplinePath& p) {
        return "<CubicSplinePath waypoints=" + std::to_string(p.waypoints().rows()) + " dof=" + std::to_string(p.dof()) + ">";
      });

  py::class_<SampledPath, PiecewisePolynomialPath, std::shared_ptr<SampledPath>>(m, "SampledPath")
      .def(py::init([](py::handle s, py::handle q, py::handle dq, py::handle ddq) {
             return std::make_shared<SampledPath>(to_vector(s, "s"), to_matrix(q, "q", true), to_matrix(dq, "dq", true),
                                                  to_matrix(ddq, "ddq", true));
           }),
           "s"_a, "q"_a, "dq"_a, "ddq"_a, "q, q', q'' given at samples s; quintic Hermite in between.")
      .def_property_readonly("samples", &SampledPath::samples)
      .def("__repr__", [](const SampledPath& p) {
        return "<SampledPath samples=" + std::to_string(p.samples().size()) + " dof=" + std::to_string(p.dof()) + ">";
      });
}

}  // namespace pathpace::python
