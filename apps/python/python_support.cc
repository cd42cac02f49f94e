// The Python module's support (python_support.h).
#include "apps/python/python_support.h"

#include <dlfcn.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/case/plausible_ranges.h"
#include "apps/report/check_writers.h"
#include "apps/report/command_output.h"
#include "apps/report/compare_writer.h"
#include "apps/report/tolerance_writer.h"
#include "apps/study/check_scene.h"
#include "apps/study/tolerance_study.h"
#include "dynamics/solver/integrator.h"
#include "lib/spline.h"

namespace needle::python {

py::object ToPython(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<long long>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<unsigned long long>());
    case nlohmann::json::value_t::number_float:
      return py::float_(j.get<double>());
    case nlohmann::json::value_t::string:
      return py::str(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const auto& v : j) out.append(ToPython(v));
      return std::move(out);
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (auto it = j.begin(); it != j.end(); ++it) out[py::str(it.key())] = ToPython(it.value());
      return std::move(out);
    }
    default:
      throw std::logic_error("a JSON value of no known type");
  }
}

py::dict Result(const CommandOutput& r) {
  py::dict out = ToPython(r.json);
  py::dict columns;
  for (const auto& [key, values] : r.columns) {
    py::array_t<double> a(static_cast<py::ssize_t>(values.size()));
    std::copy(values.begin(), values.end(), a.mutable_data());
    columns[py::str(key)] = std::move(a);
  }
  out["columns"] = std::move(columns);
  out["exit_status"] = r.status;
  return out;
}

std::string Repr(const py::handle& v) {
  std::string s = py::repr(v).cast<std::string>();
  if (s.size() > 40) s = s.substr(0, 30) + "…(" + std::to_string(s.size()) + " characters)";
  return s;
}

std::string TypeName(const py::handle& v) {
  return py::str(py::type::of(v).attr("__name__")).cast<std::string>();
}

std::string AType(const py::handle& v) {
  const std::string t = TypeName(v);
  return (t.find_first_of("aeiou") == 0 ? "an " : "a ") + t;
}

std::string PyNumber(double v) {
  if (v == std::floor(v) && std::fabs(v) < 1e16) return std::to_string(static_cast<long long>(v));
  return py::repr(py::float_(v)).cast<std::string>();
}

bool IsBool(const py::handle& v) {
  const std::string t = TypeName(v);
  return py::isinstance<py::bool_>(v) || t == "bool_" || t == "bool";
}

std::optional<double> Number(const py::object& v, const std::string& key, const std::string& what,
                             const std::string& range, double lo, double hi) {
  if (v.is_none()) return std::nullopt;
  const std::string rule = key + "=" + Repr(v) + ": expected " + what + " in " + range;
  const bool number = py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) ||
                      (!py::isinstance<py::str>(v) && py::hasattr(v, "__float__"));
  if (IsBool(v) || !number) throw CaseError(rule + ", not " + AType(v));
  double d = NAN;
  try {
    d = v.attr("__float__")().cast<double>();
  } catch (const py::error_already_set&) {  // OverflowError: an integer beyond a double
  }
  if (!(std::isfinite(d) && d >= lo && d <= hi)) throw CaseError(rule);
  return d;
}

std::optional<double> Number(const py::object& v, const std::string& key, const std::string& what,
                             const PlausibleRange& r) {
  const double lo = r.lo / r.unit_si, hi = r.hi / r.unit_si;
  return Number(v, key, what, "[" + PyNumber(lo) + ", " + PyNumber(hi) + "]", lo, hi);
}

std::optional<double> Speed(const py::object& v, const std::string& key) {
  return Number(v, key, "a speed in rpm", kCrankSpeedRange);
}

unsigned long long Whole(const py::object& v, const std::string& key, const std::string& what,
                         const PlausibleRange& r) {
  const std::string rule =
      key + "=" + Repr(v) + ": expected " + what + " in " +
      (&r == &kSeedRange ? RangeText(r) : "[" + PyNumber(r.lo) + ", " + PyNumber(r.hi) + "]");
  // An integer, Python's or NumPy's (what has __index__).
  if (IsBool(v) || !(py::isinstance<py::int_>(v) || py::hasattr(v, "__index__")))
    throw CaseError(rule + ", not " + AType(v));
  unsigned long long n = 0;
  try {
    // A negative or too large integer does not cast.
    n = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr())).cast<unsigned long long>();
  } catch (const py::cast_error&) {
    throw CaseError(rule);
  }
  if (&r != &kSeedRange && (static_cast<double>(n) < r.lo || static_cast<double>(n) > r.hi))
    throw CaseError(rule);
  return n;
}

std::optional<std::string> Text(const py::object& v, const std::string& key,
                                const std::string& what) {
  if (v.is_none()) return std::nullopt;
  if (!py::isinstance<py::str>(v))
    throw CaseError(key + "=" + Repr(v) + ": expected " + what + ", not " + AType(v));
  return v.cast<std::string>();
}

std::optional<std::string> MethodKeyword(const py::object& v) {
  const auto m = Text(v, "method", "one of " + MethodList());
  if (const std::string fault = m ? MethodNameFault(*m) : ""; !fault.empty())
    throw CaseError("method=" + Repr(v) + ": " + fault);
  return m;
}

std::optional<double> Rtol(const py::object& v) {
  return Number(v, "rtol", "a relative tolerance", RtolRangeText(), kMinRtol, kMaxRtol);
}

bool Flag(const py::object& v, const std::string& key) {
  if (!IsBool(v))
    throw CaseError(key + "=" + Repr(v) + ": expected True or False, not " + AType(v));
  return v.attr("__bool__")().cast<bool>();
}

namespace {

// One value; a key the case format cannot hold is refused in one line.
template <typename Add>
void AddValue(const py::handle& v, const std::string& where, Add add) {
  if (py::isinstance<py::bool_>(v)) {
    add(v.cast<bool>());
  } else if (py::isinstance<py::int_>(v)) {
    try {
      add(v.cast<long long>());
    } catch (const py::cast_error&) {
      // Beyond TOML's 64-bit integers: as the number it is, for the key's own check to judge.
      double d = NAN;
      try {
        d = v.attr("__float__")().cast<double>();
      } catch (const py::error_already_set&) {
      }
      if (!std::isfinite(d))
        throw CaseError(where + ": " + Repr(v) + " is too large for a number (a double)");
      add(d);
    }
  } else if (py::isinstance<py::float_>(v)) {
    add(v.cast<double>());
  } else if (py::isinstance<py::str>(v)) {
    add(v.cast<std::string>());
  } else if (py::isinstance<py::dict>(v)) {
    add(ToToml(v.cast<py::dict>(), where));
  } else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v) ||
             py::isinstance<py::array>(v)) {
    add(ToTomlArray(py::list(py::reinterpret_borrow<py::object>(v)), where));
  } else if (py::hasattr(v, "__float__")) {  // NumPy scalars
    add(v.attr("__float__")().cast<double>());
  } else {
    throw CaseError(where + ": expected a number, string, bool, list or dict, got " + AType(v));
  }
}

}  // namespace

toml::table ToToml(const py::dict& d, const std::string& where) {
  toml::table t;
  for (const auto& [k, v] : d) {
    const std::string key = py::str(k).cast<std::string>();
    // As the file's messages name it: "[engine]", "[engine] speed_rpm", "title".
    const std::string path = where.empty() ? (py::isinstance<py::dict>(v) ? "[" + key + "]" : key)
                             : where[0] == '[' && where.find(' ') == std::string::npos
                                 ? where + " " + key
                                 : where + "." + key;
    AddValue(v, path, [&](auto&& value) { t.insert(key, std::forward<decltype(value)>(value)); });
  }
  return t;
}

toml::array ToTomlArray(const py::sequence& s, const std::string& where) {
  toml::array a;
  for (const auto& v : s)
    AddValue(v, where, [&](auto&& value) { a.push_back(std::forward<decltype(value)>(value)); });
  return a;
}

std::string TomlText(const py::dict& d, const std::string& name) {
  std::ostringstream text;
  try {
    text << toml::toml_formatter(ToToml(d, ""));
  } catch (const CaseError& e) {
    throw CaseError(name + ": " + e.what());
  }
  return text.str();
}

py::object FromToml(const toml::node& n) {
  if (const auto* t = n.as_table()) {
    py::dict out;
    for (const auto& [k, v] : *t) out[py::str(std::string(k.str()))] = FromToml(v);
    return std::move(out);
  }
  if (const auto* a = n.as_array()) {
    py::list out;
    for (const auto& v : *a) out.append(FromToml(v));
    return std::move(out);
  }
  if (const auto v = n.value<bool>(); v && n.is_boolean()) return py::bool_(*v);
  if (n.is_integer()) return py::int_(*n.value<int64_t>());
  if (n.is_floating_point()) return py::float_(*n.value<double>());
  if (n.is_string()) return py::str(*n.value<std::string>());
  std::ostringstream s;  // dates and times: as TOML writes them
  n.visit([&](const auto& v) { s << v; });
  return py::str(s.str());
}

bool IsPath(const py::handle& source) {
  return py::isinstance<py::str>(source) || py::isinstance<py::bytes>(source) ||
         py::isinstance(source, py::module_::import("os").attr("PathLike"));
}

std::string PathOf(const py::handle& source) {
  return py::module_::import("os").attr("fsdecode")(source).cast<std::string>();
}

std::shared_ptr<const Case> Validated(PyCase& pc) {
  std::string text = TomlText(pc.data, pc.name);
  if (pc.loaded && text == pc.text) return pc.loaded;
  auto c = std::make_shared<const Case>(ParseCase(text, pc.name));
  pc.text = std::move(text);
  pc.loaded = c;
  return c;
}

py::dict DeepCopy(const py::dict& d) {
  return py::module_::import("copy").attr("deepcopy")(d).cast<py::dict>();
}

std::string NotCsv(const py::object& cycle) {
  return "cycle=" + Repr(cycle) + ": only for a bare CSV lift table; a case states [engine] cycle";
}

[[noreturn]] void NoKey(const py::object& key) {
  PyErr_SetObject(PyExc_KeyError, key.ptr());
  throw py::error_already_set();
}

PyCase LoadAnyCase(const py::object& source, const std::optional<std::string>& name,
                   const py::object& cycle_arg, const std::string& function) {
  const auto cycle = Text(cycle_arg, "cycle", "'four-stroke' or 'two-stroke'");
  if (cycle && !ParseEngineCycle(*cycle))
    throw CaseError("cycle=" + Repr(cycle_arg) + ": expected 'four-stroke' or 'two-stroke'");
  PyCase pc;
  if (py::isinstance<PyCase>(source)) {
    PyCase& other = source.cast<PyCase&>();
    if (cycle) throw CaseError(NotCsv(cycle_arg));
    pc = other;
    pc.data = DeepCopy(other.data);
    if (name) pc.name = *name, pc.loaded.reset();
    Validated(pc);
    return pc;
  }
  if (py::isinstance<py::dict>(source)) {
    if (cycle) throw CaseError(NotCsv(cycle_arg));
    pc.data = DeepCopy(source.cast<py::dict>());
    pc.name = name.value_or("<dict>");
    Validated(pc);
    return pc;
  }
  if (!IsPath(source))
    throw py::type_error(function +
                         ": expected a path (str or os.PathLike), a needle.Case or a "
                         "dict, got " +
                         AType(source));
  const std::string path = PathOf(source);
  pc.name = path;
  if (IsCsvPath(path)) {
    // A bare lift table: the case a file naming it would be, but for its speed (give rpm=).
    const std::string stroke = cycle.value_or("four-stroke");
    pc.loaded = std::make_shared<const Case>(CaseFromLiftCsv(path, *ParseEngineCycle(stroke)));
    py::dict engine, lift;
    engine["cycle"] = stroke;
    lift["csv"] = std::filesystem::path(path).filename().string();
    pc.data["engine"] = engine;
    pc.data["lift"] = lift;
  } else {
    if (cycle) throw CaseError(NotCsv(cycle_arg));
    pc.loaded = std::make_shared<const Case>(LoadCase(path));  // the command line's messages
    pc.data = FromToml(toml::parse_file(path)).cast<py::dict>();
  }
  pc.text = TomlText(pc.data, pc.name);
  return pc;
}

std::shared_ptr<const Case> CaseOf(const py::object& source, const std::string& function) {
  if (py::isinstance<PyCase>(source)) return Validated(source.cast<PyCase&>());
  return LoadAnyCase(source, std::nullopt, py::none(), function).loaded;
}

void RequireSpeedOf(const Case& c, const std::optional<double>& rpm, const std::string& keyword) {
  RequireSpeedOf(c.path, c.engine.speed_rpm, rpm, keyword);
}

void RequireSpeedOf(const std::string& path, double speed_rpm, const std::optional<double>& rpm,
                    const std::string& keyword) {
  if (speed_rpm > 0.0 || rpm) return;
  throw CaseError(keyword.empty()
                      ? path +
                            " is a bare CSV lift table with no [engine] speed_rpm; set "
                            "case['engine']['speed_rpm']"
                      : keyword + "=None: " + path +
                            " is a bare CSV lift table with no [engine] speed_rpm; give " +
                            keyword + "=");
}

void RethrowNamingKeywords(const CaseError& e,
                           const std::vector<std::pair<std::string, std::string>>& options) {
  const std::string what = e.what();
  for (const auto& [option, keyword] : options) {
    const size_t at = what.find(option + ": ");  // first, or after the case's "PATH: "
    if (at != std::string::npos && (at == 0 || what.compare(at - 2, 2, ": ") == 0))
      throw CaseError(what.substr(0, at) + keyword + what.substr(at + option.size()));
  }
  throw e;
}

namespace {

// The check of a call against `s` (CheckCalls), `function` naming it in the messages.
std::function<void(const py::args&, const py::kwargs&)> CallCheck(const std::string& function,
                                                                  const Signature& s) {
  const auto list = [&s](size_t from, size_t to) {
    std::string out;
    for (size_t i = from; i < to; ++i) out += (i == from ? "" : ", ") + s.names[i];
    return out;
  };
  const std::string all = list(0, s.names.size());
  const std::string by_position = list(0, s.positional),
                    by_keyword = list(s.positional, s.names.size());
  return [=](const py::args& args, const py::kwargs& kwargs) {
    if (args.size() > s.positional)
      throw py::type_error(function +
                           (s.positional == 0
                                ? " takes no positional arguments"
                                : " takes " + std::to_string(s.positional) +
                                      " positional argument(s) (" + by_position + ")") +
                           ", got " + std::to_string(args.size()) +
                           (by_keyword.empty() ? "" : "; give " + by_keyword + " by keyword"));
    for (const auto& [key, value] : kwargs) {
      const std::string k = py::str(key);
      const auto at = std::find(s.names.begin(), s.names.end(), k);
      if (at == s.names.end())
        throw py::type_error(function + " got an unexpected keyword argument '" + k +
                             "'; expected one of " + all);
      if (static_cast<size_t>(at - s.names.begin()) < args.size())
        throw py::type_error(function + " got argument '" + k +
                             "' by position and by keyword; it takes " + all);
    }
    for (size_t i = args.size(); i < s.names.size(); ++i) {
      const std::string& n = s.names[i];
      const bool required = std::find(s.required.begin(), s.required.end(), n) != s.required.end();
      if (required && !kwargs.contains(py::str(n)))
        throw py::type_error(function + " missing the argument '" + n + "'; it takes " + all);
    }
  };
}

}  // namespace

void CheckCalls(py::module_& m, const char* name, const Signature& s) {
  const py::object original = m.attr(name);
  const auto check = CallCheck(std::string(name) + "()", s);
  py::options options;
  options.disable_function_signatures();  // the original's doc below starts with its own
  m.attr(name) = py::cpp_function(
      [original, check](const py::args& args, const py::kwargs& kwargs) -> py::object {
        check(args, kwargs);
        return original(*args, **kwargs);
      },
      py::name(name), py::scope(m),
      py::doc(py::str(original.attr("__doc__")).cast<std::string>().c_str()));
}

void CheckMethodCalls(py::object cls, const char* name, const Signature& s) {
  const py::object original = cls.attr(name);
  const std::string class_name = py::str(cls.attr("__name__"));
  const auto check = CallCheck(class_name + "." + name + "()", s);
  py::options options;
  options.disable_function_signatures();
  cls.attr(name) = py::cpp_function(
      [original, check](const py::object& self, const py::args& args,
                        const py::kwargs& kwargs) -> py::object {
        check(args, kwargs);
        return original(self, *args, **kwargs);
      },
      py::name(name), py::is_method(cls),
      py::doc(py::str(original.attr("__doc__")).cast<std::string>().c_str()));
}

std::string ModuleFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&ModuleFolder), &info) == 0 || info.dli_fname == nullptr)
    return ".";
  return std::filesystem::path(info.dli_fname).parent_path().string();
}

void SetStudyKeywords(ToleranceOptions& o, const py::object& seed, const py::object& first_sample,
                      const py::object& threads) {
  o.seed = Whole(seed, "seed", "a whole number", kSeedRange);
  o.first_sample =
      static_cast<int>(Whole(first_sample, "first_sample", "a sample number", kFirstSampleRange));
  o.threads = static_cast<int>(Whole(threads, "threads", "a number of threads", kThreadsRange));
}

}  // namespace needle::python
