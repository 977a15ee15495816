#pragma once
// numpy -> Eigen with house-style errors: a wrong shape or dtype raises InvalidInputError naming the
// argument instead of pybind11's generic TypeError.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/contact_forces.hpp"
#include "pathpace/errors.hpp"

namespace pathpace::python {

namespace py = pybind11;

inline py::array_t<double, py::array::c_style | py::array::forcecast> as_float_array(py::handle obj,
                                                                                     const std::string& name) {
  if (obj.is_none()) throw InvalidInput(name + " must be an array, got None");
  try {
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  } catch (const py::error_already_set&) {
  }
  throw InvalidInput(name + " must be an array of numbers");
}

inline std::string shape_str(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// A 1-D array (or a scalar when allow_scalar) as an Eigen vector.
inline Eigen::VectorXd to_vector(py::handle obj, const std::string& name) {
  auto a = as_float_array(obj, name);
  if (!a) throw InvalidInput(name + " must be an array of numbers");
  if (a.ndim() == 0) return Eigen::VectorXd::Constant(1, *a.data());
  if (a.ndim() != 1) throw InvalidInput(name + " has shape " + shape_str(a) + ", expected a 1-D array");
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
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

inline ContactOptions contact_options(int cone_edges, double friction_margin, double min_normal_force, double torque_scale,
                                     double torque_margin) {
  ContactOptions o;
  o.cone_edges = cone_edges;
  o.friction_margin = friction_margin;
  o.min_normal_force = min_normal_force;
  o.torque_scale = torque_scale;
  o.torque_margin = torque_margin;
  return o;
}

/// A Python scalar or 0-d array (functions of s or t then return one row instead of a matrix).
inline bool is_scalar(py::handle h) {
  return py::isinstance<py::float_>(h) || py::isinstance<py::int_>(h) ||
         (py::isinstance<py::array>(h) && py::array(py::reinterpret_borrow<py::object>(h)).ndim() == 0);
}

/// Force-distribution results over samples, as arrays (the Python ContactForces).
struct ForceSamples {
  py::array_t<bool> feasible;   // (S,)
  Eigen::VectorXd margin;       // (S,)
  py::array_t<double> forces;   // (S, m, 3)
  Eigen::MatrixXd torques;      // (S, n)
  bool scalar = false;          // one sample asked for as a scalar: drop the leading axis
};

inline ForceSamples to_force_samples(const std::vector<ContactForces>& v, int contacts, int joints, bool scalar) {
  ForceSamples out;
  const auto S = static_cast<py::ssize_t>(v.size());
  out.feasible = py::array_t<bool>(S);
  out.forces = py::array_t<double>({S, static_cast<py::ssize_t>(contacts), static_cast<py::ssize_t>(3)});
  out.margin.resize(S);
  out.torques.resize(S, joints);
  auto fe = out.feasible.mutable_unchecked<1>();
  auto fo = out.forces.mutable_unchecked<3>();
  for (py::ssize_t s = 0; s < S; ++s) {
    const ContactForces& c = v[static_cast<size_t>(s)];
    fe(s) = c.feasible;
    out.margin[s] = c.margin;
    out.torques.row(s) = c.torques.transpose();
    for (int i = 0; i < contacts; ++i)
      for (int d = 0; d < 3; ++d) fo(s, i, d) = c.forces(i, d);
  }
  out.scalar = scalar;
  return out;
}

}  // namespace pathpace::python
