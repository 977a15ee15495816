// Paths: the abstract Path (open to Python subclasses through a trampoline) and the three concrete ones. All
// use py::smart_holder, which keeps a Python subclass alive while C++ holds it (as for Constraint).
#include <cmath>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "common.hpp"
#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/auto_grid.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/piecewise_polynomial_path.hpp"
#include "pathpace/sampled_path.hpp"
#include "paths/sub_path.hpp"

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

// A Path whose dof, s_begin, s_end and evaluate are Python (pathpace.paths.CallbackPath, InterpolatorPath, a
// user's subclass). C++ calls it from any thread, with or without the GIL (solve and auto_grid release it):
// each call takes it. Python sees s clamped to the domain, once per batch; what comes back is checked
// (three arrays (m, dof), finite) so that a wrong callback is an InvalidInput naming it, not wrong rows.
// Exceptions raised in Python come back as they were (error_already_set).
class PyPath : public Path, public py::trampoline_self_life_support {
 public:
  int dof() const override {
    py::gil_scoped_acquire gil;
    return static_cast<int>(to_int(attribute("dof"), class_name() + ".dof", 1, 1 << 20));
  }
  double s_begin() const override {
    py::gil_scoped_acquire gil;
    return to_double(attribute("s_begin"), class_name() + ".s_begin");
  }
  double s_end() const override {
    py::gil_scoped_acquire gil;
    return to_double(attribute("s_end"), class_name() + ".s_end");
  }

  void evaluate(double s, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> dq,
                Eigen::Ref<Eigen::VectorXd> ddq) const override {
    Eigen::MatrixXd mq, mdq, mddq;
    evaluate(Eigen::VectorXd::Constant(1, s), mq, mdq, mddq);
    q = mq.row(0).transpose();
    dq = mdq.row(0).transpose();
    ddq = mddq.row(0).transpose();
  }

  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& s, Eigen::MatrixXd& q, Eigen::MatrixXd& dq,
                Eigen::MatrixXd& ddq) const override {
    py::gil_scoped_acquire gil;
    py::function f = py::get_override(static_cast<const Path*>(this), "evaluate");
    if (!f) throw Error("a Python subclass of pathpace.Path must define evaluate(s)");
    const double a = s_begin(), b = s_end();
    const Eigen::Index n = dof();
    const Eigen::VectorXd x = s.cwiseMax(a).cwiseMin(b);
    py::object r = f(py::array_t<double>(x.size(), x.data()));
    const std::string what = class_name() + ".evaluate(s)";
    if (!py::isinstance<py::tuple>(r) && !py::isinstance<py::list>(r)) type_error(what, "a tuple (q, dq, ddq)", r);
    py::sequence seq = py::reinterpret_borrow<py::sequence>(r);
    if (seq.size() != 3)
      throw InvalidInput(what + " returned " + std::to_string(seq.size()) + " items, expected 3 (q, dq, ddq)");
    q = checked(seq[0], what + "[0] (q)", x, n);
    dq = checked(seq[1], what + "[1] (dq)", x, n);
    ddq = checked(seq[2], what + "[2] (ddq)", x, n);
  }

 private:
  py::handle self() const {
    return py::detail::get_object_handle(static_cast<const Path*>(this), py::detail::get_type_info(typeid(Path)));
  }
  std::string class_name() const { return type_name(self()); }

  // `name` may be a property, a plain attribute or a method of the Python class; Path's own (abstract) is not.
  py::object attribute(const char* name) const {
    py::handle me = self();
    py::object base = py::type::of<Path>().attr("__dict__")[name];
    if (py::getattr(py::type::handle_of(me), name).is(base))
      throw Error("a Python subclass of pathpace.Path must define " + std::string(name));
    py::object v = py::getattr(me, name);
    return PyCallable_Check(v.ptr()) ? v() : v;
  }

  // One of q, dq, ddq: (m, n) (or (m,) when n = 1), every entry finite.
  static Eigen::MatrixXd checked(py::handle h, const std::string& what, const Eigen::VectorXd& s, Eigen::Index n) {
    Eigen::MatrixXd v = to_matrix(h, what, n == 1);
    if (v.rows() != s.size() || v.cols() != n)
      throw InvalidInput(what + " has shape (" + std::to_string(v.rows()) + ", " + std::to_string(v.cols()) + ") for " +
                         std::to_string(s.size()) + " values of s, expected (" + std::to_string(s.size()) + ", " +
                         std::to_string(n) + ")");
    for (Eigen::Index i = 0; i < v.rows(); ++i)
      for (Eigen::Index j = 0; j < n; ++j)
        if (!std::isfinite(v(i, j)))
          throw InvalidInput(what + "[" + std::to_string(i) + ", " + std::to_string(j) + "] = " +
                             py::repr(py::float_(v(i, j))).cast<std::string>() + " at s = " +
                             py::repr(py::float_(s[i])).cast<std::string>() + " must be finite");
    return v;
  }
};

void bind_path(py::module_& m) {
  py::class_<Path, PyPath, py::smart_holder>(m, "Path", doc::Path)
      .def(py::init<>())
      .def_property_readonly("dof", &Path::dof, doc::Path_dof)
      .def_property_readonly("s_begin", &Path::s_begin, doc::Path_s_begin)
      .def_property_readonly("s_end", &Path::s_end, doc::Path_s_end)
      .def("q", [](const Path& p, py::handle s) { return eval(p, s, 0); }, "s"_a, doc::Path_q)
      .def("dq", [](const Path& p, py::handle s) { return eval(p, s, 1); }, "s"_a, doc::Path_dq)
      .def("ddq", [](const Path& p, py::handle s) { return eval(p, s, 2); }, "s"_a, doc::Path_ddq)
      .def("evaluate", [](const Path& p, py::handle s) {
        return py::make_tuple(eval(p, s, 0), eval(p, s, 1), eval(p, s, 2));
      }, "s"_a, doc::Path_evaluate)
      .def("__call__", [](const Path& p, py::handle s, py::handle order) {
        const int k = static_cast<int>(to_int(order, "order", 0, 2));
        return eval(p, s, k);
      }, "s"_a, "order"_a = 0, doc::Path_call_)
      // The concrete paths pickle by their own state (py::pickle overrides this), CallbackPath and
      // InterpolatorPath by __reduce__. A user's subclass without either would get Python's "cannot pickle
      // 'X' object", which says neither what nor how: this names the class and the two ways out.
      .def("__getstate__", [](py::handle self) -> py::object {
        const std::string cls = type_name(self);
        throw py::type_error(cls + " does not pickle: a Python subclass of pathpace.Path needs its own __reduce__ "
                             "(e.g. `def __reduce__(self): return " + cls + ", (<constructor arguments>,)`) or "
                             "__getstate__/__setstate__; or give the path as a module-level function f(s) -> (q, dq, ddq) "
                             "through pathpace.paths.CallbackPath(f, s_begin, s_end), which pickles");
      });
}

void bind_piecewise_polynomial_path(py::module_& m) {
  py::class_<PiecewisePolynomialPath, Path, py::smart_holder>(m, "PiecewisePolynomialPath",
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
  py::class_<CubicSplinePath, PiecewisePolynomialPath, py::smart_holder>(m, "CubicSplinePath", doc::CubicSplinePath)
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
  py::class_<SampledPath, PiecewisePolynomialPath, py::smart_holder>(m, "SampledPath", doc::SampledPath)
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

// The tail [s0, s_end] of a path without pieces (TimeScalingProblem.restarted on a callback path): private,
// so that a restarted problem's path is a Path that pickles, as (parent, s0).
void bind_sub_path(py::module_& m) {
  py::class_<detail::SubPath, Path, py::smart_holder>(m, "_SubPath")
      .def_property_readonly("parent", [](const detail::SubPath& p) { return std::const_pointer_cast<Path>(p.parent()); })
      .def(py::pickle([](const detail::SubPath& p) { return py::make_tuple(std::const_pointer_cast<Path>(p.parent()), p.s_begin()); },
                      [](const py::tuple& t) {
                        check_state(t, 2, "_SubPath");
                        auto parent = to_object<Path>(t[0], "parent", "Path");
                        return std::make_shared<detail::SubPath>(std::move(parent), to_double(t[1], "s0"));
                      }))
      .def("__repr__", [](const detail::SubPath& p) {
        return "<_SubPath s=[" + std::to_string(p.s_begin()) + ", " + std::to_string(p.s_end()) + "] of " +
               py::repr(py::cast(std::const_pointer_cast<Path>(p.parent()))).cast<std::string>() + ">";
      });
}

}  // namespace

void bind_paths(py::module_& m) {
  bind_path(m);
  bind_piecewise_polynomial_path(m);
  bind_cubic_spline_path(m);
  bind_sampled_path(m);
  bind_sub_path(m);
  m.def("auto_grid", [](py::handle path_arg, py::handle tolerance, py::handle min_intervals, py::handle max_intervals) {
    const auto path = to_path(path_arg);  // any path-like, as TimeScalingProblem(path, grid="auto") takes
    const double tol = to_double(tolerance, "tolerance");
    const int lo = to_int32(min_intervals, "min_intervals"), hi = to_int32(max_intervals, "max_intervals");
    py::gil_scoped_release release;
    return auto_grid(*path, tol, lo, hi);
  }, "path"_a, "tolerance"_a = 1e-3, "min_intervals"_a = 16, "max_intervals"_a = 1000000, doc::auto_grid);
}

}  // namespace pathpace::python
