// The Constraint base and the kinematic and torque constraints (contacts: bind_contacts.cpp).
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/constraints/acceleration_limits.hpp"
#include "pathpace/constraints/jerk_limits.hpp"
#include "pathpace/constraints/frame_limits.hpp"
#include "pathpace/constraints/linear_constraint.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/constraints/velocity_limits.hpp"
#include "pathpace/path_samples.hpp"
#include "pathpace/robot_model.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

// VelocityLimits and AccelerationLimits: (lo, hi, joint_names), named `lo_name`, `hi_name` in Python.
template <typename Limits>
void bind_joint_limits(py::module_& m, const char* name, const char* doc, const char* lo_name, const char* hi_name,
                       const Eigen::VectorXd& (Limits::*lo)() const, const Eigen::VectorXd& (Limits::*hi)() const,
                       const char* lo_doc, const char* hi_doc, const char* names_doc) {
  py::class_<Limits, Constraint, py::smart_holder>(m, name, doc)
      .def(py::init([lo_name, hi_name](py::handle a, py::handle b, py::handle joint_names) {
             return std::make_shared<Limits>(to_vector(a, lo_name), to_vector(b, hi_name),
                                             to_string_list(joint_names, "joint_names", true));
           }),
           py::arg(lo_name), py::arg(hi_name), "joint_names"_a = py::none())
      .def_property_readonly(lo_name, lo, lo_doc)
      .def_property_readonly(hi_name, hi, hi_doc)
      .def_property_readonly("joint_names", &Limits::joint_names, names_doc)
      .def(py::pickle([lo, hi](const Limits& c) { return py::make_tuple((c.*lo)(), (c.*hi)(), c.joint_names()); },
                      [name, lo_name, hi_name](const py::tuple& t) {
                        check_state(t, 3, name);
                        return std::make_shared<Limits>(to_vector(t[0], lo_name), to_vector(t[1], hi_name),
                                                        t[2].cast<std::vector<std::string>>());
                      }));
}

void bind_jerk_limits(py::module_& m) {
  py::class_<JerkLimits, std::shared_ptr<JerkLimits>>(m, "JerkLimits", doc::JerkLimits)
      .def(py::init([](py::handle a, py::handle b, py::handle joint_names) {
             return std::make_shared<JerkLimits>(to_vector(a, "jmin"), to_vector(b, "jmax"),
                                                 to_string_list(joint_names, "joint_names", true));
           }),
           "jmin"_a, "jmax"_a, "joint_names"_a = py::none())
      .def_property_readonly("jmin", &JerkLimits::jmin, doc::JerkLimits_jmin)
      .def_property_readonly("jmax", &JerkLimits::jmax, doc::JerkLimits_jmax)
      .def_property_readonly("joint_names", &JerkLimits::joint_names, doc::JerkLimits_joint_names);
}

void bind_linear_constraint(py::module_& m) {
  py::class_<LinearConstraint, Constraint, py::smart_holder>(m, "LinearConstraint", doc::LinearConstraint)
      .def(py::init([](py::handle A, py::handle B, py::handle C, py::handle lo, py::handle hi, py::handle label) {
             return std::make_shared<LinearConstraint>(to_rows(A, "A"), to_rows(B, "B"), to_rows(C, "C"),
                                                       to_rows(lo, "lo"), to_rows(hi, "hi"), to_string_arg(label, "label"));
           }),
           "A"_a, "B"_a, "C"_a, "lo"_a, "hi"_a, "label"_a = "linear")
      .def(py::pickle([](const LinearConstraint& c) { return py::make_tuple(c.A(), c.B(), c.C(), c.lo(), c.hi(), c.label()); },
                      [](const py::tuple& t) {
                        check_state(t, 6, "LinearConstraint");
                        return std::make_shared<LinearConstraint>(to_rows(t[0], "A"), to_rows(t[1], "B"), to_rows(t[2], "C"),
                                                                  to_rows(t[3], "lo"), to_rows(t[4], "hi"),
                                                                  t[5].cast<std::string>());
                      }));
}

void bind_frame_limits(py::module_& m) {
  py::class_<FrameLimits, Constraint, py::smart_holder>(m, "FrameLimits", doc::FrameLimits)
      .def(py::init([](py::handle robot, py::handle link, py::handle quantity, py::handle lo, py::handle hi,
                       py::handle frame, py::handle point) {
             const FrameQuantity q = frame_quantity(to_string_arg(quantity, "quantity"));
             const bool speed = q == FrameQuantity::TranslationalSpeed;
             return std::make_shared<FrameLimits>(to_object<RobotModel>(robot, "robot", "RobotModel"),
                                                  to_string_arg(link, "link"), q, optional_vector(lo, "lo"),
                                                  optional_vector(hi, speed ? "v_max" : "hi"),
                                                  frame_axes(to_string_arg(frame, "frame")), to_point(point, "point"));
           }),
           "robot"_a, "link"_a, "quantity"_a, "lo"_a = py::none(), "hi"_a = py::none(), py::kw_only(), "frame"_a = "world",
           "point"_a = py::make_tuple(0.0, 0.0, 0.0))
      .def_property_readonly("robot", [](const FrameLimits& c) { return std::const_pointer_cast<RobotModel>(c.robot()); },
                             doc::FrameLimits_robot)
      .def_property_readonly("link", &FrameLimits::link, doc::FrameLimits_link)
      .def_property_readonly("quantity", [](const FrameLimits& c) { return to_string(c.quantity()); }, doc::FrameLimits_quantity)
      .def_property_readonly("frame", [](const FrameLimits& c) { return to_string(c.axes()); }, doc::FrameLimits_frame)
      .def_property_readonly("lo", &FrameLimits::lo, doc::FrameLimits_lo)
      .def_property_readonly("hi", &FrameLimits::hi, doc::FrameLimits_hi)
      .def_property_readonly("point", &FrameLimits::point, doc::FrameLimits_point)
      .def("evaluate_at", [](const FrameLimits& c, py::handle q, py::handle dq, py::handle ddq) {
        PathSamples ps;
        ps.q = to_matrix(q, "q");
        ps.dq = to_matrix(dq, "dq");
        ps.ddq = to_matrix(ddq, "ddq");
        if (ps.dq.rows() != ps.q.rows() || ps.dq.cols() != ps.q.cols() || ps.ddq.rows() != ps.q.rows() ||
            ps.ddq.cols() != ps.q.cols())
          throw InvalidInput("q, dq and ddq must have the same shape (m, nq)");
        ps.s = Eigen::VectorXd::LinSpaced(ps.q.rows(), 0.0, static_cast<double>(ps.q.rows() - 1));
        py::gil_scoped_release release;
        return c.evaluate(ps);
      }, "q"_a, "dq"_a, "ddq"_a, doc::FrameLimits_evaluate_at)
      .def(py::pickle([](const FrameLimits& c) {
                        return py::make_tuple(std::const_pointer_cast<RobotModel>(c.robot()), c.link(), to_string(c.quantity()),
                                              c.lo(), c.hi(), to_string(c.axes()), c.point());
                      },
                      [](const py::tuple& t) {
                        check_state(t, 7, "FrameLimits");
                        return std::make_shared<FrameLimits>(t[0].cast<std::shared_ptr<RobotModel>>(), t[1].cast<std::string>(),
                                                             frame_quantity(t[2].cast<std::string>()), to_vector(t[3], "lo"),
                                                             to_vector(t[4], "hi"), frame_axes(t[5].cast<std::string>()),
                                                             to_point(t[6], "point"));
                      }));
}

}  // namespace

void bind_constraints(py::module_& m) {
  // Constraint itself: bind_constraint_base.cpp (the trampoline a Python subclass needs).
  bind_joint_limits<VelocityLimits>(m, "VelocityLimits", doc::VelocityLimits, "vmin", "vmax", &VelocityLimits::vmin,
                                    &VelocityLimits::vmax, doc::VelocityLimits_vmin, doc::VelocityLimits_vmax,
                                    doc::VelocityLimits_joint_names);
  bind_jerk_limits(m);
  bind_joint_limits<AccelerationLimits>(m, "AccelerationLimits", doc::AccelerationLimits, "amin", "amax",
                                        &AccelerationLimits::amin, &AccelerationLimits::amax, doc::AccelerationLimits_amin,
                                        doc::AccelerationLimits_amax, doc::AccelerationLimits_joint_names);
  bind_linear_constraint(m);
}

void bind_torque_limits(py::module_& m) {
  py::class_<TorqueLimits, Constraint, py::smart_holder>(m, "TorqueLimits", doc::TorqueLimits)
      .def(py::init([](py::handle robot, py::object tau_min, py::object tau_max, py::handle scale, py::handle margin) {
             auto r = to_object<RobotModel>(robot, "robot", "RobotModel");
             Eigen::VectorXd lo = optional_vector(tau_min, "tau_min");
             Eigen::VectorXd hi = optional_vector(tau_max, "tau_max");
             return std::make_shared<TorqueLimits>(std::move(r), lo, hi, to_double(scale, "scale"), to_double(margin, "margin"));
           }),
           "robot"_a, "tau_min"_a = py::none(), "tau_max"_a = py::none(), "scale"_a = 1.0, "margin"_a = 0.0)
      .def_property_readonly("tau_min", &TorqueLimits::tau_min, doc::TorqueLimits_tau_min)
      .def_property_readonly("tau_max", &TorqueLimits::tau_max, doc::TorqueLimits_tau_max)
      // The stored limits already include scale and margin: rebuilt with scale 1 and margin 0.
      .def(py::pickle([](const TorqueLimits& c) {
                        return py::make_tuple(std::const_pointer_cast<RobotModel>(c.robot()), c.tau_min(), c.tau_max());
                      },
                      [](const py::tuple& t) {
                        check_state(t, 3, "TorqueLimits");
                        return std::make_shared<TorqueLimits>(t[0].cast<std::shared_ptr<RobotModel>>(), to_vector(t[1], "tau_min"),
                                                              to_vector(t[2], "tau_max"), 1.0, 0.0);
                      }));
  bind_frame_limits(m);  // after RobotModel (bind_robot), which its constructor takes
}

}  // namespace pathpace::python
