// SecondOrderConstraint (F(q) w <= g(q), w = inverse_dynamics(q, qd, qdd)) from Python callables: the
// functions object that calls them, pickling, and the class itself.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>

#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/errors.hpp"
#include "second_order.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The callables and how to call them. C++ calls the functions from any thread, with or without the GIL
// (add_constraint, solve and the continuous audit release it): each call takes it first. An exception the
// callable raises leaves as it was (error_already_set), through evaluate() back to the Python caller.
class PyFunctions : public SecondOrderFunctions {
 public:
  PyFunctions(py::object id, py::object F, py::object g, bool vectorized, std::string who)
      : id_(std::move(id)), F_(std::move(F)), g_(std::move(g)), vectorized_(vectorized), who_(std::move(who)) {
    if (!PyCallable_Check(id_.ptr())) type_error("inverse_dynamics", "a callable w = f(q, qd, qdd)", id_);
    inverse_dynamics = [this](const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd, const Eigen::MatrixXd& qdd) {
      return call_id(q, qd, qdd);
    };
    // None: torque limits, whose F and g torque_limits sets.
    if (PyCallable_Check(F_.ptr()))
      this->F = [this](const Eigen::MatrixXd& q) { return call_F(q); };
    else if (!F_.is_none())
      F_constant = to_matrix(F_, "F");
    if (PyCallable_Check(g_.ptr()))
      this->g = [this](const Eigen::MatrixXd& q) { return call_g(q); };
    else if (!g_.is_none())
      g_constant = to_vector(g_, "g");
  }
  ~PyFunctions() override {
    if (!Py_IsInitialized()) return;  // at exit: the interpreter owns nothing any more
    py::gil_scoped_acquire gil;
    id_ = py::object();
    F_ = py::object();
    g_ = py::object();
  }
  PyFunctions(const PyFunctions&) = delete;
  PyFunctions& operator=(const PyFunctions&) = delete;

  const py::object& id() const { return id_; }
  const py::object& F_object() const { return F_; }
  const py::object& g_object() const { return g_; }
  bool vectorized() const { return vectorized_; }

 private:
  py::object id_, F_, g_;
  bool vectorized_;
  std::string who_;  // "constraint 'torque limits'": what the messages name

  std::string returned(const char* what) const { return who_ + ": the value " + what + " returned"; }

  // A 2-D result of m rows (a 1-D one of length m is one column); the C++ side checks the row count.
  Eigen::MatrixXd rows_of(const py::object& r, const char* what) const {
    return to_matrix(r, returned(what), true);
  }

  Eigen::MatrixXd call_id(const Eigen::MatrixXd& q, const Eigen::MatrixXd& qd, const Eigen::MatrixXd& qdd) const {
    py::gil_scoped_acquire gil;
    if (vectorized_) return rows_of(id_(q, qd, qdd), "inverse_dynamics(q, qd, qdd)");
    Eigen::MatrixXd w;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const Eigen::VectorXd wi = to_vector(id_(Eigen::VectorXd(q.row(i).transpose()), Eigen::VectorXd(qd.row(i).transpose()),
                                               Eigen::VectorXd(qdd.row(i).transpose())),
                                           returned("inverse_dynamics(q[i], qd[i], qdd[i])") + " at row " + std::to_string(i));
      if (i == 0) w.resize(q.rows(), wi.size());
      if (wi.size() != w.cols())
        throw InvalidInput(returned("inverse_dynamics(q[i], qd[i], qdd[i])") + " at row " + std::to_string(i) + " has size " +
                           std::to_string(wi.size()) + ", expected " + std::to_string(w.cols()) + " (as at row 0)");
      w.row(i) = wi.transpose();
    }
    return w;
  }

  Eigen::MatrixXd call_F(const Eigen::MatrixXd& q) const {
    py::gil_scoped_acquire gil;
    const Eigen::Index m = q.rows();
    if (!vectorized_) {
      Eigen::MatrixXd out;
      for (Eigen::Index i = 0; i < m; ++i) {
        const std::string what = returned("F(q[i])") + " at grid point " + std::to_string(i);
        const Eigen::MatrixXd Fi = to_matrix(F_(Eigen::VectorXd(q.row(i).transpose())), what);
        if (i == 0) out.resize(m * Fi.rows(), Fi.cols());
        if (Fi.rows() * m != out.rows() || Fi.cols() != out.cols())
          throw InvalidInput(what + " has shape (" + std::to_string(Fi.rows()) + ", " + std::to_string(Fi.cols()) +
                             "), expected (" + std::to_string(out.rows() / m) + ", " + std::to_string(out.cols()) +
                             ") (as at grid point 0)");
        out.middleRows(i * Fi.rows(), Fi.rows()) = Fi;
      }
      return out;
    }
    const py::object r = F_(q);
    auto a = as_float_array(r, returned("F(q)"));
    if (a.ndim() != 3 || a.shape(0) != m)
      throw InvalidInput(returned("F(q)") + " has shape " + shape_str(a) + ", expected (" + std::to_string(m) +
                         ", r, nw): one matrix F(q_i) per row of q");
    return Eigen::Map<const RowMajor>(a.data(), a.shape(0) * a.shape(1), a.shape(2));
  }

  Eigen::MatrixXd call_g(const Eigen::MatrixXd& q) const {
    py::gil_scoped_acquire gil;
    if (vectorized_) return rows_of(g_(q), "g(q)");
    Eigen::MatrixXd out;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const std::string what = returned("g(q[i])") + " at grid point " + std::to_string(i);
      const Eigen::VectorXd gi = to_vector(g_(Eigen::VectorXd(q.row(i).transpose())), what);
      if (i == 0) out.resize(q.rows(), gi.size());
      if (gi.size() != out.cols())
        throw InvalidInput(what + " has size " + std::to_string(gi.size()) + ", expected " + std::to_string(out.cols()) +
                           " (as at grid point 0)");
      out.row(i) = gi.transpose();
    }
    return out;
  }
};

std::string who(const std::string& name) { return "constraint '" + name + "'"; }

const PyFunctions& py_functions(const SecondOrderConstraint& c) {
  const auto* f = dynamic_cast<const PyFunctions*>(c.functions().get());
  if (!f) throw py::type_error(who(c.name()) + " holds C++ functions (std::function), which do not pickle");
  return *f;
}

// pickle.dumps(obj), or a PicklingError naming the constraint and the callable (a lambda or a local function
// does not pickle: the state would fail later, in pickle itself, naming neither).
void require_picklable(const SecondOrderConstraint& c, const char* what, const py::object& obj) {
  py::module_ pickle = py::module_::import("pickle");
  try {
    pickle.attr("dumps")(obj);
  } catch (py::error_already_set& e) {
    const std::string msg = who(c.name()) + ": its " + what + " " + py::repr(obj).cast<std::string>() +
                            " does not pickle (" + e.what() +
                            "); define it at module level (a lambda or a local function does not pickle) or give "
                            "an object with __reduce__";
    PyErr_SetString(pickle.attr("PicklingError").ptr(), msg.c_str());
    throw py::error_already_set();
  }
}

py::tuple second_order_state(const SecondOrderConstraint& c) {
  const PyFunctions& f = py_functions(c);
  require_picklable(c, "inverse_dynamics", f.id());
  if (c.is_torque_limits())
    return py::make_tuple("torque", f.id(), c.tau_min(), c.tau_max(), f.vectorized(), c.joint_names());
  require_picklable(c, "F", f.F_object());
  require_picklable(c, "g", f.g_object());
  const SecondOrderOptions& o = c.options();
  return py::make_tuple("general", f.id(), f.F_object(), f.g_object(), f.vectorized(), o.name, o.labels, o.family,
                        c.g_scale());
}

std::shared_ptr<SecondOrderConstraint> second_order_from_state(const py::tuple& t) {
  if (t.size() < 1 || !py::isinstance<py::str>(t[0]))
    throw InvalidInput("SecondOrderConstraint pickle state must begin with its kind ('torque' or 'general')");
  const std::string kind = t[0].cast<std::string>();
  std::vector<py::object> v;
  for (py::handle h : t) v.push_back(py::reinterpret_borrow<py::object>(h));
  std::shared_ptr<const SecondOrderConstraint> c;
  if (kind == "torque") {
    check_state(t, 6, "SecondOrderConstraint (torque)");
    c = callback_torque_limits(v[1], v[2], v[3], py::float_(1.0), py::float_(0.0), v[4],
                               v[5].cast<std::vector<std::string>>());
  } else {
    check_state(t, 9, "SecondOrderConstraint");
    c = callback_second_order(v[1], v[2], v[3], v[5], v[6], v[7], v[4]);
    const double scale = v[8].cast<double>();
    if (scale != 1.0) c = c->with_g_scale(scale);
  }
  return std::const_pointer_cast<SecondOrderConstraint>(c);
}

}  // namespace

std::shared_ptr<const SecondOrderConstraint> callback_torque_limits(py::handle inverse_dynamics, py::handle tau_min,
                                                                    py::handle tau_max, py::handle scale,
                                                                    py::handle margin, py::handle vectorized,
                                                                    const std::vector<std::string>& joint_names) {
  if (tau_min.is_none() || tau_max.is_none())
    throw InvalidInput(std::string(tau_min.is_none() ? "tau_min" : "tau_max") +
                       " must be given (one per joint) with inverse_dynamics: there is no URDF effort limit to default to");
  const Eigen::VectorXd lo = to_vector(tau_min, "tau_min"), hi = to_vector(tau_max, "tau_max");
  const double s = to_double(scale, "scale"), mg = to_double(margin, "margin");
  const bool vec = to_bool(vectorized, "vectorized");
  // F and g: eq. 15's constant rows, which torque_limits sets.
  auto f = std::make_shared<PyFunctions>(py::reinterpret_borrow<py::object>(inverse_dynamics), py::none(), py::none(),
                                         vec, who("torque limits"));
  return SecondOrderConstraint::torque_limits(std::move(f), lo, hi, s, mg,
                                              static_cast<Eigen::Index>(joint_names.size()) == lo.size()
                                                  ? joint_names
                                                  : std::vector<std::string>());
}

std::shared_ptr<const SecondOrderConstraint> callback_second_order(py::handle inverse_dynamics, py::handle F,
                                                                   py::handle g, py::handle name, py::handle labels,
                                                                   py::handle family, py::handle vectorized) {
  SecondOrderOptions o;
  o.name = to_string_arg(name, "name");
  o.labels = to_string_list(labels, "labels", true);
  o.family = to_string_arg(family, "family");
  const bool vec = to_bool(vectorized, "vectorized");
  if (F.is_none()) type_error("F", "a callable F(q) or an array (r, nw)", F);
  if (g.is_none()) type_error("g", "a callable g(q) or an array (r,)", g);
  auto f = std::make_shared<PyFunctions>(py::reinterpret_borrow<py::object>(inverse_dynamics),
                                         py::reinterpret_borrow<py::object>(F), py::reinterpret_borrow<py::object>(g), vec,
                                         who(o.name));
  return std::make_shared<SecondOrderConstraint>(std::move(f), std::move(o));
}

void bind_second_order(py::module_& m) {
  py::class_<SecondOrderConstraint, Constraint, py::smart_holder>(m, "SecondOrderConstraint", doc::SecondOrderConstraint)
      .def(py::init([](py::handle id, py::handle F, py::handle g, py::handle name, py::handle labels, py::handle family,
                       py::handle vectorized) {
             return std::const_pointer_cast<SecondOrderConstraint>(
                 callback_second_order(id, F, g, name, labels, family, vectorized));
           }),
           "inverse_dynamics"_a, "F"_a, "g"_a, py::kw_only(), "name"_a = "second-order constraint", "labels"_a = py::none(),
           "family"_a = "second order", "vectorized"_a = true)
      .def_static("torque_limits",
                  [](py::handle id, py::handle tau_min, py::handle tau_max, py::handle scale, py::handle margin,
                     py::handle vectorized) {
                    return std::const_pointer_cast<SecondOrderConstraint>(
                        callback_torque_limits(id, tau_min, tau_max, scale, margin, vectorized, {}));
                  },
                  "inverse_dynamics"_a, "tau_min"_a, "tau_max"_a, py::kw_only(), "scale"_a = 1.0, "margin"_a = 0.0,
                  "vectorized"_a = true, doc::SecondOrderConstraint_torque_limits)
      .def_property_readonly("inverse_dynamics", [](const SecondOrderConstraint& c) { return py_functions(c).id(); },
                             doc::SecondOrderConstraint_inverse_dynamics)
      // None for torque limits (their F and g are eq. 15's constant rows).
      .def_property_readonly("F", [](const SecondOrderConstraint& c) { return py_functions(c).F_object(); },
                             doc::SecondOrderConstraint_F)
      .def_property_readonly("g", [](const SecondOrderConstraint& c) { return py_functions(c).g_object(); },
                             doc::SecondOrderConstraint_g)
      .def_property_readonly("vectorized", [](const SecondOrderConstraint& c) { return py_functions(c).vectorized(); },
                             doc::SecondOrderConstraint_vectorized)
      .def_property_readonly("tau_min", [](const SecondOrderConstraint& c) -> py::object {
        return c.is_torque_limits() ? py::cast(c.tau_min()) : py::object(py::none());
      }, doc::SecondOrderConstraint_tau_min)
      .def_property_readonly("tau_max", [](const SecondOrderConstraint& c) -> py::object {
        return c.is_torque_limits() ? py::cast(c.tau_max()) : py::object(py::none());
      }, doc::SecondOrderConstraint_tau_max)
      .def(py::pickle(&second_order_state, &second_order_from_state));
}

}  // namespace pathpace::python
