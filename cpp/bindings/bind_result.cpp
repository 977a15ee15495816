// Results of a solve: Status and Result (with its stats dict and pickle state).
#include <type_traits>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "common.hpp"
#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/result.hpp"
#include "pathpace/path.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/trajectory.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

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
  f("jerk_iterations", s.jerk_iterations);
  f("jerk_linearised_gap", s.jerk_linearised_gap);
  f("second_order_duration", s.second_order_duration);
  f("projection_ranged_certificates", s.projection_ranged_certificates);
  f("projection_lps_dense", s.projection_lps_dense);
  f("projection_lps_dense_fallback", s.projection_lps_dense_fallback);
  f("projection_pivots", s.projection_pivots);
  f("projection_fallback_cap", s.projection_fallback_cap);
  f("projection_fallback_small_pivot", s.projection_fallback_small_pivot);
  f("projection_fallback_unbounded", s.projection_fallback_unbounded);
  f("projection_fallback_singular", s.projection_fallback_singular);
  f("projection_fallback_certificate", s.projection_fallback_certificate);
  f("audit_lps_glpk", s.audit_lps_glpk);
  f("projection_rounds", s.projection_rounds);
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
  constexpr size_t kThirdStatsStateSize = 26;   // ... and before the jerk statistics
  constexpr size_t kFourthStatsStateSize = 29;  // ... and before the projection's ranging, dense and pivot counts
  constexpr size_t kFifthStatsStateSize = 33;   // ... and before the dense simplex's fallbacks by cause
  constexpr size_t kSixthStatsStateSize = 38;   // ... and before the audit's GLPK slice LPs
  constexpr size_t kSeventhStatsStateSize = 39; // ... and before the projection's refinement rounds
  if (st.size() != kFirstStatsStateSize && st.size() != kSecondStatsStateSize && st.size() != kThirdStatsStateSize &&
      st.size() != kFourthStatsStateSize && st.size() != kFifthStatsStateSize && st.size() != kSixthStatsStateSize &&
      st.size() != kSeventhStatsStateSize)
    check_state(st, kStatsStateSize, "Result stats");
  SolverStats s;
  size_t i = 0;
  for_each_stat(s, [&](const char*, auto& value) {
    if (i < st.size()) value = st[i++].cast<std::decay_t<decltype(value)>>();
  });
  return s;
}

py::dict drift_dict(const ContactDrift& d) {
  return py::dict("constraint"_a = d.constraint, "contact"_a = d.contact, "link"_a = d.link, "s"_a = d.s,
                  "drift"_a = d.drift, "tolerance"_a = d.tolerance, "message"_a = d.message());
}

py::tuple result_state(const Result& r) {
  return py::make_tuple(
      static_cast<int>(r.status), r.message, r.duration, r.s, r.sdot, r.times, r.sddot,
      py::make_tuple(r.infeasibility.grid_index, r.infeasibility.s, r.infeasibility.constraints),
      stats_state(r.stats),
      std::const_pointer_cast<Path>(r.path), std::const_pointer_cast<RobotModel>(r.robot),
      std::const_pointer_cast<ContactConstraint>(r.contacts), r.relaxation, r.binding.strings(),
      phases_list(r.contact_phases), drift_list(r.contact_drift), r.tau_min, r.tau_max, r.sddot_points);
}

Result result_from_state(const py::tuple& t) {
  if (t.size() != 15 && t.size() != 18) check_state(t, 19, "Result");  // 15: before contact_drift, tau_min/max; 18: before sddot_points
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
  if (t.size() >= 18) {
    r.contact_drift = drift_vector(t[15]);
    r.tau_min = to_vector(t[16], "tau_min");
    r.tau_max = to_vector(t[17], "tau_max");
  }
  if (t.size() == 19) r.sddot_points = to_vector(t[18], "sddot_points");
  return r;
}

}  // namespace

void bind_result(py::module_& m) {
  py::enum_<Status>(m, "Status", doc::Status)
      .value("OPTIMAL", Status::Optimal)
      .value("INFEASIBLE", Status::Infeasible)
      .value("ITERATION_LIMIT", Status::IterationLimit)
      .value("NUMERICAL_ERROR", Status::NumericalError)
      .value("UNBOUNDED", Status::Unbounded)
      .value("TIME_LIMIT", Status::TimeLimit);

  py::class_<Result>(m, "Result", doc::Result)
      .def_readonly("status", &Result::status, doc::Result_status)
      .def_property_readonly("ok", &Result::ok, doc::Result_ok)
      .def_readonly("message", &Result::message, doc::Result_message)
      .def_readonly("duration", &Result::duration, doc::Result_duration)
      .def_readonly("s", &Result::s, doc::Result_s)
      .def_readonly("sdot", &Result::sdot, doc::Result_sdot)
      .def_readonly("times", &Result::times, doc::Result_times)
      .def_readonly("sddot", &Result::sddot, doc::Result_sddot)
      .def_property_readonly("sddot_points", [](const Result& r) -> py::object {
        return r.sddot_points.size() ? py::cast(r.sddot_points) : py::object(py::none());
      }, doc::Result_sddot_points)
      .def_property_readonly("infeasible_index", [](const Result& r) { return r.infeasibility.grid_index; },
                             doc::Result_infeasible_index)
      .def_property_readonly("infeasible_s", [](const Result& r) { return r.infeasibility.s; }, doc::Result_infeasible_s)
      .def_property_readonly("binding_constraints", [](const Result& r) { return r.infeasibility.constraints; },
                             doc::Result_binding_constraints)
      .def_property_readonly("stats", [](const Result& r) { return stats_dict(r.stats); }, doc::Result_stats)
      .def_readonly("relaxation", &Result::relaxation, doc::Result_relaxation)
      .def_property_readonly("binding", [](const Result& r) { return r.binding.strings(); }, doc::Result_binding)
      .def_property_readonly("contact_drift", [](const Result& r) {
        py::list out;
        for (const ContactDrift& d : r.contact_drift) out.append(drift_dict(d));
        return out;
      }, doc::Result_contact_drift)
      .def_property_readonly("tau_min", [](const Result& r) -> py::object {
        return r.tau_min.size() ? py::cast(r.tau_min) : py::object(py::none());
      }, doc::Result_tau_min)
      .def_property_readonly("tau_max", [](const Result& r) -> py::object {
        return r.tau_max.size() ? py::cast(r.tau_max) : py::object(py::none());
      }, doc::Result_tau_max)
      .def("trajectory", [](const Result& r) { return std::make_shared<Trajectory>(r.trajectory()); }, doc::Result_trajectory)
      .def("__bool__", &Result::ok, doc::Result_bool_)
      .def(py::pickle(&result_state, &result_from_state))
      .def("__repr__", [](const Result& r) {
        std::string s = "<Result status=" + std::string(to_string(r.status));
        if (r.ok()) s += " duration=" + short_number(r.duration);
        if (!r.contact_drift.empty()) s += " moving_contacts=" + std::to_string(r.contact_drift.size());
        else if (!r.message.empty()) s += " message='" + r.message + "'";
        return s + ">";
      });
}

}  // namespace pathpace::python
