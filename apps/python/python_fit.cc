// needle.fit (apps/study/fit_job.h): the case's unknowns fitted to measured traces, each a CSV
// path or arrays, returning the dict of `needle fit --json`.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

#include "apps/case/bound_case.h"
#include "apps/case/measured_trace.h"
#include "apps/python/python_scene.h"
#include "apps/python/python_support.h"
#include "apps/report/fit_writer.h"
#include "apps/study/fit_job.h"
#include "lib/case_error.h"
#include "lib/units.h"

namespace needle::python {

namespace {

constexpr PlausibleRange kStartsRange{"starts", 1, 64, "", 1, "a local search from each"};

// One trace of `traces=[(source, rpm), …]`: a path to a CSV, or (crank_deg, lift_mm) arrays.
MeasuredTrace TraceOf(const py::handle& item, size_t index, const BoundCase& b) {
  const std::string where = "traces[" + std::to_string(index) + "]";
  if (!py::isinstance<py::tuple>(item) && !py::isinstance<py::list>(item)) {
    throw CaseError(where + ": expected (path or (crank_deg, lift_mm), rpm), got " + AType(item));
  }
  const py::sequence pair = py::reinterpret_borrow<py::sequence>(item);
  if (pair.size() != 2) throw CaseError(where + ": expected (source, rpm), a pair");
  const std::optional<double> speed = Speed(pair[1], where + "'s rpm");
  if (!speed) throw CaseError(where + ": the trace's rpm is None; expected a speed in rpm");
  const double rpm = *speed;
  const py::object source = pair[0];
  if (IsPath(source)) return ReadMeasuredTrace(PathOf(source), rpm, b);
  if (!py::isinstance<py::sequence>(source) || py::len(source) != 2) {
    throw CaseError(where + ": expected a path or (crank_deg, lift_mm) arrays, got " +
                    AType(source));
  }
  MeasuredTrace t;
  t.path = where;
  t.speed_rpm = rpm;
  const auto deg = py::array_t<double, py::array::forcecast>::ensure(source[py::int_(0)]);
  const auto mm = py::array_t<double, py::array::forcecast>::ensure(source[py::int_(1)]);
  if (!deg || !mm || deg.ndim() != 1 || mm.ndim() != 1 || deg.size() != mm.size()) {
    throw CaseError(where + ": crank_deg and lift_mm must be 1-D arrays of one length");
  }
  for (py::ssize_t i = 0; i < deg.size(); ++i) {
    t.table.crank_rad.push_back(deg.at(i) * kDeg);
    t.table.lift_m.push_back(mm.at(i) * 1e-3);
  }
  CheckMeasuredTrace(t, b);
  return t;
}

}  // namespace

void DefFit(py::module_& m) {
  Def(
      m, "fit",
      [](const py::object& source, const py::object& traces, const py::object& free,
         const py::object& bounds, const py::object& starts, const py::object& seed,
         const py::object& liftoff) {
        SceneSource scene(source, "fit");
        const std::shared_ptr<const BoundCase> b = scene.Shared();
        FitOptions o;
        if (py::isinstance<py::str>(free)) {
          throw CaseError("free: expected a list of keys, e.g. ['" + std::string(py::str(free)) +
                          "'], got a string");
        }
        for (const py::handle& k : py::iterable(free)) {
          o.free.push_back(ParseFitKey(py::str(k), "free"));
        }
        if (!bounds.is_none()) {
          for (const py::handle& k : py::iterable(bounds)) {
            o.bounds.push_back(ParseFitBound(py::str(k), "bounds"));
          }
        }
        o.starts = static_cast<int>(Whole(starts, "starts", "a number of starts", kStartsRange));
        o.seed = Whole(seed, "seed", "a seed", kSeedRange);
        o.predict_liftoff = Flag(liftoff, "liftoff");
        std::vector<MeasuredTrace> ts;
        size_t index = 0;
        if (!py::isinstance<py::iterable>(traces) || py::isinstance<py::str>(traces))
          throw py::type_error("traces=" + Repr(traces) +
                               ": expected a list of (path or (crank_deg, lift_mm), rpm), got " +
                               AType(traces));
        for (const py::handle& item : py::iterable(traces))
          ts.push_back(TraceOf(item, index++, *b));
        return Run([&] {
          CommandOutput out;
          out.json = FitJson(*b, FitCase(*b, ts, o));
          return out;
        });
      },
      py::arg("case"), py::kw_only(), py::arg("traces"), py::arg("free"),
      py::arg("bounds") = py::none(), py::arg("starts") = 12, py::arg("seed") = 1,
      py::arg("liftoff") = true,
      "needle fit: the case's unknowns (free=['train.play_mm', …]) fitted to measured traces "
      "(traces=[(path or (crank_deg, lift_mm), rpm), …]), each with its 95 % interval; the dict "
      "of `needle fit --json`");
}

}  // namespace needle::python
