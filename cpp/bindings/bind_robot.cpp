// The robot model and torque limits.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
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

RobotModelOptions options(bool floating_base, py::object locked, py::handle gravity) {
  RobotModelOptions o;
  o.floating_base = floating_base;
  if (!locked.is_none()) {
    if (!py::isinstance<py::dict>(locked)) throw InvalidInput("locked_joints must be a dict {joint name: value}");
    for (auto item : locked.cast<py::dict>()) o.locked_joints[item.first.cast<std::string>()] = item.second.cast<double>();
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

}  // namespace

void bind_robot(py::module_& m) {
  py::class_<RobotModel, std::shared_ptr<RobotModel>>(m, "RobotModel", "A rigid-body tree from a URDF (immutable).")
      .def_static("from_urdf", [](const std::string& path, bool floating_base, py::object locked_joints, py::handle gravity) {
        return std::make_shared<RobotModel>(RobotModel::from_urdf_file(path, options(floating_base, locked_joints, gravity)));
      }, "path"_a, "floating_base"_a = false, "locked_joints"_a = py::none(), "gravity"_a = py::make_tuple(0.0, 0.0, -9.81))
      .def_static("from_urdf_string", [](const std::string& xml, bool floating_base, py::object locked_joints, py::handle gravity) {
        return std::make_shared<RobotModel>(RobotModel::from_urdf_string(xml, options(floating_base, locked_joints, gravity)));
      }, "xml"_a, "floating_base"_a = false, "locked_joints"_a = py::none(), "gravity"_a = py::make_tuple(0.0, 0.0, -9.81))
      .def_static("combine", [](const std::vector<std::shared_ptr<RobotModel>>& parts, const std::string& name) {
        std::vector<RobotModel> v;
        for (size_t i = 0; i < parts.size(); ++i) {
          if (!parts[i]) throw InvalidInput("parts[" + std::to_string(i) + "] must be a RobotModel, not None");
          v.push_back(*parts[i]);
        }
        return std::make_shared<RobotModel>(RobotModel::combine(v, name));
      }, "parts"_a, "name"_a = "",
         "One model of several independent trees (robots and free objects, sec. III.b); q concatenates the parts'. "
         "Link names must be unique; a joint name shared by parts becomes '<part>/<joint>'.")
      .def_static("free_object", [](const std::string& name, double mass, py::handle com, py::handle inertia, py::handle gravity) {
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
      .def("inverse_dynamics", [](const RobotModel& r, py::handle q, py::handle qd, py::handle qdd) {
        return r.inverse_dynamics(qvec(r, q, "q"), qvec(r, qd, "qd"), qvec(r, qdd, "qdd"));
      }, "q"_a, "qd"_a, "qdd"_a, "τ = M(q) q̈ + C(q, q̇) q̇ + g(q)")
      .def("mass_matrix", [](const RobotModel& r, py::handle q) { return r.mass_matrix(qvec(r, q, "q")); }, "q"_a)
      .def("gravity", [](const RobotModel& r, py::handle q) { return r.gravity_torques(qvec(r, q, "q")); }, "q"_a,
           "g(q): the joint torques that hold the robot still at q")
      .def("frame_placement", [](const RobotModel& r, py::handle q, const std::string& link) {
        return r.frame_placement(qvec(r, q, "q"), link);
      }, "q"_a, "link"_a, "4x4 world placement of the link frame")
      .def("point_jacobian", [](const RobotModel& r, py::handle q, const std::string& link, py::handle point) {
        const Eigen::VectorXd p = to_vector(point, "point");
        if (p.size() != 3) throw InvalidInput("point has size " + std::to_string(p.size()) + ", expected 3");
        return r.point_jacobian(qvec(r, q, "q"), link, p);
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
      .def("__repr__", [](const RobotModel& r) { return "<RobotModel '" + r.name() + "' nq=" + std::to_string(r.nq()) + ">"; });

  py::class_<TorqueLimits, Constraint, std::shared_ptr<TorqueLimits>>(m, "TorqueLimits")
      .def(py::init([](std::shared_ptr<RobotModel> robot, py::object tau_min, py::object tau_max, double scale, double margin) {
             Eigen::VectorXd lo = tau_min.is_none() ? Eigen::VectorXd() : to_vector(tau_min, "tau_min");
             Eigen::VectorXd hi = tau_max.is_none() ? Eigen::VectorXd() : to_vector(tau_max, "tau_max");
             return std::make_shared<TorqueLimits>(std::move(robot), lo, hi, scale, margin);
           }),
           "robot"_a, "tau_min"_a = py::none(), "tau_max"_a = py::none(), "scale"_a = 1.0, "margin"_a = 0.0)
      .def_property_readonly("tau_min", &TorqueLimits::tau_min)
      .def_property_readonly("tau_max", &TorqueLimits::tau_max);

  py::class_<Contact>(m, "Contact",
                      "A point fixed in a link (link coordinates) touching the world, or `other_link` when given. The "
                      "normal points into `link`: world coordinates for a world contact, other_link's frame otherwise.")
      .def(py::init([](const std::string& link, py::handle point, py::handle normal, double friction, py::object other_link) {
             Contact c;
             c.link = link;
             if (!other_link.is_none()) c.other_link = other_link.cast<std::string>();
             const Eigen::VectorXd p = to_vector(point, "point"), nrm = to_vector(normal, "normal");
             if (p.size() != 3) throw InvalidInput("point has size " + std::to_string(p.size()) + ", expected 3");
             if (nrm.size() != 3) throw InvalidInput("normal has size " + std::to_string(nrm.size()) + ", expected 3");
             c.point = p;
             c.normal = nrm;
             c.friction = friction;
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
      }, "(samples, nq) joint torques with these forces");

  py::class_<ContactConstraint, Constraint, std::shared_ptr<ContactConstraint>>(m, "ContactConstraint")
      .def(py::init([](std::shared_ptr<RobotModel> robot, std::vector<Contact> contacts, int cone_edges, double friction_margin,
                       double min_normal_force, double torque_scale, double torque_margin, py::object tau_min,
                       py::object tau_max, double min_link_normal_force, int max_lps) {
             ContactOptions o = contact_options(cone_edges, friction_margin, min_normal_force, torque_scale, torque_margin);
             o.min_link_normal_force = min_link_normal_force;
             o.max_lps = max_lps;
             return std::make_shared<ContactConstraint>(
                 std::move(robot), std::move(contacts), o,
                 tau_min.is_none() ? Eigen::VectorXd() : to_vector(tau_min, "tau_min"),
                 tau_max.is_none() ? Eigen::VectorXd() : to_vector(tau_max, "tau_max"));
           }),
           "robot"_a, "contacts"_a, "cone_edges"_a = 8, "friction_margin"_a = 0.0, "min_normal_force"_a = 0.0,
           "torque_scale"_a = 1.0, "torque_margin"_a = 0.0, "tau_min"_a = py::none(), "tau_max"_a = py::none(),
           "min_link_normal_force"_a = 0.0, "max_lps"_a = 2000,
           "See TimeScalingProblem.add_contacts: points in link frames, normals in the world frame; margins per "
           "point (min_normal_force) and per link (min_link_normal_force).")
      .def_property_readonly("tau_min", &ContactConstraint::tau_min, "after scale and margin (and any merged TorqueLimits)")
      .def_property_readonly("tau_max", &ContactConstraint::tau_max)
      .def_property_readonly("projected_contacts", &ContactConstraint::projected_contacts,
                             "indices of the contacts whose forces enter the projection LPs (flat groups: hull vertices)")
      .def_property_readonly("contacts", &ContactConstraint::contacts)
      .def_property_readonly("robot", [](const ContactConstraint& c) { return std::const_pointer_cast<RobotModel>(c.robot()); })
      .def("force_distribution", [](const ContactConstraint& c, py::handle q, py::handle qd, py::handle qdd) {
        const bool scalar = py::array(py::reinterpret_borrow<py::object>(q)).ndim() == 1;
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
      .def("max_drift", [](const ContactConstraint& c, const std::shared_ptr<Path>& path, py::handle s) {
        Eigen::MatrixXd q, dq, ddq;
        const Eigen::VectorXd sv = to_vector(s, "s");
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
}

}  // namespace pathpace::python
