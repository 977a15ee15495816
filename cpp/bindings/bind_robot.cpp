// The robot model and torque limits.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "convert.hpp"
#include "robot/torque_lanes.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/path.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/robot_workspace.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

RobotModelOptions options(py::handle floating_base, py::object locked, py::handle gravity) {
  RobotModelOptions o;
  o.floating_base = to_bool(floating_base, "floating_base");
  if (!locked.is_none()) {
    if (!py::isinstance<py::dict>(locked)) type_error("locked_joints", "a dict {joint name: value}", locked);
    for (auto item : locked.cast<py::dict>()) {
      if (!py::isinstance<py::str>(item.first)) type_error("locked_joints key", "a joint name (str)", item.first);
      const std::string joint = item.first.cast<std::string>();
      o.locked_joints[joint] = to_double(item.second, "locked_joints['" + joint + "']");
    }
  }
  const Eigen::VectorXd g = to_vector(gravity, "gravity");
  if (g.size() != 3) throw InvalidInput("gravity has size " + std::to_string(g.size()) + ", expected 3");
  o.gravity = g;
  return o;
}

Eigen::VectorXd qvec(const RobotModel& r, py::handle h, const char* name) {
  Eigen::VectorXd v = to_vector(h, name);
  if (v.size() != r.nq())
    throw InvalidInput(std::string(name) + " has size " + std::to_string(v.size()) + ", robot '" + r.name() + "' has " +
                       std::to_string(r.nq()) + " joints");
  return v;
}

// A model pickles as the record of how it was built (RobotModel::Source), nested for combine().
py::tuple source_state(const RobotModel::Source& s) {
  switch (s.kind) {
    case RobotModel::Source::Kind::Urdf: {
      py::dict locked;
      for (const auto& [name, value] : s.options.locked_joints) locked[py::str(name)] = value;
      return py::make_tuple("urdf", s.urdf, s.options.floating_base, locked, Eigen::VectorXd(s.options.gravity));
    }
    case RobotModel::Source::Kind::Combine: {
      py::list parts;
      for (const RobotModel& p : s.parts) parts.append(source_state(p.source()));
      return py::make_tuple("combine", parts, s.name);
    }
    case RobotModel::Source::Kind::FreeObject:
      return py::make_tuple("free_object", s.name, s.mass, Eigen::VectorXd(s.com), Eigen::MatrixXd(s.inertia),
                            Eigen::VectorXd(s.options.gravity));
  }
  throw InvalidInput("robot model source has an unknown kind");
}

RobotModel::Source state_source(const py::tuple& t) {
  if (t.size() < 1) throw InvalidInput("RobotModel pickle state is empty");
  const std::string kind = t[0].cast<std::string>();
  RobotModel::Source s;
  if (kind == "urdf") {
    check_state(t, 5, "RobotModel (urdf)");
    s.kind = RobotModel::Source::Kind::Urdf;
    s.urdf = t[1].cast<std::string>();
    s.options = options(t[2], t[3], t[4]);
  } else if (kind == "combine") {
    check_state(t, 3, "RobotModel (combine)");
    s.kind = RobotModel::Source::Kind::Combine;
    for (auto part : t[1].cast<py::list>()) s.parts.push_back(RobotModel::rebuild(state_source(part.cast<py::tuple>())));
    s.name = t[2].cast<std::string>();
  } else if (kind == "free_object") {
    check_state(t, 6, "RobotModel (free_object)");
    s.kind = RobotModel::Source::Kind::FreeObject;
    s.name = t[1].cast<std::string>();
    s.mass = t[2].cast<double>();
    s.com = to_vector(t[3], "com");
    s.inertia = to_matrix(t[4], "inertia");
    s.options.gravity = to_vector(t[5], "gravity");
  } else {
    throw InvalidInput("RobotModel pickle state kind = '" + kind + "' must be 'urdf', 'combine' or 'free_object'");
  }
  return s;
}

}  // namespace

void bind_robot(py::module_& m) {
  // RobotModel.from_urdf and, under the C++ name, RobotModel.from_urdf_file.
  const auto from_urdf_file = [](py::handle path, py::handle floating_base, py::object locked_joints, py::handle gravity) {
    const std::string file = to_string_arg(path, "path", true);
    return std::make_shared<RobotModel>(RobotModel::from_urdf_file(file, options(floating_base, locked_joints, gravity)));
  };
  py::class_<RobotModel, std::shared_ptr<RobotModel>>(m, "RobotModel", "A rigid-body tree from a URDF (immutable).")
      .def_static("from_urdf", from_urdf_file, "path"_a, "floating_base"_a = false, "locked_joints"_a = py::none(), "gravity"_a = py::make_tuple(0.0, 0.0, -9.81))
      .def_static("from_urdf_string", [](py::handle xml, py::handle floating_base, py::object locked_joints, py::handle gravity) {
        const std::string text = to_string_arg(xml, "xml");
        return std::make_shared<RobotModel>(RobotModel::from_urdf_string(text, options(floating_base, locked_joints, gravity)));
      }, "xml"_a, "floating_base"_a = false, "locked_joints"_a = py::none(), "gravity"_a = py::make_tuple(0.0, 0.0, -9.81))
      .def_static("combine", [](py::handle parts, py::handle name) {
        const std::vector<py::object> items = to_items(parts, "parts", "a list of pathpace.RobotModel");
        std::vector<RobotModel> v;
        for (size_t i = 0; i < items.size(); ++i)
          v.push_back(*to_object<RobotModel>(items[i], "parts[" + std::to_string(i) + "]", "RobotModel"));
        return std::make_shared<RobotModel>(RobotModel::combine(v, to_string_arg(name, "name")));
      }, "parts"_a, "name"_a = "",
         "One model of several independent trees (robots and free objects, sec. III.b); q concatenates the parts'. "
         "Link names must be unique; a joint name shared by parts becomes '<part>/<joint>'.")
      .def_static("free_object", [](py::handle name_arg, py::handle mass_arg, py::handle com, py::handle inertia, py::handle gravity) {
        const std::string name = to_string_arg(name_arg, "name");
        const double mass = to_double(mass_arg, "mass");
        const Eigen::VectorXd c = to_vector(com, "com"), g = to_vector(gravity, "gravity");
        if (c.size() != 3) throw InvalidInput("com has size " + std::to_string(c.size()) + ", expected 3");
        if (g.size() != 3) throw InvalidInput("gravity has size " + std::to_string(g.size()) + ", expected 3");
        const Eigen::MatrixXd I = to_matrix(inertia, "inertia");
        if (I.rows() != 3 || I.cols() != 3)
          throw InvalidInput("inertia has shape (" + std::to_string(I.rows()) + ", " + std::to_string(I.cols()) + "), expected (3, 3)");
        return std::make_shared<RobotModel>(RobotModel::free_object(name, mass, c, I, g));
      }, "name"_a, "mass"_a, "com"_a = py::make_tuple(0.0, 0.0, 0.0),
         "inertia"_a = Eigen::MatrixXd(Eigen::MatrixXd::Zero(3, 3)), "gravity"_a = py::make_tuple(0.0, 0.0, -9.81),
         "A free rigid body: one link `name` with six floating coordinates (x, y, z, rz, ry, rx) and zero effort; "
         "inertia about the centre of mass `com`, in the link frame.")
      .def_property_readonly("nq", &RobotModel::nq)
      .def_property_readonly("name", &RobotModel::name)
      .def_property_readonly("joint_names", &RobotModel::joint_names)
      .def_property_readonly("joint_units", [](const RobotModel& r) {
        std::vector<std::string> out;
        for (RobotModel::JointType t : r.joint_types()) out.push_back(t == RobotModel::JointType::Prismatic ? "m" : "rad");
        return out;
      }, "The unit of each coordinate q[j]: 'rad' (revolute) or 'm' (prismatic; a floating base's x, y, z)")
      .def_property_readonly("link_names", &RobotModel::link_names)
      .def_property_readonly("velocity_limits", &RobotModel::velocity_limits)
      .def_property_readonly("effort_limits", &RobotModel::effort_limits)
      .def_property_readonly("position_limits", [](const RobotModel& r) {
        Eigen::MatrixXd l(2, r.nq());
        l.row(0) = r.lower_position_limits().transpose();
        l.row(1) = r.upper_position_limits().transpose();
        return l;
      }, "(2, nq): lower and upper")
      .def_property_readonly("gravity_vector", &RobotModel::gravity, "the gravity acceleration in the world frame")
      .def("center_of_mass", [](const RobotModel& r, py::handle q) { return r.center_of_mass(qvec(r, q, "q")); }, "q"_a,
           "Centre of mass of the moving bodies at q.\n\n"
           "Parameters\n----------\nq : array_like (nq,)\n    Joint positions (rad or m).\n\n"
           "Returns\n-------\nndarray (3,)\n    World coordinates in m. Links fixed to the world are not counted "
           "(as pinocchio's centerOfMass).")
      .def_property_readonly("mass", &RobotModel::mass, "float: total mass of the moving bodies in kg")
      // The C++ names, so that code reads the same in both languages.
      .def_static("from_urdf_file", from_urdf_file, "path"_a, "floating_base"_a = false, "locked_joints"_a = py::none(), "gravity"_a = py::make_tuple(0.0, 0.0, -9.81))
      .def("gravity_torques", [](const RobotModel& r, py::handle q) { return r.gravity_torques(qvec(r, q, "q")); }, "q"_a)
      .def_property_readonly("mimic_joints", [](const RobotModel& r) {
        py::list out;
        for (const auto& mj : r.mimic_joints()) out.append(py::make_tuple(mj.name, mj.joint, mj.multiplier, mj.offset));
        return out;
      }, "list of (name, joint, multiplier, offset): q[name] = multiplier · q[joint] + offset; not in q")
      .def(py::pickle([](const RobotModel& r) { return source_state(r.source()); },
                      [](const py::tuple& t) { return std::make_shared<RobotModel>(RobotModel::rebuild(state_source(t))); }))
      .def("inverse_dynamics", [](const RobotModel& r, py::handle q, py::handle qd, py::handle qdd) {
        return r.inverse_dynamics(qvec(r, q, "q"), qvec(r, qd, "qd"), qvec(r, qdd, "qdd"));
      }, "q"_a, "qd"_a, "qdd"_a, "τ = M(q) q̈ + C(q, q̇) q̇ + g(q)")
      .def("mass_matrix", [](const RobotModel& r, py::handle q) { return r.mass_matrix(qvec(r, q, "q")); }, "q"_a)
      .def("gravity", [](const RobotModel& r, py::handle q) { return r.gravity_torques(qvec(r, q, "q")); }, "q"_a,
           "g(q): the joint torques that hold the robot still at q")
      .def("frame_placement", [](const RobotModel& r, py::handle q, py::handle link) {
        return r.frame_placement(qvec(r, q, "q"), to_string_arg(link, "link"));
      }, "q"_a, "link"_a, "4x4 world placement of the link frame")
      .def("point_jacobian", [](const RobotModel& r, py::handle q, py::handle link, py::handle point) {
        const std::string l = to_string_arg(link, "link");
        const Eigen::VectorXd p = to_vector(point, "point");
        if (p.size() != 3) throw InvalidInput("point has size " + std::to_string(p.size()) + ", expected 3");
        return r.point_jacobian(qvec(r, q, "q"), l, p);
      }, "q"_a, "link"_a, "point"_a = py::make_tuple(0.0, 0.0, 0.0), "(3, nq) world-frame Jacobian of a point fixed in the link")
      .def("path_torque_coefficients", [](const RobotModel& r, py::handle q, py::handle dq, py::handle ddq) {
        const Eigen::MatrixXd Q = to_matrix(q, "q"), D = to_matrix(dq, "dq"), DD = to_matrix(ddq, "ddq");
        if (Q.cols() != r.nq()) throw InvalidInput("q has " + std::to_string(Q.cols()) + " columns, robot has " + std::to_string(r.nq()) + " joints");
        if (D.rows() != Q.rows() || D.cols() != Q.cols() || DD.rows() != Q.rows() || DD.cols() != Q.cols())
          throw InvalidInput("q, dq and ddq must have the same shape (m, nq)");
        Eigen::MatrixXd A(Q.rows(), Q.cols()), B(Q.rows(), Q.cols()), C(Q.rows(), Q.cols());
        {
          py::gil_scoped_release release;
          RobotWorkspace ws(r);
          Eigen::VectorXd a(r.nq()), b(r.nq()), c(r.nq());
          for (Eigen::Index k = 0; k < Q.rows(); ++k) {
            r.path_torque_coefficients(ws, Q.row(k).transpose(), D.row(k).transpose(), DD.row(k).transpose(), a, b, c);
            A.row(k) = a.transpose();
            B.row(k) = b.transpose();
            C.row(k) = c.transpose();
          }
        }
        return py::make_tuple(A, B, C);
      }, "q"_a, "dq"_a, "ddq"_a, "eq. (12): τ = a ṡ² + b s̈ + c at each row; arrays (m, nq)")
      .def_property_readonly("frozen_mimic_joints", &RobotModel::frozen_mimic_joints,
                             "Mimic joints locked without their joint: frozen at their value while their joint moves "
                             "(the relation dropped, as in a model reduced on them alone); lock their joint to keep it")
      .def("__repr__", [](const RobotModel& r) {
        std::string s = "<RobotModel '" + r.name() + "' nq=" + std::to_string(r.nq());
        if (!r.frozen_mimic_joints().empty()) {
          s += " frozen_mimic_joints=[";
          for (size_t i = 0; i < r.frozen_mimic_joints().size(); ++i) s += (i ? ", '" : "'") + r.frozen_mimic_joints()[i] + "'";
          s += "]";
        }
        return s + ">";
      });

  py::class_<TorqueLimits, Constraint, py::smart_holder>(m, "TorqueLimits")
      .def(py::init([](py::handle robot, py::object tau_min, py::object tau_max, py::handle scale, py::handle margin) {
             auto r = to_object<RobotModel>(robot, "robot", "RobotModel");
             Eigen::VectorXd lo = optional_vector(tau_min, "tau_min");
             Eigen::VectorXd hi = optional_vector(tau_max, "tau_max");
             return std::make_shared<TorqueLimits>(std::move(r), lo, hi, to_double(scale, "scale"), to_double(margin, "margin"));
           }),
           "robot"_a, "tau_min"_a = py::none(), "tau_max"_a = py::none(), "scale"_a = 1.0, "margin"_a = 0.0)
      .def_property_readonly("tau_min", &TorqueLimits::tau_min)
      .def_property_readonly("tau_max", &TorqueLimits::tau_max)
      // The stored limits already include scale and margin: rebuilt with scale 1 and margin 0.
      .def(py::pickle([](const TorqueLimits& c) {
                        return py::make_tuple(std::const_pointer_cast<RobotModel>(c.robot()), c.tau_min(), c.tau_max());
                      },
                      [](const py::tuple& t) {
                        check_state(t, 3, "TorqueLimits");
                        return std::make_shared<TorqueLimits>(t[0].cast<std::shared_ptr<RobotModel>>(), to_vector(t[1], "tau_min"),
                                                              to_vector(t[2], "tau_max"), 1.0, 0.0);
                      }));

  py::class_<Contact>(m, "Contact",
                      "A point fixed in a link (link coordinates) touching the world, or `other_link` when given. The "
                      "normal points into `link`: world coordinates for a world contact, other_link's frame otherwise.")
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
      .def_readonly("link", &Contact::link)
      .def_readonly("point", &Contact::point)
      .def_readonly("normal", &Contact::normal)
      .def_readonly("friction", &Contact::friction)
      .def_property_readonly("other_link", [](const Contact& c) -> py::object {
        return c.other_link.empty() ? py::object(py::none()) : py::object(py::str(c.other_link));
      })
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

  py::class_<ForceSamples>(m, "ContactForces",
                           "Force-distribution LP results: the most robust contact forces at each sample and their "
                           "margin in N (>= 0: realisable within the cones; < 0: needs forces that do not exist).")
      .def_property_readonly("feasible", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::bool_(f.feasible.at(0))) : py::object(f.feasible);
      }, "False where no forces of any sign meet the torque limits")
      .def_property_readonly("margin", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::float_(f.margin[0])) : py::cast(f.margin);
      }, "δ in N: the smallest cone weight, or normal force beyond the minimum")
      .def_property_readonly("forces", [](const ForceSamples& f) -> py::object {
        if (!f.scalar) return f.forces;
        return f.forces.attr("__getitem__")(0);
      }, "(samples, contacts, 3) world-frame force on each contact's link")
      .def_property_readonly("torques", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::cast(Eigen::VectorXd(f.torques.row(0).transpose())) : py::cast(f.torques);
      }, "(samples, nq) joint torques with these forces")
      .def_property_readonly("phase", [](const ForceSamples& f) -> py::object {
        return f.scalar ? py::object(py::int_(f.phase[0])) : py::cast(f.phase);
      }, "index of the contact phase of each sample (Trajectory.contact_forces with add_contact_phases: the later "
         "phase at a switch); -1 without phases. forces has max contacts over the phases rows, NaN beyond a phase's own");

  py::class_<ContactConstraint, Constraint, py::smart_holder>(m, "ContactConstraint")
      .def(py::init([](py::handle robot, py::handle contacts, py::handle cone_edges, py::handle friction_margin,
                       py::handle min_normal_force, py::handle torque_scale, py::handle torque_margin, py::handle tau_min,
                       py::handle tau_max, py::handle min_link_normal_force, py::handle max_lps, py::handle cone_offset,
                       py::handle projection_tolerance) {
             const ContactOptions o = contact_options_arg(cone_edges, friction_margin, min_normal_force, torque_scale,
                                                          torque_margin, min_link_normal_force, max_lps, cone_offset,
                                                          projection_tolerance);
             return std::make_shared<ContactConstraint>(to_object<RobotModel>(robot, "robot", "RobotModel"),
                                                        to_contacts(contacts, "contacts"), o,
                                                        optional_vector(tau_min, "tau_min"), optional_vector(tau_max, "tau_max"));
           }),
           "robot"_a, "contacts"_a, "cone_edges"_a = 8, "friction_margin"_a = 0.0, "min_normal_force"_a = 0.0,
           "torque_scale"_a = 1.0, "torque_margin"_a = 0.0, "tau_min"_a = py::none(), "tau_max"_a = py::none(),
           "min_link_normal_force"_a = 0.0, "max_lps"_a = 2000, "cone_offset"_a = 0.0, "projection_tolerance"_a = 0.0,
           "See TimeScalingProblem.add_contacts: points in link frames, normals in the world frame; margins per "
           "point (min_normal_force, cone_offset) and per link (min_link_normal_force).")
      .def_property_readonly("tau_min", &ContactConstraint::tau_min, "after scale and margin (and any merged TorqueLimits)")
      .def_property_readonly("tau_max", &ContactConstraint::tau_max)
      .def_property_readonly("projected_contacts", &ContactConstraint::projected_contacts,
                             "indices of the contacts whose cone weights enter the projection LPs (flat groups: hull vertices)")
      .def_property_readonly("section_contacts", &ContactConstraint::section_contacts,
                             "indices of the contacts whose per-point minimum enters the projection LPs as k/2 bounded "
                             "tangential weights (min_normal_force > cone_offset, even cone_edges, reduced flat groups)")
      .def_property_readonly("contacts", &ContactConstraint::contacts)
      .def_property_readonly("active_begin", [](const ContactConstraint& c) { return c.options().active_begin; },
                             "the phase's first s (-inf: the whole path; see TimeScalingProblem.add_contact_phases)")
      .def_property_readonly("active_end", [](const ContactConstraint& c) { return c.options().active_end; })
      .def_property_readonly("label", [](const ContactConstraint& c) { return c.options().label; },
                             "prefix of its row labels, e.g. 'phases[1]'")
      .def_property_readonly("rest_at_begin", [](const ContactConstraint& c) { return c.options().rest_at_begin; },
                             "the no-impact row's label if the phase forces sdot = 0 at its first point, else ''")
      // Rebuilt from the robot, contacts, options and the stored limits (which include torque_scale and
      // torque_margin, so those are 1 and 0 in the copy).
      .def(py::pickle([](const ContactConstraint& c) {
                        const ContactOptions& o = c.options();
                        return py::make_tuple(std::const_pointer_cast<RobotModel>(c.robot()), c.contacts(), o.cone_edges,
                                              o.friction_margin, o.min_normal_force, o.cap, c.tau_min(), c.tau_max(),
                                              o.min_link_normal_force, o.max_lps,
                                              py::make_tuple(o.active_begin, o.active_end, o.label, o.rest_at_begin),
                                              o.cone_offset, o.projection_tolerance);
                      },
                      [](const py::tuple& t) {
                        // 11 / 12 entries: a state written before cone_offset / projection_tolerance (then 0).
                        if (t.size() != 11 && t.size() != 12) check_state(t, 13, "ContactConstraint");
                        ContactOptions o = contact_options(t[2].cast<int>(), t[3].cast<double>(), t[4].cast<double>(), 1.0, 0.0);
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
                        std::shared_ptr<ContactConstraint> out;
                        {
                          py::gil_scoped_release release;
                          out = std::make_shared<ContactConstraint>(std::move(robot), std::move(contacts), o, std::move(lo),
                                                                    std::move(hi));
                        }
                        return out;
                      }))
      .def_property_readonly("robot", [](const ContactConstraint& c) { return std::const_pointer_cast<RobotModel>(c.robot()); })
      .def("force_distribution", [](const ContactConstraint& c, py::handle q, py::handle qd, py::handle qdd) {
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
          out = c.force_distribution(Q, QD, QDD);
        }
        return to_force_samples(out, static_cast<int>(c.contacts().size()), c.robot()->nq(), scalar);
      }, "q"_a, "qd"_a, "qdd"_a,
         "The force-distribution LP at each row of q, qd, qdd (arrays (samples, nq), or one configuration): "
         "how a timing is audited between grid points.")
      .def("max_drift", [](const ContactConstraint& c, py::handle path_arg, py::handle s) {
        const auto path = to_object<Path>(path_arg, "path", "Path");
        if (path->dof() != c.robot()->nq())
          throw InvalidInput("path has " + std::to_string(path->dof()) + " coordinates, robot '" + c.robot()->name() +
                             "' has " + std::to_string(c.robot()->nq()) + " joints");
        Eigen::MatrixXd q, dq, ddq;
        const Eigen::VectorXd sv = to_vector(s, "s");
        for (Eigen::Index i = 0; i < sv.size(); ++i)
          if (std::isnan(sv[i])) throw InvalidInput("s[" + std::to_string(i) + "] = nan must be a number");
        path->evaluate(sv, q, dq, ddq);
        PathSamples ps;
        ps.s = sv;
        ps.q = q;
        ps.dq = dq;
        ps.ddq = ddq;
        int which = -1;
        const double d = c.max_drift(ps, &which);
        return py::make_tuple(d, which);
      }, "path"_a, "s"_a, "(largest distance a contact point moves along path at s, index of that contact)");

  m.def("_torque_lanes_supported", &detail::torque_lanes_supported,
        "Samples per sweep of the widest torque-row variant this CPU runs (8, 4, 2 or 1); the environment "
        "variable PATHPACE_TORQUE_LANES forces a narrower one (tests run each).");
}

}  // namespace pathpace::python
