// needle-bench dynamics and exact: work against precision of every method; exact against dopri5.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/bench/bench_common.h"
#include "apps/bench/work_precision.h"
#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/study/check_scene.h"
#include "apps/study/spring_sizing_scene.h"
#include "dynamics/overspeed.h"
#include "lib/cam_laws.h"
#include "lib/input_file.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle::bench {

namespace {

struct Row {
  std::string scene, method;
  double rtol, ms;
  long steps, rhs, events;
  RunErrors err;
  double energy;
  std::string failure;
};

// Cost (ms or rhs) to reach a lift error on the Pareto front of one method, interpolated in
// log-log between the two runs that bracket it; NaN when never reached.
double CostToReach(const std::vector<Row>& rows, const std::string& method, double target_m,
                   bool rhs) {
  std::vector<std::pair<double, double>> pts;  // (error, cost)
  for (const Row& r : rows) {
    if (r.method != method || !r.failure.empty() || !std::isfinite(r.err.lift_m)) continue;
    pts.push_back({std::max(r.err.lift_m, 1e-16), rhs ? double(r.rhs) : r.ms});
  }
  std::sort(pts.begin(), pts.end(), [](auto a, auto b) { return a.second < b.second; });
  double best_err = INFINITY;
  std::vector<std::pair<double, double>> front;  // errors falling as cost rises
  for (auto p : pts) {
    if (p.first < best_err) {
      front.push_back(p);
      best_err = p.first;
    }
  }
  for (size_t i = 0; i < front.size(); ++i) {
    if (front[i].first <= target_m) {
      if (i == 0) return front[0].second;
      const auto [e0, c0] = front[i - 1];
      const auto [e1, c1] = front[i];
      const double w = (std::log(target_m) - std::log(e0)) / (std::log(e1) - std::log(e0));
      return std::exp(std::log(c0) + w * (std::log(c1) - std::log(c0)));
    }
  }
  return NAN;
}

// As CostToReach, for the contact-force error (N), in right-hand-side evaluations.
double CostToReachForce(const std::vector<Row>& rows, const std::string& method, double target_N) {
  std::vector<Row> as_lift = rows;
  for (Row& r : as_lift) r.err.lift_m = r.err.force_N;
  return CostToReach(as_lift, method, target_N, true);
}

// `auto` by tolerance (issue 33: it must not pick a method that is slower at equal error): at
// each rtol, the method AutoMethod picks, its time and lift error; the fastest run at that rtol;
// and the fastest run of any method and tolerance whose lift error is at most auto's (exact's
// own error taken as the reference's uncertainty, `floor_m`, not 0), with the ratio. The
// no-event baseline is left out: it locates no impact, and auto never runs it.
std::string AutoByTolerance(const Scene& scene, double rpm, const std::vector<double>& tolerances,
                            const std::vector<Row>& rows, double floor_m) {
  std::ostringstream md;
  md << "`auto` by tolerance: its pick, the fastest method at that rtol, and the fastest run of "
        "any method and rtol at most as wrong as auto's (exact's error taken as the reference's "
        "uncertainty; the event-locating methods, not the no-event baseline):\n\n"
     << "| rtol | auto | ms | lift error µm | fastest at this rtol | fastest at ≤ auto's error | "
        "auto / that |\n|---|---|---|---|---|---|---|\n";
  double worst = 0.0, worst_asked = 0.0;
  std::string worst_at, worst_asked_at;
  for (double rtol : tolerances) {
    const std::string pick = MethodName(AutoMethod(scene, rpm, rtol).method);
    const Row* mine = nullptr;
    const Row* same_rtol = nullptr;
    for (const Row& r : rows) {
      if (!r.failure.empty() || r.method == "baseline-dopri5") continue;
      const bool untoleranced = r.method == "exact";
      if (r.method == pick && (untoleranced || r.rtol == rtol)) mine = &r;
      if ((untoleranced || r.rtol == rtol) && (!same_rtol || r.ms < same_rtol->ms)) same_rtol = &r;
    }
    if (!mine) continue;
    const auto error = [&](const Row& r) {
      return r.method == "exact" ? floor_m : std::max(r.err.lift_m, floor_m);
    };
    const Row* best = nullptr;
    for (const Row& r : rows) {
      if (r.failure.empty() && r.method != "baseline-dopri5" && error(r) <= error(*mine) &&
          (!best || r.ms < best->ms))
        best = &r;
    }
    const auto name = [](const Row& r) {
      return r.method == "exact" ? r.method : r.method + " " + Num(r.rtol, 1);
    };
    const double ratio = mine->ms / best->ms;
    if (ratio > worst) worst = ratio, worst_at = Num(rtol, 1);
    const double asked = mine->ms / same_rtol->ms;
    if (asked > worst_asked) {
      worst_asked = asked;
      worst_asked_at = Num(rtol, 1) + ": " + pick + " " + Num(mine->ms) + " ms, " +
                       name(*same_rtol) + " " + Num(same_rtol->ms) + " ms at " +
                       Num(std::max(same_rtol->err.lift_m, floor_m) / error(*mine), 2) +
                       " times its lift error";
    }
    md << "| " << Num(rtol, 1) << " | " << pick << " | " << Num(mine->ms) << " | "
       << Num(error(*mine) * 1e6, 2) << " | " << name(*same_rtol) << " (" << Num(same_rtol->ms)
       << ") | " << name(*best) << " (" << Num(best->ms) << ") | " << Num(ratio, 3) << " |\n";
  }
  md << "\nAt equal error `auto` is at most " << Num(worst, 3) << "× the fastest"
     << (worst > 1.0 ? " (at rtol " + worst_at + ")" : "") << ". At the rtol asked, at most "
     << Num(worst_asked, 3) << "× the fastest method at that rtol"
     << (worst_asked > 1.0 ? " (at " + worst_asked_at + ")" : "") << ".\n\n";
  return md.str();
}

}  // namespace

namespace {

// Every method at every tolerance on one scene (one row: `exact` takes no tolerance), errors
// against the reference run `ref` on `grid`.
std::vector<Row> MeasureScene(const BenchScene& bs, const Scene& scene,
                              const std::vector<double>& grid, const MeasuredRun& ref,
                              const std::vector<double>& tolerances, int repeats) {
  std::vector<Row> rows;
  for (Method m : Methods()) {
    for (double rtol : tolerances) {
      if (MethodIsClosedForm(m) && rtol != tolerances.front()) continue;  // no tolerance
      const MeasuredRun run = MeasureRun(scene, bs.rpm, m, rtol, grid, repeats);
      Row r{bs.name,
            run.method,
            rtol,
            run.median_seconds * 1e3,
            run.stats.steps,
            run.stats.rhs_evaluations,
            run.stats.events,
            CompareRuns(run, ref),
            run.energy_residual,
            run.failure};
      if (!MethodIsEventDriven(m)) r.err.event_rad.reset();
      rows.push_back(r);
      std::cerr << bs.name << " " << run.method << " " << rtol << ": " << Num(r.ms)
                << " ms, lift error " << Num(r.err.lift_m * 1e6) << " um"
                << (run.failure.empty() ? "" : " FAILED: " + run.failure) << '\n';
    }
  }
  return rows;
}

// The scene's rows as out_dir/work-precision-NAME.csv.
void WriteSceneCsv(const std::string& out_dir, const BenchScene& bs, const std::vector<Row>& rows) {
  std::ostringstream csv;
  csv << "scene,method,rtol,median_ms,steps,rhs_evaluations,events,lift_error_um,contact_force_"
         "error_N,"
         "event_angle_error_deg,impacts,reference_impacts,energy_residual,failure\n";
  for (const Row& r : rows) {
    csv << r.scene << ',' << r.method << ',' << r.rtol << ',' << r.ms << ',' << r.steps << ','
        << r.rhs << ',' << r.events << ',' << r.err.lift_m * 1e6 << ',' << r.err.force_N << ','
        << (r.err.event_rad ? std::to_string(*r.err.event_rad / kDeg) : "") << ','
        << r.err.event_count << ',' << r.err.reference_event_count << ',' << r.energy << ",\""
        << r.failure << "\"\n";
  }
  WriteFileAtomically(out_dir + "/work-precision-" + bs.name + ".csv", csv.str());
}

// The scene's section: the reference's uncertainty, each method's cost to 1 µm and 1 nm,
// `auto`'s against the fastest, and event location against the no-event baseline.
std::string SceneCosts(const BenchScene& bs, const Scene& scene, const MeasuredRun& ref,
                       const RunErrors& ref_err, const std::vector<Row>& rows) {
  std::ostringstream md;
  const double oscillations = ContactOscillationsPerEvent(scene, bs.rpm);
  const std::string auto_pick = MethodName(AutoMethod(scene, bs.rpm, 1e-8).method);
  md << "### " << bs.name << ": " << bs.note << "\n\n"
     << "Reference uncertainty: " << Num(ref_err.lift_m * 1e6)
     << " µm of lift. Impacts in the reference: " << ref.impacts.size() << ". `auto` picks "
     << auto_pick << " at the default rtol 1e-8 (" << Num(oscillations, 4)
     << " contact oscillations per event).\n\n"
     << "| method | ms to 1 µm | ms to 1 nm | rhs to 1 µm | rhs to 1 nm "
        "|\n|---|---|---|---|---|\n";
  std::string fastest_um, fastest_nm;
  double best_um = INFINITY, best_nm = INFINITY;
  for (Method m : Methods()) {
    const std::string name = MethodName(m);
    const double t_um = CostToReach(rows, name, 1e-6, false),
                 t_nm = CostToReach(rows, name, 1e-9, false);
    md << "| " << name << " | " << Num(t_um) << " | " << Num(t_nm) << " | "
       << Num(CostToReach(rows, name, 1e-6, true)) << " | "
       << Num(CostToReach(rows, name, 1e-9, true)) << " |\n";
    if (t_um < best_um) best_um = t_um, fastest_um = name;
    if (t_nm < best_nm) best_nm = t_nm, fastest_nm = name;
  }
  const double auto_um = CostToReach(rows, auto_pick, 1e-6, false),
               auto_nm = CostToReach(rows, auto_pick, 1e-9, false);
  md << "\nFastest to 1 µm: **" << fastest_um << "** (" << Num(best_um) << " ms); to 1 nm: **"
     << fastest_nm << "** (" << Num(best_nm) << " ms). `auto` (" << auto_pick << ") needs "
     << Num(auto_um) << " ms and " << Num(auto_nm) << " ms: " << Num(auto_um / best_um, 2)
     << "× and " << Num(auto_nm / best_nm, 2) << "× the fastest.\n";
  const double ev_um = CostToReach(rows, "dopri5", 1e-6, true),
               base_um = CostToReach(rows, "baseline-dopri5", 1e-6, true);
  const double ev_01 = CostToReach(rows, "dopri5", 1e-7, true),
               base_01 = CostToReach(rows, "baseline-dopri5", 1e-7, true);
  const double ev_f = CostToReachForce(rows, "dopri5", 1.0),
               base_f = CostToReachForce(rows, "baseline-dopri5", 1.0);
  md << "At equal contact-force error (1 N): " << Num(ev_f, 4) << " against " << Num(base_f, 4)
     << " (" << Num(base_f / ev_f, 2) << "×). ";
  EventRatios().push_back({bs.name, base_01 / ev_01});
  md << "Event location against the baseline (max(0, …) inside the right-hand side, no events), "
     << "right-hand-side evaluations at equal lift error: 1 µm " << Num(ev_um, 4) << " against "
     << Num(base_um, 4) << " (" << Num(base_um / ev_um, 2) << "×), 0.1 µm " << Num(ev_01, 4)
     << " against " << Num(base_01, 4) << " (" << Num(base_01 / ev_01, 2) << "×).\n\n";
  return md.str();
}

// The largest event-angle error and energy residual of dopri5 and cvode-bdf by tolerance.
std::string EventAndEnergyByTolerance(const std::vector<Row>& rows,
                                      const std::vector<double>& tolerances) {
  std::ostringstream md;
  md << "Largest event-angle error and energy residual by tolerance (dopri5 / cvode-bdf):\n\n| "
        "rtol | dopri5 event deg | "
        "dopri5 energy | cvode-bdf event deg | cvode-bdf energy |\n|---|---|---|---|---|\n";
  for (double rtol : tolerances) {
    auto find = [&](const std::string& name) -> const Row* {
      for (const Row& r : rows)
        if (r.method == name && r.rtol == rtol) return &r;
      return nullptr;
    };
    const Row* a = find("dopri5");
    const Row* b = find("cvode-bdf");
    auto ev = [](const Row* r) {
      if (!r || !r->failure.empty()) return std::string("failed");
      return r->err.event_rad ? Num(*r->err.event_rad / kDeg, 2)
                              : "impacts differ (" + std::to_string(r->err.event_count) + " vs " +
                                    std::to_string(r->err.reference_event_count) + ")";
    };
    md << "| " << Num(rtol, 1) << " | " << ev(a) << " | " << (a ? Num(a->energy, 2) : "–") << " | "
       << ev(b) << " | " << (b ? Num(b->energy, 2) : "–") << " |\n";
  }
  return md.str();
}

}  // namespace

std::string RunDynamics(const std::string& out_dir, int repeats, bool quick) {
  std::ostringstream md;
  md << "## Dynamics: work against precision\n\n"
     << "Reference: method `exact`, the closed form (its own uncertainty: the largest lift\n"
     << "difference to Dormand–Prince at rtol 1e-13, shown per scene; `exact` takes no tolerance\n"
     << "and has one row). Errors on 2001 points\n"
     << "of the window; times are medians of " << repeats << " runs on one core.\n\n";
  std::vector<double> tolerances;
  for (int e = 3; e <= 12; ++e) {
    if (quick && e % 3 != 0) continue;
    tolerances.push_back(std::pow(10.0, -e));
  }
  {
    // A second of untimed runs first: without it the first scene's first tolerances were
    // measured up to 1.5× slow in some runs on this machine (the rest of the run was not).
    const BenchScene& bs = Scenes().front();
    const Scene scene = *BindBundled(bs.file).scene;
    const std::vector<double> grid = WindowGrid(scene, bs.rpm, 2000);
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(1))
      MeasureRun(scene, bs.rpm, Named("dopri5"), 1e-6, grid, 1);
  }
  for (const BenchScene& bs : Scenes()) {
    const BoundCase c = BindBundled(bs.file);
    const Scene scene = *c.scene;
    const std::vector<double> grid = WindowGrid(scene, bs.rpm, 2000);
    const MeasuredRun ref = MeasureRun(scene, bs.rpm, Named("exact"), 1e-13, grid, 1);
    const MeasuredRun check = MeasureRun(scene, bs.rpm, Named("dopri5"), 1e-13, grid, 1);
    const RunErrors ref_err = CompareRuns(check, ref);
    const std::vector<Row> rows = MeasureScene(bs, scene, grid, ref, tolerances, repeats);
    WriteSceneCsv(out_dir, bs, rows);
    md << SceneCosts(bs, scene, ref, ref_err, rows);
    md << AutoByTolerance(scene, bs.rpm, tolerances, rows, ref_err.lift_m);
    md << EventAndEnergyByTolerance(rows, tolerances);
    md << '\n';
  }
  return md.str();
}

// The coil chain by method "exact" (issue 53; auto's pick for a chain without clash) against
// dopri5 at the case's tolerance and at rtol 1e-12: the surge study's N (5, 10, 20, 40) on the
// two chain scenes, `basu-example1-surge` at 520 rpm (near its n_dyn; rated 125 rpm) and
// `engine-2000rpm-surging-spring` at its rated 2000 rpm, forced dynamic, as `needle simulate`
// runs them; medians of 5 × repeats interleaved runs (dopri5 at 1e-12: one run), with each
// run's steps, energy residual and least coil gap.
std::string LongChainRow(int repeats) {
  std::ostringstream md;
  md << "### The coil chain by method exact\n\n"
     << "The surge study's chains (5, 10, 20, 40 coil masses), forced dynamic, as `needle "
     << "simulate` runs them: `basu-example1-surge` at 520 rpm (4 revolutions, near its n_dyn; "
     << "rated 125 rpm) and `engine-2000rpm-surging-spring` at its rated 2000 rpm; medians of "
     << 5 * repeats
     << " interleaved runs (dopri5 at 1e-12: one run). auto takes exact for a chain without "
        "clash (docs/exact.md).\n\n"
     << "| case | coil masses | method | ms | steps | energy residual | least coil gap mm |\n"
     << "|---|---|---|---|---|---|---|\n";
  struct ChainCase {
    std::string name;
    double rpm;
  };
  for (const ChainCase& cc : {ChainCase{"basu-example1-surge", 520.0},
                              ChainCase{"engine-2000rpm-surging-spring", 2000.0}}) {
    Case chain = LoadCase(CaseDir() + cc.name + ".toml");
    for (const int masses : {5, 10, 20, 40}) {
      // The chain as a case of `masses` coil masses binds it (its mass, damping and travel).
      chain.spring->masses = masses;
      const BoundCase c = Bind(chain);
      const Scene& scene = *c.scene;
      struct Run {
        std::string method;
        double rtol;
        int runs;
        std::vector<double> times;
        SimulationResult last;
      };
      std::vector<Run> runs = {{"dopri5", c.run.integrator.rtol, 5 * repeats, {}, {}},
                               {"exact", c.run.integrator.rtol, 5 * repeats, {}, {}},
                               {"dopri5", 1e-12, 1, {}, {}}};
      for (int r = 0; r < 5 * repeats; ++r) {
        for (Run& run : runs) {
          if (r >= run.runs) continue;
          SimulationOptions o = c.run;
          o.force_dynamic = true;
          o.method = run.method;
          o.integrator.rtol = run.rtol;
          if (run.rtol == 1e-12) o.integrator.atol_m = DefaultAtol(1e-12);
          const auto t0 = std::chrono::steady_clock::now();
          run.last = Simulate(scene, cc.rpm, o);
          run.times.push_back(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
      }
      for (Run& run : runs) {
        std::sort(run.times.begin(), run.times.end());
        md << "| " << cc.name << " | " << masses << " | " << run.last.method;
        if (run.method != "exact") md << " rtol " << Num(run.rtol);
        md << " | " << Num(run.times[run.times.size() / 2] * 1e3) << " | " << run.last.stats.steps
           << " | " << Num(run.last.energy_residual) << " | "
           << (run.last.min_coil_gap_m ? Num(*run.last.min_coil_gap_m * 1e3, 10) : "–") << " |\n";
      }
    }
  }
  md << "\n";
  return md.str();
}

// Method "exact" against dopri5 at rtol 1e-8 (issue 33): run time (median of interleaved runs,
// Simulate as a user calls it, forced dynamic), lift and force error on the window grid against
// dopri5 at rtol 1e-12, the pieces and the energy residual, per scene; the ratio exact/dopri5.
std::string RunExactComparison(int repeats) {
  struct ExactScene {
    std::string name, file;
    double rpm;
  };
  std::vector<ExactScene> scenes;
  for (const BenchScene& bs : Scenes()) scenes.push_back({bs.name, bs.file, bs.rpm});
  scenes.push_back({"lash-1100", "basu-example2.toml", 1100});
  std::ostringstream md;
  md << "## Method `exact` against dopri5 at rtol 1e-8\n\n"
     << "Each run as `needle simulate` makes it (forced dynamic, no series), medians of "
     << 20 * repeats << " interleaved runs on one core; errors on 2001 points of the window "
     << "against dopri5 at rtol 1e-12.\n\n"
     << "| scene | rpm | exact µs | pieces | exact lift error µm | exact energy residual | "
        "dopri5 1e-8 µs | steps | dopri5 lift error µm | exact / dopri5 |\n"
     << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ExactScene& es : scenes) {
    const BoundCase c = BindBundled(es.file);
    const Scene scene = *c.scene;
    const std::vector<double> grid = WindowGrid(scene, es.rpm, 2000);
    const MeasuredRun ref = MeasureRun(scene, es.rpm, Named("dopri5"), 1e-12, grid, 1);
    const MeasuredRun ex = MeasureRun(scene, es.rpm, Named("exact"), 1e-8, grid, 1);
    const MeasuredRun dp = MeasureRun(scene, es.rpm, Named("dopri5"), 1e-8, grid, 1);
    SimulationOptions o = c.run;
    o.force_dynamic = true;
    SimulationOptions oe = o, od = o;
    oe.method = "exact";
    od.method = "dopri5";
    od.integrator.rtol = 1e-8;
    od.integrator.atol_m = DefaultAtol(1e-8);
    std::vector<double> te, td;
    long pieces = 0, steps = 0;
    double residual = 0.0;
    for (int r = 0; r < 20 * repeats; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      const SimulationResult a = Simulate(scene, es.rpm, oe);
      te.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      t0 = std::chrono::steady_clock::now();
      const SimulationResult b = Simulate(scene, es.rpm, od);
      td.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      pieces = a.stats.steps;
      steps = b.stats.steps;
      residual = a.energy_residual;
    }
    std::sort(te.begin(), te.end());
    std::sort(td.begin(), td.end());
    const double me = te[te.size() / 2] * 1e6, mdp = td[td.size() / 2] * 1e6;
    md << "| " << es.name << " | " << es.rpm << " | " << Num(me) << " | " << pieces << " | "
       << Num(CompareRuns(ex, ref).lift_m * 1e6) << " | " << Num(residual, 2) << " | " << Num(mdp)
       << " | " << steps << " | " << Num(CompareRuns(dp, ref).lift_m * 1e6) << " | "
       << Num(me / mdp, 3) << " |\n";
  }
  md << '\n' << LongChainRow(repeats);
  return md.str();
}

}  // namespace needle::bench
