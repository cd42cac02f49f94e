#include "apps/study/dynamics_jobs.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "apps/case/plausible_ranges.h"
#include "apps/study/check_scene.h"
#include "lib/output.h"
#include "spring/quasi_static.h"

namespace needle {

namespace {

SimulationOptions Options(const BoundCase& c, const std::optional<std::string>& method,
                          const std::optional<double>& rtol) {
  SimulationOptions o = c.run;
  if (method) {
    if (const std::string fault = MethodNameFault(*method); !fault.empty())
      throw CaseError("--method: " + fault);
    o.method = *method;
  }
  if (rtol) {
    RequireIn("--rtol", rtol, kMinRtol, kMaxRtol, "a relative tolerance");
    o.integrator.rtol = *rtol;
    if (!c.atol_given) o.integrator.atol_m = DefaultAtol(*rtol);
  }
  return o;
}

}  // namespace

CaseRun SimulateCase(const BoundCase& c, const SimulateJobOptions& o,
                     const std::function<void(const SeriesPoint&)>& series_sink) {
  RequireSpeed(o.speed_rpm);
  const Scene scene = SceneFor(c, c.lift.law);  // throws what is missing
  SimulationOptions sim = Options(c, o.method, o.rtol);
  sim.force_dynamic = o.dynamic;
  // Streamed: to the caller's sink, and as SI columns when asked; none is kept as a whole.
  std::vector<std::vector<double>> si(SeriesColumns().size());
  sim.record_series = series_sink || o.series;
  if (sim.record_series) {
    sim.series_sink = [&](const SeriesPoint& p) {
      if (series_sink) series_sink(p);
      if (!o.series) return;
      const std::array<double, 7> row = SeriesRow(p);
      for (size_t i = 0; i < row.size(); ++i) si[i].push_back(row[i]);
    };
  }
  for (size_t i = 0; i < o.grid_deg.size(); ++i) {
    if (!std::isfinite(o.grid_deg[i]) || (i > 0 && !(o.grid_deg[i] > o.grid_deg[i - 1]))) {
      throw CaseError("--grid: the crank angles must be finite and increase strictly (at " +
                      std::to_string(i) + ")");
    }
    sim.grid_rad.push_back(o.grid_deg[i] * kDeg);
  }
  if (o.cycles) {
    sim.cycles = *o.cycles;
    const auto refusal = sim.cycles > 1 ? CyclesRefusal(scene) : std::nullopt;
    if (refusal) throw CaseError("--cycles: " + *refusal);
  }
  if (!o.grid_deg.empty() && sim.cycles > 1) {
    throw CaseError("--grid: a grid of crank angles needs one revolution; the run has " +
                    std::to_string(sim.cycles) + " ([solver] cycles or --cycles)");
  }
  const double speed = o.speed_rpm.value_or(c.engine.speed_rpm);
  CaseRun run{c, speed, sim.integrator.rtol, NAN, Simulate(scene, speed, sim), {}};
  if (o.quasi_static) run.liftoff_rpm_quasi_static = QuasiStaticLiftoffRpm(scene);
  if (!si[0].empty()) run.series_si = std::move(si);
  return run;
}

CaseOverspeed OverspeedOfCase(const BoundCase& c, const OverspeedJobOptions& o,
                              const std::function<void(int, int)>& progress) {
  RequireIn("--threads", o.threads, kThreadsRange.lo, kThreadsRange.hi, "a number of threads");
  RequireIn("--step-rpm", o.step_rpm, kSpeedStepRange.lo, kSpeedStepRange.hi,
            "a speed step in rpm");
  RequireSpeed(o.from_rpm, "--from");
  RequireSpeed(o.to_rpm, "--to");
  const Scene scene = SceneFor(c, c.lift.law);  // throws what is missing
  const double n_qs = QuasiStaticLiftoffRpm(scene);
  OverspeedOptions opt;
  opt.simulation = Options(c, o.method, o.rtol);
  opt.simulation.steady_state = c.overspeed && c.overspeed->steady_state;  // [overspeed]
  opt.threads = o.threads;
  opt.step_rpm = o.step_rpm.value_or(0.0);
  const SweepRange range = DefaultSweepRange(c, c.engine.speed_rpm, n_qs);
  opt.from_rpm = o.from_rpm.value_or(range.from_rpm);
  opt.to_rpm = o.to_rpm.value_or(range.to_rpm);
  if (!(opt.from_rpm > 0.0) || !std::isfinite(opt.from_rpm) || opt.from_rpm > 1e7)
    throw CaseError("--from: expected a speed in (0, 1e7] rpm, got " +
                    std::to_string(opt.from_rpm));
  if (!std::isfinite(opt.to_rpm) || opt.to_rpm > 1e9)
    throw CaseError("--to: expected a finite speed up to 1e9 rpm, got " +
                    std::to_string(opt.to_rpm));
  if (!(opt.to_rpm > opt.from_rpm)) {
    // Named by what set it: an option given, else the case (its [overspeed] or the defaults).
    const std::string where = o.to_rpm ? "--to" : o.from_rpm ? "--from" : c.path;
    throw CaseError(where + ": the sweep range is empty: to " + Fixed(opt.to_rpm, 1) +
                    " rpm must exceed from " + Fixed(opt.from_rpm, 1) + " rpm");
  }
  return CaseOverspeed{c, opt, n_qs, OverspeedSearch(scene, opt, progress)};
}

}  // namespace needle
