// The Python module `needle` (pybind11): the commands of the `needle` program as functions of a
// loaded case, returning what `--json` prints as a dict, with the command's table as NumPy
// arrays in SI under "columns" and its exit status under "exit_status". Bad input raises
// needle.CaseError (a ValueError) with the command line's one-line message. Computations run
// with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

#include "apps/cli/cam_command.h"
#include "apps/cli/command_output.h"
#include "apps/cli/dynamics_command.h"
#include "apps/cli/kinematics_command.h"
#include "apps/cli/spring_command.h"
#include "apps/cli/tolerance_command.h"
#include "apps/scene/case_file.h"

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

// A Python dict as a TOML table (the case-file format), for the loaders. `where` names the key.
toml::table ToToml(const py::dict& d, const std::string& where);

toml::array ToTomlArray(const py::sequence& s, const std::string& where);

// One value; a key the case format cannot hold is refused in one line.
template <typename Add>
void AddValue(const py::handle& v, const std::string& where, Add add) {
  if (py::isinstance<py::bool_>(v)) {
    add(v.cast<bool>());
  } else if (py::isinstance<py::int_>(v)) {
    add(v.cast<long long>());
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
    throw CaseError("<dict>: " + where + ": expected a number, string, bool, list or dict, got " +
                    py::str(py::type::of(v).attr("__name__")).cast<std::string>());
  }
}

toml::table ToToml(const py::dict& d, const std::string& where) {
  toml::table t;
  for (const auto& [k, v] : d) {
    const std::string key = py::str(k).cast<std::string>();
    const std::string path = where.empty() ? key : where + "." + key;
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
std::string TomlText(const py::dict& d) {
  std::ostringstream text;
  text << toml::toml_formatter(ToToml(d, ""));
  return text.str();
}

bool IsPath(const py::handle& source) {
  return py::isinstance<py::str>(source) ||
         py::isinstance(source, py::module_::import("os").attr("PathLike"));
}

std::string PathOf(const py::handle& source) { return py::str(source).cast<std::string>(); }

Case LoadAnyCase(const py::object& source, const std::optional<std::string>& name,
                 const std::string& cycle) {
  if (py::isinstance<py::dict>(source)) {
    return ParseCase(TomlText(source.cast<py::dict>()), name.value_or("<dict>"));
  }
  if (!IsPath(source)) throw CaseError("load_case: expected a path or a dict");
  const std::string path = PathOf(source);
  return IsCsvPath(path) ? CaseFromLiftCsv(path, cycle) : LoadCase(path);
}

// Runs `compute` without the GIL and returns its result as a dict.
template <typename Compute>
py::dict Run(Compute compute) {
  CommandOutput r;
  {
    py::gil_scoped_release release;
    r = compute();
  }
  return Result(r);
}

}  // namespace
}  // namespace needle

PYBIND11_MODULE(needle, m) {
  using namespace needle;
  using py::arg;
  m.doc() =
      "needle: cam-driven needle valves. Every function returns what `needle COMMAND --json` "
      "prints, as a dict, with the command's table as NumPy arrays in SI under 'columns' and its "
      "exit status (0, or 1 when a check fails) under 'exit_status'.";
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

  py::class_<Case>(m, "Case", "A loaded case (a TOML file, a bare CSV lift table, or a dict)")
      .def_property_readonly("path", [](const Case& c) { return c.path; })
      .def_property_readonly("title", [](const Case& c) { return c.title; })
      .def_property_readonly("speed_rpm", [](const Case& c) { return c.engine.speed_rpm; })
      .def("__repr__", [](const Case& c) { return "<needle.Case " + c.path + ">"; });

  m.def("load_case", &LoadAnyCase, arg("source"), py::kw_only(), arg("name") = py::none(),
        arg("cycle") = "four-stroke",
        "Loads a case: a path to a TOML case or a bare CSV lift table (then `cycle`), or a dict "
        "with the case file's sections (`name` is its path in messages and relative paths).");

  m.def(
      "kinematics",
      [](const Case& c, std::optional<double> rpm, double step_deg,
         std::optional<std::string> spline) {
        KinematicsCommandOptions o;
        o.speed_rpm = rpm;
        o.step_deg = step_deg;
        o.spline = spline;
        o.json = true;
        return Run([&] { return ComputeKinematics(c, o); });
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), arg("step_deg") = 5.0,
      arg("spline") = py::none(), "needle kinematics: the velocity and acceleration table");

  m.def(
      "spring",
      [](const Case& c, std::optional<double> rpm) {
        SpringCommandOptions o;
        o.speed_rpm = rpm;
        o.json = true;
        return Run([&] { return ComputeSpring(c, o); });
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), "needle spring: the spring check");

  m.def(
      "simulate",
      [](const Case& c, std::optional<double> rpm, std::optional<std::string> method,
         std::optional<double> rtol, bool dynamic, bool series) {
        SimulateCommandOptions o;
        o.speed_rpm = rpm;
        o.method = method;
        o.rtol = rtol;
        o.dynamic = dynamic;
        o.series = series;
        o.json = true;
        return Run([&] { return ComputeSimulate(c, o); });
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), arg("method") = py::none(),
      arg("rtol") = py::none(), arg("dynamic") = false, arg("series") = false,
      "needle simulate: one dynamic run (series=True: the time series under 'columns')");

  m.def(
      "overspeed",
      [](const Case& c, std::optional<double> from_rpm, std::optional<double> to_rpm,
         std::optional<double> step_rpm, std::optional<std::string> method,
         std::optional<double> rtol, int threads) {
        OverspeedCommandOptions o;
        o.from_rpm = from_rpm;
        o.to_rpm = to_rpm;
        o.step_rpm = step_rpm;
        o.method = method;
        o.rtol = rtol;
        o.threads = threads;
        o.json = true;
        return Run([&] { return ComputeOverspeed(c, o); });
      },
      arg("case"), py::kw_only(), arg("from_rpm") = py::none(), arg("to_rpm") = py::none(),
      arg("step_rpm") = py::none(), arg("method") = py::none(), arg("rtol") = py::none(),
      arg("threads") = 0, "needle overspeed: the dynamic lift-off speed n_dyn beside n_qs");

  m.def(
      "synth",
      [](const py::object& spec, std::optional<std::string> name) {
        const SynthesisFile f =
            py::isinstance<py::dict>(spec)
                ? ParseSynthesisFile(TomlText(spec.cast<py::dict>()), name.value_or("<dict>"))
            : IsPath(spec) ? LoadSynthesisFile(PathOf(spec))
                           : throw CaseError("synth: expected a path or a dict");
        SynthCommandOptions o;
        o.json = true;
        return Run([&] { return ComputeSynth(f, o); });
      },
      arg("spec"), py::kw_only(), arg("name") = py::none(),
      "needle synth: a rise law under derivative limits, from a spec file or dict");

  m.def(
      "tolerance",
      [](const Case& c, int samples, uint64_t seed, int first_sample, int threads) {
        ToleranceOptions o;
        o.samples = samples;
        o.seed = seed;
        o.first_sample = first_sample;
        o.threads = threads;
        return Run([&] {
          CommandOutput out;
          out.json = ToleranceJson(c, RunToleranceStudy(c, o));
          return out;
        });
      },
      py::arg("case"), py::kw_only(), py::arg("samples") = 1000, py::arg("seed") = 1,
      py::arg("first_sample") = 0, py::arg("threads") = 0,
      "needle tolerance: a Monte-Carlo study (samples [first_sample, first_sample + samples) of "
      "the seed's study: shards of one study on several machines are its parts)");

  m.def(
      "profile",
      [](const Case& c) {
        ProfileCommandOptions o;
        o.json = true;
        return Run([&] { return ComputeProfile(c, o); });
      },
      arg("case"), "needle profile: the cam profile and its follower checks");
}
