// needle-bench kinematics and overspeed: the splines, the overspeed search, check and a
// tolerance sample (the performance targets: bench_targets.cc; the sizing: bench_sizing.cc).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "apps/bench/bench_common.h"
#include "apps/bench/work_precision.h"
#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/study/check_scene.h"
#include "apps/study/tolerance_study.h"
#include "dynamics/overspeed.h"
#include "lib/cam_laws.h"
#include "lib/input_file.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/helical_spring.h"

extern char** environ;

namespace needle::bench {

struct KinRow {
  double v5 = NAN, v1 = NAN, a5 = NAN, a1 = NAN, a1r = NAN, build5 = NAN, build1 = NAN, table = NAN;
};

std::string RunKinematics(const std::string& out_dir, int repeats) {
  std::ostringstream csv, md;
  std::map<std::string, KinRow> summary;

  csv << "law,spline,spacing_deg,rounding_mm,velocity_rel_error,acceleration_rel_error,build_us,"
         "table_1000_us\n";
  const double beta = 60.0 * kDeg, h = 2.5e-3;
  for (CamLawKind k : {CamLawKind::kCycloidal, CamLawKind::kHarmonic, CamLawKind::kPoly345}) {
    const CamLaw law(k, h, beta);
    for (SplineKind kind : AllSplineKinds()) {
      for (double step : {5.0, 2.5, 1.25, 1.0, 0.5}) {
        for (double rounding : {0.0, 0.01}) {
          LiftTable t;
          const int n = static_cast<int>(std::lround(60.0 / step));
          for (int i = 0; i <= n; ++i) {
            double s = law.Lift(beta * i / n);
            if (rounding > 0) s = std::round(s / (rounding * 1e-3)) * rounding * 1e-3;
            t.crank_rad.push_back(beta * i / n);
            t.lift_m.push_back(s);
          }
          SplineOptions o;
          o.kind = kind;
          const LiftLaw lift(t, o);
          double ev = 0, ea = 0, sv = 0, sa = 0;
          for (int i = 0; i <= 3000; ++i) {
            const double th = beta * i / 3000.0;
            ev = std::max(ev, std::abs(lift.Derivative(th, 1) - law.Derivative(th, 1)));
            sv = std::max(sv, std::abs(law.Derivative(th, 1)));
            if (lift.HasAcceleration()) {
              ea = std::max(ea, std::abs(lift.Derivative(th, 2) - law.Derivative(th, 2)));
              sa = std::max(sa, std::abs(law.Derivative(th, 2)));
            }
          }
          const double build = MedianSeconds([&] { LiftLaw l(t, o); }, repeats * 20);
          volatile double sink = 0;  // keeps the timed evaluations from being optimised away
          const double table = MedianSeconds(
              [&] {
                const Kinematics kin(lift, 400);
                for (int i = 0; i < 1000; ++i) {
                  const KinematicsPoint p = kin.At(beta * i / 999.0);
                  sink = sink + p.lift_m + p.velocity_m_s + p.acceleration_m_s2.value_or(0.0) +
                         p.jerk_m_s3.value_or(0.0);
                }
              },
              repeats * 20);
          csv << law.name() << ',' << SplineKindName(kind) << ',' << step << ',' << rounding << ','
              << ev / sv << ',' << (lift.HasAcceleration() ? std::to_string(ea / sa) : "") << ','
              << build * 1e6 << ',' << table * 1e6 << '\n';
          if (k == CamLawKind::kCycloidal) {
            KinRow& row = summary[SplineKindName(kind)];
            const double a_rel = lift.HasAcceleration() ? ea / sa : NAN;
            if (rounding == 0.0 && step == 5.0)
              row.v5 = ev / sv, row.a5 = a_rel, row.build5 = build * 1e6;
            if (rounding == 0.0 && step == 1.0)
              row.v1 = ev / sv, row.a1 = a_rel, row.build1 = build * 1e6, row.table = table * 1e6;
            if (rounding > 0.0 && step == 1.0) row.a1r = a_rel;
          }
        }
      }
    }
  }
  WriteFileAtomically(out_dir + "/kinematics.csv", csv.str());
  md << "## Kinematics\n\nRelative velocity and acceleration error of each spline against "
        "closed-form rises (2.5 mm over 60°), by table spacing, exact and rounded to 0.01 mm, "
        "with the time to build the spline and to evaluate a 1000-row table (lift, velocity, "
        "acceleration, jerk): `kinematics.csv`. The cycloidal rise:\n\n"
        "| spline | v err 5° | v err 1° | a err 5° | a err 1° | a err 1°, rounded | build µs (13 / "
        "61 "
        "points) | 1000-row table µs |\n|---|---|---|---|---|---|---|---|\n";
  for (SplineKind kind : AllSplineKinds()) {
    const KinRow& r = summary[SplineKindName(kind)];
    md << "| " << SplineKindName(kind) << " | " << Num(r.v5, 2) << " | " << Num(r.v1, 2) << " | "
       << Num(r.a5, 2) << " | " << Num(r.a1, 2) << " | " << Num(r.a1r, 2) << " | "
       << Num(r.build5, 3) << " / " << Num(r.build1, 3) << " | " << Num(r.table, 3) << " |\n";
  }
  md << "\nInterpolated acceleration from tables rounded to 0.01 mm is useless at fine spacing "
        "(several times the true peak at 1°); the smoothing spline keeps it near 10 %.\n\n";
  return md.str();
}

// main's overspeed search before the force-led scan (commit 2cacad4) on one thread, kept here
// only to time it against the new one in the same process: upward in fixed steps Δn (2.5 % of
// from, at least 1 rpm) from `from`, every run to the end of its window, then bisection; a
// lift-off at `from` is reported as n_dyn = from.
std::optional<double> FixedStepOverspeed(const Scene& scene, OverspeedOptions o, int* runs) {
  SimulationOptions sim = o.simulation;
  sim.force_dynamic = true;
  sim.record_series = false;
  const double step = std::max(1.0, 0.025 * o.from_rpm);
  const auto lifts = [&](double n) {
    ++*runs;
    const OverspeedRow row = RowFromResult(Simulate(scene, n, sim));
    return row.lifts_off || row.status == RunStatus::kBudget;
  };
  double lo = 0.0, hi = 0.0;
  for (long i = 0;; ++i) {
    const double n = std::min(o.from_rpm + step * static_cast<double>(i), o.to_rpm);
    if (lifts(n)) {
      if (i == 0) return n;
      lo = n - step;
      hi = n;
      break;
    }
    if (n >= o.to_rpm) return std::nullopt;
  }
  while (hi - lo > o.resolution_rpm) {
    const double mid = lo + 0.5 * (hi - lo);
    (lifts(mid) ? hi : lo) = mid;
  }
  return hi;
}

namespace {

// The wall time of f(), ms.
template <typename F>
double MsOf(const F& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The median of v (its upper one for an even count).
double MedianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The search alone on a lash-and-lift-off scene (Example 2, 600 to 1300 rpm).
std::string ComparisonSearch(int repeats) {
  std::ostringstream md;
  const BoundCase c = BindBundled("basu-example2.toml");
  const Scene scene = *c.scene;
  OverspeedOptions o = SearchOptions(c, 600, 1300);
  std::vector<double> timed_before, timed_after;
  int runs_before = 0;
  std::optional<double> before;
  OverspeedResult after;
  for (int r = 0; r < 3 * repeats; ++r) {
    runs_before = 0;
    timed_before.push_back(MsOf([&] { before = FixedStepOverspeed(scene, o, &runs_before); }));
    timed_after.push_back(MsOf([&] { after = OverspeedSearch(scene, o); }));
  }
  const double b = MedianOf(timed_before), a = MedianOf(timed_after);
  md << "| overspeed search, `basu-example2` 600–1300 rpm to 0.5 rpm | " << runs_before << " → "
     << after.rows.size() << " | " << Num(before.value_or(NAN), 5) << " → "
     << Num(after.n_dyn_rpm.value_or(NAN), 5) << " | " << Num(b) << " ms | " << Num(a) << " ms | "
     << Num(b / a, 3) << "× |\n";
  return md.str();
}

// `check` of Example 1 end to end without its report, and Example 2's (a tolerance sample
// before the next row: a check on one thread): the check itself now, and before as the check now
// less its sweep plus main's sweep of the same range (the rest of the check is the same code).
std::string ComparisonChecks(int repeats) {
  std::ostringstream md;
  for (const auto& [name, what] : std::vector<std::pair<std::string, std::string>>{
           {"basu-example1.toml", "`check basu-example1` without report"},
           {"basu-example2.toml",
            "`check basu-example2` without report (a tolerance sample before it took from the "
            "nominal)"}}) {
    const BoundCase c = BindBundled(name);
    const LiftLaw& law = *c.lift.law;
    const Scene scene = *c.scene;
    CheckOptions co;
    co.threads = 1;
    co.record_series = false;
    const SweepRange range = DefaultSweepRange(c, c.engine.speed_rpm, QuasiStaticLiftoffRpm(scene));
    OverspeedOptions o = SearchOptions(c, range.from_rpm, range.to_rpm);
    o.simulation.steady_state = c.overspeed && c.overspeed->steady_state;
    std::vector<double> check, sweep_new, sweep_old;
    int runs_before = 0;
    std::optional<double> before;
    CheckResult after;
    for (int r = 0; r < 3 * repeats; ++r) {
      check.push_back(MsOf([&] { after = CheckScene(c, law, co); }));
      sweep_new.push_back(MsOf([&] { OverspeedSearch(scene, o); }));
      runs_before = 0;
      sweep_old.push_back(MsOf([&] { before = FixedStepOverspeed(scene, o, &runs_before); }));
    }
    const double a = MedianOf(check);
    const double b = a - MedianOf(sweep_new) + MedianOf(sweep_old);
    md << "| " << what << " (before: less the new sweep, plus main's) | " << runs_before << " → "
       << (after.sweep ? after.sweep->rows.size() : 0) << " sweep runs | "
       << Num(before.value_or(NAN), 5) << " → "
       << Num(after.sweep && after.sweep->n_dyn_rpm ? *after.sweep->n_dyn_rpm : NAN, 5) << " | "
       << Num(b) << " ms | " << Num(a) << " ms | " << Num(b / a, 3) << "× |\n";
  }
  return md.str();
}

// One tolerance sample as the study runs it: 20 samples of `name` (seed 1) on one thread, per
// sample, with `target` the (empty: none). Before: each sample a full check
// (ToleranceOptions::reuse_nominal off). After: the nominal checked once (its cost included, 1/20
// of it a sample), each sample for its verdict only, its scan on from the nominal's n_dyn past f·n.
// The same samples both ways: their verdicts compared, and n_dyn.
std::string ComparisonToleranceSample(const std::string& name, const std::string& target,
                                      int repeats) {
  std::ostringstream md;
  const BoundCase c = BindBundled(name + ".toml");
  ToleranceOptions o;
  o.samples = 20;
  o.seed = 1;
  o.threads = 1;
  std::vector<double> before, after;
  std::vector<ToleranceSample> full, reused;
  for (int r = 0; r < repeats; ++r) {
    o.reuse_nominal = false;
    before.push_back(MsOf([&] { full = RunToleranceSamples(c, o); }) / o.samples);
    o.reuse_nominal = true;
    after.push_back(MsOf([&] { reused = RunToleranceSamples(c, o); }) / o.samples);
  }
  int differ = 0;
  double worst = 0.0, mean_before = 0.0, mean_after = 0.0;
  for (size_t i = 0; i < full.size(); ++i) {
    differ += full[i].pass != reused[i].pass || full[i].failing != reused[i].failing;
    const double x = full[i].outputs.at("overspeed.liftoff_rpm_dynamic");
    const double y = reused[i].outputs.at("overspeed.liftoff_rpm_dynamic");
    worst = std::max(worst, std::abs(x - y));
    mean_before += x / full.size();
    mean_after += y / full.size();
  }
  const double b = MedianOf(before), a = MedianOf(after);
  md << "| one tolerance sample of `" << name
     << "` (20 samples on one thread, per sample; after: the nominal's check included" << target
     << ") | full checks → verdict only, "
        "scan on from the nominal's n_dyn past f·n; verdicts differing: "
     << differ << " of " << full.size() << " | mean " << Num(mean_before, 5) << " → "
     << Num(mean_after, 5) << " (largest change " << Num(worst, 2) << " rpm) | " << Num(b)
     << " ms | " << Num(a) << " ms | " << Num(b / a, 3) << "× |\n";
  // Where a sample's time goes: the same samples with the spring given by its rate, the coil
  // geometry dropped, so no surge study (its three coil-chain runs; issue 39 added it after
  // issue 33 set the target) and no helical check. Both ways measured here, interleaved.
  BoundCase rate_only = c;
  rate_only.spring->rate_N_m = HelicalRate(*rate_only.spring->helical);
  rate_only.spring->helical.reset();
  rate_only.scene = BindScene(rate_only, rate_only.lift.law);
  std::vector<double> with, without;
  for (int r = 0; r < repeats; ++r) {
    with.push_back(MsOf([&] { reused = RunToleranceSamples(c, o); }) / o.samples);
    without.push_back(MsOf([&] { RunToleranceSamples(rate_only, o); }) / o.samples);
  }
  const double w = MedianOf(with), wo = MedianOf(without);
  md << "| the same sample, its spring by its rate only (no coil geometry: no surge study and "
        "its coil-chain runs"
     << target
     << ") | with the surge study → without | the surge "
        "study's share "
     << Num(100.0 * (w - wo) / w, 2) << " % | " << Num(w) << " ms | " << Num(wo) << " ms | "
     << Num(w / wo, 3) << "× |\n";
  return md.str();
}

}  // namespace

// Before (main's fixed-step search, full runs) against after (the force-led search, runs that
// stop at lift-off), one thread, interleaved repeats in this one process, medians.
std::string RunOverspeedComparison(int repeats) {
  std::ostringstream md;
  md << "## The overspeed search before and after (one thread, medians of interleaved runs in "
        "one process)\n\n| what | runs before → after | n_dyn before → after | before | after | "
        "ratio |\n|---|---|---|---|---|---|\n";
  md << ComparisonSearch(repeats) << ComparisonChecks(repeats)
     << ComparisonToleranceSample("basu-example2", "; target ≤ 3 ms", repeats)
     << ComparisonToleranceSample("engine-2000rpm-surging-spring", "", repeats);
  md << '\n';
  return md.str();
}

}  // namespace needle::bench
