// What simulate and overspeed compute and print: ComputeSimulate and ComputeOverspeed
// (dynamics_command.h), the JSON object, the text and the CSV of each.
#include <unistd.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/case_scene.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/dynamics_command.h"
#include "apps/cli/progress_bar.h"
#include "apps/report/command_output.h"
#include "apps/report/output_paths.h"
#include "apps/report/result_writers.h"
#include "apps/study/check_scene.h"
#include "dynamics/overspeed.h"
#include "dynamics/simulation.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/quasi_static.h"

namespace needle {

namespace {

SimulationOptions Options(const Case& c, const std::optional<std::string>& method,
                          const std::optional<double>& rtol) {
  SimulationOptions o = OptionsFromCase(c);
  if (method) {
    if (*method != "auto" && !ParseMethod(*method)) {
      throw CaseError("--method: unknown method \"" + *method + "\"; expected " + MethodList());
    }

    o.method = *method;
  }
  if (rtol) {
    if (!(*rtol >= kMinRtol && *rtol <= kMaxRtol))
      throw CaseError("--rtol: must be in " + RtolRangeText() + ", got " + std::to_string(*rtol));
    o.integrator.rtol = *rtol;
    if (!(c.solver && c.solver->atol_m)) o.integrator.atol_m = DefaultAtol(*rtol);
  }
  return o;
}

// The revolutions of a run of several: one row each, then whether the state repeated.
std::string CyclesText(const SimulationResult& r) {
  std::ostringstream out;
  out << "cycle  start_deg  impacts  jumps  jump_deg  max_gap_mm  end_lift_mm  end_velocity_m_s\n";
  for (const CycleSummary& c : r.cycles) {
    const std::vector<Field> f = CycleFields(c);
    const auto v = [&f](const char* key) { return ValueText(FieldAt(f, key)); };
    out << std::setw(5) << v("index") << std::setw(11) << v("start_deg") << std::setw(9)
        << v("impacts") << std::setw(7) << v("jumps") << std::setw(10) << v("jump_deg")
        << std::setw(12) << v("max_gap_mm") << std::setw(13) << v("end_lift_mm") << std::setw(18)
        << v("end_velocity_m_s") << '\n';
  }
  if (r.period_cycles > 0) {
    out << "periodic: the state repeats every " << r.period_cycles << " revolution"
        << (r.period_cycles > 1 ? "s" : "") << " from cycle " << r.periodic_from << " on ("
        << r.cycles.size() << " of " << r.cycles_asked << " run)\n";
  } else {
    out << "not periodic within " << r.cycles.size() << " revolutions (period up to " << kMaxPeriod
        << " looked for)\n";
  }
  if (r.judged_from > 0) out << "lift-off judged from cycle " << r.judged_from << " on\n";
  return out.str();
}

}  // namespace

CommandOutput ComputeSimulate(const Case& c, const SimulateCommandOptions& o,
                              const std::function<void(const SeriesPoint&)>& series_sink) {
  RequireSpeed(o.speed_rpm);
  const Scene scene = MakeScene(c);
  SimulationOptions sim = Options(c, o.method, o.rtol);
  sim.force_dynamic = o.dynamic;
  // Streamed: to the caller's sink, and as SI columns when asked; none is kept as a whole.
  const std::vector<Column> columns = SeriesColumns();
  std::vector<std::vector<double>> si(columns.size());
  sim.record_series = series_sink || o.series;
  if (sim.record_series) {
    sim.series_sink = [&](const SeriesPoint& p) {
      if (series_sink) series_sink(p);
      if (!o.series) return;
      const std::array<double, 7> row = SeriesRow(p);
      for (size_t i = 0; i < row.size(); ++i) si[i].push_back(row[i]);
    };
  }
  if (o.cycles) {
    sim.cycles = *o.cycles;
    const auto refusal = sim.cycles > 1 ? CyclesRefusal(scene) : std::nullopt;
    if (refusal) throw CaseError("--cycles: " + *refusal);
  }
  const double speed = o.speed_rpm.value_or(c.engine.speed_rpm);
  const SimulationResult r = Simulate(scene, speed, sim);
  if (o.csv && r.skipped) throw CaseError("--csv: no time series to write, " + r.method_reason);

  CommandOutput result;
  result.status = r.liftoff() ? 1 : 0;
  const std::vector<Field> fields = SimulationFields(r);
  const auto text = [&fields](const char* key) { return ValueText(FieldAt(fields, key)); };
  if (!si[0].empty()) {
    for (size_t i = 0; i < columns.size(); ++i)
      result.columns[columns[i].SiKey()] = std::move(si[i]);
  }
  std::ostringstream out;
  if (o.json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["speed_rpm"] = speed;
    j["method"] = r.method;
    j["method_reason"] = r.method_reason;
    j["skipped_dynamics"] = r.skipped;
    j["liftoff"] = r.liftoff();
    const bool with_cycle = r.cycles_asked > 1;
    j["episodes"] =
        RecordList(r.episodes, [&](const Episode& e) { return EpisodeFields(e, with_cycle); });
    const nlohmann::json impacts =
        RecordList(r.impacts, [&](const Impact& i) { return ImpactFields(i, with_cycle); });
    if (with_cycle) {
      j["cycles"] = RecordList(r.cycles, CycleFields);
      j["cycles_asked"] = r.cycles_asked;
      j["period_cycles"] =
          r.period_cycles > 0 ? nlohmann::json(r.period_cycles) : nlohmann::json(nullptr);
      j["periodic_from"] =
          r.period_cycles > 0 ? nlohmann::json(r.periodic_from) : nlohmann::json(nullptr);
      j["judged_from"] = r.judged_from;
    }
    j["impacts"] = impacts;
    PutFields(j, fields);
    j["rtol"] = sim.integrator.rtol;
    j["status"] = RunStatusName(r.status);
    j["status_reason"] = r.status_reason;
    j["liftoff_rpm_quasi_static"] = Finite(QuasiStaticLiftoffRpm(scene));
    result.json = std::move(j);
  } else {
    out << (c.title.empty() ? c.path : c.title) << '\n'
        << "speed " << Fixed(speed, 1) << " rpm; method " << r.method << " (" << r.method_reason
        << ")\n";
    if (!r.skipped) {
      out << "window " << text("window_start_deg") << " .. " << text("window_end_deg")
          << " deg; rtol " << sim.integrator.rtol << "; " << text("steps") << " steps, "
          << text("rhs_evaluations") << " rhs evaluations, " << text("events")
          << " events; energy residual " << r.energy_residual << '\n';
      if (r.status != RunStatus::kComplete) {
        out << "run " << RunStatusName(r.status) << ": " << r.status_reason << '\n';
      } else if (r.run_end_rad > r.window_end_rad) {
        out << "run went on to " << text("run_end_deg") << " deg, where the needle came to rest\n";
      }
    }
    out << "max lift " << text("max_lift_mm") << " mm at " << text("max_lift_deg") << " deg\n"
        << "contact force: max " << text("max_contact_force_N") << " N, min during the lift "
        << text("min_contact_force_during_lift_N") << " N; max seat force "
        << text("max_seat_force_N") << " N\n";
    if (r.min_coil_gap_m) {
      out << "coil gap: least " << text("min_coil_gap_mm")
          << " mm to solid in the run (N times the most compressed segment's); "
          << text("coil_clashes") << " coil clashes\n";
    }
    if (r.cycles_asked > 1 && !r.skipped) {
      out << CyclesText(r);
    }
    out << (r.liftoff()                      ? "LIFT-OFF: the needle leaves the cam\n"
            : r.status == RunStatus::kBudget ? "no lift-off up to where the run stopped; "
                                               "undecided past it\n"
                                             : "no lift-off\n");
    for (const Episode& e : r.episodes) {
      const std::vector<Field> ef = EpisodeFields(e, false);
      out << "  " << e.kind << " " << ValueText(FieldAt(ef, "start_deg")) << " .. "
          << TextAt(ef, "end_deg") << ", largest gap " << TextAt(ef, "max_gap_mm")
          << (e.open ? " (still open when the run ended)" : "") << '\n';
    }
    for (const Impact& i : r.impacts) {
      const std::vector<Field> f = ImpactFields(i, false);
      out << "  impact " << i.kind << " at " << TextAt(f, "crank_deg") << ", "
          << TextAt(f, "speed_m_s") << '\n';
    }
  }
  result.text = out.str();
  return result;
}

CommandOutput ComputeOverspeed(const Case& c, const OverspeedCommandOptions& o,
                               const std::function<void(int, int)>& progress) {
  RequireIn("--threads", o.threads, kThreadsRange.lo, kThreadsRange.hi, "a number of threads");
  RequireIn("--step-rpm", o.step_rpm, kSpeedStepRange.lo, kSpeedStepRange.hi,
            "a speed step in rpm");
  RequireSpeed(o.from_rpm, "--from");
  RequireSpeed(o.to_rpm, "--to");
  const Scene scene = MakeScene(c);
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
    throw CaseError(c.path + ": the sweep range is empty: to " + Fixed(opt.to_rpm, 1) +
                    " rpm must exceed from " + Fixed(opt.from_rpm, 1) + " rpm");
  }
  const OverspeedResult r = OverspeedSearch(scene, opt, progress);
  CommandOutput result;
  result.status = r.n_dyn_rpm && *r.n_dyn_rpm <= c.engine.speed_rpm ? 1 : 0;
  std::vector<std::vector<double>> rows_si;
  for (const OverspeedRow& row : r.rows) rows_si.push_back(OverspeedRowSi(row));
  result.columns = SiColumns(OverspeedColumns(), rows_si);
  std::ostringstream out;
  if (o.json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["from_rpm"] = opt.from_rpm;
    j["to_rpm"] = opt.to_rpm;
    j["liftoff_rpm_quasi_static"] = Finite(n_qs);
    PutFields(j, OverspeedFields(r));
    j["cycles"] = opt.simulation.cycles;
    j["steady_state"] = opt.simulation.steady_state;
    j["rows"] = RecordList(r.rows, OverspeedRowFields);
    result.json = std::move(j);
  } else {
    out << (c.title.empty() ? c.path : c.title) << '\n'
        << "sweep " << Fixed(opt.from_rpm, 1) << " .. " << Fixed(opt.to_rpm, 1) << " rpm on "
        << r.threads
        << " threads, scanned upward led by the least contact force (steps of at "
           "most "
        << Fixed(100 * opt.max_step_fraction, 0) << " % of the speed; " << Fixed(r.step_rpm, 2)
        << " rpm where the force gives no guidance)\n";
    if (opt.simulation.cycles > 1) {
      out << opt.simulation.cycles << " cam revolutions per speed (until the state repeats); "
          << (opt.simulation.steady_state
                  ? "lift-off judged on the steady state (the repeating period, else the "
                    "revolutions after the first)\n"
                  : "lift-off in any of them counts\n");
    }
    out << "quasi-static lift-off n_qs = "
        << (std::isfinite(n_qs) ? Fixed(n_qs, 1) + " rpm" : "none") << '\n'
        << "dynamic lift-off n_dyn = ";
    if (r.n_dyn_rpm) {
      out << Fixed(*r.n_dyn_rpm, 1) << " rpm"
          << (r.lifts_off_at_start ? " (below the start of the range, where it lifts off)" : "")
          << " (bracket " << Fixed(r.bracket_low_rpm, 2) << " .. " << Fixed(r.bracket_high_rpm, 2)
          << ")\n";
    } else if (r.status == "floor") {
      out << "none found: the needle lifts off at every speed tried down to "
          << Fixed(r.floor_rpm, 1) << " rpm\n";
    } else if (r.status == "budget") {
      out << "none up to " << Fixed(r.scanned_to_rpm, 1) << " rpm, where the scan budget ("
          << opt.max_speeds << " speeds) ended it; give a larger --step-rpm or a smaller --to\n";
    } else if (r.status == "not-following") {
      out << "undecided: the needle does not follow its cam at " << Fixed(r.scanned_to_rpm, 1)
          << " rpm (see `needle simulate` there)\n";
    } else if (r.status == "run-budget") {
      out << "undecided: the run at " << Fixed(r.scanned_to_rpm, 1)
          << " rpm stopped on its budget before showing lift-off (see its row)\n";
    } else {
      out << "none in the range\n";
    }
    out << "\n  speed rpm  min Fc N   jump deg  max gap mm  max impact m/s\n";
    for (const OverspeedRow& row : r.rows) {
      const std::vector<Field> f = OverspeedRowFields(row);
      const auto shown = [&f](const char* key) { return *FieldAt(f, key).Shown(); };
      char line[160];
      std::snprintf(line, sizeof line, "%11.2f %9.1f %10.3f %11.4f %15.4f%s\n", shown("speed_rpm"),
                    shown("min_contact_force_N"), shown("jump_deg"), shown("max_gap_mm"),
                    shown("max_impact_speed_m_s"), row.lifts_off ? "  lift-off" : "");
      out << line;
      if (row.status != RunStatus::kComplete && row.status != RunStatus::kStopped)
        out << "             run " << RunStatusName(row.status) << ": " << row.status_reason
            << '\n';
    }
  }
  result.text = out.str();
  return result;
}

}  // namespace needle
