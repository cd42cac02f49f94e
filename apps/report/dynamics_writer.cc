// The JSON objects, texts and columns of a run and of the overspeed search: dynamics_writer.h.
#include "apps/report/dynamics_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/report/result_writers.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

namespace {

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

namespace {

// The needle at the run's grid of crank angles (SimulationOptions::grid_rad): crank_deg,
// lift_mm and contact_force_N, each a list.
nlohmann::json GridJson(const SimulationResult& r, double speed_rpm) {
  nlohmann::json g = {{"crank_deg", nlohmann::json::array()},
                      {"lift_mm", nlohmann::json::array()},
                      {"contact_force_N", nlohmann::json::array()}};
  const double theta_a = r.window_start_rad, omega = OmegaFromRpm(speed_rpm);
  for (const GridPoint& p : r.grid) {
    g["crank_deg"].push_back((theta_a + omega * p.time_s) / kDeg);
    g["lift_mm"].push_back(p.lift_m * 1e3);
    g["contact_force_N"].push_back(p.contact_force_N);
  }
  return g;
}

}  // namespace

CommandOutput WriteSimulate(const CaseRun& run, bool json) {
  const BoundCase& c = run.c;
  const SimulationResult& r = run.result;
  const double speed = run.speed_rpm;
  CommandOutput result;
  result.status = r.liftoff() ? 1 : 0;
  const std::vector<Field> fields = SimulationFields(r);
  const auto text = [&fields](const char* key) { return ValueText(FieldAt(fields, key)); };
  if (!run.series_si.empty()) {
    const std::vector<Column> columns = SeriesColumns();
    for (size_t i = 0; i < columns.size(); ++i)
      result.columns[columns[i].SiKey()] = run.series_si[i];
  }
  std::ostringstream out;
  if (json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["speed_rpm"] = speed;
    j["method"] = r.method;
    j["method_reason"] = r.method_reason;
    j["skipped_dynamics"] = r.skipped;
    j["liftoff"] = r.liftoff();
    if (!r.grid.empty()) j["grid"] = GridJson(r, speed);
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
    j["rtol"] = run.rtol;
    j["status"] = RunStatusName(r.status);
    j["status_reason"] = r.status_reason;
    j["liftoff_rpm_quasi_static"] = Finite(run.liftoff_rpm_quasi_static);
    PutLiftTableWarnings(j, c.lift.choice, *c.lift.law);
    result.json = std::move(j);
  } else {
    out << (c.title.empty() ? c.path : c.title) << '\n'
        << "speed " << Fixed(speed, 1) << " rpm; method " << r.method << " (" << r.method_reason
        << ")\n";
    out << LiftTableWarnings(c.lift.choice, *c.lift.law, "the run reads");
    if (!r.skipped) {
      out << "window " << text("window_start_deg") << " .. " << text("window_end_deg")
          << " deg; rtol " << run.rtol << "; " << text("steps") << " steps, "
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
    // A jump where no gap opens (the contact force falls to zero and the needle grazes the cam)
    // is a lift-off still, as check judges one; the words say what the numbers show.
    const bool opens = std::any_of(r.episodes.begin(), r.episodes.end(),
                                   [](const Episode& e) { return e.max_gap_m > 0.0; });
    out << (r.liftoff() && opens             ? "LIFT-OFF: the needle leaves the cam\n"
            : r.liftoff()                    ? "LIFT-OFF: the contact force falls to zero (the "
                                               "needle grazes the cam, no gap opens)\n"
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

CommandOutput WriteOverspeed(const CaseOverspeed& search, bool json) {
  const BoundCase& c = search.c;
  const OverspeedOptions& opt = search.options;
  const OverspeedResult& r = search.result;
  const double n_qs = search.liftoff_rpm_quasi_static;
  CommandOutput result;
  result.status = r.n_dyn_rpm && *r.n_dyn_rpm <= c.engine.speed_rpm ? 1 : 0;
  std::vector<std::vector<double>> rows_si;
  for (const OverspeedRow& row : r.rows) rows_si.push_back(OverspeedRowSi(row));
  result.columns = SiColumns(OverspeedColumns(), rows_si);
  std::ostringstream out;
  if (json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["from_rpm"] = opt.from_rpm;
    j["to_rpm"] = opt.to_rpm;
    j["liftoff_rpm_quasi_static"] = Finite(n_qs);
    PutFields(j, OverspeedFields(r));
    j["cycles"] = opt.simulation.cycles;
    j["steady_state"] = opt.simulation.steady_state;
    j["rows"] = RecordList(r.rows, OverspeedRowFields);
    PutLiftTableWarnings(j, c.lift.choice, *c.lift.law);
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
    out << LiftTableWarnings(c.lift.choice, *c.lift.law, "the runs read");
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
