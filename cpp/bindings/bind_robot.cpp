// The robot model.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "convert.hpp"
#include "docstrings.hpp"
#include "robot/torque_lanes.hpp"
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

void bind_robot_constructors(py::class_<RobotModel, std::shared_ptr<RobotModel>>& cls) {
  // RobotModel.from_urdf and, under the C++ name, RobotModel.from_urdf_file.
  const auto from_urdf_file = [](py::handle path, py::handle floating_base, py::object locked_joints, py::handle gravity) {
    const std::string file = to_string_arg(path, "path", true);
    return std::make_shared<RobotModel>(RobotModel::from_urdf_file(file, options(floating_base, locked_joints, gravity)));
  };
  cls.def_static("from_urdf", from_urdf_file, "path"_a, "floating_base"_a = false, "locked_joints"_a = py::none(),
                 "gravity"_a = py::make_tuple(0.0, 0.0, -9.81), doc::RobotModel_from_urdf)
      .def_static("from_urdf_string", [](py::handle xml, py::handle floating_base, py::object locked_joints, py::handle gravity) {
        const std::string text = to_string_arg(xml, "xml");
        return std::make_shared<RobotModel>(RobotModel::from_urdf_string(text, options(floating_base, locked_joints, gravity)));
      }, "xml"_a, "floating_base"_a = false, "locked_joints"_a = py::none(), "gravity"_a = py::make_tuple(0.0, 0.0, -9.81),
         doc::RobotModel_from_urdf_string)
      .def_static("combine", [](py::handle parts, py::handle name) {
        const std::vector<py::object> items = to_items(parts, "parts", "a list of pathpace.RobotModel");
        std::vector<RobotModel> v;
        for (size_t i = 0; i < items.size(); ++i)
          v.push_back(*to_object<RobotModel>(items[i], "parts[" + std::to_string(i) + "]", "RobotModel"));
        return std::make_shared<RobotModel>(RobotModel::combine(v, to_string_arg(name, "name")));
      }, "parts"_a, "name"_a = "", doc::RobotModel_combine)
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
         doc::RobotModel_free_object)
      // The C++ name, so that code reads the same in both languages.
      .def_static("from_urdf_file", from_urdf_file, "path"_a, "floating_base"_a = false, "locked_joints"_a = py::none(),
                  "gravity"_a = py::make_tuple(0.0, 0.0, -9.81), doc::RobotModel_from_urdf_file)
      .def(py::pickle([](const RobotModel& r) { return source_state(r.source()); },
                      [](const py::tuple& t) { return std::make_shared<RobotModel>(RobotModel::rebuild(state_source(t))); }));
}

void bind_robot_properties(py::class_<RobotModel, std::shared_ptr<RobotModel>>& cls) {
  cls.def_property_readonly("nq", &RobotModel::nq, doc::RobotModel_nq)
      .def_property_readonly("name", &RobotModel::name, doc::RobotModel_name)
      .def_property_readonly("joint_names", &RobotModel::joint_names, doc::RobotModel_joint_names)
      .def_property_readonly("joint_units", [](const RobotModel& r) {
        std::vector<std::string> out;
        for (RobotModel::JointType t : r.joint_types()) out.push_back(t == RobotModel::JointType::Prismatic ? "m" : "rad");
        return out;
      }, doc::RobotModel_joint_units)
      .def_property_readonly("link_names", &RobotModel::link_names, doc::RobotModel_link_names)
      .def_property_readonly("velocity_limits", &RobotModel::velocity_limits, doc::RobotModel_velocity_limits)
      .def_property_readonly("effort_limits", &RobotModel::effort_limits, doc::RobotModel_effort_limits)
      .def_property_readonly("position_limits", [](const RobotModel& r) {
        Eigen::MatrixXd l(2, r.nq());
        l.row(0) = r.lower_position_limits().transpose();
        l.row(1) = r.upper_position_limits().transpose();
        return l;
      }, doc::RobotModel_position_limits)
      .def_property_readonly("gravity_vector", &RobotModel::gravity, doc::RobotModel_gravity_vector)
      .def_property_readonly("mass", &RobotModel::mass, doc::RobotModel_mass)
      .def_property_readonly("mimic_joints", [](const RobotModel& r) {
        py::list out;
        for (const auto& mj : r.mimic_joints()) out.append(py::make_tuple(mj.name, mj.joint, mj.multiplier, mj.offset));
        return out;
      }, doc::RobotModel_mimic_joints)
      .def_property_readonly("frozen_mimic_joints", &RobotModel::frozen_mimic_joints, doc::RobotModel_frozen_mimic_joints)
      .def("__repr__", [](const RobotModel& r) {
        std::string s = "<RobotModel '" + r.name() + "' nq=" + std::to_string(r.nq());
        if (!r.frozen_mimic_joints().empty()) {
          s += " frozen_mimic_joints=[";
          for (size_t i = 0; i < r.frozen_mimic_joints().size(); ++i) s += (i ? ", '" : "'") + r.frozen_mimic_joints()[i] + "'";
          s += "]";
        }
        return s + ">";
      });
}

void bind_robot_dynamics(py::class_<RobotModel, std::shared_ptr<RobotModel>>& cls) {
  cls.def("center_of_mass", [](const RobotModel& r, py::handle q) { return r.center_of_mass(qvec(r, q, "q")); }, "q"_a,
          doc::RobotModel_center_of_mass)
      .def("gravity_torques", [](const RobotModel& r, py::handle q) { return r.gravity_torques(qvec(r, q, "q")); }, "q"_a,
           doc::RobotModel_gravity_torques)
      .def("inverse_dynamics", [](const RobotModel& r, py::handle q, py::handle qd, py::handle qdd) {
        return r.inverse_dynamics(qvec(r, q, "q"), qvec(r, qd, "qd"), qvec(r, qdd, "qdd"));
      }, "q"_a, "qd"_a, "qdd"_a, doc::RobotModel_inverse_dynamics)
      .def("mass_matrix", [](const RobotModel& r, py::handle q) { return r.mass_matrix(qvec(r, q, "q")); }, "q"_a,
           doc::RobotModel_mass_matrix)
      .def("gravity", [](const RobotModel& r, py::handle q) { return r.gravity_torques(qvec(r, q, "q")); }, "q"_a,
           doc::RobotModel_gravity)
      .def("frame_placement", [](const RobotModel& r, py::handle q, py::handle link) {
        return r.frame_placement(qvec(r, q, "q"), to_string_arg(link, "link"));
      }, "q"_a, "link"_a, doc::RobotModel_frame_placement)
      .def("point_jacobian", [](const RobotModel& r, py::handle q, py::handle link, py::handle point) {
        const std::string l = to_string_arg(link, "link");
        const Eigen::VectorXd p = to_vector(point, "point");
        if (p.size() != 3) throw InvalidInput("point has size " + std::to_string(p.size()) + ", expected 3");
        return r.point_jacobian(qvec(r, q, "q"), l, p);
      }, "q"_a, "link"_a, "point"_a = py::make_tuple(0.0, 0.0, 0.0), doc::RobotModel_point_jacobian)
      .def("frame_jacobian", [](const RobotModel& r, py::handle q, py::handle link, py::handle point) {
        const std::string l = to_string_arg(link, "link");
        return r.frame_jacobian(qvec(r, q, "q"), l, to_point(point, "point"));
      }, "q"_a, "link"_a, "point"_a = py::make_tuple(0.0, 0.0, 0.0), doc::RobotModel_frame_jacobian)
      .def("path_frame_motion", [](const RobotModel& r, py::handle q, py::handle dq, py::handle ddq, py::handle link,
                                   py::handle point) {
        const Eigen::MatrixXd Q = to_matrix(q, "q"), D = to_matrix(dq, "dq"), DD = to_matrix(ddq, "ddq");
        const std::string l = to_string_arg(link, "link");
        const Eigen::Vector3d p = to_point(point, "point");
        RobotModel::FrameMotion f;
        {
          py::gil_scoped_release release;
          f = r.path_frame_motion(Q, D, DD, l, p);
        }
        return py::make_tuple(f.velocity, f.angular_velocity, f.acceleration, f.angular_acceleration);
      }, "q"_a, "dq"_a, "ddq"_a, "link"_a, "point"_a = py::make_tuple(0.0, 0.0, 0.0), doc::RobotModel_path_frame_motion)
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
      }, "q"_a, "dq"_a, "ddq"_a, doc::RobotModel_path_torque_coefficients);
}

}  // namespace

void bind_robot(py::module_& m) {
  py::class_<RobotModel, std::shared_ptr<RobotModel>> cls(m, "RobotModel", doc::RobotModel);
  bind_robot_constructors(cls);
  bind_robot_properties(cls);
  bind_robot_dynamics(cls);
  m.def("_torque_lanes_supported", &detail::torque_lanes_supported, doc::torque_lanes_supported);
}

}  // namespace pathpace::python
