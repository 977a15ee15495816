// The Constraint base, open to Python subclasses (a trampoline), and what their evaluate() reads and returns:
// PathSamples (read-only) and ConstraintRows. The derived classes are bound in bind_problem.cpp / bind_robot.cpp
// with the same holder (py::smart_holder), which keeps a Python subclass alive while C++ holds it.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/constraints/constraint.hpp"
#include "pathpace/errors.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

// A Constraint whose hooks may be Python methods. C++ calls them from any thread, with or without the GIL
// (solve, relaxation, pickle's setstate and add_constraint release it): each override takes it first.
// Exceptions raised in Python come back as they were (error_already_set).
class PyConstraint : public Constraint, public py::trampoline_self_life_support {
 public:
  // `name` may be a method, a property or a plain class attribute of the Python class.
  std::string name() const override {
    py::gil_scoped_acquire gil;
    py::handle self = py::detail::get_object_handle(static_cast<const Constraint*>(this),
                                                   py::detail::get_type_info(typeid(Constraint)));
    py::object base = py::type::of<Constraint>().attr("__dict__")["name"];
    py::object mine = py::getattr(py::type::handle_of(self), "name");
    if (mine.is(base)) throw Error("a Python subclass of pathpace.Constraint must define name");
    py::object v = py::getattr(self, "name");
    if (PyCallable_Check(v.ptr())) v = v();
    if (!py::isinstance<py::str>(v)) throw py::type_error("Constraint.name must be a str, got " + type_name(v));
    return v.cast<std::string>();
  }

  ConstraintRows evaluate(const PathSamples& samples) const override {
    py::gil_scoped_acquire gil;
    py::function f = py::get_override(static_cast<const Constraint*>(this), "evaluate");
    if (!f) throw Error("a Python subclass of pathpace.Constraint must define evaluate(samples)");
    py::object r = f(samples);  // a copy: the samples may outlive this call on the Python side
    if (!py::isinstance<ConstraintRows>(r))
      type_error("constraint '" + name() + "': evaluate(samples)", "a pathpace.ConstraintRows", r);
    return r.cast<ConstraintRows>();
  }

  std::string family() const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const Constraint*>(this), "family"))
      return f().cast<std::string>();
    return Constraint::family();
  }

  std::shared_ptr<const Constraint> relaxed(double scale) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const Constraint*>(this), "relaxed")) return constraint_or_null(f(scale), "relaxed");
    return Constraint::relaxed(scale);
  }

  std::shared_ptr<const Constraint> with_joint_names(const std::vector<std::string>& names) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const Constraint*>(this), "with_joint_names"))
      return constraint_or_null(f(names), "with_joint_names");
    return Constraint::with_joint_names(names);
  }

  bool per_grid_point() const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const Constraint*>(this), "per_grid_point")) return f().cast<bool>();
    return Constraint::per_grid_point();
  }

  std::shared_ptr<const Constraint> at_grid_points(const std::vector<Eigen::Index>& kept) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const Constraint*>(this), "at_grid_points")) {
      auto c = constraint_or_null(f(kept), "at_grid_points");
      if (!c) throw Error("constraint '" + name() + "': at_grid_points returned None");
      return c;
    }
    return Constraint::at_grid_points(kept);
  }

 private:
  std::shared_ptr<const Constraint> constraint_or_null(const py::object& r, const char* hook) const {
    if (r.is_none()) return nullptr;
    if (!py::isinstance<Constraint>(r))
      type_error("constraint '" + name() + "': " + hook, "a pathpace.Constraint or None", r);
    return r.cast<std::shared_ptr<Constraint>>();
  }
};

// (N+1, r) arrays of one shape; a 1-D array of length N+1 is one row.
ConstraintRows make_rows(py::handle a, py::handle b, py::handle c, py::handle labels) {
  ConstraintRows rows;
  const Eigen::MatrixXd ma = to_matrix(a, "a", true), mb = to_matrix(b, "b", true), mc = to_matrix(c, "c", true);
  auto shape = [](const Eigen::MatrixXd& m) { return "(" + std::to_string(m.rows()) + ", " + std::to_string(m.cols()) + ")"; };
  if (mb.rows() != ma.rows() || mb.cols() != ma.cols())
    throw InvalidInput("b has shape " + shape(mb) + ", expected a's " + shape(ma));
  if (mc.rows() != ma.rows() || mc.cols() != ma.cols())
    throw InvalidInput("c has shape " + shape(mc) + ", expected a's " + shape(ma));
  rows.labels = to_string_list(labels, "labels");
  if (static_cast<Eigen::Index>(rows.labels.size()) != ma.cols())
    throw InvalidInput("labels has " + std::to_string(rows.labels.size()) + " entries, expected one per row (" +
                       std::to_string(ma.cols()) + ")");
  rows.a = ma;
  rows.b = mb;
  rows.c = mc;
  return rows;  // valid_by_construction stays false: the problem checks every entry (add_constraint)
}

}  // namespace

void bind_constraint_base(py::module_& m) {
  py::class_<PathSamples>(m, "PathSamples", doc::PathSamples)
      .def_readonly("s", &PathSamples::s, doc::PathSamples_s)
      .def_readonly("q", &PathSamples::q, doc::PathSamples_q)
      .def_readonly("dq", &PathSamples::dq, doc::PathSamples_dq)
      .def_readonly("ddq", &PathSamples::ddq, doc::PathSamples_ddq)
      .def("__len__", &PathSamples::size)
      .def_property_readonly("dof", &PathSamples::dof, doc::PathSamples_dof);

  py::class_<ConstraintRows>(m, "ConstraintRows", doc::ConstraintRows)
      .def(py::init(&make_rows), "a"_a, "b"_a, "c"_a, "labels"_a)
      .def_property_readonly("a", [](const ConstraintRows& r) { return Eigen::MatrixXd(r.a); }, doc::ConstraintRows_a)
      .def_property_readonly("b", [](const ConstraintRows& r) { return Eigen::MatrixXd(r.b); }, doc::ConstraintRows_b)
      .def_property_readonly("c", [](const ConstraintRows& r) { return Eigen::MatrixXd(r.c); }, doc::ConstraintRows_c)
      .def_readonly("labels", &ConstraintRows::labels, doc::ConstraintRows_labels)
      .def_property_readonly("rows", &ConstraintRows::rows, doc::ConstraintRows_rows);

  // Hooks a Python subclass may override (evaluate and name it must); called on a library constraint, they
  // answer as in C++.
  py::class_<Constraint, PyConstraint, py::smart_holder>(m, "Constraint", doc::Constraint)
      .def(py::init<>())
      .def_property_readonly("name", &Constraint::name, doc::Constraint_name)
      .def("evaluate",
           [](const Constraint& c, py::handle samples) {
             if (!py::isinstance<PathSamples>(samples)) type_error("samples", "a pathpace.PathSamples", samples);
             return c.evaluate(samples.cast<const PathSamples&>());
           },
           "samples"_a, doc::Constraint_evaluate)
      .def("family", &Constraint::family, doc::Constraint_family)
      .def("relaxed",
           [](const Constraint& c, py::handle scale) {
             return std::const_pointer_cast<Constraint>(c.relaxed(to_double(scale, "scale")));
           },
           "scale"_a, doc::Constraint_relaxed)
      .def("per_grid_point", &Constraint::per_grid_point, doc::Constraint_per_grid_point)
      .def("at_grid_points",
           [](const Constraint& c, py::handle kept_arg) {
             std::vector<Eigen::Index> kept;
             for (const py::object& k : to_items(kept_arg, "kept", "a list of int"))
               kept.push_back(static_cast<Eigen::Index>(to_int(k, "kept[" + std::to_string(kept.size()) + "]", 0,
                                                               std::numeric_limits<Eigen::Index>::max())));
             return std::const_pointer_cast<Constraint>(c.at_grid_points(kept));
           },
           "kept"_a, doc::Constraint_at_grid_points)
      .def("with_joint_names",
           [](const Constraint& c, py::handle names) {
             return std::const_pointer_cast<Constraint>(c.with_joint_names(to_string_list(names, "names")));
           },
           "names"_a, doc::Constraint_with_joint_names);
}

}  // namespace pathpace::python
