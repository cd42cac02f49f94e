// needle.Scene: a case bound once, run many times (python_scene.h).
#include "apps/python/python_scene.h"

#include <memory>
#include <utility>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/case/plausible_ranges.h"
#include "apps/python/python_support.h"
#include "apps/report/check_writers.h"
#include "apps/report/dynamics_writer.h"
#include "apps/report/kinematics_writer.h"
#include "apps/study/check_scene.h"
#include "apps/study/dynamics_jobs.h"
#include "apps/study/kinematics_table.h"

namespace needle::python {

using py::arg;

SceneSource::SceneSource(const py::object& source, const std::string& function)
    : function_(function) {
  if (py::isinstance<PyScene>(source)) {
    bound_ = source.cast<PyScene>().bound;
    return;
  }
  loaded_ = CaseOf(source, function);
}

void SceneSource::SetSpline(const std::string& spline) {
  if (!loaded_)
    throw CaseError(function_ + ": spline= needs a case; a needle.Scene is bound with its own");
  spline_ = spline;
}

const std::string& SceneSource::path() const { return bound_ ? bound_->path : loaded_->path; }

double SceneSource::speed_rpm() const {
  return bound_ ? bound_->engine.speed_rpm : loaded_->engine.speed_rpm;
}

std::shared_ptr<const BoundCase> SceneSource::Shared() {
  if (!bound_) {
    bound_ = std::make_shared<const BoundCase>(
        Bind(spline_ ? WithSpline(*loaded_, *spline_, "--spline") : *loaded_));
  }
  return bound_;
}

py::dict SceneKinematics(SceneSource s, const py::object& rpm, const py::object& step_deg,
                         const py::object& spline) {
  KinematicsTableOptions o;
  o.speed_rpm = Speed(rpm, "rpm");
  RequireSpeedOf(s.path(), s.speed_rpm(), o.speed_rpm, "rpm");
  o.step_deg = *Number(step_deg, "step_deg", "a spacing in crank degrees", kTableStepRange);
  if (const auto kind = Text(spline, "spline", "one of " + SplineKindList())) {
    if (!ParseSplineKind(*kind))
      throw CaseError("spline=" + Repr(spline) + ": unknown kind; expected one of " +
                      SplineKindList());
    s.SetSpline(*kind);
  }
  KinematicsWriting json;
  json.json = true;
  return Run([&] { return WriteKinematics(MakeKinematicsTable(s.Bound(), o), json); },
             {{"--rpm", "rpm=" + Repr(rpm)},
              {"--step", "step_deg=" + Repr(step_deg)},
              {"--spline", "spline=" + Repr(spline)}});
}

py::dict SceneSimulate(SceneSource s, const py::object& rpm, const py::object& method,
                       const py::object& rtol, const py::object& dynamic, const py::object& series,
                       const py::object& grid_deg) {
  SimulateJobOptions o;
  if (!grid_deg.is_none()) {
    for (const py::handle& v : py::iterable(grid_deg)) {
      const std::optional<double> deg =
          Number(py::reinterpret_borrow<py::object>(v), "grid_deg", "a crank angle in deg",
                 "within ±720 deg", -720.0, 720.0);
      if (!deg) throw CaseError("grid_deg: None is not a crank angle; expected numbers in deg");
      o.grid_deg.push_back(*deg);
    }
  }
  o.speed_rpm = Speed(rpm, "rpm");
  RequireSpeedOf(s.path(), s.speed_rpm(), o.speed_rpm, "rpm");
  o.method = MethodKeyword(method);
  o.rtol = Rtol(rtol);
  o.dynamic = Flag(dynamic, "dynamic");
  o.series = Flag(series, "series");
  return Run([&] { return WriteSimulate(SimulateCase(s.Bound(), o), true); },
             {{"--rpm", "rpm=" + Repr(rpm)},
              {"--method", "method=" + Repr(method)},
              {"--rtol", "rtol=" + Repr(rtol)},
              {"--grid", "grid_deg"}});
}

py::dict SceneOverspeed(SceneSource s, const py::object& from_rpm, const py::object& to_rpm,
                        const py::object& step_rpm, const py::object& method,
                        const py::object& rtol, const py::object& threads) {
  OverspeedJobOptions o;
  o.from_rpm = Speed(from_rpm, "from_rpm");
  o.to_rpm = Speed(to_rpm, "to_rpm");
  o.step_rpm = Number(step_rpm, "step_rpm", "a speed step in rpm", kSpeedStepRange);
  o.method = MethodKeyword(method);
  o.rtol = Rtol(rtol);
  o.threads = static_cast<int>(Whole(threads, "threads", "a number of threads", kThreadsRange));
  RequireSpeedOf(s.path(), s.speed_rpm(), std::nullopt, "");
  return Run([&] { return WriteOverspeed(OverspeedOfCase(s.Bound(), o), true); },
             {{"--from", "from_rpm=" + Repr(from_rpm)},
              {"--to", "to_rpm=" + Repr(to_rpm)},
              {"--step-rpm", "step_rpm=" + Repr(step_rpm)},
              {"--method", "method=" + Repr(method)},
              {"--rtol", "rtol=" + Repr(rtol)},
              {"--threads", "threads=" + Repr(threads)}});
}

py::dict SceneCheck(SceneSource s, const py::object& rpm) {
  CheckOptions options;
  options.speed_rpm = Speed(rpm, "rpm");
  RequireSpeedOf(s.path(), s.speed_rpm(), options.speed_rpm, "rpm");
  return Run(
      [&] {
        const BoundCase& b = s.Bound();
        const CheckResult r = CheckScene(b, options);
        CommandOutput out;
        out.json = CheckJson(b, *b.lift.law, r, "");
        out.json.erase("report");  // no report is written from Python
        out.status = r.pass ? 0 : 1;
        return out;
      },
      {{"--rpm", "rpm=" + Repr(rpm)}});
}

void DefScene(py::module_& m) {
  py::class_<PyScene> scene(
      m, "Scene",
      "A case bound once: its lift law chosen and built, its dynamic scene and run options made. "
      "Run it many times (scene.simulate(rpm=…) in a loop over speeds) without reading or "
      "binding the case again. A snapshot: a needle.Case changed afterwards does not change it.");
  scene
      .def(py::init([](const py::object& source) {
             SceneSource s(source, "Scene");
             py::gil_scoped_release release;
             return PyScene{s.Shared()};
           }),
           arg("case"), "needle.Scene(case): a path, a needle.Case or a dict, bound once")
      .def_property_readonly("path", [](const PyScene& s) { return s.bound->path; })
      .def_property_readonly("title", [](const PyScene& s) { return s.bound->title; })
      .def_property_readonly("speed_rpm",
                             [](const PyScene& s) { return s.bound->engine.speed_rpm; })
      .def("__repr__", [](const PyScene& s) { return "<needle.Scene " + s.bound->path + ">"; });
  // Each method's keywords checked in one line, as the module's functions are (issue 51's
  // trial: scene.check(foo=1) gave pybind11's multi-line list of signatures).
  DefMethod(
      scene, "kinematics",
      [](const PyScene& s, const py::object& rpm, const py::object& step_deg) {
        return SceneKinematics(SceneSource(s), rpm, step_deg);
      },
      py::kw_only(), arg("rpm") = py::none(), arg("step_deg") = 5.0,
      "needle kinematics of the scene (as needle.kinematics)");
  DefMethod(
      scene, "simulate",
      [](const PyScene& s, const py::object& rpm, const py::object& method, const py::object& rtol,
         const py::object& dynamic, const py::object& series, const py::object& grid_deg) {
        return SceneSimulate(SceneSource(s), rpm, method, rtol, dynamic, series, grid_deg);
      },
      py::kw_only(), arg("rpm") = py::none(), arg("method") = py::none(), arg("rtol") = py::none(),
      arg("dynamic") = false, arg("series") = false, arg("grid_deg") = py::none(),
      "needle simulate of the scene (as needle.simulate)");
  DefMethod(
      scene, "overspeed",
      [](const PyScene& s, const py::object& from_rpm, const py::object& to_rpm,
         const py::object& step_rpm, const py::object& method, const py::object& rtol,
         const py::object& threads) {
        return SceneOverspeed(SceneSource(s), from_rpm, to_rpm, step_rpm, method, rtol, threads);
      },
      py::kw_only(), arg("from_rpm") = py::none(), arg("to_rpm") = py::none(),
      arg("step_rpm") = py::none(), arg("method") = py::none(), arg("rtol") = py::none(),
      arg("threads") = 0, "needle overspeed of the scene (as needle.overspeed)");
  DefMethod(
      scene, "check",
      [](const PyScene& s, const py::object& rpm) { return SceneCheck(SceneSource(s), rpm); },
      py::kw_only(), arg("rpm") = py::none(),
      "needle check of the scene (as needle.check: the dict of check --json)");
}

}  // namespace needle::python
