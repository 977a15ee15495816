#pragma once
// numpy -> Eigen with house-style errors: a wrong shape or dtype raises InvalidInputError naming the
// argument instead of pybind11's generic TypeError.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/errors.hpp"

namespace pathpace::python {

namespace py = pybind11;

/// The Python type name of h, for "got <type>" in messages.
inline std::string type_name(py::handle h) { return py::str(py::type::handle_of(h).attr("__name__")).cast<std::string>(); }

/// A TypeError naming the argument and the expected type (instead of pybind11's whole signature).
[[noreturn]] inline void type_error(const std::string& name, const std::string& expected, py::handle got) {
  throw py::type_error(name + " must be " + expected + ", got " + (got.is_none() ? std::string("None") : type_name(got)));
}

/// "name[i]" or "name[i, j, ...]" for the flat index `flat` of an array of shape `shape`.
inline std::string element_name(const std::string& name, const py::array& a, py::ssize_t flat) {
  std::vector<py::ssize_t> idx(static_cast<size_t>(a.ndim()));
  for (py::ssize_t d = a.ndim(); d-- > 0;) {
    idx[static_cast<size_t>(d)] = flat % a.shape(d);
    flat /= a.shape(d);
  }
  std::string out = name + "[";
  for (size_t d = 0; d < idx.size(); ++d) out += (d ? ", " : "") + std::to_string(idx[d]);
  return out + "]";
}

/// numpy would turn None into NaN, a complex number into its real part, and refuse "a" only as a whole:
/// an array of objects, strings or complex numbers is checked element by element here, so that the error
/// names the element ("waypoints[1, 0] must be a number, got None").
inline void require_real_elements(const py::array& a, const std::string& name) {
  const char kind = a.dtype().kind();
  if (kind != 'O' && kind != 'U' && kind != 'S' && kind != 'c') return;
  py::ssize_t i = 0;
  for (py::handle item : a.attr("flat")) {
    const std::string where = element_name(name, a, i++);
    if (kind == 'c' || PyComplex_Check(item.ptr()))
      throw InvalidInput(where + " = " + py::repr(item).cast<std::string>() + " must be a real number");
    if (item.is_none() || py::isinstance<py::str>(item) || py::isinstance<py::bytes>(item) ||
        !PyObject_HasAttrString(item.ptr(), "__float__"))
      type_error(where, "a number", item);
  }
}

inline py::array_t<double, py::array::c_style | py::array::forcecast> as_float_array(py::handle obj,
                                                                                     const std::string& name) {
  if (obj.is_none()) throw InvalidInput(name + " must be an array, got None");
  if (py::isinstance<py::str>(obj) || py::isinstance<py::bytes>(obj) || py::isinstance<py::dict>(obj))
    throw InvalidInput(name + " must be an array of numbers, got " + type_name(obj));
  // ensure() returns an empty handle (not an exception) when numpy cannot convert the object
  // (a string, a ragged list, a dict): dereferencing that crashed the interpreter. numpy.asarray raises
  // instead (a ragged list); `a` then stays the default array of shape (0,), so `converted` says which.
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  bool converted = false;
  try {
    // A float array passes straight through; anything else is first read as numpy reads it, to see what
    // its elements are.
    if (!py::isinstance<py::array_t<double>>(obj)) {
      py::array raw = py::isinstance<py::array>(obj) ? py::reinterpret_borrow<py::array>(obj)
                                                     : py::array(py::module_::import("numpy").attr("asarray")(obj));
      const char kind = raw.dtype().kind();
      // A list with a str (or complex) element became an array of str (complex): its own elements name the culprit.
      if (!py::isinstance<py::array>(obj) && (kind == 'U' || kind == 'S' || kind == 'c'))
        require_real_elements(py::module_::import("numpy").attr("asarray")(obj, py::arg("dtype") = "object"), name);
      require_real_elements(raw, name);
      a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
    } else {
      a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
    }
    converted = true;
  } catch (const py::error_already_set&) {
  }
  if (!converted || !a) {
    PyErr_Clear();
    throw InvalidInput(name + " must be an array of numbers (not ragged), got " + type_name(obj));
  }
  return a;
}

/// A real number: int, float, a numpy scalar or a 0-d array. Not None, str, bool or a sequence.
inline double to_double(py::handle h, const std::string& name) {
  if (h.is_none() || py::isinstance<py::str>(h) || py::isinstance<py::bytes>(h) || PyBool_Check(h.ptr()))
    type_error(name, "a number", h);
  if (py::isinstance<py::float_>(h) || py::isinstance<py::int_>(h)) {
    const double v = PyFloat_AsDouble(h.ptr());
    if (v == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      throw InvalidInput(name + " = " + py::repr(h).cast<std::string>() + " is too large for a float");
    }
    return v;
  }
  if (py::isinstance<py::array>(h)) {
    py::array a = py::reinterpret_borrow<py::array>(h);
    if (a.ndim() != 0) type_error(name, "a number (not an array of shape " + py::str(a.attr("shape")).cast<std::string>() + ")", h);
  }
  if (!PyObject_HasAttrString(h.ptr(), "__float__")) type_error(name, "a number", h);
  const double v = PyFloat_AsDouble(h.ptr());
  if (v == -1.0 && PyErr_Occurred()) {
    PyErr_Clear();
    type_error(name, "a number", h);
  }
  return v;
}

/// An integer (Python int or numpy integer; not bool or float) in [lo, hi].
inline long long to_int(py::handle h, const std::string& name, long long lo, long long hi) {
  if (h.is_none() || PyBool_Check(h.ptr()) || py::isinstance<py::float_>(h) || !PyIndex_Check(h.ptr()))
    type_error(name, "an int", h);
  py::object idx = py::reinterpret_steal<py::object>(PyNumber_Index(h.ptr()));
  if (!idx) {
    PyErr_Clear();
    type_error(name, "an int", h);
  }
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(idx.ptr(), &overflow);
  if (overflow || v < lo || v > hi)
    throw InvalidInput(name + " = " + py::str(idx).cast<std::string>() + " must be in [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "]");
  return v;
}

/// An int-sized integer (any value an int holds; the C++ side checks the range that makes sense).
inline int to_int32(py::handle h, const std::string& name) {
  return static_cast<int>(to_int(h, name, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

inline bool to_bool(py::handle h, const std::string& name) {
  if (PyBool_Check(h.ptr())) return h.ptr() == Py_True;
  if (py::hasattr(h, "dtype") && py::str(h.attr("dtype")).cast<std::string>() == "bool" && py::hasattr(h, "__bool__"))
    return PyObject_IsTrue(h.ptr()) == 1;
  type_error(name, "a bool", h);
}

/// A str (or, when path_like, anything os.fspath accepts).
inline std::string to_string_arg(py::handle h, const std::string& name, bool path_like = false) {
  if (py::isinstance<py::str>(h)) return h.cast<std::string>();
  if (path_like && !h.is_none() && py::hasattr(h, "__fspath__")) {
    py::object p = py::module_::import("os").attr("fspath")(h);
    if (py::isinstance<py::str>(p)) return p.cast<std::string>();
  }
  type_error(name, path_like ? "a str or os.PathLike" : "a str", h);
}

/// A pathpace object (never None: a null shared_ptr would be dereferenced).
template <typename T>
std::shared_ptr<T> to_object(py::handle h, const std::string& name, const std::string& type) {
  if (h.is_none() || !py::isinstance<T>(h)) type_error(name, "a pathpace." + type, h);
  return h.cast<std::shared_ptr<T>>();
}

/// The items of a list or tuple (or any sized sequence: not a str, not a 0-d array).
inline std::vector<py::object> to_items(py::handle h, const std::string& name, const std::string& expected) {
  if (h.is_none() || py::isinstance<py::str>(h) || py::isinstance<py::bytes>(h) || !PySequence_Check(h.ptr()))
    type_error(name, expected, h);
  const Py_ssize_t n = PySequence_Size(h.ptr());
  if (n < 0) {
    PyErr_Clear();
    type_error(name, expected, h);
  }
  std::vector<py::object> out;
  for (Py_ssize_t i = 0; i < n; ++i) {
    PyObject* item = PySequence_GetItem(h.ptr(), i);
    if (!item) {
      PyErr_Clear();
      type_error(name, expected, h);
    }
    out.push_back(py::reinterpret_steal<py::object>(item));
  }
  return out;
}

/// A list (or tuple) of str; None gives an empty list when allow_none (the C++ default: no names).
inline std::vector<std::string> to_string_list(py::handle h, const std::string& name, bool allow_none = false) {
  if (allow_none && h.is_none()) return {};
  const char* expected = allow_none ? "a list of str or None" : "a list of str";
  if (py::isinstance<py::array>(h) || py::isinstance<py::dict>(h)) type_error(name, expected, h);
  std::vector<std::string> out;
  const std::vector<py::object> items = to_items(h, name, expected);
  for (size_t i = 0; i < items.size(); ++i) out.push_back(to_string_arg(items[i], name + "[" + std::to_string(i) + "]"));
  return out;
}

/// A sequence of pathpace.Contact.
inline std::vector<Contact> to_contacts(py::handle h, const std::string& name) {
  if (py::isinstance<Contact>(h)) type_error(name, "a list of pathpace.Contact", h);
  std::vector<Contact> out;
  const std::vector<py::object> items = to_items(h, name, "a list of pathpace.Contact");
  for (size_t i = 0; i < items.size(); ++i) {
    if (!py::isinstance<Contact>(items[i])) type_error(name + "[" + std::to_string(i) + "]", "a pathpace.Contact", items[i]);
    out.push_back(items[i].cast<Contact>());
  }
  return out;
}

inline std::string shape_str(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// A 1-D array as an Eigen vector (a scalar or 0-d array: one entry).
inline Eigen::VectorXd to_vector(py::handle obj, const std::string& name) {
  auto a = as_float_array(obj, name);
  if (!a) throw InvalidInput(name + " must be an array of numbers");
  if (a.ndim() == 0) return Eigen::VectorXd::Constant(1, *a.data());
  if (a.ndim() != 1) throw InvalidInput(name + " has shape " + shape_str(a) + ", expected a 1-D array");
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

/// None -> an empty vector (the C++ default, e.g. the URDF's limits), else a 1-D array as to_vector.
inline Eigen::VectorXd optional_vector(py::handle h, const std::string& name) {
  return h.is_none() ? Eigen::VectorXd() : to_vector(h, name);
}

/// A 2-D array as an Eigen matrix; a 1-D array of length m becomes (m, 1) when one_d_as_column.
inline Eigen::MatrixXd to_matrix(py::handle obj, const std::string& name, bool one_d_as_column = false) {
  auto a = as_float_array(obj, name);
  if (!a) throw InvalidInput(name + " must be an array of numbers");
  if (a.ndim() == 1 && one_d_as_column) return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
  if (a.ndim() != 2) throw InvalidInput(name + " has shape " + shape_str(a) + ", expected a 2-D array");
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(a.data(), a.shape(0), a.shape(1));
}

/// Values of a path parameter (s of Path.q, ContactConstraint.max_drift): a vector without NaN.
inline Eigen::VectorXd to_path_parameters(py::handle h, const std::string& name) {
  Eigen::VectorXd s = to_vector(h, name);
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (std::isnan(s[i])) throw InvalidInput(name + "[" + std::to_string(i) + "] = nan must be a number");
  return s;
}

/// Rows per grid point (N+1, r) of a LinearConstraint; a 1-D array of length N+1 is one row.
inline Eigen::MatrixXd to_rows(py::handle h, const char* name) { return to_matrix(h, name, true); }

/// A point in link coordinates (frame limits, point Jacobians): three numbers.
inline Eigen::Vector3d to_point(py::handle h, const std::string& name) {
  const Eigen::VectorXd p = to_vector(h, name);
  if (p.size() != 3) throw InvalidInput(name + " has size " + std::to_string(p.size()) + ", expected 3 (x, y, z in the link frame, m)");
  return p;
}

/// A pickled state tuple of the expected length (a state from another version is refused, named).
inline void check_state(const py::tuple& t, size_t size, const char* what) {
  if (t.size() != size)
    throw InvalidInput(std::string(what) + " pickle state has " + std::to_string(t.size()) + " entries, expected " +
                       std::to_string(size));
}

/// A Python scalar or 0-d array (functions of s or t then return one row instead of a matrix).
inline bool is_scalar(py::handle h) {
  return py::isinstance<py::float_>(h) || py::isinstance<py::int_>(h) ||
         (py::isinstance<py::array>(h) && py::array(py::reinterpret_borrow<py::object>(h)).ndim() == 0);
}

/// The rows of a function of s or t evaluated at `at`: one row (n,) for a scalar, all (m, n) otherwise.
inline py::object rows_at(py::handle at, const Eigen::MatrixXd& rows) {
  if (is_scalar(at)) return py::cast(Eigen::VectorXd(rows.row(0).transpose()));
  return py::cast(rows);
}

/// p, p', p'' of a Path or q, q̇, q̈ of a Trajectory (which = 0, 1, 2) at `at`, whose values are x; the
/// GIL is released while it evaluates.
template <typename Curve>
py::object evaluate_at(const Curve& curve, py::handle at, const Eigen::VectorXd& x, int which) {
  Eigen::MatrixXd d0, d1, d2;
  {
    py::gil_scoped_release release;
    curve.evaluate(x, d0, d1, d2);
  }
  return rows_at(at, which == 0 ? d0 : (which == 1 ? d1 : d2));
}

}  // namespace pathpace::python
