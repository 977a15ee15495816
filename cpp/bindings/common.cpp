#include "common.hpp"

#include "convert.hpp"

namespace pathpace::python {

std::shared_ptr<Path> to_path(py::handle path_arg, const std::string& name) {
  if (path_arg.is_none() || py::isinstance<Path>(path_arg)) return to_object<Path>(path_arg, name, "Path");
  return to_object<Path>(py::module_::import("pathpace.paths").attr("as_path")(path_arg), name, "Path");
}

py::list drift_list(const std::vector<ContactDrift>& v) {
  py::list out;
  for (const ContactDrift& d : v) out.append(py::make_tuple(d.constraint, d.contact, d.link, d.s, d.drift, d.tolerance));
  return out;
}

std::vector<ContactDrift> drift_vector(py::handle h) {
  std::vector<ContactDrift> out;
  for (py::handle item : h) {
    const py::tuple x = item.cast<py::tuple>();
    check_state(x, 6, "contact drift");
    out.push_back({x[0].cast<std::string>(), x[1].cast<int>(), x[2].cast<std::string>(), x[3].cast<double>(),
                   x[4].cast<double>(), x[5].cast<double>()});
  }
  return out;
}

Guarantee parse_guarantee(const std::string& g) {
  if (g == "grid") return Guarantee::Grid;
  if (g == "continuous") return Guarantee::Continuous;
  throw InvalidInput("guarantee = '" + g + "' must be one of 'grid', 'continuous'");
}

ForceDistribution parse_distribution(py::handle h) {
  const std::string d = to_string_arg(h, "distribution");
  if (d == "centre") return ForceDistribution::Centre;
  if (d == "vertex") return ForceDistribution::Vertex;
  throw InvalidInput("distribution = '" + d + "' must be 'centre' or 'vertex'");
}

ForceSamples to_force_samples(const std::vector<ContactForces>& v, int contacts, int joints, bool scalar) {
  ForceSamples out;
  const auto S = static_cast<py::ssize_t>(v.size());
  out.feasible = py::array_t<bool>(S);
  out.forces = py::array_t<double>({S, static_cast<py::ssize_t>(contacts), static_cast<py::ssize_t>(3)});
  out.margin.resize(S);
  out.centred = py::array_t<bool>(S);
  out.slack.resize(S);
  auto ce = out.centred.mutable_unchecked<1>();
  out.torques.resize(S, joints);
  out.phase = Eigen::VectorXi::Constant(S, -1);
  auto fe = out.feasible.mutable_unchecked<1>();
  auto fo = out.forces.mutable_unchecked<3>();
  for (py::ssize_t s = 0; s < S; ++s) {
    const ContactForces& c = v[static_cast<size_t>(s)];
    fe(s) = c.feasible;
    out.margin[s] = c.margin;
    ce(s) = c.centred;
    out.slack[s] = c.slack;
    out.torques.row(s) = c.torques.transpose();
    // Contact phases have their own numbers of contacts: rows beyond a phase's own are NaN.
    for (int i = 0; i < contacts; ++i)
      for (int d = 0; d < 3; ++d) fo(s, i, d) = i < c.forces.rows() ? c.forces(i, d) : std::numeric_limits<double>::quiet_NaN();
  }
  out.scalar = scalar;
  return out;
}

}  // namespace pathpace::python
