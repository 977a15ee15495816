// A call that no overload of a bound function accepts gets a TypeError naming the argument and the type
// it expects ("TimeScalingProblem.relaxation(): max_scale must be a float, got str"), instead of pybind11's
// list of every signature and every argument's repr.
//
// Done once, for every function of the module: after all bindings, each pybind11 function's method table
// entry (PyMethodDef::ml_meth, read by CPython at every call) is pointed at named_dispatcher, which calls
// pybind11's dispatcher and, only when that fails to match any overload, rewrites the error from the
// function records (argument names, defaults, the signature's types). Overload resolution, docstrings,
// signatures and pickling are pybind11's own, unchanged. Most bindings take py::handle and convert with
// convert.hpp's helpers, which name the argument themselves; what reaches this file is a wrong number of
// arguments, an unknown keyword, a wrong `self`, or an argument of one of the few typed parameters.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <unordered_map>
#include <vector>

namespace py = pybind11;

namespace pathpace::python {

namespace {

using FastCall = PyObject* (*)(PyObject*, PyObject* const*, size_t, PyObject*);
FastCall pybind11_dispatcher = nullptr;  // the same function for every pybind11 function

std::string type_name_of(py::handle h) {
  return h.is_none() ? "None" : py::str(py::type::handle_of(h).attr("__name__")).cast<std::string>();
}

// The parameter types of a pybind11 signature "(a: T, b: U = 1) -> R", split at the top-level commas.
std::vector<std::string> parameter_types(const std::string& sig) {
  std::vector<std::string> out;
  const size_t open = sig.find('(');
  if (open == std::string::npos) return out;
  int depth = 0;
  std::string cur;
  for (size_t i = open + 1; i < sig.size(); ++i) {
    const char c = sig[i];
    if (depth == 0 && (c == ',' || c == ')')) {
      out.push_back(cur);
      cur.clear();
      if (c == ')') break;
      continue;
    }
    if (c == '[' || c == '(' || c == '{') ++depth;
    if (c == ']' || c == ')' || c == '}') --depth;
    cur += c;
  }
  // The markers of keyword-only ("*") and positional-only ("/") parameters are no parameters.
  out.erase(std::remove_if(out.begin(), out.end(),
                           [](const std::string& p) { return p.find_first_not_of(" */") == std::string::npos && !p.empty(); }),
            out.end());
  for (std::string& p : out) {  // "name: type = default" -> "type"
    const size_t colon = p.find(": ");
    p = colon == std::string::npos ? std::string() : p.substr(colon + 2);
    const size_t eq = p.rfind(" = ");
    if (eq != std::string::npos) p = p.substr(0, eq);
  }
  return out;
}

// The type a pybind11 type name stands for, when it is one of this module's classes.
py::object module_class(const std::string& type) {
  const std::string name = type.substr(type.rfind('.') == std::string::npos ? 0 : type.rfind('.') + 1);
  py::module_ core = py::module_::import("pathpace._core");
  if (!py::hasattr(core, name.c_str())) return py::object();
  py::object t = core.attr(name.c_str());
  return PyType_Check(t.ptr()) ? t : py::object();
}

// A signature's type, as far as this file tells types apart.
struct Kind {
  enum What { kAny, kFloat, kInt, kBool, kStr, kStrList, kClass } what = kAny;
  bool optional = false;  // None accepted
  py::object cls;         // kClass
  std::string name;       // kClass: the class's name
};

// The alternatives of "A | B | None" (or "typing.Optional[A]"), split at the top level.
std::vector<std::string> alternatives(const std::string& type) {
  std::vector<std::string> out;
  if (type.compare(0, 16, "typing.Optional[") == 0 && !type.empty() && type.back() == ']')
    return {type.substr(16, type.size() - 17), "None"};
  int depth = 0;
  size_t begin = 0;
  for (size_t i = 0; i < type.size(); ++i) {
    if (type[i] == '[') ++depth;
    if (type[i] == ']') --depth;
    if (depth == 0 && type.compare(i, 3, " | ") == 0) {
      out.push_back(type.substr(begin, i - begin));
      begin = i + 3;
    }
  }
  out.push_back(type.substr(begin));
  return out;
}

Kind kind_of(const std::string& type) {
  Kind k;
  bool any = false, flt = false, integer = false;
  for (const std::string& a : alternatives(type)) {
    if (a == "None") k.optional = true;
    else if (a.empty() || a == "object" || a == "typing.Any" || a == "Any") any = true;
    else if (a == "float" || a == "typing.SupportsFloat") flt = true;
    else if (a == "int" || a == "typing.SupportsInt" || a == "typing.SupportsIndex") integer = true;
    else if (a == "bool") k.what = Kind::kBool;
    else if (a == "str") k.what = Kind::kStr;
    else if (a == "list[str]" || a == "collections.abc.Sequence[str]") k.what = Kind::kStrList;
    else if (py::object cls = module_class(a)) {
      k.what = Kind::kClass;
      k.cls = cls;
      k.name = py::str(cls.attr("__name__")).cast<std::string>();
    } else {
      any = true;  // e.g. an Eigen array: its shape and entries are the call's to check
    }
  }
  if (any) k.what = Kind::kAny;
  else if (flt) k.what = Kind::kFloat;
  else if (integer) k.what = Kind::kInt;
  return k;
}

// Whether the caster of a type of this kind takes `value` (asked of the caster itself); true where it
// cannot be told here.
bool accepts(py::handle value, const Kind& k) {
  if (value.is_none() && k.optional) return true;
  switch (k.what) {
    case Kind::kAny: return true;
    case Kind::kFloat: return py::detail::make_caster<double>().load(value, true);
    case Kind::kInt: return py::detail::make_caster<long long>().load(value, true);
    case Kind::kBool: return py::detail::make_caster<bool>().load(value, true);
    case Kind::kStr: return py::detail::make_caster<std::string>().load(value, true);
    case Kind::kStrList: return py::detail::make_caster<std::vector<std::string>>().load(value, true);
    case Kind::kClass: return PyObject_IsInstance(value.ptr(), k.cls.ptr()) == 1;
  }
  return true;
}

std::string expected(const Kind& k) {
  const char* names[] = {"any object", "a float", "an int", "a bool", "a str", "a list of str", ""};
  const std::string e = k.what == Kind::kClass ? "a pathpace." + k.name : names[k.what];
  return k.optional ? e + " or None" : e;
}

// The names the patched functions were found under ("Class.attr"), for those whose records have none
// (property accessors).
std::unordered_map<const py::detail::function_record*, std::string>& found_names() {
  static std::unordered_map<const py::detail::function_record*, std::string> names;
  return names;
}

// "Class.method", "Class" (a constructor) or "function".
std::string function_name(const py::detail::function_record& rec) {
  if (rec.name == nullptr || rec.name[0] == '\0') {
    auto it = found_names().find(&rec);
    if (it != found_names().end()) return it->second;
  }
  std::string scope;
  if (rec.scope && PyType_Check(rec.scope.ptr())) scope = py::str(rec.scope.attr("__name__")).cast<std::string>();
  if (rec.is_constructor) return scope;
  return scope.empty() ? std::string(rec.name) : scope + "." + rec.name;
}

// Why this overload does not take the call ("" if it cannot be told).
std::string mismatch(const py::detail::function_record& rec, PyObject* const* args, size_t nargs, PyObject* kwnames) {
  const bool has_self = rec.is_method || rec.is_constructor;
  const size_t shown = has_self ? 1 : 0;  // `self` is not counted in what a user passed
  const size_t npos = rec.nargs_pos;
  if (!rec.has_args && nargs > npos)
    return "takes " + std::to_string(npos - shown) + " positional argument" + (npos - shown == 1 ? "" : "s") + " but " +
           std::to_string(nargs - shown) + " were given";
  std::vector<PyObject*> value(std::max<size_t>(rec.args.size(), rec.nargs), nullptr);
  for (size_t i = 0; i < nargs && i < value.size(); ++i) value[i] = args[i];
  const size_t nkw = kwnames ? static_cast<size_t>(PyTuple_GET_SIZE(kwnames)) : 0;
  for (size_t j = 0; j < nkw; ++j) {
    const std::string key = py::str(PyTuple_GET_ITEM(kwnames, j)).cast<std::string>();
    size_t i = 0;
    while (i < rec.args.size() && (rec.args[i].name == nullptr || key != rec.args[i].name)) ++i;
    if (i == rec.args.size()) {
      if (rec.has_kwargs) continue;
      return "got an unexpected keyword argument '" + key + "'";
    }
    if (i < rec.nargs_pos_only) return "got positional-only argument '" + key + "' as a keyword";
    if (value[i]) return "got multiple values for argument '" + key + "'";
    value[i] = args[nargs + j];
  }
  const std::vector<std::string> types = parameter_types(rec.signature ? rec.signature : "");
  // Constructors: args[0] is the instance being made (always of the class); the record's first argument too.
  // A function bound without argument names (a property accessor) has no argument records: its arguments
  // are "arg0", ... as in its signature (a property's arg0 is the instance: "self" here).
  const bool unnamed = rec.args.empty();
  const bool accessor = unnamed && found_names().count(&rec);
  const size_t count = unnamed ? rec.nargs : rec.args.size();
  for (size_t i = rec.is_constructor ? 1 : 0; i < count; ++i) {
    const py::detail::argument_record* a = unnamed ? nullptr : &rec.args[i];
    const std::string name = a && a->name ? std::string(a->name) : accessor && i == 0 ? "self" : "arg" + std::to_string(i);
    if (!value[i]) {
      if (!a || !a->value) return "missing required argument '" + name + "'";
      continue;
    }
    const Kind kind = kind_of(i < types.size() ? types[i] : std::string());
    if ((value[i] == Py_None && a && !a->none) || !accepts(value[i], kind)) {
      if (kind.what == Kind::kAny) return name + " must not be None";
      return name + " must be " + expected(kind) + ", got " + type_name_of(value[i]);
    }
  }
  return "";
}

std::string describe(PyObject* self, PyObject* const* args, size_t nargsf, PyObject* kwnames) {
  const py::detail::function_record* rec = py::detail::function_record_ptr_from_PyObject(self);
  const size_t nargs = static_cast<size_t>(PyVectorcall_NARGS(nargsf));
  const std::string prefix = function_name(*rec) + "(): ";
  if (!rec->next) {
    const std::string why = mismatch(*rec, args, nargs, kwnames);
    return prefix + (why.empty() ? "the arguments do not match " + function_name(*rec) + std::string(rec->signature) : why);
  }
  std::string out = prefix + "the arguments match none of its signatures:";
  for (const py::detail::function_record* it = rec; it; it = it->next) {
    const std::string why = mismatch(*it, args, nargs, kwnames);
    out += std::string("\n    ") + function_name(*it) + it->signature + ": " + (why.empty() ? "the types do not match" : why);
  }
  return out;
}

// pybind11's own check of a constructor's instance, before any overload is tried.
constexpr const char* kBadInit = "__init__(self, ...) called with invalid or missing `self` argument";

// pybind11's message when no overload of `rec` takes the call (and not one raised inside the call, by a
// function that this file did not patch).
bool is_dispatch_failure(const py::detail::function_record& rec, const std::string& msg) {
  const std::string head = std::string(rec.name ? rec.name : "") + "(): incompatible ";
  return msg.compare(0, head.size(), head) == 0 &&
         msg.find(" arguments. The following argument types are supported") != std::string::npos;
}

PyObject* named_dispatcher(PyObject* self, PyObject* const* args, size_t nargsf, PyObject* kwnames) {
  PyObject* out = pybind11_dispatcher(self, args, nargsf, kwnames);
  if (out || !PyErr_ExceptionMatches(PyExc_TypeError)) return out;
  PyObject *type, *value, *tb;
  PyErr_Fetch(&type, &value, &tb);
  PyErr_NormalizeException(&type, &value, &tb);
  std::string msg;
  try {
    msg = py::str(value).cast<std::string>();
    const py::detail::function_record* rec = py::detail::function_record_ptr_from_PyObject(self);
    if (is_dispatch_failure(*rec, msg)) {
      msg = describe(self, args, nargsf, kwnames);
    } else if (msg == kBadInit) {
      const std::string cls = function_name(*rec);
      msg = cls + "(): " +
            (PyVectorcall_NARGS(nargsf) == 0 ? "missing required argument 'self'"
                                              : "self must be a pathpace." + cls + ", got " + type_name_of(args[0]));
    } else {
      msg.clear();
    }
  } catch (...) {  // the rewrite must never hide the original error
    msg.clear();
  }
  if (msg.empty()) {
    PyErr_Restore(type, value, tb);
    return nullptr;
  }
  Py_XDECREF(type);
  Py_XDECREF(value);
  Py_XDECREF(tb);
  PyErr_SetString(PyExc_TypeError, msg.c_str());
  return nullptr;
}

void patch_function(py::handle f, const std::string& found_as) {
  if (f && PyInstanceMethod_Check(f.ptr())) f = PyInstanceMethod_GET_FUNCTION(f.ptr());
  if (!f || !PyCFunction_Check(f.ptr())) return;
  PyObject* self = PyCFunction_GET_SELF(f.ptr());
  py::detail::function_record* rec = self ? py::detail::function_record_ptr_from_PyObject(self) : nullptr;
  if (!rec || !rec->def) return;
  PyMethodDef* def = rec->def;
  if ((def->ml_flags & (METH_FASTCALL | METH_KEYWORDS)) != (METH_FASTCALL | METH_KEYWORDS)) return;
  auto meth = reinterpret_cast<FastCall>(reinterpret_cast<void (*)()>(def->ml_meth));
  if (meth == &named_dispatcher) return;
  if (!pybind11_dispatcher) pybind11_dispatcher = meth;
  if (meth != pybind11_dispatcher) return;  // not pybind11's (or another pybind11 build's) dispatcher
  if (rec->name == nullptr || rec->name[0] == '\0') found_names()[rec] = found_as;
  def->ml_meth = reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&named_dispatcher));
}

// A class attribute's functions: methods (instancemethod), static methods, property accessors.
void patch_attribute(py::handle v, const std::string& found_as) {
  if (PyInstanceMethod_Check(v.ptr()) || PyCFunction_Check(v.ptr())) return patch_function(v, found_as);
  py::module_ builtins = py::module_::import("builtins");
  if (py::isinstance(v, builtins.attr("staticmethod"))) return patch_function(v.attr("__func__"), found_as);
  if (py::isinstance(v, builtins.attr("property"))) {
    patch_function(v.attr("fget"), found_as);
    patch_function(v.attr("fset"), found_as);
  }
}

}  // namespace

void name_argument_errors(py::module_& m) {
  for (auto item : m.attr("__dict__").cast<py::dict>()) {
    py::handle v = item.second;
    const std::string name = py::str(item.first).cast<std::string>();
    if (PyCFunction_Check(v.ptr())) {
      patch_function(v, name);
    } else if (PyType_Check(v.ptr()) && py::hasattr(v, "__module__") &&
               py::str(v.attr("__module__")).cast<std::string>() == py::str(m.attr("__name__")).cast<std::string>()) {
      for (auto attr : v.attr("__dict__").cast<py::dict>())
        patch_attribute(attr.second, name + "." + py::str(attr.first).cast<std::string>());
    }
  }
}

}  // namespace pathpace::python
