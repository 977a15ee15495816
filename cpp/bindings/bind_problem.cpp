// Constraints, the problem, results and trajectories.
#include <type_traits>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <mutex>
#include <unordered_map>

#include "convert.hpp"
#include "pathpace/auto_grid.hpp"
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

// Trajectory.contact_wrenches: the C++ result, with whether t was a scalar (then no sample axis).
struct WrenchSamples {
  ContactWrenches w;
  bool scalar = false;
  // (samples, 3 L) -> (samples, L, 3), or (L, 3) for a scalar t.
  py::array_t<double> per_link(const Eigen::MatrixXd& a) const {
    const auto S = static_cast<py::ssize_t>(a.rows()), L = static_cast<py::ssize_t>(w.links.size());
    py::array_t<double> out = scalar ? py::array_t<double>({L, py::ssize_t(3)}) : py::array_t<double>({S, L, py::ssize_t(3)});
    double* d = out.mutable_data();
    for (py::ssize_t i = 0; i < (scalar ? 1 : S); ++i)
      for (py::ssize_t c = 0; c < 3 * L; ++c) d[i * 3 * L + c] = a(i, c);
    return out;
  }
};

WrenchSamples wrench_samples(const Trajectory& tr, py::handle t) {
  const Eigen::VectorXd tv = to_vector(t, "t");
  WrenchSamples out;
  out.scalar = is_scalar(t);
  py::gil_scoped_release release;  // the force-distribution LPs
  out.w = tr.contact_wrenches(tv);
  return out;
}

Guarantee parse_guarantee(const std::string& g) {
  if (g == "grid") return Guarantee::Grid;
  if (g == "continuous") return Guarantee::Continuous;
  throw InvalidInput("guarantee = '" + g + "' must be one of 'grid', 'continuous'");
}

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

template <typename T>
std::shared_ptr<T> optional_ptr(py::handle h) {
  return h.is_none() ? std::shared_ptr<T>() : h.cast<std::shared_ptr<T>>();
}

// Python threads may share a problem: solve() releases the GIL while it reads the rows that add_*()
// appends to (and add_torque_limits / add_contacts release it while they evaluate), so an add during a
// solve freed the rows under the solver. A problem is therefore either read (any number of solves,
// feasible sets) or modified (one add at a time), never both: the second caller gets pathpace.Error
// at once instead of waiting (plain Python code that does this has a race it should know about).
class ProblemUse {
 public:
  enum Kind { kRead, kWrite };
  ProblemUse(const TimeScalingProblem& p, Kind kind, const char* what) : p_(&p), kind_(kind) {
    std::lock_guard<std::mutex> lock(mutex());
    auto& [readers, writers] = uses()[p_];
    if (writers > 0 || (kind == kWrite && readers > 0)) {
      if (readers == 0 && writers == 0) uses().erase(p_);
      throw Error(std::string(what) + ": this TimeScalingProblem is being " + (writers > 0 ? "modified" : "solved") +
                  " in another thread; add every constraint before solving from several threads");
    }
    (kind == kWrite ? writers : readers) += 1;
  }
  ~ProblemUse() {
    std::lock_guard<std::mutex> lock(mutex());
    auto it = uses().find(p_);
    (kind_ == kWrite ? it->second.second : it->second.first) -= 1;
    if (it->second.first == 0 && it->second.second == 0) uses().erase(it);
  }
  ProblemUse(const ProblemUse&) = delete;
  ProblemUse& operator=(const ProblemUse&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static std::unordered_map<const TimeScalingProblem*, std::pair<int, int>>& uses() {
    static std::unordered_map<const TimeScalingProblem*, std::pair<int, int>> u;
    return u;
  }
  const TimeScalingProblem* p_;
  Kind kind_;
};

// Adds a constraint with the GIL released (its rows may take long to evaluate), as the only user.
void add_released(TimeScalingProblem& p, std::shared_ptr<Constraint> c, const char* what) {
  ProblemUse use(p, ProblemUse::kWrite, what);
  py::gil_scoped_release release;
  p.add_constraint(std::move(c));
}

// Contact phases in pickle states: a list of ContactConstraint.
py::list phases_list(const std::vector<std::shared_ptr<const ContactConstraint>>& v) {
  py::list out;
  for (const auto& c : v) out.append(std::const_pointer_cast<ContactConstraint>(c));
  return out;
}
std::vector<std::shared_ptr<const ContactConstraint>> phases_vector(py::handle h) {
  std::vector<std::shared_ptr<const ContactConstraint>> out;
  for (py::handle c : h) out.push_back(c.cast<std::shared_ptr<ContactConstraint>>());
  return out;
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
  if (items.size() == 4 && !items[3].is_none()) {
    if (!py::isinstance<py::dict>(items[3])) type_error(name + ".options", "a dict of margins", items[3]);
    ContactOptions o = base;
    for (const auto& [key_h, value] : items[3].cast<py::dict>()) {
      const std::string key = py::str(key_h);
      const std::string arg = name + ".options['" + key + "']";
      if (key == "friction_margin") o.friction_margin = to_double(value, arg);
      else if (key == "min_normal_force") o.min_normal_force = to_double(value, arg);
      else if (key == "min_link_normal_force") o.min_link_normal_force = to_double(value, arg);
      else if (key == "cone_offset") o.cone_offset = to_double(value, arg);
      else if (key == "cone_edges") o.cone_edges = to_int32(value, arg);
      else
        throw InvalidInput(name + ".options has key '" + key + "', expected friction_margin, min_normal_force, "
                           "min_link_normal_force, cone_offset or cone_edges");
    }
    ph.options = o;
  }
  return ph;
}

// drift_tolerance of add_contacts / add_contact_phases, in metres.
// (its range is checked by check_contact_drift, in C++).
double drift_tolerance_arg(py::handle h) { return to_double(h, "drift_tolerance"); }

// drift= of add_contacts / add_contact_phases: "auto" (warn up to 10x drift_tolerance, error beyond), "warn", "error".
DriftPolicy drift_policy_arg(py::handle h) {
  const std::string v = py::isinstance<py::str>(h) ? h.cast<std::string>() : std::string();
  if (v == "auto") return DriftPolicy::Auto;
  if (v == "warn") return DriftPolicy::Warn;
  if (v == "error") return DriftPolicy::Error;
  throw InvalidInput("drift = " + py::repr(h).cast<std::string>() + ", expected 'auto', 'warn' or 'error'");
}

py::dict drift_dict(const ContactDrift& d) {
  return py::dict("constraint"_a = d.constraint, "contact"_a = d.contact, "link"_a = d.link, "s"_a = d.s,
                  "drift"_a = d.drift, "tolerance"_a = d.tolerance, "message"_a = d.message());
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

// %.6g: what a __repr__ shows of a number.
std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void warn(const std::string& msg) {
  py::module_::import("warnings").attr("warn")(msg, py::module_::import("builtins").attr("UserWarning"), 2);
}

// Every SolverStats field, once: the stats dict and both ways of Result's pickle state go through this.
// The order is the pickle state's (a state of another length is refused by check_state): a new field goes
// at the end, so that older states are still told apart.
template <typename Stats, typename F>
constexpr void for_each_stat(Stats& s, F&& f) {
  f("slp_iterations", s.slp_iterations);
  f("lp_solves", s.lp_solves);
  f("greatest_element", s.greatest_element);
  f("gap", s.gap);
  f("average_halfplanes", s.average_halfplanes);
  f("time_constraints", s.time_constraints);
  f("time_feasible_sets", s.time_feasible_sets);
  f("time_reachability", s.time_reachability);
  f("time_slp", s.time_slp);
  f("audit_rounds", s.audit_rounds);
  f("audit_cuts", s.audit_cuts);
  f("audit_worst", s.audit_worst);
  f("windows", s.windows);
  f("window_points", s.window_points);
  f("time_projection", s.time_projection);
  f("projection_lp_solves", s.projection_lp_solves);
  f("inexact_points", s.inexact_points);
  f("newton_steps", s.newton_steps);
  // Appended after the 18 entries of the first pickles (they still load: the rest stays 0).
  f("projection_lps_initial", s.projection_lps_initial);
  f("projection_lps_vertex", s.projection_lps_vertex);
  f("projection_lps_certificate", s.projection_lps_certificate);
  f("projection_lps_cap_growth", s.projection_lps_cap_growth);
  f("projection_lps_cold_retry", s.projection_lps_cold_retry);
  f("audit_lps", s.audit_lps);
  f("audit_projections", s.audit_projections);
  f("audit_reused", s.audit_reused);
}
// The pickle state's length, counted from for_each_stat (not written by hand beside it).
constexpr size_t stats_state_size() {
  SolverStats s{};
  size_t n = 0;
  for_each_stat(s, [&n](const char*, const auto&) { ++n; });
  return n;
}
constexpr size_t kStatsStateSize = stats_state_size();

py::dict stats_dict(const SolverStats& s) {
  py::dict out;
  for_each_stat(s, [&](const char* name, const auto& value) { out[name] = value; });
  return out;
}

py::tuple stats_state(const SolverStats& s) {
  py::list out;
  for_each_stat(s, [&](const char*, const auto& value) { out.append(value); });
  return py::tuple(out);
}

SolverStats stats_from_state(const py::tuple& st) {
  constexpr size_t kFirstStatsStateSize = 18;   // pickles written before the projection's LP causes
  constexpr size_t kSecondStatsStateSize = 23;  // ... and before the audit's LP and projection counts
  if (st.size() != kFirstStatsStateSize && st.size() != kSecondStatsStateSize)
    check_state(st, kStatsStateSize, "Result stats");
  SolverStats s;
  size_t i = 0;
  for_each_stat(s, [&](const char*, auto& value) {
    if (i < st.size()) value = st[i++].cast<std::decay_t<decltype(value)>>();
  });
  return s;
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

}  // namespace

void bind_constraints(py::module_& m) {
  // Constraint itself: bind_constraint_base.cpp (a Python subclass's trampoline; one holder for the hierarchy).
  py::class_<VelocityLimits, Constraint, py::smart_holder>(m, "VelocityLimits")
      .def(py::init([](py::handle vmin, py::handle vmax, py::handle joint_names) {
             return std::make_shared<VelocityLimits>(to_vector(vmin, "vmin"), to_vector(vmax, "vmax"),
                                                     to_string_list(joint_names, "joint_names", true));
           }),
           "vmin"_a, "vmax"_a, "joint_names"_a = py::none())
      .def_property_readonly("vmin", &VelocityLimits::vmin)
      .def_property_readonly("vmax", &VelocityLimits::vmax)
      .def_property_readonly("joint_names", &VelocityLimits::joint_names)
      .def(py::pickle([](const VelocityLimits& c) { return py::make_tuple(c.vmin(), c.vmax(), c.joint_names()); },
                      [](const py::tuple& t) {
                        check_state(t, 3, "VelocityLimits");
                        return std::make_shared<VelocityLimits>(to_vector(t[0], "vmin"), to_vector(t[1], "vmax"),
                                                                t[2].cast<std::vector<std::string>>());
                      }));

  py::class_<AccelerationLimits, Constraint, py::smart_holder>(m, "AccelerationLimits")
      .def(py::init([](py::handle amin, py::handle amax, py::handle joint_names) {
             return std::make_shared<AccelerationLimits>(to_vector(amin, "amin"), to_vector(amax, "amax"),
                                                         to_string_list(joint_names, "joint_names", true));
           }),
           "amin"_a, "amax"_a, "joint_names"_a = py::none())
      .def_property_readonly("amin", &AccelerationLimits::amin)
      .def_property_readonly("amax", &AccelerationLimits::amax)
      .def_property_readonly("joint_names", &AccelerationLimits::joint_names)
      .def(py::pickle([](const AccelerationLimits& c) { return py::make_tuple(c.amin(), c.amax(), c.joint_names()); },
                      [](const py::tuple& t) {
                        check_state(t, 3, "AccelerationLimits");
                        return std::make_shared<AccelerationLimits>(to_vector(t[0], "amin"), to_vector(t[1], "amax"),
                                                                    t[2].cast<std::vector<std::string>>());
                      }));

  py::class_<LinearConstraint, Constraint, py::smart_holder>(m, "LinearConstraint")
      .def(py::init([](py::handle A, py::handle B, py::handle C, py::handle lo, py::handle hi, py::handle label) {
             return std::make_shared<LinearConstraint>(rows_arg(A, "A"), rows_arg(B, "B"), rows_arg(C, "C"),
                                                       rows_arg(lo, "lo"), rows_arg(hi, "hi"), to_string_arg(label, "label"));
           }),
           "A"_a, "B"_a, "C"_a, "lo"_a, "hi"_a, "label"_a = "linear")
      .def(py::pickle([](const LinearConstraint& c) { return py::make_tuple(c.A(), c.B(), c.C(), c.lo(), c.hi(), c.label()); },
                      [](const py::tuple& t) {
                        check_state(t, 6, "LinearConstraint");
                        return std::make_shared<LinearConstraint>(rows_arg(t[0], "A"), rows_arg(t[1], "B"), rows_arg(t[2], "C"),
                                                                  rows_arg(t[3], "lo"), rows_arg(t[4], "hi"),
                                                                  t[5].cast<std::string>());
                      }));
}

void bind_problem(py::module_& m) {
  py::enum_<Status>(m, "Status", "How a solve ended.")
      .value("OPTIMAL", Status::Optimal)
      .value("INFEASIBLE", Status::Infeasible)
      .value("ITERATION_LIMIT", Status::IterationLimit)
      .value("NUMERICAL_ERROR", Status::NumericalError)
      .value("UNBOUNDED", Status::Unbounded)
      .value("TIME_LIMIT", Status::TimeLimit);

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
      .def("contains", [](const FeasibleSet& f, py::handle x, py::handle u, py::handle tol) {
        return f.contains(to_double(x, "x"), to_double(u, "u"), to_double(tol, "tol"));
      }, "x"_a, "u"_a, "tol"_a = 1e-9)
      .def("__repr__", [](const FeasibleSet& f) {
        return "<FeasibleSet k=" + std::to_string(f.index) + " halfplanes=" + std::to_string(f.halfplanes.rows()) +
               (f.empty ? " empty" : "") + ">";
      });

  py::class_<WrenchSamples>(m, "ContactWrenches", "Per-link totals of a contact-force distribution (Trajectory.contact_wrenches).")
      .def_property_readonly("links", [](const WrenchSamples& w) { return w.w.links; }, "links on either side of a contact")
      .def_property_readonly("force", [](const WrenchSamples& w) { return w.per_link(w.w.force); },
                             "(samples, links, 3) world-frame force on each link, N")
      .def_property_readonly("moment", [](const WrenchSamples& w) { return w.per_link(w.w.moment); },
                             "(samples, links, 3) moment about each link's origin, world axes, N·m")
      .def_property_readonly("center_of_pressure", [](const WrenchSamples& w) { return w.per_link(w.w.center_of_pressure); },
                             "(samples, links, 3) world-frame centre of pressure, m (NaN: no push, or several normals)")
      .def_property_readonly("normal_force", [](const WrenchSamples& w) -> py::object {
        if (w.scalar) return py::cast(Eigen::VectorXd(w.w.normal_force.row(0).transpose()));
        return py::cast(w.w.normal_force);
      }, "(samples, links) sum of the normal forces into each link, N");

  py::class_<Trajectory, std::shared_ptr<Trajectory>>(m, "Trajectory", "q(t) = p(s(t)) with s(t) piecewise quadratic (eq. 24).")
      .def(py::init([](py::handle path, py::handle s, py::handle sdot) {
             return std::make_shared<Trajectory>(to_object<Path>(path, "path", "Path"), to_vector(s, "s"),
                                                 to_vector(sdot, "sdot"));
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
        Eigen::VectorXi phase;  // with the forces, inside the release: the phase of each t is evaluated once
        {
          py::gil_scoped_release release;
          out = tr.contact_forces(tv, &phase);
        }
        if (tr.contact_phases().empty())
          return to_force_samples(out, static_cast<int>(tr.contacts()->contacts().size()), tr.contacts()->robot()->nq(),
                                  is_scalar(t));
        size_t m = 0;
        for (const auto& c : tr.contact_phases()) m = std::max(m, c->contacts().size());
        ForceSamples f = to_force_samples(out, static_cast<int>(m), tr.contact_phases()[0]->robot()->nq(), is_scalar(t));
        f.phase = std::move(phase);
        return f;
      }, "t"_a, "Contact forces at each t from the force-distribution LP, with their margin (pp.ContactForces). With "
                "contact phases each t uses its phase (the later one at a switch; .phase says which), forces padded "
                "with NaN to the largest phase.")
      .def("contact_wrenches", &wrench_samples, "t"_a)
      .def("centers_of_pressure", [](const Trajectory& tr, py::handle t) {
        const WrenchSamples w = wrench_samples(tr, t);
        return w.per_link(w.w.center_of_pressure);
      }, "t"_a)
      .def("contact_phase", [](const Trajectory& tr, py::handle t) -> py::object {
        const Eigen::VectorXi out = tr.contact_phase(to_vector(t, "t"));
        return is_scalar(t) ? py::object(py::int_(out[0])) : py::cast(out);
      }, "t"_a, "Index into contact_phases of the phase at each t (the later one at a switch); -1 without phases.")
      .def_property_readonly("contact_phases", [](const Trajectory& tr) {
        std::vector<std::shared_ptr<ContactConstraint>> out;
        for (const auto& c : tr.contact_phases()) out.push_back(std::const_pointer_cast<ContactConstraint>(c));
        return out;
      }, "the ContactConstraint of each phase (add_contact_phases), in order of s; [] without phases")
      .def_property_readonly("contacts", [](const Trajectory& tr) { return std::const_pointer_cast<ContactConstraint>(tr.contacts()); })
      .def_property_readonly("robot", [](const Trajectory& tr) { return std::const_pointer_cast<RobotModel>(tr.robot()); },
                             "RobotModel or None: the robot whose torque limits or contacts shaped this trajectory")
      .def("q", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 0); }, "t"_a,
           "q(t): shape (n,) for a scalar t, (len(t), n) for an array")
      .def("qd", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 1); }, "t"_a)
      .def("qdd", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 2); }, "t"_a)
      .def("evaluate", [](const Trajectory& tr, py::handle t) {
        return py::make_tuple(at_times(tr, t, 0), at_times(tr, t, 1), at_times(tr, t, 2));
      }, "t"_a, "(q, qd, qdd) at each t")
      .def("sample", [](const Trajectory& tr, py::handle dt_arg, py::handle max_memory_arg) {
        const double dt = to_double(dt_arg, "dt");
        const double max_memory = to_double(max_memory_arg, "max_memory");
        if (!(max_memory > 0.0)) throw InvalidInput("max_memory = " + std::to_string(max_memory) + " must be > 0 (bytes)");
        if (dt > 0.0 && std::isfinite(dt)) {
          // t, q, qd and qdd as doubles, plus the path's own p, p', p'' while evaluating: refuse before allocating.
          const double samples = std::floor(tr.duration() / dt) + 2.0;
          const double bytes = samples * (1.0 + 6.0 * tr.path()->dof()) * 8.0;
          if (bytes > max_memory) {
            char msg[320];
            std::snprintf(msg, sizeof msg,
                          "dt = %g gives %.3g samples of a %d-coordinate trajectory of duration %g: about %.3g GB, more "
                          "than max_memory = %.3g GB; use a larger dt or raise max_memory",
                          dt, samples, tr.path()->dof(), tr.duration(), bytes / 1e9, max_memory / 1e9);
            throw InvalidInput(msg);
          }
        }
        const Eigen::VectorXd t = tr.sample_times(dt);
        Eigen::MatrixXd q, qd, qdd;
        {
          py::gil_scoped_release release;
          tr.evaluate(t, q, qd, qdd);
        }
        return py::dict("t"_a = t, "q"_a = q, "qd"_a = qd, "qdd"_a = qdd);
      }, "dt"_a, "max_memory"_a = 1e9, "uniform resampling: dict of t (m,), q, qd, qdd (m, n)")
      .def("sample_times", [](const Trajectory& tr, py::handle dt) { return tr.sample_times(to_double(dt, "dt")); }, "dt"_a)
      .def("__call__", [](const Trajectory& tr, py::handle t, int order) {
        if (order < 0 || order > 2) throw InvalidInput("order = " + std::to_string(order) + " must be 0, 1 or 2");
        return at_times(tr, t, order);
      }, "t"_a, "order"_a = 0,
         "q(t) (order 0, rad or m), q̇(t) (1, per s) or q̈(t) (2, per s²), as toppra's ``traj(t, order)``.\n\n"
         "Parameters\n----------\nt : float or array_like (m,)\n    Times in s, clamped to [0, duration].\n"
         "order : {0, 1, 2}\n\nReturns\n-------\nndarray\n    (n,) for a scalar t, (m, n) for an array.")
      .def("time_spline", [](const Trajectory& tr) {
        std::shared_ptr<CubicSplinePath> out;
        {
          py::gil_scoped_release release;
          out = std::make_shared<CubicSplinePath>(tr.time_spline());
        }
        return out;
      }, "A C² cubic spline in time through the grid (toppra's ParametrizeSpline).\n\n"
         "Returns\n-------\nCubicSplinePath\n    Parameter t in s (knots = ``times``), through q(t_k) = p(s_k), clamped to "
         "q̇ = p'(s) ṡ at both ends; its ``q``, ``dq``, ``ddq`` are q(t), q̇(t), q̈(t) with q̈ continuous. Between "
         "grid points it departs from the exact timing by O(Δt⁴), so check it against the limits.")
      .def(py::pickle([](const Trajectory& tr) {
                        return py::make_tuple(std::const_pointer_cast<Path>(tr.path()), tr.grid(), tr.sdot_grid(),
                                              std::const_pointer_cast<RobotModel>(tr.robot()),
                                              std::const_pointer_cast<ContactConstraint>(tr.contacts()),
                                              phases_list(tr.contact_phases()));
                      },
                      [](const py::tuple& t) {
                        check_state(t, 6, "Trajectory");
                        auto tr = std::make_shared<Trajectory>(t[0].cast<std::shared_ptr<Path>>(), to_vector(t[1], "s"),
                                                               to_vector(t[2], "sdot"));
                        tr->set_robot(optional_ptr<RobotModel>(t[3]));
                        tr->set_contacts(optional_ptr<ContactConstraint>(t[4]));
                        tr->set_contact_phases(phases_vector(t[5]));
                        return tr;
                      }))
      .def("__repr__", [](const Trajectory& tr) {
        std::string s = "<Trajectory duration=" + short_number(tr.duration()) + " s dof=" +
                        std::to_string(tr.path()->dof()) + " grid_points=" + std::to_string(tr.grid().size());
        if (tr.robot()) s += " robot='" + tr.robot()->name() + "'";
        if (!tr.contact_phases().empty()) s += " contact_phases=" + std::to_string(tr.contact_phases().size());
        else if (tr.contacts()) s += " contacts=" + std::to_string(tr.contacts()->contacts().size());
        return s + ">";
      })
      .def("torques", [](const Trajectory& tr, py::handle t, py::handle robot_arg) -> py::object {
        const auto robot = robot_arg.is_none() ? nullptr : to_object<RobotModel>(robot_arg, "robot", "RobotModel");
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
      }, "t"_a, "robot"_a = py::none(), "τ(t) by inverse dynamics (the problem's robot unless one is given)");

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
      .def_readonly("relaxation", &Result::relaxation,
                    "For an INFEASIBLE result: dict family -> smallest scale of that family's limits that makes the "
                    "problem feasible, e.g. {'torque': 1.18, 'velocity': inf} (see TimeScalingProblem.relaxation)")
      .def_property_readonly("binding", [](const Result& r) { return r.binding.strings(); },
                    "For a timed result: per interval (N entries) the label of the constraint that binds there, "
                    "'' where none does, typically the interval of a switch (to colour a phase-plane plot by the active limit)")
      .def_property_readonly("contact_drift", [](const Result& r) {
        py::list out;
        for (const ContactDrift& d : r.contact_drift) out.append(drift_dict(d));
        return out;
      }, "Contacts the path moves although they should hold (add_contacts with drift='warn', or 'auto' within 10x "
         "drift_tolerance): dicts of constraint, contact, link, s, drift (m), tolerance (m), message; [] if none")
      .def_property_readonly("tau_min", [](const Result& r) -> py::object {
        return r.tau_min.size() ? py::cast(r.tau_min) : py::object(py::none());
      }, "The torque limits this solve held (after scale and margin; the problem's TorqueLimits, else its contact "
         "constraint's), or None without torque limits")
      .def_property_readonly("tau_max", [](const Result& r) -> py::object {
        return r.tau_max.size() ? py::cast(r.tau_max) : py::object(py::none());
      }, "See tau_min")
      .def("trajectory", [](const Result& r) { return std::make_shared<Trajectory>(r.trajectory()); })
      .def("__bool__", &Result::ok, "True when the timing is usable (``ok``): ``if res: ...``")
      .def(py::pickle([](const Result& r) {
                        return py::make_tuple(
                            static_cast<int>(r.status), r.message, r.duration, r.s, r.sdot, r.times, r.sddot,
                            py::make_tuple(r.infeasibility.grid_index, r.infeasibility.s, r.infeasibility.constraints),
                            stats_state(r.stats),
                            std::const_pointer_cast<Path>(r.path), std::const_pointer_cast<RobotModel>(r.robot),
                            std::const_pointer_cast<ContactConstraint>(r.contacts), r.relaxation, r.binding.strings(),
                            phases_list(r.contact_phases), drift_list(r.contact_drift), r.tau_min, r.tau_max);
                      },
                      [](const py::tuple& t) {
                        if (t.size() != 15) check_state(t, 18, "Result");  // 15: before contact_drift, tau_min/max
                        Result r;
                        r.status = static_cast<Status>(t[0].cast<int>());
                        r.message = t[1].cast<std::string>();
                        r.duration = t[2].cast<double>();
                        r.s = to_vector(t[3], "s");
                        r.sdot = to_vector(t[4], "sdot");
                        r.times = to_vector(t[5], "times");
                        r.sddot = to_vector(t[6], "sddot");
                        const py::tuple inf = t[7].cast<py::tuple>();
                        r.infeasibility.grid_index = inf[0].cast<Eigen::Index>();
                        r.infeasibility.s = inf[1].cast<double>();
                        r.infeasibility.constraints = inf[2].cast<std::vector<std::string>>();
                        r.stats = stats_from_state(t[8].cast<py::tuple>());
                        r.path = optional_ptr<Path>(t[9]);
                        r.robot = optional_ptr<RobotModel>(t[10]);
                        r.contacts = optional_ptr<ContactConstraint>(t[11]);
                        r.relaxation = t[12].cast<std::map<std::string, double>>();
                        r.binding = BindingLabels(t[13].cast<std::vector<std::string>>());
                        r.contact_phases = phases_vector(t[14]);
                        if (t.size() == 18) {
                          r.contact_drift = drift_vector(t[15]);
                          r.tau_min = to_vector(t[16], "tau_min");
                          r.tau_max = to_vector(t[17], "tau_max");
                        }
                        return r;
                      }))
      .def("__repr__", [](const Result& r) {
        std::string s = "<Result status=" + std::string(to_string(r.status));
        if (r.ok()) s += " duration=" + short_number(r.duration);
        if (!r.contact_drift.empty()) s += " moving_contacts=" + std::to_string(r.contact_drift.size());
        else if (!r.message.empty()) s += " message='" + r.message + "'";
        return s + ">";
      });

  py::class_<TimeScalingProblem, std::shared_ptr<TimeScalingProblem>>(m, "TimeScalingProblem")
      .def(py::init([](py::handle path_arg, py::object grid, double grid_tolerance) {
             auto path = to_object<Path>(path_arg, "path", "Path");
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
             if (grid.is_none())
               type_error("grid", "an int (number of intervals), an array of s or 'auto'", grid);
             if (PyIndex_Check(grid.ptr()) && !py::isinstance<py::array>(grid)) {
               long long n = 0;
               try {
                 n = to_int(grid, "grid", 1, 100000000);
               } catch (const InvalidInput&) {
                 throw InvalidInput("grid = " + py::str(grid).cast<std::string>() +
                                    " must be in [1, 1e8] (number of intervals N)");
               }
               return std::make_shared<TimeScalingProblem>(std::move(path), static_cast<int>(n));
             }
             Eigen::VectorXd g = to_vector(grid, "grid");
             return std::make_shared<TimeScalingProblem>(std::move(path), std::move(g));
           }),
           "path"_a, "grid"_a = 100, "grid_tolerance"_a = 1e-3,
           "grid: N (uniform intervals), an increasing array of s from s_begin to s_end, or 'auto' "
           "(pathpace.auto_grid(path, grid_tolerance): refined where the path bends; the N used is "
           "problem.intervals).")
      .def("add_velocity_limits", [](TimeScalingProblem& p, py::handle vmin, py::handle vmax) {
        ProblemUse use(p, ProblemUse::kWrite, "add_velocity_limits");
        p.add_velocity_limits(to_vector(vmin, "vmin"), to_vector(vmax, "vmax"));
      }, "vmin"_a, "vmax"_a)
      .def("add_acceleration_limits", [](TimeScalingProblem& p, py::handle amin, py::handle amax) {
        ProblemUse use(p, ProblemUse::kWrite, "add_acceleration_limits");
        p.add_acceleration_limits(to_vector(amin, "amin"), to_vector(amax, "amax"));
      }, "amin"_a, "amax"_a)
      .def("add_linear_constraint", [](TimeScalingProblem& p, py::handle A, py::handle B, py::handle C, py::handle lo,
                                       py::handle hi, py::handle label) {
        ProblemUse use(p, ProblemUse::kWrite, "add_linear_constraint");
        p.add_linear_constraint(rows_arg(A, "A"), rows_arg(B, "B"), rows_arg(C, "C"), rows_arg(lo, "lo"),
                                rows_arg(hi, "hi"), to_string_arg(label, "label"));
      }, "A"_a, "B"_a, "C"_a, "lo"_a, "hi"_a, "label"_a = "linear")
      .def("add_torque_limits", [](TimeScalingProblem& p, py::handle robot, py::object tau_min,
                                   py::object tau_max, py::handle scale, py::handle margin) {
        Eigen::VectorXd lo = optional_vector(tau_min, "tau_min");
        Eigen::VectorXd hi = optional_vector(tau_max, "tau_max");
        auto c = std::make_shared<TorqueLimits>(to_object<RobotModel>(robot, "robot", "RobotModel"), lo, hi,
                                                to_double(scale, "scale"), to_double(margin, "margin"));
        add_released(p, std::move(c), "add_torque_limits");
      }, "robot"_a, "tau_min"_a = py::none(), "tau_max"_a = py::none(), "scale"_a = 1.0, "margin"_a = 0.0,
         "τ_L <= τ <= τ_U along the path (URDF effort by default; scale and margin shrink it, sec. V.D)")
      .def("add_contact_phases", [](TimeScalingProblem& p, py::handle robot_arg, py::handle phases_arg, py::handle cone_edges,
                                    py::handle friction_margin, py::handle min_normal_force, py::handle torque_scale,
                                    py::handle torque_margin, py::handle drift_tolerance_h, py::handle tau_min,
                                    py::handle tau_max, py::handle min_link_normal_force, py::handle max_lps,
                                    py::handle impact_tolerance, py::handle cone_offset, py::handle projection_tolerance, py::handle drift_h) {
        const ContactOptions o = contact_options_arg(cone_edges, friction_margin, min_normal_force, torque_scale,
                                                     torque_margin, min_link_normal_force, max_lps, cone_offset,
                                                     projection_tolerance);
        auto robot = to_object<RobotModel>(robot_arg, "robot", "RobotModel");
        const std::vector<py::object> items = to_items(phases_arg, "phases", "a list of (s_begin, s_end, contacts)");
        std::vector<ContactPhase> phases;
        for (size_t i = 0; i < items.size(); ++i) phases.push_back(contact_phase_arg(items[i], i, o));
        const double drift_tolerance = drift_tolerance_arg(drift_tolerance_h);
        const DriftPolicy drift = drift_policy_arg(drift_h);
        const double impact = to_double(impact_tolerance, "impact_tolerance");
        const Eigen::VectorXd lo = optional_vector(tau_min, "tau_min");
        const Eigen::VectorXd hi = optional_vector(tau_max, "tau_max");
        std::vector<ContactDrift> moved;
        {
          ProblemUse use(p, ProblemUse::kWrite, "add_contact_phases");
          py::gil_scoped_release release;
          const size_t before = p.contact_drift().size();
          // Each phase must keep its own contacts in place on its own stretch (check_contact_drift).
          p.add_contact_phases(robot, phases, o, lo, hi, impact, drift_tolerance, drift);
          moved.assign(p.contact_drift().begin() + static_cast<long>(before), p.contact_drift().end());
        }
        for (const ContactDrift& d : moved) warn(d.message());
      }, "robot"_a, "phases"_a, "cone_edges"_a = 8, "friction_margin"_a = 0.0, "min_normal_force"_a = 0.0,
         "torque_scale"_a = 1.0, "torque_margin"_a = 0.0, "drift_tolerance"_a = 1e-6, "tau_min"_a = py::none(),
         "tau_max"_a = py::none(), "min_link_normal_force"_a = 0.0, "max_lps"_a = 2000, "impact_tolerance"_a = 1e-6,
         "cone_offset"_a = 0.0, "projection_tolerance"_a = 0.0, "drift"_a = "auto")
      .def("add_contacts", [](TimeScalingProblem& p, py::handle robot, py::handle contacts, py::handle cone_edges,
                              py::handle friction_margin, py::handle min_normal_force, py::handle torque_scale,
                              py::handle torque_margin, py::handle drift_tolerance_h, py::handle tau_min,
                              py::handle tau_max, py::handle min_link_normal_force, py::handle max_lps,
                              py::handle cone_offset, py::handle projection_tolerance, py::handle drift_h) {
        const ContactOptions o = contact_options_arg(cone_edges, friction_margin, min_normal_force, torque_scale,
                                                     torque_margin, min_link_normal_force, max_lps, cone_offset,
                                                     projection_tolerance);
        auto c = std::make_shared<ContactConstraint>(
            to_object<RobotModel>(robot, "robot", "RobotModel"), to_contacts(contacts, "contacts"), o,
            optional_vector(tau_min, "tau_min"), optional_vector(tau_max, "tau_max"));
        const double drift_tolerance = drift_tolerance_arg(drift_tolerance_h);
        const DriftPolicy drift = drift_policy_arg(drift_h);
        std::vector<ContactDrift> moved;
        {
          ProblemUse use(p, ProblemUse::kWrite, "add_contacts");
          py::gil_scoped_release release;
          const size_t before = p.contact_drift().size();
          p.add_contacts(std::move(c), drift_tolerance, drift);  // checks the drift (check_contact_drift)
          moved.assign(p.contact_drift().begin() + static_cast<long>(before), p.contact_drift().end());
        }
        for (const ContactDrift& d : moved) warn(d.message());
      }, "robot"_a, "contacts"_a, "cone_edges"_a = 8, "friction_margin"_a = 0.0, "min_normal_force"_a = 0.0,
         "torque_scale"_a = 1.0, "torque_margin"_a = 0.0, "drift_tolerance"_a = 1e-6, "tau_min"_a = py::none(),
         "tau_max"_a = py::none(), "min_link_normal_force"_a = 0.0, "max_lps"_a = 2000, "cone_offset"_a = 0.0,
         "projection_tolerance"_a = 0.0, "drift"_a = "auto")
      .def("add_constraint", [](TimeScalingProblem& p, py::handle c) {
        add_released(p, to_object<Constraint>(c, "constraint", "Constraint"), "add_constraint");
      }, "constraint"_a)
      .def("set_boundary_speeds", [](TimeScalingProblem& p, py::handle sdot_begin, py::handle sdot_end) {
        const double b = to_double(sdot_begin, "sdot_begin"), e = to_double(sdot_end, "sdot_end");
        ProblemUse use(p, ProblemUse::kWrite, "set_boundary_speeds");
        p.set_boundary_speeds(b, e);
      }, "sdot_begin"_a = 0.0, "sdot_end"_a = 0.0)
      .def("set_boundary_velocities", [](TimeScalingProblem& p, py::handle qd_begin, py::handle qd_end, py::handle tolerance) {
        const Eigen::VectorXd b = to_vector(qd_begin, "qd_begin"), e = to_vector(qd_end, "qd_end");
        const double tol = to_double(tolerance, "tolerance");
        ProblemUse use(p, ProblemUse::kWrite, "set_boundary_velocities");
        p.set_boundary_velocities(b, e, tol);
      }, "qd_begin"_a, "qd_end"_a, "tolerance"_a = 1e-6,
         "Boundary conditions as joint velocities q̇ (rad/s or m/s) at s_begin and s_end.\n\n"
         "q̇ = p'(s) ṡ (eq. 10): each must be a non-negative multiple of the path tangent p'; the speeds\n"
         "ṡ = p'·q̇ / |p'|² are then set as by ``set_boundary_speeds``.\n\n"
         "Parameters\n----------\nqd_begin, qd_end : array_like (n,)\n    Joint velocities at the ends.\n"
         "tolerance : float\n    Allowed |q̇ - p' ṡ|∞ relative to |q̇|.\n\n"
         "Raises\n------\nInvalidInputError\n    Naming the joint index where q̇ is not along p'.")
      // Rebuilt from (path, grid, constraints, settings): constraint rows are evaluated again. The settings
      // are a dict of every ProblemSettings field (the list restarted() carries over too).
      .def(py::pickle([](const TimeScalingProblem& p) {
                        std::vector<std::shared_ptr<Constraint>> cs;
                        for (const auto& c : p.constraints()) cs.push_back(std::const_pointer_cast<Constraint>(c));
                        return py::make_tuple(std::const_pointer_cast<Path>(p.path()), p.grid(), cs,
                                              settings_state(p.settings()), drift_list(p.contact_drift()));
                      },
                      [](const py::tuple& t) {
                        if (t.size() != 4) check_state(t, 5, "TimeScalingProblem");  // 4: before contact drift
                        auto p = std::make_shared<TimeScalingProblem>(t[0].cast<std::shared_ptr<Path>>(), to_vector(t[1], "grid"));
                        const auto cs = t[2].cast<std::vector<std::shared_ptr<Constraint>>>();
                        const ProblemSettings settings = settings_from_state(t[3]);
                        {
                          py::gil_scoped_release release;
                          for (const auto& c : cs) p->add_constraint(c);
                        }
                        p->set_settings(settings);
                        if (t.size() == 5) p->set_contact_drift(drift_vector(t[4]));
                        return p;
                      }))
      .def("set_zero_boundary_accelerations", [](TimeScalingProblem& p, py::handle at_begin, py::handle at_end) {
        const bool b = to_bool(at_begin, "at_begin"), e = to_bool(at_end, "at_end");
        ProblemUse use(p, ProblemUse::kWrite, "set_zero_boundary_accelerations");
        p.set_zero_boundary_accelerations(b, e);
      }, "at_begin"_a = true, "at_end"_a = true,
         "sddot = 0 at s_begin and/or s_end (q̈ = p'' ṡ² there: no jump of q̈ from or to a cruise). With sddot "
         "constant per interval (eq. 24) it holds on the whole first/last interval, so the boundary speed there must "
         "be > 0 (set_boundary_speeds); solve() raises InvalidInputError otherwise.")
      .def("set_joint_names", [](TimeScalingProblem& p, py::handle names_arg) {
        std::vector<std::string> names = to_string_list(names_arg, "names");
        ProblemUse use(p, ProblemUse::kWrite, "set_joint_names");
        p.set_joint_names(std::move(names));
      }, "names"_a,
         "Names of the path's coordinates for the labels and messages of velocity and acceleration limits\n"
         "(set automatically from the robot of add_torque_limits / add_contacts when it has one joint per coordinate).")
      .def("__repr__", [](const TimeScalingProblem& p) {
        std::string names;
        for (const auto& c : p.constraints()) names += (names.empty() ? "" : ", ") + c->name();
        std::string s = "<TimeScalingProblem dof=" + std::to_string(p.samples().dof()) + " intervals=" +
                        std::to_string(p.intervals()) + " s=[" + short_number(p.grid()[0]) + ", " +
                        short_number(p.grid()[p.intervals()]) + "] constraints=[" + names + "] sdot=(" +
                        short_number(p.sdot_begin()) + ", " + short_number(p.sdot_end()) + ")";
        if (!p.contact_drift().empty()) s += " moving_contacts=" + std::to_string(p.contact_drift().size());
        return s + ">";
      })
      .def_property_readonly("joint_names", &TimeScalingProblem::joint_names, "list of str: see set_joint_names")
      .def_property_readonly("sdot_begin", &TimeScalingProblem::sdot_begin)
      .def_property_readonly("sdot_end", &TimeScalingProblem::sdot_end)
      .def_property_readonly("grid", &TimeScalingProblem::grid)
      .def_property_readonly("intervals", &TimeScalingProblem::intervals)
      .def_property_readonly("path", [](const TimeScalingProblem& p) { return std::const_pointer_cast<Path>(p.path()); })
      .def_property_readonly("constraints", [](const TimeScalingProblem& p) {
        ProblemUse use(p, ProblemUse::kRead, "constraints");
        std::vector<std::shared_ptr<Constraint>> out;
        for (const auto& c : p.constraints()) out.push_back(std::const_pointer_cast<Constraint>(c));
        return out;
      })
      .def("feasible_set", [](const TimeScalingProblem& p, py::handle k) {
        const long long i = to_int(k, "k", std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
        ProblemUse use(p, ProblemUse::kRead, "feasible_set");
        return p.feasible_set(static_cast<Eigen::Index>(i));
      }, "k"_a)
      .def("relaxation", [](const TimeScalingProblem& p, double max_scale, double tolerance, const std::string& guarantee) {
        const Guarantee g = parse_guarantee(guarantee);
        ProblemUse use(p, ProblemUse::kRead, "relaxation");
        py::gil_scoped_release release;
        return p.relaxation(max_scale, tolerance, g);
      }, "max_scale"_a = 1e3, "tolerance"_a = 1e-3, "guarantee"_a = "grid",
         "Smallest uniform relaxation of each constraint family that makes the problem feasible.\n\n"
         "Returns a dict family -> scale >= 1 ('velocity', 'acceleration', 'torque', and 'all' = every family "
         "together when there are several): the family's limit intervals widened by that factor about zero, the "
         "others unchanged, give a feasible problem; within `tolerance` (relative) of the smallest such factor; "
         "inf if `max_scale` is not enough. 1.0 for every family of a feasible problem.")
      .def("restarted", [](const TimeScalingProblem& p, py::handle s0, py::handle sdot0) {
        const double a = to_double(s0, "s0"), b = to_double(sdot0, "sdot0");
        ProblemUse use(p, ProblemUse::kRead, "restarted");
        py::gil_scoped_release release;
        return p.restarted(a, b);
      }, "s0"_a, "sdot0"_a,
           "The problem that continues a running trajectory from path parameter s0 at speed sdot0 (>= 0): the "
           "path's tail [s0, s_end] on the grid points beyond s0, the same constraints and every setting pickling "
           "keeps (end speed, sddot = 0 at the end, joint names; sddot = 0 at the start only when s0 = s_begin). A "
           "LinearConstraint keeps its rows at the kept grid points (s0 must then be a grid point). Its result "
           "starts at q = p(s0), qd = p'(s0)*sdot0 (no jump); its times count from the restart.")
      .def("solve", [](const TimeScalingProblem& p, py::handle method, py::handle max_iterations,
                       py::handle tolerance, py::handle initial_trust_region, py::handle lp_feasibility_tolerance,
                       py::handle explain, py::handle guarantee, py::handle audit_points, py::handle audit_tolerance,
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
        ProblemUse use(p, ProblemUse::kRead, "solve");
        py::gil_scoped_release release;
        return p.solve(o);
      }, "method"_a = "auto", "max_iterations"_a = SolverOptions().max_iterations,
         "tolerance"_a = SolverOptions().tolerance,
         "initial_trust_region"_a = SolverOptions().initial_trust_region,
         "lp_feasibility_tolerance"_a = SolverOptions().lp_feasibility_tolerance,
         "explain"_a = SolverOptions().explain, "guarantee"_a = "grid", "audit_points"_a = SolverOptions().audit_points,
         "audit_tolerance"_a = SolverOptions().audit_tolerance, "max_audit_rounds"_a = SolverOptions().max_audit_rounds,
         "time_limit"_a = SolverOptions().time_limit);
}

}  // namespace pathpace::python
