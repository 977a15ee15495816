// Constraints, the problem, results and trajectories.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "pathpace/constraints/acceleration_limits.hpp"
#include "pathpace/constraints/linear_constraint.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/constraints/torque_limits.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/constraints/velocity_limits.hpp"
#include "pathpace/errors.hpp"
#include "pathpace/time_scaling_problem.hpp"
#include "pathpace/trajectory.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

Method parse_method(const std::string& m) {
  if (m == "auto") return Method::Auto;
  if (m == "slp") return Method::Slp;
  throw InvalidInput("method = '" + m + "' must be one of 'auto', 'slp'");
}

// 1-D arrays of length N+1 stand for one row per grid point.
Eigen::MatrixXd rows_arg(py::handle h, const char* name) { return to_matrix(h, name, true); }

// q, qd or qdd at scalar or array t; a scalar gives a 1-D row.
py::object at_times(const Trajectory& tr, py::handle t, int which) {
  const Eigen::VectorXd tv = to_vector(t, "t");
  Eigen::MatrixXd q, qd, qdd;
  {
    py::gil_scoped_release release;
    tr.evaluate(tv, q, qd, qdd);
  }
  const Eigen::MatrixXd& out = which == 0 ? q : (which == 1 ? qd : qdd);
  if (is_scalar(t)) return py::cast(Eigen::VectorXd(out.row(0).transpose()));
  return py::cast(out);
}

py::dict stats_dict(const SolverStats& s) {
  return py::dict("slp_iterations"_a = s.slp_iterations, "lp_solves"_a = s.lp_solves,
                  "greatest_element"_a = s.greatest_element, "gap"_a = s.gap, "average_halfplanes"_a = s.average_halfplanes,
                  "time_feasible_sets"_a = s.time_feasible_sets, "time_reachability"_a = s.time_reachability,
                  "time_slp"_a = s.time_slp, "time_constraints"_a = s.time_constraints,
                  "time_projection"_a = s.time_projection, "projection_lp_solves"_a = s.projection_lp_solves,
                  "inexact_points"_a = s.inexact_points);
}

}  // namespace

void bind_constraints(py::module_& m) {
  py::class_<Constraint, std::shared_ptr<Constraint>>(m, "Constraint",
                                                      "Base of all constraints: half-planes a·x + b·u <= c per grid point.")
      .def_property_readonly("name", &Constraint::name);

  py::class_<VelocityLimits, Constraint, std::shared_ptr<VelocityLimits>>(m, "VelocityLimits")
      .def(py::init([](py::handle vmin, py::handle vmax) {
             return std::make_shared<VelocityLimits>(to_vector(vmin, "vmin"), to_vector(vmax, "vmax"));
           }),
           "vmin"_a, "vmax"_a)
      .def_property_readonly("vmin", &VelocityLimits::vmin)
      .def_property_readonly("vmax", &VelocityLimits::vmax);

  py::class_<AccelerationLimits, Constraint, std::shared_ptr<AccelerationLimits>>(m, "AccelerationLimits")
      .def(py::init([](py::handle amin, py::handle amax) {
             return std::make_shared<AccelerationLimits>(to_vector(amin, "amin"), to_vector(amax, "amax"));
           }),
           "amin"_a, "amax"_a)
      .def_property_readonly("amin", &AccelerationLimits::amin)
      .def_property_readonly("amax", &AccelerationLimits::amax);

  py::class_<LinearConstraint, Constraint, std::shared_ptr<LinearConstraint>>(m, "LinearConstraint")
      .def(py::init([](py::handle A, py::handle B, py::handle C, py::handle lo, py::handle hi,
                       const std::string& label) {
             return std::make_shared<LinearConstraint>(rows_arg(A, "A"), rows_arg(B, "B"), rows_arg(C, "C"),
                                                       rows_arg(lo, "lo"), rows_arg(hi, "hi"), label);
           }),
           "A"_a, "B"_a, "C"_a, "lo"_a, "hi"_a, "label"_a = "linear");
}

void bind_problem(py::module_& m) {
  py::enum_<Status>(m, "Status", "How a solve ended.")
      .value("OPTIMAL", Status::Optimal)
      .value("INFEASIBLE", Status::Infeasible)
      .value("ITERATION_LIMIT", Status::IterationLimit)
      .value("NUMERICAL_ERROR", Status::NumericalError)
      .value("UNBOUNDED", Status::Unbounded);

  py::class_<FeasibleSet>(m, "FeasibleSet", "The pruned feasible polygon of (x, u) = (sdot^2, sddot) at one grid point.")
      .def_readonly("index", &FeasibleSet::index)
      .def_readonly("s", &FeasibleSet::s)
      .def_readonly("halfplanes", &FeasibleSet::halfplanes, "(r, 3) rows [a, b, c] of a·x + b·u <= c")
      .def_readonly("labels", &FeasibleSet::labels)
      .def_readonly("x_min", &FeasibleSet::x_min)
      .def_readonly("x_max", &FeasibleSet::x_max)
      .def_readonly("x_max_label", &FeasibleSet::x_max_label)
      .def_readonly("vertices", &FeasibleSet::vertices, "(v, 2) counter-clockwise vertices (x, u)")
      .def_readonly("empty", &FeasibleSet::empty)
      .def_readonly("bounded", &FeasibleSet::bounded)
      .def_readonly("exact", &FeasibleSet::exact, "False where the contact polygon is only an inner approximation")
      .def("contains", &FeasibleSet::contains, "x"_a, "u"_a, "tol"_a = 1e-9)
      .def("__repr__", [](const FeasibleSet& f) {
        return "<FeasibleSet k=" + std::to_string(f.index) + " halfplanes=" + std::to_string(f.halfplanes.rows()) +
               (f.empty ? " empty" : "") + ">";
      });

  py::class_<Trajectory, std::shared_ptr<Trajectory>>(m, "Trajectory", "q(t) = p(s(t)) with s(t) piecewise quadratic (eq. 24).")
      .def(py::init([](std::shared_ptr<Path> path, Eigen::VectorXd s, Eigen::VectorXd sdot) {
             return std::make_shared<Trajectory>(std::move(path), std::move(s), std::move(sdot));
           }),
           "path"_a, "s"_a, "sdot"_a)
      .def_property_readonly("duration", &Trajectory::duration)
      .def_property_readonly("times", &Trajectory::times)
      .def_property_readonly("grid", &Trajectory::grid)
      .def_property_readonly("sdot_grid", &Trajectory::sdot_grid)
      .def_property_readonly("path", [](const Trajectory& t) { return std::const_pointer_cast<Path>(t.path()); })
      .def("s", [](const Trajectory& tr, py::handle t) -> py::tuple {
        Eigen::VectorXd s, sd, sdd;
        tr.evaluate_s(to_vector(t, "t"), s, sd, sdd);
        if (is_scalar(t)) return py::make_tuple(s[0], sd[0], sdd[0]);
        return py::make_tuple(s, sd, sdd);
      }, "t"_a, "(s, sdot, sddot) at each t")
      .def("contact_forces", [](const Trajectory& tr, py::handle t) {
        const Eigen::VectorXd tv = to_vector(t, "t");
        std::vector<ContactForces> out;
        {
          py::gil_scoped_release release;
          out = tr.contact_forces(tv);
        }
        return to_force_samples(out, static_cast<int>(tr.contacts()->contacts().size()), tr.contacts()->robot()->nq(),
                                is_scalar(t));
      }, "t"_a, "Contact forces at each t from the force-distribution LP, with their margin (pp.ContactForces).")
      .def_property_readonly("contacts", [](const Trajectory& tr) { return std::const_pointer_cast<ContactConstraint>(tr.contacts()); })
      .def("q", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 0); }, "t"_a,
           "q(t): shape (n,) for a scalar t, (len(t), n) for an array")
      .def("qd", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 1); }, "t"_a)
      .def("qdd", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 2); }, "t"_a)
      .def("evaluate", [](const Trajectory& tr, py::handle t) {
        return py::make_tuple(at_times(tr, t, 0), at_times(tr, t, 1), at_times(tr, t, 2));
      }, "t"_a, "(q, qd, qdd) at each t")
      .def("sample", [](const Trajectory& tr, double dt) {
        const Eigen::VectorXd t = tr.sample_times(dt);
        Eigen::MatrixXd q, qd, qdd;
        {
          py::gil_scoped_release release;
          tr.evaluate(t, q, qd, qdd);
        }
        return py::dict("t"_a = t, "q"_a = q, "qd"_a = qd, "qdd"_a = qdd);
      }, "dt"_a, "uniform resampling: dict of t (m,), q, qd, qdd (m, n)")
      .def("sample_times", &Trajectory::sample_times, "dt"_a)
      .def("torques", [](const Trajectory& tr, py::handle t, std::shared_ptr<RobotModel> robot) -> py::object {
        const RobotModel* r = robot ? robot.get() : tr.robot().get();
        if (!r) throw InvalidInput("robot: this trajectory was not shaped by torque limits; pass robot=");
        const Eigen::VectorXd tv = to_vector(t, "t");
        Eigen::MatrixXd tau;
        {
          py::gil_scoped_release release;
          tau = tr.torques(tv, *r);
        }
        if (is_scalar(t)) return py::cast(Eigen::VectorXd(tau.row(0).transpose()));
        return py::cast(tau);
      }, "t"_a, "robot"_a = nullptr, "τ(t) by inverse dynamics (the problem's robot unless one is given)");

  py::class_<Result>(m, "Result")
      .def_readonly("status", &Result::status)
      .def_property_readonly("ok", &Result::ok)
      .def_readonly("message", &Result::message)
      .def_readonly("duration", &Result::duration)
      .def_readonly("s", &Result::s)
      .def_readonly("sdot", &Result::sdot)
      .def_readonly("times", &Result::times)
      .def_readonly("sddot", &Result::sddot)
      .def_property_readonly("infeasible_index", [](const Result& r) { return r.infeasibility.grid_index; })
      .def_property_readonly("infeasible_s", [](const Result& r) { return r.infeasibility.s; })
      .def_property_readonly("binding_constraints", [](const Result& r) { return r.infeasibility.constraints; })
      .def_property_readonly("stats", [](const Result& r) { return stats_dict(r.stats); })
      .def("trajectory", [](const Result& r) { return std::make_shared<Trajectory>(r.trajectory()); })
      .def("__repr__", [](const Result& r) {
        std::string s = "<Result status=" + std::string(to_string(r.status));
        if (r.ok()) s += " duration=" + std::to_string(r.duration);
        else if (!r.message.empty()) s += " message='" + r.message + "'";
        return s + ">";
      });

  py::class_<TimeScalingProblem, std::shared_ptr<TimeScalingProblem>>(m, "TimeScalingProblem")
      .def(py::init([](std::shared_ptr<Path> path, py::object grid) {
             if (py::isinstance<py::int_>(grid)) {
               const long long n = grid.cast<long long>();
               if (n < 1 || n > 100000000)
                 throw InvalidInput("grid = " + std::to_string(n) + " must be in [1, 1e8] (number of intervals N)");
               return std::make_shared<TimeScalingProblem>(std::move(path), static_cast<int>(n));
             }
             if (py::isinstance<py::float_>(grid) || py::isinstance<py::bool_>(grid))
               throw InvalidInput("grid must be an int (number of intervals) or an array of s");
             Eigen::VectorXd g = to_vector(grid, "grid");
             return std::make_shared<TimeScalingProblem>(std::move(path), std::move(g));
           }),
           "path"_a, "grid"_a = 100)
      .def("add_velocity_limits", [](TimeScalingProblem& p, py::handle vmin, py::handle vmax) {
        p.add_velocity_limits(to_vector(vmin, "vmin"), to_vector(vmax, "vmax"));
      }, "vmin"_a, "vmax"_a)
      .def("add_acceleration_limits", [](TimeScalingProblem& p, py::handle amin, py::handle amax) {
        p.add_acceleration_limits(to_vector(amin, "amin"), to_vector(amax, "amax"));
      }, "amin"_a, "amax"_a)
      .def("add_linear_constraint", [](TimeScalingProblem& p, py::handle A, py::handle B, py::handle C, py::handle lo,
                                       py::handle hi, const std::string& label) {
        p.add_linear_constraint(rows_arg(A, "A"), rows_arg(B, "B"), rows_arg(C, "C"), rows_arg(lo, "lo"),
                                rows_arg(hi, "hi"), label);
      }, "A"_a, "B"_a, "C"_a, "lo"_a, "hi"_a, "label"_a = "linear")
      .def("add_torque_limits", [](TimeScalingProblem& p, std::shared_ptr<RobotModel> robot, py::object tau_min,
                                   py::object tau_max, double scale, double margin) {
        Eigen::VectorXd lo = tau_min.is_none() ? Eigen::VectorXd() : to_vector(tau_min, "tau_min");
        Eigen::VectorXd hi = tau_max.is_none() ? Eigen::VectorXd() : to_vector(tau_max, "tau_max");
        auto c = std::make_shared<TorqueLimits>(std::move(robot), lo, hi, scale, margin);
        py::gil_scoped_release release;
        p.add_constraint(std::move(c));
      }, "robot"_a, "tau_min"_a = py::none(), "tau_max"_a = py::none(), "scale"_a = 1.0, "margin"_a = 0.0,
         "τ_L <= τ <= τ_U along the path (URDF effort by default; scale and margin shrink it, sec. V.D)")
      .def("add_contacts", [](TimeScalingProblem& p, std::shared_ptr<RobotModel> robot, std::vector<Contact> contacts,
                              int cone_edges, double friction_margin, double min_normal_force, double torque_scale,
                              double torque_margin, double drift_tolerance, py::object tau_min, py::object tau_max,
                              double min_link_normal_force, int max_lps) {
        ContactOptions o = contact_options(cone_edges, friction_margin, min_normal_force, torque_scale, torque_margin);
        o.min_link_normal_force = min_link_normal_force;
        o.max_lps = max_lps;
        auto c = std::make_shared<ContactConstraint>(
            std::move(robot), std::move(contacts), o,
            tau_min.is_none() ? Eigen::VectorXd() : to_vector(tau_min, "tau_min"),
            tau_max.is_none() ? Eigen::VectorXd() : to_vector(tau_max, "tau_max"));
        int which = -1;
        const double drift = c->max_drift(p.samples(), &which);
        if (drift > drift_tolerance) {
          // The path must keep every contact in place (c(p(s)) = d); say which one it does not.
          const std::string msg = "contact " + std::to_string(which) + " (link '" + c->contacts()[static_cast<size_t>(which)].link +
                                  "') moves by " + std::to_string(drift) + " m along the path: the path does not keep it in place";
          py::module_::import("warnings").attr("warn")(msg, py::module_::import("builtins").attr("UserWarning"), 2);
        }
        py::gil_scoped_release release;
        p.add_constraint(std::move(c));
      }, "robot"_a, "contacts"_a, "cone_edges"_a = 8, "friction_margin"_a = 0.0, "min_normal_force"_a = 0.0,
         "torque_scale"_a = 1.0, "torque_margin"_a = 0.0, "drift_tolerance"_a = 1e-6, "tau_min"_a = py::none(),
         "tau_max"_a = py::none(), "min_link_normal_force"_a = 0.0, "max_lps"_a = 2000,
         "Torque limits with frictional contact forces (eq. 17-18), projected to (sdot^2, sddot) per grid point "
         "(sec. IV.C; each polygon is the hull of LP optima with every edge certified by its own LP).\n"
         "Contact points are in their link's frame, normals in the world frame (other_link's for a robot-robot "
         "contact). tau_min/tau_max: torque limits (default -/+ URDF effort; 0 on a floating base), shrunk by "
         "torque_scale and torque_margin (N m per side). add_torque_limits on the same robot, before or after, "
         "merges into this one projection (both limits hold).\n"
         "Margins (sec. V.D): friction_margin: the cone of mu (1 - friction_margin), i.e. every force keeps this "
         "fraction of its friction in reserve; min_normal_force: N per contact point; min_link_normal_force: N per "
         "link, the sum of the normal forces of the link's points (e.g. a whole sole). cone_edges: edges of the "
         "inscribed friction pyramid. max_lps: LPs per grid point before the polygon is reported inexact "
         "(FeasibleSet.exact, stats['inexact_points']).")
      .def("add_constraint", [](TimeScalingProblem& p, std::shared_ptr<Constraint> c) {
        py::gil_scoped_release release;
        p.add_constraint(std::move(c));
      }, "constraint"_a)
      .def("set_boundary_speeds", &TimeScalingProblem::set_boundary_speeds, "sdot_begin"_a = 0.0, "sdot_end"_a = 0.0)
      .def_property_readonly("sdot_begin", &TimeScalingProblem::sdot_begin)
      .def_property_readonly("sdot_end", &TimeScalingProblem::sdot_end)
      .def_property_readonly("grid", &TimeScalingProblem::grid)
      .def_property_readonly("intervals", &TimeScalingProblem::intervals)
      .def_property_readonly("path", [](const TimeScalingProblem& p) { return std::const_pointer_cast<Path>(p.path()); })
      .def_property_readonly("constraints", [](const TimeScalingProblem& p) {
        std::vector<std::shared_ptr<Constraint>> out;
        for (const auto& c : p.constraints()) out.push_back(std::const_pointer_cast<Constraint>(c));
        return out;
      })
      .def("feasible_set", &TimeScalingProblem::feasible_set, "k"_a)
      .def("solve", [](const TimeScalingProblem& p, const std::string& method, int max_iterations,
                       double tolerance, double initial_trust_region, double lp_feasibility_tolerance) {
        SolverOptions o;
        o.method = parse_method(method);
        o.max_iterations = max_iterations;
        o.tolerance = tolerance;
        o.initial_trust_region = initial_trust_region;
        o.lp_feasibility_tolerance = lp_feasibility_tolerance;
        py::gil_scoped_release release;
        return p.solve(o);
      }, "method"_a = "auto", "max_iterations"_a = SolverOptions().max_iterations,
         "tolerance"_a = SolverOptions().tolerance,
         "initial_trust_region"_a = SolverOptions().initial_trust_region,
         "lp_feasibility_tolerance"_a = SolverOptions().lp_feasibility_tolerance);
}

}  // namespace pathpace::python
