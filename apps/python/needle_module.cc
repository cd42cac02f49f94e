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

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/case/plausible_ranges.h"
#include "apps/python/python_scene.h"
#include "apps/python/python_support.h"
#include "apps/report/cam_writer.h"
#include "apps/report/check_writers.h"
#include "apps/report/command_output.h"
#include "apps/report/compare_writer.h"
#include "apps/report/dynamics_writer.h"
#include "apps/report/kinematics_writer.h"
#include "apps/report/size_writer.h"
#include "apps/report/spring_writer.h"
#include "apps/report/tolerance_writer.h"
#include "apps/study/check_scene.h"
#include "apps/study/tolerance_study.h"
#include "dynamics/solver/integrator.h"
#include "lib/spline.h"

namespace needle::python {
namespace {

using py::arg;

// needle.Case, needle.Scene and load_case: the case as Python holds it.
void DefCase(py::module_& m) {
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

  DefScene(m);
  DefFit(m);

  Def(
      m, "load_case",
      [](const py::object& source, const std::optional<std::string>& name,
         const py::object& cycle) { return LoadAnyCase(source, name, cycle, "load_case"); },
      arg("source"), py::kw_only(), arg("name") = py::none(), arg("cycle") = py::none(),
      "Loads a case: a path (str or os.PathLike) to a TOML case or a bare CSV lift table (then "
      "`cycle`, 'four-stroke' by default, or 'two-stroke'), a dict with the case file's sections "
      "(`name` is its path in messages and relative paths), or a needle.Case (a copy).");
}

// The commands of one case: kinematics, spring, size, simulate, overspeed, check, profile.
void DefCaseCommands(py::module_& m) {
  Def(
      m, "kinematics",
      [](const py::object& source, const py::object& rpm, const py::object& step_deg,
         const py::object& spline) {
        return SceneKinematics(SceneSource(source, "kinematics"), rpm, step_deg, spline);
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), arg("step_deg") = 5.0,
      arg("spline") = py::none(), "needle kinematics: the velocity and acceleration table");

  Def(
      m, "spring",
      [](const py::object& source, const py::object& rpm) {
        const auto c = CaseOf(source, "spring");
        const std::optional<double> speed = Speed(rpm, "rpm");
        RequireSpeedOf(*c, speed, "rpm");
        return Run([&] { return WriteSpring(CheckCaseSpring(Bind(*c), speed), true); },
                   {{"--rpm", "rpm=" + Repr(rpm)}});
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), "needle spring: the spring check");

  Def(
      m, "size",
      [](const py::object& source) {
        const auto c = CaseOf(source, "size");
        return Run([&] {
          SizeWriting json;
          json.json = true;
          const BoundCase b = Bind(*c);
          return WriteSize(b, SizeCase(b, *b.lift.law), json);
        });
      },
      arg("case"),
      "needle size: the lightest spring that passes every limit, verified by the check (the "
      "JSON object of `needle size --json`)");

  Def(
      m, "simulate",
      [](const py::object& source, const py::object& rpm, const py::object& method,
         const py::object& rtol, const py::object& dynamic, const py::object& series,
         const py::object& grid_deg) {
        return SceneSimulate(SceneSource(source, "simulate"), rpm, method, rtol, dynamic, series,
                             grid_deg);
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(), arg("method") = py::none(),
      arg("rtol") = py::none(), arg("dynamic") = false, arg("series") = false,
      arg("grid_deg") = py::none(),
      "needle simulate: one dynamic run (series=True: the time series under 'columns'; grid_deg: "
      "the needle's lift at those crank angles under 'grid', as a lift sensor reads it); a loop "
      "over speeds binds the case once with needle.Scene(case).simulate(rpm=…)");

  Def(
      m, "overspeed",
      [](const py::object& source, const py::object& from_rpm, const py::object& to_rpm,
         const py::object& step_rpm, const py::object& method, const py::object& rtol,
         const py::object& threads) {
        return SceneOverspeed(SceneSource(source, "overspeed"), from_rpm, to_rpm, step_rpm, method,
                              rtol, threads);
      },
      arg("case"), py::kw_only(), arg("from_rpm") = py::none(), arg("to_rpm") = py::none(),
      arg("step_rpm") = py::none(), arg("method") = py::none(), arg("rtol") = py::none(),
      arg("threads") = 0, "needle overspeed: the dynamic lift-off speed n_dyn beside n_qs");

  Def(
      m, "check",
      [](const py::object& source, const py::object& rpm) {
        return SceneCheck(SceneSource(source, "check"), rpm);
      },
      arg("case"), py::kw_only(), arg("rpm") = py::none(),
      "needle check: everything the scene needs, one verdict (the dict of check --json; no "
      "report)");

  Def(
      m, "profile",
      [](const py::object& source) {
        const auto c = CaseOf(source, "profile");
        RequireSpeedOf(*c, std::nullopt, "");
        CamWriting json;
        json.json = true;
        return Run([&] { return WriteProfile(ProfileOfCase(Bind(*c)), json); });
      },
      arg("case"), "needle profile: the cam profile and its follower checks");
}

// compare (two cases), design (an engine file) and synth (a spec).
void DefDesignCommands(py::module_& m) {
  Def(
      m, "compare",
      [](const py::object& a, const py::object& b, const py::object& rpm) {
        const auto ca = CaseOf(a, "compare"), cb = CaseOf(b, "compare");
        const std::optional<double> speed = Speed(rpm, "rpm");
        RequireSpeedOf(*ca, speed, "rpm");
        RequireSpeedOf(*cb, speed, "rpm");
        return Run(
            [&] {
              BoundCase a_bound = Bind(*ca);  // A's problem first
              const Comparison cmp = CompareCases(std::move(a_bound), Bind(*cb), speed);
              CommandOutput out;
              out.json = CompareJson(cmp, "");
              for (nlohmann::json* j : {&out.json, &out.json["a"], &out.json["b"]})
                j->erase("report");  // no report is written from Python
              out.status = cmp.status();
              return out;
            },
            {{"--rpm", "rpm=" + Repr(rpm)}});
      },
      arg("a"), arg("b"), py::kw_only(), arg("rpm") = py::none(),
      "needle compare: two designs checked side by side, the verdicts that flip");

  Def(
      m, "design",
      [](const py::object& engine, std::optional<std::string> name) {
        const DesignInputs in =
            FromPathOrDict(engine, name, "design", LoadDesignInputs, ParseDesignInputs);
        return Run([&] { return WriteDesign(in, DesignFromEngine(in), true, std::nullopt); });
      },
      arg("engine"), py::kw_only(), arg("name") = py::none(),
      "needle design: Basu's design chain from an engine file or dict");

  Def(
      m, "synth",
      [](const py::object& spec, std::optional<std::string> name) {
        const SynthesisFile f =
            FromPathOrDict(spec, name, "synth", LoadSynthesisFile, ParseSynthesisFile);
        CamWriting json;
        json.json = true;
        return Run([&] { return WriteSynth(f, SynthesizeCam(f), json); });
      },
      arg("spec"), py::kw_only(), arg("name") = py::none(),
      "needle synth: a rise law under derivative limits, from a spec file or dict");
}

// The tolerance study, whole and in shards, and the case text a shard reads.
void DefStudies(py::module_& m) {
  Def(
      m, "tolerance",
      [](const py::object& source, const py::object& samples, const py::object& seed,
         const py::object& first_sample, const py::object& threads) {
        const auto c = CaseOf(source, "tolerance");
        ToleranceOptions o;
        o.samples =
            static_cast<int>(Whole(samples, "samples", "a number of samples", kSamplesRange));
        SetStudyKeywords(o, seed, first_sample, threads);
        RequireSpeedOf(*c, std::nullopt, "");
        return Run([&] {
          CommandOutput out;
          const BoundCase b = Bind(*c);
          out.json = ToleranceJson(b, RunToleranceStudy(b, o));
          return out;
        });
      },
      py::arg("case"), py::kw_only(), py::arg("samples") = 1000, py::arg("seed") = 1,
      py::arg("first_sample") = 0, py::arg("threads") = 0,
      "needle tolerance: a Monte-Carlo study (samples [first_sample, first_sample + samples) of "
      "the seed's study: shards of one study on several machines are its parts)");

  Def(
      m, "tolerance_shard",
      [](const std::string& text, const std::string& path, const py::object& seed,
         const py::object& first_sample, const py::object& samples, const py::object& threads,
         const std::optional<std::string>& shown_as) {
        ToleranceOptions o;
        o.samples =
            static_cast<int>(Whole(samples, "samples", "a number of samples", kSamplesRange));
        SetStudyKeywords(o, seed, first_sample, threads);
        std::vector<ToleranceSample> result;
        {
          py::gil_scoped_release release;
          Case c = ParseCase(text, path);
          if (shown_as) c.path = *shown_as;
          RequireSpeedOf(c, std::nullopt, "");
          result = RunToleranceSamples(Bind(c), o);
        }
        return ShardArrays(result, o.seed, o.first_sample, CaseDigest(text));
      },
      py::arg("text"), py::kw_only(), py::arg("path"), py::arg("seed"), py::arg("first_sample"),
      py::arg("samples"), py::arg("threads") = 1, py::arg("shown_as") = py::none(),
      "A shard of a tolerance study as a worker computes it: the case file's text (read as the "
      "file `path` would be: a lift CSV beside it; `shown_as`: the path its messages give), the "
      "samples [first_sample, first_sample + samples) of the seed's study, as arrays: "
      "input_keys/inputs/input_present, output_keys/outputs/output_present (samples × keys), "
      "pass, failing (each sample's failing items), refused (the model's reason, or '')");

  Def(
      m, "case_text",
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

  Def(
      m, "tolerance_reduce",
      [](const py::object& source, const py::sequence& shards, const py::object& seed,
         const py::object& first_sample, const py::object& threads, double seconds) {
        std::shared_ptr<const Case> c;
        std::string text;
        if (py::isinstance<PyCase>(source)) {
          PyCase& pc = source.cast<PyCase&>();
          c = Validated(pc);
          text = pc.text;
        } else {
          const PyCase pc = LoadAnyCase(source, std::nullopt, py::none(), "tolerance_reduce");
          c = pc.loaded;
          text = pc.text;
        }
        ToleranceOptions o;
        SetStudyKeywords(o, seed, first_sample, threads);
        std::vector<ToleranceSample> samples =
            ShardSamples(shards, o.seed, o.first_sample, CaseDigest(text));
        o.samples = static_cast<int>(samples.size());
        return Run([&] {
          const BoundCase b = Bind(*c);
          ToleranceResult r = ReduceToleranceStudy(b, o, std::move(samples));
          r.seconds = seconds;
          CommandOutput out;
          out.json = ToleranceJson(b, r);
          return out;
        });
      },
      py::arg("case"), py::arg("shards"), py::kw_only(), py::arg("seed"),
      py::arg("first_sample") = 0, py::arg("threads") = 1, py::arg("seconds") = 0.0,
      "The study of gathered shards (tolerance_shard's dicts, in sample order, the first "
      "starting at first_sample): what needle.tolerance returns for those samples, computed by "
      "the same code (threads and seconds: what the report states of the run)");
}

}  // namespace
}  // namespace needle::python

PYBIND11_MODULE(needle, m) {
  using namespace needle;
  using namespace needle::python;
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

  DefCase(m);
  DefCaseCommands(m);
  DefDesignCommands(m);
  DefStudies(m);
}
