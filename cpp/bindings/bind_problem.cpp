// The problem: its construction, add_* and set_*, and what it computes (feasible sets, relaxation,
// restart, solve); FeasibleSet with it.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>

#include "common.hpp"
#include "contact_options.hpp"
#include "convert.hpp"
#include "docstrings.hpp"
#include "second_order.hpp"
#include "pathpace/auto_grid.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/time_scaling_problem.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

using ProblemClass = py::class_<TimeScalingProblem, std::shared_ptr<TimeScalingProblem>>;
using Use = TimeScalingProblem::Use;

Method parse_method(const std::string& m) {
  if (m == "auto") return Method::Auto;
  if (m == "slp") return Method::Slp;
  throw InvalidInput("method = '" + m + "' must be one of 'auto', 'slp'");
}

// drift= of add_contacts / add_contact_phases: "auto" (warn up to 10x drift_tolerance, error beyond), "warn", "error".
DriftPolicy drift_policy_arg(py::handle h) {
  const std::string v = py::isinstance<py::str>(h) ? h.cast<std::string>() : std::string();
  if (v == "auto") return DriftPolicy::Auto;
  if (v == "warn") return DriftPolicy::Warn;
  if (v == "error") return DriftPolicy::Error;
  throw InvalidInput("drift = " + py::repr(h).cast<std::string>() + ", expected 'auto', 'warn' or 'error'");
}

// The drifts that add_contacts / add_contact_phases let through (C++ decides which), as UserWarnings.
void warn(const std::vector<ContactDrift>& drifts) {
  for (const ContactDrift& d : drifts)
    py::module_::import("warnings").attr("warn")(d.message(), py::module_::import("builtins").attr("UserWarning"), 2);
}

// One item of add_contact_phases' phases: (s_begin, s_end, contacts) or (s_begin, s_end, contacts, options),
// options a dict of this phase's own margins.
ContactPhase contact_phase_arg(py::handle h, size_t i, const ContactOptions& base) {
  const std::string name = "phases[" + std::to_string(i) + "]";
  const char* expected = "a tuple (s_begin, s_end, contacts) or (s_begin, s_end, contacts, options)";
  const std::vector<py::object> items = to_items(h, name, expected);
  if (items.size() != 3 && items.size() != 4)
    throw InvalidInput(name + " has " + std::to_string(items.size()) + " entries, expected " + expected);
  ContactPhase ph;
  ph.s_begin = to_double(items[0], name + ".s_begin");
  ph.s_end = to_double(items[1], name + ".s_end");
  ph.contacts = to_contacts(items[2], name + ".contacts");
  if (items.size() == 4 && !items[3].is_none()) ph.options = phase_options(items[3], name, base);
  return ph;
}

// A problem's settings in its pickle state: {name: value} over ProblemSettings::for_each.
py::dict settings_state(const ProblemSettings& s) {
  py::dict out;
  ProblemSettings::for_each(s, [&](const char* name, const auto& value) { out[name] = value; });
  return out;
}

ProblemSettings settings_from_state(py::handle h) {
  if (!py::isinstance<py::dict>(h)) throw InvalidInput("TimeScalingProblem pickle state: settings must be a dict");
  const py::dict d = py::reinterpret_borrow<py::dict>(h);
  ProblemSettings s;
  size_t n = 0;
  ProblemSettings::for_each(s, [&](const char* name, auto& value) {
    if (!d.contains(name)) throw InvalidInput(std::string("TimeScalingProblem pickle state: settings has no '") + name + "'");
    value = d[name].cast<std::decay_t<decltype(value)>>();
    ++n;
  });
  if (d.size() != n)
    throw InvalidInput("TimeScalingProblem pickle state: settings has " + std::to_string(d.size()) + " entries, expected " +
                       std::to_string(n));
  return s;
}

void bind_feasible_set(py::module_& m) {
  py::class_<FeasibleSet>(m, "FeasibleSet", doc::FeasibleSet)
      .def_readonly("index", &FeasibleSet::index, doc::FeasibleSet_index)
      .def_readonly("s", &FeasibleSet::s, doc::FeasibleSet_s)
      .def_readonly("halfplanes", &FeasibleSet::halfplanes, doc::FeasibleSet_halfplanes)
      .def_readonly("labels", &FeasibleSet::labels, doc::FeasibleSet_labels)
      .def_readonly("x_min", &FeasibleSet::x_min, doc::FeasibleSet_x_min)
      .def_readonly("x_max", &FeasibleSet::x_max, doc::FeasibleSet_x_max)
      .def_readonly("x_max_label", &FeasibleSet::x_max_label, doc::FeasibleSet_x_max_label)
      .def_readonly("vertices", &FeasibleSet::vertices, doc::FeasibleSet_vertices)
      .def_readonly("empty", &FeasibleSet::empty, doc::FeasibleSet_empty)
      .def_readonly("bounded", &FeasibleSet::bounded, doc::FeasibleSet_bounded)
      .def_readonly("exact", &FeasibleSet::exact, doc::FeasibleSet_exact)
      .def("contains", [](const FeasibleSet& f, py::handle x, py::handle u, py::handle tol) {
        return f.contains(to_double(x, "x"), to_double(u, "u"), to_double(tol, "tol"));
      }, "x"_a, "u"_a, "tol"_a = 1e-9, doc::FeasibleSet_contains)
      .def("__repr__", [](const FeasibleSet& f) {
        return "<FeasibleSet k=" + std::to_string(f.index) + " halfplanes=" + std::to_string(f.halfplanes.rows()) +
               (f.empty ? " empty" : "") + ">";
      });
}

// add_frame_velocity_limits and add_frame_acceleration_limits take the same arguments (per-axis lo/hi of a
// point on a link): one binding body, the C++ method its only difference.
using FrameAxisLimits = void (TimeScalingProblem::*)(std::shared_ptr<const RobotModel>, const std::string&,
                                                     const Eigen::VectorXd&, const Eigen::VectorXd&, bool, FrameAxes,
                                                     const Eigen::Vector3d&);
auto frame_axis_limits(FrameAxisLimits method) {
  return [method](TimeScalingProblem& p, py::handle robot, py::handle link, py::handle lo, py::handle hi,
                  py::handle angular, py::handle frame, py::handle point) {
    auto r = to_object<RobotModel>(robot, "robot", "RobotModel");
    const std::string l = to_string_arg(link, "link");
    const Eigen::VectorXd a = to_vector(lo, "lo"), b = to_vector(hi, "hi");
    const bool ang = to_bool(angular, "angular");
    const FrameAxes axes = frame_axes(to_string_arg(frame, "frame"));
    const Eigen::Vector3d pt = to_point(point, "point");
    py::gil_scoped_release release;
    (p.*method)(std::move(r), l, a, b, ang, axes, pt);
  };
}

std::shared_ptr<TimeScalingProblem> make_grid_problem(py::handle path_arg, py::object grid, py::handle tolerance_arg) {
  auto path = to_path(path_arg);
  const double grid_tolerance = to_double(tolerance_arg, "grid_tolerance");
  if (py::isinstance<py::str>(grid)) {
    const std::string g = grid.cast<std::string>();
    if (g != "auto") throw InvalidInput("grid = '" + g + "' must be 'auto', an int or an array of s");
    Eigen::VectorXd s;
    {
      py::gil_scoped_release release;
      s = auto_grid(*path, grid_tolerance);
    }
    return std::make_shared<TimeScalingProblem>(std::move(path), std::move(s));
  }
  if (py::isinstance<py::float_>(grid) || PyBool_Check(grid.ptr()))
    throw InvalidInput("grid must be an int (number of intervals) or an array of s");
  if (grid.is_none()) type_error("grid", "an int (number of intervals), an array of s or 'auto'", grid);
  if (PyIndex_Check(grid.ptr()) && !py::isinstance<py::array>(grid)) {
    long long n = 0;
    try {
      n = to_int(grid, "grid", 1, 100000000);
    } catch (const InvalidInput&) {
      throw InvalidInput("grid = " + py::str(grid).cast<std::string>() + " must be in [1, 1e8] (number of intervals N)");
    }
    return std::make_shared<TimeScalingProblem>(std::move(path), static_cast<int>(n));
  }
  Eigen::VectorXd g = to_vector(grid, "grid");
  return std::make_shared<TimeScalingProblem>(std::move(path), std::move(g));
}

// constraints=: toppra's constraint objects (or pathpace Constraints), added by pathpace.toppra_compat, which
// reads their attributes and calls the add_* that means the same (a toppra script keeps its constraint lines).
std::shared_ptr<TimeScalingProblem> make_problem(py::handle path_arg, py::object grid, py::handle tolerance_arg,
                                                 py::handle constraints) {
  auto p = make_grid_problem(path_arg, std::move(grid), tolerance_arg);
  if (!constraints.is_none()) py::module_::import("pathpace.toppra_compat").attr("add_constraints")(py::cast(p), constraints);
  return p;
}

// Rebuilt from (path, grid, constraints, settings): constraint rows are evaluated again. The settings
// are a dict of every ProblemSettings field (the list restarted() carries over too).
py::tuple problem_state(const TimeScalingProblem& p) {
  std::vector<std::shared_ptr<Constraint>> cs;
  for (const auto& c : p.constraints()) cs.push_back(std::const_pointer_cast<Constraint>(c));
  py::object jerk = py::none();
  if (p.jerk_limits()) jerk = py::make_tuple(p.jerk_limits()->jmin(), p.jerk_limits()->jmax());
  return py::make_tuple(std::const_pointer_cast<Path>(p.path()), p.grid(), cs, settings_state(p.settings()),
                        drift_list(p.contact_drift()), jerk);
}

std::shared_ptr<TimeScalingProblem> problem_from_state(const py::tuple& t) {
  if (t.size() != 4 && t.size() != 5) check_state(t, 6, "TimeScalingProblem");  // 4: before contact drift, 5: jerk
  auto p = std::make_shared<TimeScalingProblem>(t[0].cast<std::shared_ptr<Path>>(), to_vector(t[1], "grid"));
  const auto cs = t[2].cast<std::vector<std::shared_ptr<Constraint>>>();
  const ProblemSettings settings = settings_from_state(t[3]);
  {
    py::gil_scoped_release release;
    for (const auto& c : cs) p->add_constraint(c);
  }
  p->set_settings(settings);
  if (t.size() >= 5) p->set_contact_drift(drift_vector(t[4]));
  if (t.size() == 6 && !t[5].is_none()) {
    const py::tuple j = t[5].cast<py::tuple>();
    p->add_jerk_limits(to_vector(j[0], "jmin"), to_vector(j[1], "jmax"));
  }
  return p;
}

std::string problem_repr(const TimeScalingProblem& p) {
  std::string names;
  for (const auto& c : p.constraints()) names += (names.empty() ? "" : ", ") + c->name();
  std::string s = "<TimeScalingProblem dof=" + std::to_string(p.samples().dof()) + " intervals=" +
                  std::to_string(p.intervals()) + " s=[" + short_number(p.grid()[0]) + ", " +
                  short_number(p.grid()[p.intervals()]) + "] constraints=[" + names + "] sdot=(" +
                  short_number(p.sdot_begin()) + ", " + short_number(p.sdot_end()) + ")";
  if (!p.contact_drift().empty()) s += " moving_contacts=" + std::to_string(p.contact_drift().size());
  return s + ">";
}

void bind_problem_state(ProblemClass& cls) {
  cls.def(py::init(&make_problem), "path"_a, "grid"_a = 100, "grid_tolerance"_a = 1e-3, py::kw_only(),
          "constraints"_a = py::none())
      .def(py::pickle(&problem_state, &problem_from_state))
      .def("__repr__", &problem_repr)
      .def_property_readonly("joint_names", &TimeScalingProblem::joint_names, doc::TimeScalingProblem_joint_names)
      .def_property_readonly("sdot_begin", &TimeScalingProblem::sdot_begin, doc::TimeScalingProblem_sdot_begin)
      .def_property_readonly("sdot_end", &TimeScalingProblem::sdot_end, doc::TimeScalingProblem_sdot_end)
      .def_property_readonly("grid", &TimeScalingProblem::grid, doc::TimeScalingProblem_grid)
      .def_property_readonly("intervals", &TimeScalingProblem::intervals, doc::TimeScalingProblem_intervals)
      .def_property_readonly("path", [](const TimeScalingProblem& p) { return std::const_pointer_cast<Path>(p.path()); },
                             doc::TimeScalingProblem_path)
      .def_property_readonly("constraints", [](const TimeScalingProblem& p) {
        const Use use(p, Use::Read, "constraints");  // no add while the list is copied
        std::vector<std::shared_ptr<Constraint>> out;
        for (const auto& c : p.constraints()) out.push_back(std::const_pointer_cast<Constraint>(c));
        return out;
      }, doc::TimeScalingProblem_constraints);
}

void bind_problem_kinematics(ProblemClass& cls) {
  cls.def("add_velocity_limits", [](TimeScalingProblem& p, py::handle vmin, py::handle vmax) {
       p.add_velocity_limits(to_vector(vmin, "vmin"), to_vector(vmax, "vmax"));
     }, "vmin"_a, "vmax"_a, doc::TimeScalingProblem_add_velocity_limits)
      .def("add_acceleration_limits", [](TimeScalingProblem& p, py::handle amin, py::handle amax) {
        p.add_acceleration_limits(to_vector(amin, "amin"), to_vector(amax, "amax"));
      }, "amin"_a, "amax"_a, doc::TimeScalingProblem_add_acceleration_limits)
      .def("add_jerk_limits", [](TimeScalingProblem& p, py::handle jmin, py::handle jmax) {
        p.add_jerk_limits(to_vector(jmin, "jmin"), to_vector(jmax, "jmax"));
      }, "jmin"_a, "jmax"_a, doc::TimeScalingProblem_add_jerk_limits)
      .def("add_linear_constraint", [](TimeScalingProblem& p, py::handle A, py::handle B, py::handle C, py::handle lo,
                                       py::handle hi, py::handle label) {
        p.add_linear_constraint(to_rows(A, "A"), to_rows(B, "B"), to_rows(C, "C"), to_rows(lo, "lo"), to_rows(hi, "hi"),
                                to_string_arg(label, "label"));
      }, "A"_a, "B"_a, "C"_a, "lo"_a, "hi"_a, "label"_a = "linear", doc::TimeScalingProblem_add_linear_constraint)
      .def("add_torque_limits", [](TimeScalingProblem& p, py::handle robot, py::object tau_min, py::object tau_max,
                                   py::handle scale, py::handle margin, py::handle inverse_dynamics, py::handle vectorized) {
        std::shared_ptr<const Constraint> c;
        if (!inverse_dynamics.is_none()) {
          if (!robot.is_none())
            throw InvalidInput("add_torque_limits: robot = " + py::repr(robot).cast<std::string>() +
                               " and inverse_dynamics given: give one (the robot's own dynamics, or yours)");
          c = callback_torque_limits(inverse_dynamics, tau_min, tau_max, scale, margin, vectorized, p.joint_names());
        } else {
          Eigen::VectorXd lo = optional_vector(tau_min, "tau_min");
          Eigen::VectorXd hi = optional_vector(tau_max, "tau_max");
          c = std::make_shared<TorqueLimits>(to_object<RobotModel>(robot, "robot", "RobotModel"), lo, hi,
                                             to_double(scale, "scale"), to_double(margin, "margin"));
        }
        const Use use(p, Use::Write, "add_torque_limits");  // its name in the error, not add_constraint's
        py::gil_scoped_release release;                      // its rows may take long to evaluate
        p.add_constraint(std::move(c));
      }, "robot"_a = py::none(), "tau_min"_a = py::none(), "tau_max"_a = py::none(), "scale"_a = 1.0, "margin"_a = 0.0,
         py::kw_only(), "inverse_dynamics"_a = py::none(), "vectorized"_a = true,
         doc::TimeScalingProblem_add_torque_limits)
      .def("add_second_order_constraint", [](TimeScalingProblem& p, py::handle inverse_dynamics, py::handle F, py::handle g,
                                             py::handle name, py::handle labels, py::handle family, py::handle vectorized) {
        std::shared_ptr<const Constraint> c = callback_second_order(inverse_dynamics, F, g, name, labels, family, vectorized);
        const Use use(p, Use::Write, "add_second_order_constraint");
        py::gil_scoped_release release;
        p.add_constraint(std::move(c));
      }, "inverse_dynamics"_a, "F"_a, "g"_a, py::kw_only(), "name"_a = "second-order constraint", "labels"_a = py::none(),
         "family"_a = "second order", "vectorized"_a = true, doc::TimeScalingProblem_add_second_order_constraint)
      .def("add_frame_translational_speed_limit", [](TimeScalingProblem& p, py::handle robot, py::handle link,
                                                     py::handle v_max, py::handle point) {
        auto r = to_object<RobotModel>(robot, "robot", "RobotModel");
        const std::string l = to_string_arg(link, "link");
        const double v = to_double(v_max, "v_max");
        const Eigen::Vector3d pt = to_point(point, "point");
        py::gil_scoped_release release;
        p.add_frame_translational_speed_limit(std::move(r), l, v, pt);
      }, "robot"_a, "link"_a, "v_max"_a, py::kw_only(), "point"_a = py::make_tuple(0.0, 0.0, 0.0),
         doc::TimeScalingProblem_add_frame_translational_speed_limit)
      .def("add_frame_velocity_limits", frame_axis_limits(&TimeScalingProblem::add_frame_velocity_limits), "robot"_a,
           "link"_a, "lo"_a, "hi"_a, py::kw_only(), "angular"_a = false, "frame"_a = "world",
           "point"_a = py::make_tuple(0.0, 0.0, 0.0), doc::TimeScalingProblem_add_frame_velocity_limits)
      .def("add_frame_acceleration_limits", frame_axis_limits(&TimeScalingProblem::add_frame_acceleration_limits),
           "robot"_a, "link"_a, "lo"_a, "hi"_a, py::kw_only(), "angular"_a = false, "frame"_a = "world",
           "point"_a = py::make_tuple(0.0, 0.0, 0.0), doc::TimeScalingProblem_add_frame_acceleration_limits)
      .def("add_constraint", [](TimeScalingProblem& p, py::handle c) {
        auto constraint = to_object<Constraint>(c, "constraint", "Constraint");
        py::gil_scoped_release release;
        p.add_constraint(std::move(constraint));
      }, "constraint"_a, doc::TimeScalingProblem_add_constraint);
}

void bind_problem_contacts(ProblemClass& cls) {
  auto add_contacts = [](TimeScalingProblem& p, py::handle robot, py::handle contacts, py::handle tau_min,
                         py::handle tau_max, py::handle drift_tolerance, py::handle drift, const ContactOptions& o) {
    auto c = std::make_shared<ContactConstraint>(to_object<RobotModel>(robot, "robot", "RobotModel"),
                                                 to_contacts(contacts, "contacts"), o, optional_vector(tau_min, "tau_min"),
                                                 optional_vector(tau_max, "tau_max"));
    const double tolerance = to_double(drift_tolerance, "drift_tolerance");  // its range: check_contact_drift's
    const DriftPolicy policy = drift_policy_arg(drift);
    std::vector<ContactDrift> moved;
    {
      py::gil_scoped_release release;
      moved = p.add_contacts(std::move(c), tolerance, policy);
    }
    warn(moved);
  };
  auto add_contact_phases = [](TimeScalingProblem& p, py::handle robot_arg, py::handle phases_arg, py::handle tau_min,
                               py::handle tau_max, py::handle drift_tolerance, py::handle drift, py::handle impact_tolerance,
                               const ContactOptions& o) {
    auto robot = to_object<RobotModel>(robot_arg, "robot", "RobotModel");
    const std::vector<py::object> items = to_items(phases_arg, "phases", "a list of (s_begin, s_end, contacts)");
    std::vector<ContactPhase> phases;
    for (size_t i = 0; i < items.size(); ++i) phases.push_back(contact_phase_arg(items[i], i, o));
    const double tolerance = to_double(drift_tolerance, "drift_tolerance");
    const DriftPolicy policy = drift_policy_arg(drift);
    const double impact = to_double(impact_tolerance, "impact_tolerance");
    const Eigen::VectorXd lo = optional_vector(tau_min, "tau_min");
    const Eigen::VectorXd hi = optional_vector(tau_max, "tau_max");
    std::vector<ContactDrift> moved;
    {
      py::gil_scoped_release release;
      moved = p.add_contact_phases(robot, phases, o, lo, hi, impact, tolerance, policy);
    }
    warn(moved);
  };
  using H = py::handle;
  def_with_contact_options(cls,
                           std::make_tuple("add_contacts",
                                           with_contact_options<void, TimeScalingProblem&, H, H, H, H, H, H>(add_contacts)),
                           "robot"_a, "contacts"_a, py::kw_only(), "tau_min"_a = py::none(), "tau_max"_a = py::none(),
                           "drift_tolerance"_a = 1e-6, "drift"_a = "auto", doc::TimeScalingProblem_add_contacts);
  def_with_contact_options(
      cls,
      std::make_tuple("add_contact_phases",
                      with_contact_options<void, TimeScalingProblem&, H, H, H, H, H, H, H>(add_contact_phases)),
      "robot"_a, "phases"_a, py::kw_only(), "tau_min"_a = py::none(), "tau_max"_a = py::none(), "drift_tolerance"_a = 1e-6,
      "drift"_a = "auto", "impact_tolerance"_a = 1e-6, doc::TimeScalingProblem_add_contact_phases);
}

void bind_problem_settings(ProblemClass& cls) {
  cls.def("set_boundary_speeds", [](TimeScalingProblem& p, py::handle sdot_begin, py::handle sdot_end) {
       p.set_boundary_speeds(to_double(sdot_begin, "sdot_begin"), to_double(sdot_end, "sdot_end"));
     }, "sdot_begin"_a = 0.0, "sdot_end"_a = 0.0, doc::TimeScalingProblem_set_boundary_speeds)
      .def("set_boundary_velocities", [](TimeScalingProblem& p, py::handle qd_begin, py::handle qd_end, py::handle tolerance) {
        const Eigen::VectorXd b = to_vector(qd_begin, "qd_begin"), e = to_vector(qd_end, "qd_end");
        p.set_boundary_velocities(b, e, to_double(tolerance, "tolerance"));
      }, "qd_begin"_a, "qd_end"_a, "tolerance"_a = 1e-6, doc::TimeScalingProblem_set_boundary_velocities)
      .def("set_zero_boundary_accelerations", [](TimeScalingProblem& p, py::handle at_begin, py::handle at_end) {
        const bool b = to_bool(at_begin, "at_begin"), e = to_bool(at_end, "at_end");
        p.set_zero_boundary_accelerations(b, e);
      }, "at_begin"_a = true, "at_end"_a = true, doc::TimeScalingProblem_set_zero_boundary_accelerations)
      .def("set_joint_names", [](TimeScalingProblem& p, py::handle names) {
        p.set_joint_names(to_string_list(names, "names"));
      }, "names"_a, doc::TimeScalingProblem_set_joint_names);
}

SolverOptions solver_options(py::handle method, py::handle max_iterations, py::handle tolerance,
                             py::handle initial_trust_region, py::handle lp_feasibility_tolerance, py::handle explain,
                             py::handle guarantee, py::handle audit_points, py::handle audit_tolerance,
                             py::handle max_audit_rounds, py::handle time_limit) {
  SolverOptions o;
  o.time_limit = to_double(time_limit, "time_limit");
  o.explain = to_bool(explain, "explain");
  o.guarantee = parse_guarantee(to_string_arg(guarantee, "guarantee"));
  o.audit_points = to_int32(audit_points, "audit_points");
  o.audit_tolerance = to_double(audit_tolerance, "audit_tolerance");
  o.max_audit_rounds = to_int32(max_audit_rounds, "max_audit_rounds");
  o.method = parse_method(to_string_arg(method, "method"));
  o.max_iterations = to_int32(max_iterations, "max_iterations");
  o.tolerance = to_double(tolerance, "tolerance");
  o.initial_trust_region = to_double(initial_trust_region, "initial_trust_region");
  o.lp_feasibility_tolerance = to_double(lp_feasibility_tolerance, "lp_feasibility_tolerance");
  return o;
}

void bind_problem_solve(ProblemClass& cls) {
  const SolverOptions d;
  cls.def("feasible_set", [](const TimeScalingProblem& p, py::handle k) {
       const long long i = to_int(k, "k", std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
       return p.feasible_set(static_cast<Eigen::Index>(i));
     }, "k"_a, doc::TimeScalingProblem_feasible_set)
      .def("relaxation", [](const TimeScalingProblem& p, py::handle max_scale, py::handle tolerance, py::handle guarantee) {
        const double m = to_double(max_scale, "max_scale"), t = to_double(tolerance, "tolerance");
        const Guarantee g = parse_guarantee(to_string_arg(guarantee, "guarantee"));
        py::gil_scoped_release release;
        return p.relaxation(m, t, g);
      }, "max_scale"_a = 1e3, "tolerance"_a = 1e-3, "guarantee"_a = "grid", doc::TimeScalingProblem_relaxation)
      .def("restarted", [](const TimeScalingProblem& p, py::handle s0, py::handle sdot0) {
        const double a = to_double(s0, "s0"), b = to_double(sdot0, "sdot0");
        py::gil_scoped_release release;
        return p.restarted(a, b);
      }, "s0"_a, "sdot0"_a, doc::TimeScalingProblem_restarted)
      .def("compute_trajectory", [](py::object self, py::handle sd_start, py::handle sd_end) {
        return py::module_::import("pathpace.toppra_compat").attr("compute_trajectory")(self, sd_start, sd_end);
      }, "sd_start"_a = 0.0, "sd_end"_a = 0.0, doc::TimeScalingProblem_compute_trajectory)
      .def("solve", [](const TimeScalingProblem& p, py::handle method, py::handle max_iterations, py::handle tolerance,
                       py::handle initial_trust_region, py::handle lp_feasibility_tolerance, py::handle explain,
                       py::handle guarantee, py::handle audit_points, py::handle audit_tolerance,
                       py::handle max_audit_rounds, py::handle time_limit) {
        const SolverOptions o = solver_options(method, max_iterations, tolerance, initial_trust_region, lp_feasibility_tolerance,
                                               explain, guarantee, audit_points, audit_tolerance, max_audit_rounds, time_limit);
        py::gil_scoped_release release;
        return p.solve(o);
      }, "method"_a = "auto", "max_iterations"_a = d.max_iterations, "tolerance"_a = d.tolerance,
         "initial_trust_region"_a = d.initial_trust_region, "lp_feasibility_tolerance"_a = d.lp_feasibility_tolerance,
         "explain"_a = d.explain, "guarantee"_a = "grid", "audit_points"_a = d.audit_points,
         "audit_tolerance"_a = d.audit_tolerance, "max_audit_rounds"_a = d.max_audit_rounds, "time_limit"_a = d.time_limit,
         doc::TimeScalingProblem_solve);
}

}  // namespace

void bind_problem(py::module_& m) {
  bind_feasible_set(m);
  ProblemClass cls(m, "TimeScalingProblem", doc::TimeScalingProblem);
  bind_problem_state(cls);
  bind_problem_kinematics(cls);
  bind_problem_contacts(cls);
  bind_problem_settings(cls);
  bind_problem_solve(cls);
}

}  // namespace pathpace::python
