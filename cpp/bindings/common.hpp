#pragma once
// What several bind_*.cpp share beyond argument conversion (convert.hpp): pickle-state pieces, the
// arrays of force-distribution results, a number as __repr__ shows it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/contact_drift.hpp"
#include "pathpace/contact_forces.hpp"
#include "pathpace/path.hpp"
#include "pathpace/solver_options.hpp"

namespace pathpace::python {

namespace py = pybind11;

/// None -> a null pointer (pickle states keep optional objects as None).
template <typename T>
std::shared_ptr<T> optional_ptr(py::handle h) {
  return h.is_none() ? std::shared_ptr<T>() : h.cast<std::shared_ptr<T>>();
}

/// Contact phases in pickle states: a list of ContactConstraint.
inline py::list phases_list(const std::vector<std::shared_ptr<const ContactConstraint>>& v) {
  py::list out;
  for (const auto& c : v) out.append(std::const_pointer_cast<ContactConstraint>(c));
  return out;
}
inline std::vector<std::shared_ptr<const ContactConstraint>> phases_vector(py::handle h) {
  std::vector<std::shared_ptr<const ContactConstraint>> out;
  for (py::handle c : h) out.push_back(c.cast<std::shared_ptr<ContactConstraint>>());
  return out;
}

/// Contact drifts in pickle states: tuples (constraint, contact, link, s, drift, tolerance).
py::list drift_list(const std::vector<ContactDrift>& v);
std::vector<ContactDrift> drift_vector(py::handle h);

/// %.6g: what a __repr__ shows of a number.
inline std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// A pathpace Path as it is; anything else path-like (a scipy spline, a toppra interpolator, a callable)
/// through pathpace.as_path, which names what it cannot take. `name` names the argument (None is refused).
std::shared_ptr<Path> to_path(py::handle path_arg, const std::string& name = "path");

/// guarantee= of solve and relaxation.
Guarantee parse_guarantee(const std::string& g);

/// Force-distribution results over samples, as arrays (the Python ContactForces).
struct ForceSamples {
  py::array_t<bool> feasible;   // (S,)
  Eigen::VectorXd margin;       // (S,)
  py::array_t<double> forces;   // (S, m, 3)
  Eigen::MatrixXd torques;      // (S, n)
  Eigen::VectorXi phase;        // (S,): the contact phase of each sample (Trajectory.contact_forces), -1: none
  py::array_t<bool> centred;    // (S,)
  Eigen::VectorXd slack;        // (S,)
  bool scalar = false;          // one sample asked for as a scalar: drop the leading axis
};

/// distribution= of force_distribution / contact_forces / contact_wrenches: "centre" or "vertex".
ForceDistribution parse_distribution(py::handle distribution);

/// `contacts` rows per sample (NaN beyond a phase's own), `joints` torques.
ForceSamples to_force_samples(const std::vector<ContactForces>& v, int contacts, int joints, bool scalar);

}  // namespace pathpace::python
