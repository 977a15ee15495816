#pragma once
// ContactOptions from Python keywords, in one place: add_contacts, add_contact_phases and
// ContactConstraint(...) bind the same keyword-only block (named and defaulted from ContactOptions()),
// and each phase's options dict goes through the same fields.
#include <pybind11/pybind11.h>

#include <array>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "pathpace/constraints/contact_constraint.hpp"

namespace pathpace::python {

namespace py = pybind11;

/// Every ContactOptions field a Python caller sets, in the order of the signatures: the one list of
/// their keyword names, defaults and parsing.
template <typename Options, typename F>
void for_each_contact_option(Options& o, F&& f) {
  f("cone_edges", o.cone_edges);
  f("friction_margin", o.friction_margin);
  f("min_normal_force", o.min_normal_force);
  f("torque_scale", o.torque_scale);
  f("torque_margin", o.torque_margin);
  f("min_link_normal_force", o.min_link_normal_force);
  f("max_lps", o.max_lps);
  f("cone_offset", o.cone_offset);
  f("projection_tolerance", o.projection_tolerance);
  f("project_on_demand", o.project_on_demand);
}
inline constexpr size_t kContactOptions = 10;  // the calls of for_each_contact_option

/// The keyword arguments' values, in for_each_contact_option's order.
using ContactOptionHandles = std::array<py::handle, kContactOptions>;

/// The options given, each checked and named ("cone_edges must be an int, got str").
ContactOptions parse_contact_options(const ContactOptionHandles& given);

/// `base` with a phase's own options dict applied (`name`: "phases[1]"): only the margins a phase may
/// change, the rest is the call's.
ContactOptions phase_options(py::handle dict, const std::string& name, ContactOptions base);

namespace detail {
std::vector<py::arg_v> contact_option_arg_list();
template <size_t... I>
auto contact_option_args(std::index_sequence<I...>) {
  const std::vector<py::arg_v> v = contact_option_arg_list();
  return std::make_tuple(v[I]...);
}
}  // namespace detail

/// The pybind11 arguments of the options (a tuple of py::arg_v, defaults from ContactOptions()), to
/// pass after py::kw_only() to .def, with std::apply.
inline auto contact_option_args() { return detail::contact_option_args(std::make_index_sequence<kContactOptions>()); }

/// f(lead..., ContactOptions) as the function of (lead..., the option handles) that pybind11 binds.
template <typename R, typename... Lead, typename F>
auto with_contact_options(F f) {
  return [f](Lead... lead, py::handle o0, py::handle o1, py::handle o2, py::handle o3, py::handle o4, py::handle o5,
             py::handle o6, py::handle o7, py::handle o8, py::handle o9) -> R {
    static_assert(kContactOptions == 10, "one handle per option");
    return f(std::forward<Lead>(lead)..., parse_contact_options({o0, o1, o2, o3, o4, o5, o6, o7, o8, o9}));
  };
}

/// cls.def(def..., py::kw_only(), extra..., the option arguments): `def` is the name and function (or
/// a py::init), `extra` the keyword-only arguments before the options and the docstring.
template <typename Class, typename... Def, typename... Extra>
Class& def_with_contact_options(Class& cls, std::tuple<Def...> def, const Extra&... extra) {
  return std::apply(
      [&](auto&&... d) -> Class& {
        return std::apply([&](const auto&... opt) -> Class& { return cls.def(std::move(d)..., extra..., opt...); },
                          contact_option_args());
      },
      std::move(def));
}

}  // namespace pathpace::python
