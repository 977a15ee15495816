// Contacts: the point contact, the force-distribution results and the contact constraint.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>

#include "common.hpp"
#include "contact_options.hpp"
#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/contact_phase.hpp"
#include "pathpace/path.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/robot_model.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

void bind_contact(py::module_& m) {
  py::class_<Contact>(m, "Contact", doc::Contact)
      .def(py::init([](py::handle link, py::handle point, py::handle normal, py::handle friction, py::object other_link) {
             Contact c;
             c.link = to_string_arg(link, "link");
             if (!other_link.is_none()) c.other_link = to_string_arg(other_link, "other_link");
             const Eigen::VectorXd p = to_vector(point, "point"), nrm = to_vector(normal, "normal");
             if (p.size() != 3) throw InvalidInput("point has size " + std::to_string(p.size()) + ", expected 3");
             if (nrm.size() != 3) throw InvalidInput("normal has size " + std::to_string(nrm.size()) + ", expected 3");
             c.point = p;
             c.normal = nrm;
             c.friction = to_double(friction, "friction");
             return c;
           }),
           "link"_a, "point"_a = py::make_tuple(0.0, 0.0, 0.0), "normal"_a = py::make_tuple(0.0, 0.0, 1.0), "friction"_a = 0.5,
           "other_link"_a = py::none())
      .def_readonly("link", &Contact::link, doc::Contact_link)
      .def_readonly("point", &Contact::point, doc::Contact_point)
      .def_readonly("normal", &Contact::normal, doc::Contact_normal)
      .def_readonly("friction", &Contact::friction, doc::Contact_friction)
      .def_property_readonly("other_link", [](const Contact& c) -> py::object {
        return c.other_link.empty() ? py::object(py::none()) : py::object(py::str(c.other_link));
      }, doc::Contact_other_link)
      .def(py::pickle([](const Contact& c) {
                        return py::make_tuple(c.link, Eigen::VectorXd(c.point), Eigen::VectorXd(c.normal), c.friction, c.other_link);
                      },
                      [](const py::tuple& t) {
                        check_state(t, 5, "Contact");
                        Contact c;
                        c.link = t[0].cast<std::string>();
                        const Eigen::VectorXd p = to_vector(t[1], "point"), nrm = to_vector(t[2], "normal");
                        if (p.size() != 3 || nrm.size() != 3) throw InvalidInput("Contact pickle state: point and normal must have size 3");
                        c.point = p;
                        c.normal = nrm;
                        c.friction = t[3].cast<double>();
                        c.other_link = t[4].cast<std::string>();
                        return c;
                      }))
      .def("__repr__", [](const Contact& c) {
        return "<Contact link='" + c.link + "'" + (c.other_link.empty() ? "" : " other_link='" + c.other_link + "'") +
               " friction=" + std::to_string(c.friction) + ">";
      });
}

void bind_contact_forces(py::module_& m) {
  py::class_<ForceSamples>(m, "ContactForces", doc::ContactForces)
      .def_property_readonly("feasible", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::bool_(f.feasible.at(0))) : py::object(f.feasible);
      }, doc::ContactForces_feasible)
      .def_property_readonly("margin", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::float_(f.margin[0])) : py::cast(f.margin);
      }, doc::ContactForces_margin)
      .def_property_readonly("forces", [](const ForceSamples& f) -> py::object {
        if (!f.scalar) return f.forces;
        return f.forces.attr("__getitem__")(0);
      }, doc::ContactForces_forces)
      .def_property_readonly("torques", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::cast(Eigen::VectorXd(f.torques.row(0).transpose())) : py::cast(f.torques);
      }, doc::ContactForces_torques)
      .def_property_readonly("phase", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::int_(f.phase[0])) : py::cast(f.phase);
      }, doc::ContactForces_phase)
      .def_property_readonly("centred", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::bool_(f.centred.at(0))) : py::object(f.centred);
      }, doc::ContactForces_centred)
      .def_property_readonly("slack", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::float_(f.slack[0])) : py::cast(f.slack);
      }, doc::ContactForces_slack);
}

using ContactClass = py::class_<ContactConstraint, Constraint, py::smart_holder>;

// Rebuilt from the robot, contacts, options and the stored limits (which include torque_scale and
// torque_margin, so those are 1 and 0 in the copy).
py::tuple contact_state(const ContactConstraint& c) {
  const ContactOptions& o = c.options();
  return py::make_tuple(std::const_pointer_cast<RobotModel>(c.robot()), c.contacts(), o.cone_edges, o.friction_margin,
                        o.min_normal_force, o.cap, c.tau_min(), c.tau_max(), o.min_link_normal_force, o.max_lps,
                        py::make_tuple(o.active_begin, o.active_end, o.label, o.rest_at_begin), o.cone_offset,
                        o.projection_tolerance, py::make_tuple(c.physical_tau_min(), c.physical_tau_max()),
                        o.project_on_demand);
}

std::shared_ptr<ContactConstraint> contact_from_state(const py::tuple& t) {
  // 11 / 12 / 13 / 14 entries: a state written before cone_offset / projection_tolerance (then 0) / the
  // physical torque limits (then the stored ones) / project_on_demand (then false).
  if (t.size() < 11 || t.size() > 14) check_state(t, 15, "ContactConstraint");
  ContactOptions o;
  o.cone_edges = t[2].cast<int>();
  o.friction_margin = t[3].cast<double>();
  o.min_normal_force = t[4].cast<double>();
  o.cap = t[5].cast<double>();
  o.min_link_normal_force = t[8].cast<double>();
  o.max_lps = t[9].cast<int>();
  const py::tuple phase = t[10].cast<py::tuple>();
  check_state(phase, 4, "ContactConstraint phase");
  o.active_begin = phase[0].cast<double>();
  o.active_end = phase[1].cast<double>();
  o.label = phase[2].cast<std::string>();
  o.rest_at_begin = phase[3].cast<std::string>();
  if (t.size() >= 12) o.cone_offset = t[11].cast<double>();
  if (t.size() >= 13) o.projection_tolerance = t[12].cast<double>();
  auto robot = t[0].cast<std::shared_ptr<RobotModel>>();
  auto contacts = t[1].cast<std::vector<Contact>>();
  Eigen::VectorXd lo = to_vector(t[6], "tau_min"), hi = to_vector(t[7], "tau_max");
  Eigen::VectorXd plo, phi;
  if (t.size() >= 14) {
    const py::tuple phys = t[13].cast<py::tuple>();
    check_state(phys, 2, "ContactConstraint physical limits");
    plo = to_vector(phys[0], "physical_tau_min");
    phi = to_vector(phys[1], "physical_tau_max");
  }
  if (t.size() >= 15) o.project_on_demand = t[14].cast<bool>();
  py::gil_scoped_release release;
  auto out = std::make_shared<ContactConstraint>(std::move(robot), std::move(contacts), o, std::move(lo), std::move(hi));
  return plo.size() ? out->with_physical_torque_limits(plo, phi) : out;
}

void bind_contact_queries(ContactClass& cls) {
  cls.def("force_distribution", [](const ContactConstraint& c, py::handle q, py::handle qd, py::handle qdd,
                                   py::handle distribution) {
       const ForceDistribution dist = parse_distribution(distribution);
       const bool scalar = as_float_array(q, "q").ndim() == 1;
       auto rows = [&](py::handle h, const char* name) {
         Eigen::MatrixXd a = to_matrix(h, name, true);
         if (scalar) a.transposeInPlace();  // a single configuration: one row
         return a;
       };
       const Eigen::MatrixXd Q = rows(q, "q"), QD = rows(qd, "qd"), QDD = rows(qdd, "qdd");
       std::vector<ContactForces> out;
       {
         py::gil_scoped_release release;
         out = c.force_distribution(Q, QD, QDD, dist);
       }
       return to_force_samples(out, static_cast<int>(c.contacts().size()), c.robot()->nq(), scalar);
     }, "q"_a, "qd"_a, "qdd"_a, "distribution"_a = "centre", doc::ContactConstraint_force_distribution)
      .def("max_drift", [](const ContactConstraint& c, py::handle path_arg, py::handle s) {
        const auto path = to_object<Path>(path_arg, "path", "Path");
        if (path->dof() != c.robot()->nq())
          throw InvalidInput("path has " + std::to_string(path->dof()) + " coordinates, robot '" + c.robot()->name() +
                             "' has " + std::to_string(c.robot()->nq()) + " joints");
        PathSamples ps;
        ps.s = to_path_parameters(s, "s");
        path->evaluate(ps.s, ps.q, ps.dq, ps.ddq);
        int which = -1;
        const double d = c.max_drift(ps, &which);
        return py::make_tuple(d, which);
      }, "path"_a, "s"_a, doc::ContactConstraint_max_drift);
}

void bind_contact_constraint(py::module_& m) {
  ContactClass cls(m, "ContactConstraint", doc::ContactConstraint);
  // active_begin / active_end: one phase's stretch of s (not among the shared options: add_contacts has none, and
  // add_contact_phases sets them per phase).
  auto make = [](py::handle robot, py::handle contacts, py::handle tau_min, py::handle tau_max, py::handle begin,
                 py::handle end, ContactOptions o) {
    o.active_begin = to_double(begin, "active_begin");
    o.active_end = to_double(end, "active_end");
    return std::make_shared<ContactConstraint>(to_object<RobotModel>(robot, "robot", "RobotModel"),
                                               to_contacts(contacts, "contacts"), o, optional_vector(tau_min, "tau_min"),
                                               optional_vector(tau_max, "tau_max"));
  };
  const double inf = std::numeric_limits<double>::infinity();
  def_with_contact_options(
      cls,
      std::make_tuple(py::init(with_contact_options<std::shared_ptr<ContactConstraint>, py::handle, py::handle, py::handle,
                                                    py::handle, py::handle, py::handle>(make))),
      "robot"_a, "contacts"_a, py::kw_only(), "tau_min"_a = py::none(), "tau_max"_a = py::none(), "active_begin"_a = -inf,
      "active_end"_a = inf);
  cls.def_property_readonly("tau_min", &ContactConstraint::tau_min, doc::ContactConstraint_tau_min)
      .def_property_readonly("tau_max", &ContactConstraint::tau_max, doc::ContactConstraint_tau_max)
      .def_property_readonly("physical_tau_min", &ContactConstraint::physical_tau_min, doc::ContactConstraint_physical_tau_min)
      .def_property_readonly("physical_tau_max", &ContactConstraint::physical_tau_max, doc::ContactConstraint_physical_tau_max)
      .def_property_readonly("projected_contacts", &ContactConstraint::projected_contacts,
                             doc::ContactConstraint_projected_contacts)
      .def_property_readonly("section_contacts", &ContactConstraint::section_contacts, doc::ContactConstraint_section_contacts)
      .def_property_readonly("contacts", &ContactConstraint::contacts, doc::ContactConstraint_contacts)
      .def_property_readonly("active_begin", [](const ContactConstraint& c) { return c.options().active_begin; },
                             doc::ContactConstraint_active_begin)
      .def_property_readonly("active_end", [](const ContactConstraint& c) { return c.options().active_end; },
                             doc::ContactConstraint_active_end)
      .def_property_readonly("label", [](const ContactConstraint& c) { return c.options().label; }, doc::ContactConstraint_label)
      .def_property_readonly("rest_at_begin", [](const ContactConstraint& c) { return c.options().rest_at_begin; },
                             doc::ContactConstraint_rest_at_begin)
      .def_property_readonly("robot", [](const ContactConstraint& c) { return std::const_pointer_cast<RobotModel>(c.robot()); },
                             doc::ContactConstraint_robot)
      .def(py::pickle(&contact_state, &contact_from_state));
  bind_contact_queries(cls);
}

}  // namespace

void bind_contacts(py::module_& m) {
  bind_contact(m);
  bind_contact_forces(m);
  bind_contact_constraint(m);
  m.def("contact_phase_of_s", [](py::handle phases, py::handle s) -> py::object {
    std::vector<std::shared_ptr<const ContactConstraint>> v;
    const std::vector<py::object> items = to_items(phases, "phases", "a list of pathpace.ContactConstraint");
    for (size_t i = 0; i < items.size(); ++i)
      v.push_back(to_object<ContactConstraint>(items[i], "phases[" + std::to_string(i) + "]", "ContactConstraint"));
    const Eigen::VectorXi out = contact_phase_of_s(v, to_vector(s, "s"));
    return is_scalar(s) ? py::object(py::int_(out[0])) : py::cast(out);
  }, "phases"_a, "s"_a, doc::contact_phase_of_s);
}

}  // namespace pathpace::python
