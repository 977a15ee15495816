#include "contact_options.hpp"

#include <type_traits>

#include "convert.hpp"

namespace pathpace::python {

namespace {

template <typename T>
void parse_into(T& field, py::handle value, const std::string& name) {
  if constexpr (std::is_same_v<T, bool>)
    field = to_bool(value, name);
  else if constexpr (std::is_same_v<T, int>)
    field = to_int32(value, name);
  else
    field = to_double(value, name);
}

}  // namespace

ContactOptions parse_contact_options(const ContactOptionHandles& given) {
  ContactOptions o;
  size_t i = 0;
  for_each_contact_option(o, [&](const char* name, auto& field) { parse_into(field, given[i++], name); });
  return o;
}

ContactOptions phase_options(py::handle dict, const std::string& name, ContactOptions base) {
  // The margins of one stance; the torque limits and the LP budget are the whole call's.
  static const char* const kPhase[] = {"friction_margin", "min_normal_force", "min_link_normal_force", "cone_offset",
                                       "cone_edges"};
  if (!py::isinstance<py::dict>(dict)) type_error(name + ".options", "a dict of margins", dict);
  for (const auto& [key_h, value] : dict.cast<py::dict>()) {
    const std::string key = py::str(key_h);
    bool known = false;
    for (const char* k : kPhase) known = known || key == k;
    if (known) {
      for_each_contact_option(base, [&](const char* field_name, auto& field) {
        if (key == field_name) parse_into(field, value, name + ".options['" + key + "']");
      });
      continue;
    }
    throw InvalidInput(name + ".options has key '" + key + "', expected friction_margin, min_normal_force, "
                       "min_link_normal_force, cone_offset or cone_edges");
  }
  return base;
}

std::vector<py::arg_v> detail::contact_option_arg_list() {
  std::vector<py::arg_v> out;
  const ContactOptions defaults;
  for_each_contact_option(defaults, [&](const char* name, const auto& value) { out.push_back(py::arg(name) = value); });
  return out;
}

}  // namespace pathpace::python
