// The Python module `needle` (pybind11): the commands of the `needle` program as functions of a
// case (a path, a needle.Case or a dict), returning what `--json` prints as a dict, with the
// command's table as NumPy arrays in SI under "columns" and its exit status under "exit_status".
// Bad input raises needle.CaseError (a ValueError): a case's problem with the command line's
// one-line message, a keyword's as "KEYWORD=VALUE: …" with the value as Python writes it.
// Computations run with the GIL released.
#include <dlfcn.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/cli/cam_command.h"
#include "apps/cli/command_output.h"
#include "apps/cli/dynamics_command.h"
#include "apps/cli/kinematics_command.h"
#include "apps/cli/spring_command.h"
#include "apps/cli/tolerance_command.h"
#include "apps/scene/case_file.h"
#include "apps/scene/plausible_ranges.h"
#include "apps/scene/tolerance_study.h"
#include "dynamics/solver/integrator.h"
#include "lib/spline.h"

namespace py = pybind11;

namespace needle {
namespace {

// JSON → Python: objects to dicts, arrays to lists, null to None.
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

// What a command computed, for Python: its JSON object, with the columns and the exit status.
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

// Short repr of a Python value, for messages: what the user typed, as Python prints it.
std::string Repr(const py::handle& v) {
  std::string s = py::repr(v).cast<std::string>();
  if (s.size() > 40) s = s.substr(0, 30) + "…(" + std::to_string(s.size()) + " characters)";
  return s;
}

std::string TypeName(const py::handle& v) {
  return py::str(py::type::of(v).attr("__name__")).cast<std::string>();
}

// "a bool", "an int": the type of a refused value, as Python would name it.
std::string AType(const py::handle& v) {
  const std::string t = TypeName(v);
  return (t.find_first_of("aeiou") == 0 ? "an " : "a ") + t;
}

// A range's end as Python writes a number: 50000, 0.001, 1e-14.
std::string PyNumber(double v) {
  if (v == std::floor(v) && std::fabs(v) < 1e16) return std::to_string(static_cast<long long>(v));
  return py::repr(py::float_(v)).cast<std::string>();
}

// A bool, Python's or NumPy's (numpy.bool_ is no subclass of bool).
bool IsBool(const py::handle& v) {
  const std::string t = TypeName(v);
  return py::isinstance<py::bool_>(v) || t == "bool_" || t == "bool";
}

// A keyword's number, as Python would take it: None is absent; a bool or a non-number is
// refused; a value outside the option's range is refused as "KEY=VALUE: expected …".
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

// A keyword's whole number in [lo, hi] (a bool, a float or a string is refused).
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

// A keyword's string (None is absent).
std::optional<std::string> Text(const py::object& v, const std::string& key,
                                const std::string& what) {
  if (v.is_none()) return std::nullopt;
  if (!py::isinstance<py::str>(v))
    throw CaseError(key + "=" + Repr(v) + ": expected " + what + ", not " + AType(v));
  return v.cast<std::string>();
}
std::optional<std::string> MethodKeyword(const py::object& v) {
  const auto m = Text(v, "method", "one of " + MethodList());
  if (m && *m != "auto" && !ParseMethod(*m))
    throw CaseError("method=" + Repr(v) + ": unknown method; expected one of " + MethodList());
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

// A Python dict as a TOML table (the case-file format), for the loaders. `where` names the key;
// a value the format cannot hold throws CaseError "KEY: …" (the caller puts the case's name first).
toml::table ToToml(const py::dict& d, const std::string& where);

toml::array ToTomlArray(const py::sequence& s, const std::string& where);

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

// A case from a dict: the same text the file would hold, read by the same loader.
std::string TomlText(const py::dict& d, const std::string& name) {
  std::ostringstream text;
  try {
    text << toml::toml_formatter(ToToml(d, ""));
  } catch (const CaseError& e) {
    throw CaseError(name + ": " + e.what());
  }
  return text.str();
}

// TOML → Python: tables to dicts, arrays to lists (what tomllib gives).
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

// needle.Case: the case as the sections of its file (plain dicts, read and written like a
// dict), with the validated Case of the text it last was. A change is validated when assigned
// at the top level, and whenever the case is run.
struct PyCase {
  py::dict data;                       ///< the sections, as the file holds them
  std::string name;                    ///< its path: messages and relative paths
  std::string text;                    ///< the TOML text `loaded` was read from
  std::shared_ptr<const Case> loaded;  ///< the validated case of `text`
};

// The validated case of the sections as they are now (read again when they changed).
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

// KeyError(key), as a dict raises it.
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

// The case a function was given: a needle.Case (validated as it is now), a path or a dict.
std::shared_ptr<const Case> CaseOf(const py::object& source, const std::string& function) {
  if (py::isinstance<PyCase>(source)) return Validated(source.cast<PyCase&>());
  return LoadAnyCase(source, std::nullopt, py::none(), function).loaded;
}

// A bare CSV lift table has no speed: the command's `rpm=` gives it (as --rpm does), else the
// case must state one.
void RequireSpeedOf(const Case& c, const std::optional<double>& rpm, const std::string& keyword) {
  if (c.engine.speed_rpm > 0.0 || rpm) return;
  throw CaseError(keyword.empty()
                      ? c.path +
                            " is a bare CSV lift table with no [engine] speed_rpm; set "
                            "case['engine']['speed_rpm']"
                      : keyword + "=None: " + c.path +
                            " is a bare CSV lift table with no [engine] speed_rpm; give " +
                            keyword + "=");
}

// Runs `compute` without the GIL and returns its result as a dict. A message the command
// names an option in ("--spline: …", also after the case's path) names the keyword instead
// (`options`: option, keyword=value).
template <typename Compute>
py::dict Run(Compute compute,
             const std::vector<std::pair<std::string, std::string>>& options = {}) {
  CommandOutput r;
  try {
    py::gil_scoped_release release;
    r = compute();
  } catch (const CaseError& e) {
    const std::string what = e.what();
    for (const auto& [option, keyword] : options) {
      const size_t at = what.find(option + ": ");  // first, or after the case's "PATH: "
      if (at != std::string::npos && (at == 0 || what.compare(at - 2, 2, ": ") == 0))
        throw CaseError(what.substr(0, at) + keyword + what.substr(at + option.size()));
    }
    throw;
  }
  return Result(r);
}

// A shard's samples as arrays: each quantity a column (its keys in order), whether the sample
// has it (a refused sample has no outputs), pass, the failing items and the refusals.
py::dict ShardArrays(const std::vector<ToleranceSample>& samples, int first_sample) {
  const auto table = [&](auto member, const char* keys_name, const char* values_name,
                         const char* present_name, py::dict& out) {
    std::vector<std::string> keys;
    for (const ToleranceSample& s : samples)
      for (const auto& [k, v] : s.*member)
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    std::sort(keys.begin(), keys.end());
    const auto n = static_cast<py::ssize_t>(samples.size());
    const auto m = static_cast<py::ssize_t>(keys.size());
    py::array_t<double> values({n, m});
    py::array_t<bool> present({n, m});
    auto v = values.mutable_unchecked<2>();
    auto p = present.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& map = samples[i].*member;
      for (py::ssize_t j = 0; j < m; ++j) {
        const auto it = map.find(keys[j]);
        p(i, j) = it != map.end();
        v(i, j) = it != map.end() ? it->second : NAN;
      }
    }
    out[keys_name] = keys;
    out[values_name] = std::move(values);
    out[present_name] = std::move(present);
  };
  py::dict out;
  out["first_sample"] = first_sample;
  out["samples"] = samples.size();
  table(&ToleranceSample::inputs, "input_keys", "inputs", "input_present", out);
  table(&ToleranceSample::outputs, "output_keys", "outputs", "output_present", out);
  py::array_t<bool> pass(static_cast<py::ssize_t>(samples.size()));
  std::vector<std::vector<std::string>> failing;
  std::vector<std::string> refused;
  for (size_t i = 0; i < samples.size(); ++i) {
    pass.mutable_data()[i] = samples[i].pass;
    failing.push_back(samples[i].failing);
    refused.push_back(samples[i].refused);
  }
  out["pass"] = std::move(pass);
  out["failing"] = failing;
  out["refused"] = refused;
  return out;
}

// The samples of shards as ShardArrays gives them (or read back from its files), in order.
std::vector<ToleranceSample> ShardSamples(const py::sequence& shards) {
  std::vector<ToleranceSample> samples;
  for (const auto& handle : shards) {
    const py::dict shard = py::reinterpret_borrow<py::object>(handle).cast<py::dict>();
    const auto n = shard["samples"].cast<py::ssize_t>();
    const size_t base = samples.size();
    samples.resize(base + n);
    const auto table = [&](auto member, const char* keys_name, const char* values_name,
                           const char* present_name) {
      const auto keys = shard[keys_name].cast<std::vector<std::string>>();
      const auto values =
          shard[values_name].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
      const auto present =
          shard[present_name].cast<py::array_t<bool, py::array::c_style | py::array::forcecast>>();
      const auto m = static_cast<py::ssize_t>(keys.size());
      if (values.ndim() != 2 || values.shape(0) != n || values.shape(1) != m ||
          present.ndim() != 2 || present.shape(0) != n || present.shape(1) != m)
        throw CaseError(std::string("a shard's ") + values_name + " is not samples × keys");
      const auto v = values.unchecked<2>();
      const auto p = present.unchecked<2>();
      for (py::ssize_t i = 0; i < n; ++i)
        for (py::ssize_t j = 0; j < m; ++j)
          if (p(i, j)) (samples[base + i].*member)[keys[j]] = v(i, j);
    };
    table(&ToleranceSample::inputs, "input_keys", "inputs", "input_present");
    table(&ToleranceSample::outputs, "output_keys", "outputs", "output_present");
    const auto pass =
        shard["pass"].cast<py::array_t<bool, py::array::c_style | py::array::forcecast>>();
    const auto failing = shard["failing"].cast<std::vector<std::vector<std::string>>>();
    const auto refused = shard["refused"].cast<std::vector<std::string>>();
    if (pass.ndim() != 1 || pass.shape(0) != n || failing.size() != static_cast<size_t>(n) ||
        refused.size() != static_cast<size_t>(n))
      throw CaseError("a shard's pass, failing or refused is not one per sample");
    for (py::ssize_t i = 0; i < n; ++i) {
      samples[base + i].pass = pass.data()[i];
      samples[base + i].failing = failing[i];
      samples[base + i].refused = refused[i];
    }
  }
  return samples;
}

// The folder of this module's file: needle.distributed and the package's Python files live in
// its subfolder `needle` (the module is a package whose __init__ is compiled).
std::string ModuleFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&ModuleFolder), &info) == 0 || info.dli_fname == nullptr)
    return ".";
  return std::filesystem::path(info.dli_fname).parent_path().string();
}

}  // namespace
}  // namespace needle

PYBIND11_MODULE(needle, m) {
  using namespace needle;
  using py::arg;
  // The columns are NumPy arrays: without NumPy, no import (rather than a failure at the first
  // calculation).
  try {
    py::module_::import("numpy");
  } catch (const py::error_already_set& e) {
    throw py::import_error(
        "the needle module needs NumPy (its results hold NumPy arrays), and this Python has "
        "none: apt-get install python3-numpy, or pip install numpy (" +
        py::str(e.type().attr("__name__")).cast<std::string>() + ": " +
        py::str(e.value()).cast<std::string>() + ")");
  }
  m.doc() =
      "needle: cam-driven needle valves. Every function takes a case (a path, a needle.Case or a "
      "dict) and returns what `needle COMMAND --json` prints, as a dict, with the command's table "
      "as NumPy arrays in SI under 'columns' and its exit status (0, or 1 when a check fails) "
      "under 'exit_status'. Bad input raises needle.CaseError (a ValueError) naming the key or "
      "keyword.";
  // A package: `import needle.distributed` finds the Python parts in the folder `needle` beside
  // this file (the build's build/python/needle, the install's site-packages/needle).
  m.attr("__version__") = NEEDLE_VERSION;
  py::list package_path;
  package_path.append((std::filesystem::path(ModuleFolder()) / "needle").string());
  m.attr("__path__") = package_path;
  static py::exception<CaseError> case_error(m, "CaseError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const CaseError& e) {
      PyErr_SetString(case_error.ptr(), e.what());
    } catch (const std::invalid_argument& e) {  // the CLI's exit 2 as well
      PyErr_SetString(case_error.ptr(), e.what());
    }
  });

  py::class_<PyCase>(
      m, "Case",
      "A case: its file's sections, read and written like a dict (case['needle']['mass_kg'] = "
      "1.6, 'train' in case, case.keys(), case.to_dict()). Validated as the file would be when "
      "run, and when a section is assigned or deleted.")
      .def(py::init(
               [](const py::object& source, const std::optional<std::string>& name,
                  const py::object& cycle) { return LoadAnyCase(source, name, cycle, "Case"); }),
           arg("source"), py::kw_only(), arg("name") = py::none(), arg("cycle") = py::none(),
           "needle.Case(source): as needle.load_case(source)")
      .def_property_readonly("path", [](const PyCase& c) { return c.name; })
      .def_property_readonly("title", [](PyCase& c) { return Validated(c)->title; })
      .def_property_readonly("speed_rpm", [](PyCase& c) { return Validated(c)->engine.speed_rpm; })
      .def("__getitem__",
           [](const PyCase& c, const py::str& key) -> py::object {
             if (!c.data.contains(key)) NoKey(key);
             return c.data[key];
           })
      .def("__setitem__",
           [](PyCase& c, const py::str& key, const py::object& value) {
             py::dict trial = DeepCopy(c.data);
             trial[key] = value;
             PyCase t{trial, c.name, "", nullptr};
             Validated(t);
             c.data[key] = value;
             c.text = t.text;
             c.loaded = t.loaded;
           })
      .def("__delitem__",
           [](PyCase& c, const py::str& key) {
             if (!c.data.contains(key)) NoKey(key);
             py::dict trial = DeepCopy(c.data);
             PyDict_DelItem(trial.ptr(), key.ptr());
             PyCase t{trial, c.name, "", nullptr};
             Validated(t);
             PyDict_DelItem(c.data.ptr(), key.ptr());
             c.text = t.text;
             c.loaded = t.loaded;
           })
      .def("__contains__",
           [](const PyCase& c, const py::object& key) { return c.data.contains(key); })
      .def("__iter__", [](const PyCase& c) { return py::iter(c.data); })
      .def("__len__", [](const PyCase& c) { return c.data.size(); })
      .def("keys", [](const PyCase& c) { return c.data.attr("keys")(); })
      .def("values", [](const PyCase& c) { return c.data.attr("values")(); })
      .def("items", [](const PyCase& c) { return c.data.attr("items")(); })
      .def(
          "get",
          [](const PyCase& c, const py::object& key, const py::object& fallback) {
            return c.data.attr("get")(key, fallback);
          },
          arg("key"), arg("default") = py::none())
      .def(
          "to_dict", [](const PyCase& c) { return DeepCopy(c.data); },
          "A deep copy of the sections: a dict load_case takes back")
      .def("__repr__", [](const PyCase& c) { return "<needle.Case " + c.name + ">"; });

  m.def(
      "load_case",
      [](const py::object& source, const std::optional<std::string>& name,
         const py::object& cycle) { return LoadAnyCase(source, name, cycle, "load_case"); },
      arg("source"), py::kw_only(), arg("name") = py::none(), arg("cycle") = py::none(),
      "Loads a case: a path (str or os.PathLike) to a TOML case or a bare CSV lift table (then "
      "`cycle`, 'four-stroke' by default, or 'two-stroke'), a dict with the case file's sections "
      "(`name` is its path in messages and relative paths), or a needle.Case (a copy).");

  m.def(
      "kinematics",
      [](const py::object& source, const py::object& rpm, const py::object& step_deg,
         const py::object& spline) {
        const auto c = CaseOf(source, "kinematics");
        KinematicsCommandOptions o;
        o.speed_rpm = Speed(rpm, "rpm");
        RequireSpeedOf(*c, o.speed_rpm, "rpm");
        o.step_deg = *Number(step_deg, "step_deg", "a spacing in crank degrees", kTableStepRange);
        o.spline = Text(spline, "spline", "one of " + SplineKindList());
        if (o.spline && !ParseSplineKind(*o.spline))
          throw CaseError("spline=" + Repr(spline) + ": unknown kind; expected one of " +
                          SplineKindList());
        o.json = true;
        return Run([&] { return ComputeKinematics(*c, o); },
                   {{"--rpm", "rpm=" + Repr(rpm)},
                    {"--step", "step_deg=" + Repr(step_deg)},
                    {"--spline", "spline=" + Repr(spline)}});
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), arg("step_deg") = 5.0,
      arg("spline") = py::none(), "needle kinematics: the velocity and acceleration table");

  m.def(
      "spring",
      [](const py::object& source, const py::object& rpm) {
        const auto c = CaseOf(source, "spring");
        SpringCommandOptions o;
        o.speed_rpm = Speed(rpm, "rpm");
        RequireSpeedOf(*c, o.speed_rpm, "rpm");
        o.json = true;
        return Run([&] { return ComputeSpring(*c, o); }, {{"--rpm", "rpm=" + Repr(rpm)}});
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), "needle spring: the spring check");

  m.def(
      "simulate",
      [](const py::object& source, const py::object& rpm, const py::object& method,
         const py::object& rtol, const py::object& dynamic, const py::object& series) {
        const auto c = CaseOf(source, "simulate");
        SimulateCommandOptions o;
        o.speed_rpm = Speed(rpm, "rpm");
        RequireSpeedOf(*c, o.speed_rpm, "rpm");
        o.method = MethodKeyword(method);
        o.rtol = Rtol(rtol);
        o.dynamic = Flag(dynamic, "dynamic");
        o.series = Flag(series, "series");
        o.json = true;
        return Run([&] { return ComputeSimulate(*c, o); }, {{"--rpm", "rpm=" + Repr(rpm)},
                                                            {"--method", "method=" + Repr(method)},
                                                            {"--rtol", "rtol=" + Repr(rtol)}});
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), arg("method") = py::none(),
      arg("rtol") = py::none(), arg("dynamic") = false, arg("series") = false,
      "needle simulate: one dynamic run (series=True: the time series under 'columns')");

  m.def(
      "overspeed",
      [](const py::object& source, const py::object& from_rpm, const py::object& to_rpm,
         const py::object& step_rpm, const py::object& method, const py::object& rtol,
         const py::object& threads) {
        const auto c = CaseOf(source, "overspeed");
        OverspeedCommandOptions o;
        o.from_rpm = Speed(from_rpm, "from_rpm");
        o.to_rpm = Speed(to_rpm, "to_rpm");
        o.step_rpm = Number(step_rpm, "step_rpm", "a speed step in rpm", kSpeedStepRange);
        o.method = MethodKeyword(method);
        o.rtol = Rtol(rtol);
        o.threads =
            static_cast<int>(Whole(threads, "threads", "a number of threads", kThreadsRange));
        RequireSpeedOf(*c, std::nullopt, "");
        o.json = true;
        return Run([&] { return ComputeOverspeed(*c, o); },
                   {{"--from", "from_rpm=" + Repr(from_rpm)},
                    {"--to", "to_rpm=" + Repr(to_rpm)},
                    {"--step-rpm", "step_rpm=" + Repr(step_rpm)},
                    {"--method", "method=" + Repr(method)},
                    {"--rtol", "rtol=" + Repr(rtol)},
                    {"--threads", "threads=" + Repr(threads)}});
      },
      arg("case"), py::kw_only(), arg("from_rpm") = py::none(), arg("to_rpm") = py::none(),
      arg("step_rpm") = py::none(), arg("method") = py::none(), arg("rtol") = py::none(),
      arg("threads") = 0, "needle overspeed: the dynamic lift-off speed n_dyn beside n_qs");

  m.def(
      "synth",
      [](const py::object& spec, std::optional<std::string> name) {
        const SynthesisFile f =
            py::isinstance<py::dict>(spec)
                ? ParseSynthesisFile(TomlText(spec.cast<py::dict>(), name.value_or("<dict>")),
                                     name.value_or("<dict>"))
            : IsPath(spec)
                ? LoadSynthesisFile(PathOf(spec))
                : throw py::type_error(
                      "synth: expected a path (str or os.PathLike) or a dict, got " + AType(spec));
        SynthCommandOptions o;
        o.json = true;
        return Run([&] { return ComputeSynth(f, o); });
      },
      arg("spec"), py::kw_only(), arg("name") = py::none(),
      "needle synth: a rise law under derivative limits, from a spec file or dict");

  m.def(
      "tolerance",
      [](const py::object& source, const py::object& samples, const py::object& seed,
         const py::object& first_sample, const py::object& threads) {
        const auto c = CaseOf(source, "tolerance");
        ToleranceOptions o;
        o.samples =
            static_cast<int>(Whole(samples, "samples", "a number of samples", kSamplesRange));
        o.seed = Whole(seed, "seed", "a whole number", kSeedRange);
        o.first_sample = static_cast<int>(
            Whole(first_sample, "first_sample", "a sample number", kFirstSampleRange));
        o.threads =
            static_cast<int>(Whole(threads, "threads", "a number of threads", kThreadsRange));
        RequireSpeedOf(*c, std::nullopt, "");
        return Run([&] {
          CommandOutput out;
          out.json = ToleranceJson(*c, RunToleranceStudy(*c, o));
          return out;
        });
      },
      py::arg("case"), py::kw_only(), py::arg("samples") = 1000, py::arg("seed") = 1,
      py::arg("first_sample") = 0, py::arg("threads") = 0,
      "needle tolerance: a Monte-Carlo study (samples [first_sample, first_sample + samples) of "
      "the seed's study: shards of one study on several machines are its parts)");

  m.def(
      "tolerance_shard",
      [](const std::string& text, const std::string& path, const py::object& seed,
         const py::object& first_sample, const py::object& samples, const py::object& threads,
         const std::optional<std::string>& shown_as) {
        ToleranceOptions o;
        o.samples =
            static_cast<int>(Whole(samples, "samples", "a number of samples", kSamplesRange));
        o.seed = Whole(seed, "seed", "a whole number", kSeedRange);
        o.first_sample = static_cast<int>(
            Whole(first_sample, "first_sample", "a sample number", kFirstSampleRange));
        o.threads =
            static_cast<int>(Whole(threads, "threads", "a number of threads", kThreadsRange));
        std::vector<ToleranceSample> result;
        {
          py::gil_scoped_release release;
          Case c = ParseCase(text, path);
          if (shown_as) c.path = *shown_as;
          RequireSpeedOf(c, std::nullopt, "");
          result = RunToleranceSamples(c, o);
        }
        return ShardArrays(result, o.first_sample);
      },
      py::arg("text"), py::kw_only(), py::arg("path"), py::arg("seed"), py::arg("first_sample"),
      py::arg("samples"), py::arg("threads") = 1, py::arg("shown_as") = py::none(),
      "A shard of a tolerance study as a worker computes it: the case file's text (read as the "
      "file `path` would be: a lift CSV beside it; `shown_as`: the path its messages give), the "
      "samples [first_sample, first_sample + samples) of the seed's study, as arrays: "
      "input_keys/inputs/input_present, output_keys/outputs/output_present (samples × keys), "
      "pass, failing (each sample's failing items), refused (the model's reason, or '')");

  m.def(
      "case_text",
      [](const py::object& source) {
        if (py::isinstance<PyCase>(source)) {
          PyCase& c = source.cast<PyCase&>();
          Validated(c);
          return c.text;
        }
        return LoadAnyCase(source, std::nullopt, py::none(), "case_text").text;
      },
      py::arg("case"),
      "The TOML text of a case (a path, a needle.Case or a dict), validated: what the loader "
      "reads back as the same case (tolerance_shard's `text`)");

  m.def(
      "tolerance_reduce",
      [](const py::object& source, const py::sequence& shards, const py::object& seed,
         const py::object& first_sample, const py::object& threads, double seconds) {
        const auto c = CaseOf(source, "tolerance_reduce");
        ToleranceOptions o;
        o.seed = Whole(seed, "seed", "a whole number", kSeedRange);
        o.first_sample = static_cast<int>(
            Whole(first_sample, "first_sample", "a sample number", kFirstSampleRange));
        o.threads =
            static_cast<int>(Whole(threads, "threads", "a number of threads", kThreadsRange));
        std::vector<ToleranceSample> samples = ShardSamples(shards);
        o.samples = static_cast<int>(samples.size());
        return Run([&] {
          ToleranceResult r = ReduceToleranceStudy(*c, o, std::move(samples));
          r.seconds = seconds;
          CommandOutput out;
          out.json = ToleranceJson(*c, r);
          return out;
        });
      },
      py::arg("case"), py::arg("shards"), py::kw_only(), py::arg("seed"),
      py::arg("first_sample") = 0, py::arg("threads") = 1, py::arg("seconds") = 0.0,
      "The study of gathered shards (tolerance_shard's dicts, in sample order, the first "
      "starting at first_sample): what needle.tolerance returns for those samples, computed by "
      "the same code (threads and seconds: what the report states of the run)");

  m.def(
      "profile",
      [](const py::object& source) {
        const auto c = CaseOf(source, "profile");
        RequireSpeedOf(*c, std::nullopt, "");
        ProfileCommandOptions o;
        o.json = true;
        return Run([&] { return ComputeProfile(*c, o); });
      },
      arg("case"), "needle profile: the cam profile and its follower checks");
}
