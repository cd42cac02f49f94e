#include "apps/study/check_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <system_error>

#include "apps/case/case_profile.h"
#include "apps/study/limits_table.h"
#include "lib/lift_data.h"
#include "lib/output.h"
#include "lib/threads.h"
#include "lib/units.h"
#include "spring/quasi_static.h"
#include "spring/resonance.h"

namespace needle {

SweepRange DefaultSweepRange(const BoundCase& c, double rated_rpm, double n_qs_rpm) {
  SweepRange r;
  r.from_rpm = c.overspeed && c.overspeed->from_rpm ? *c.overspeed->from_rpm : rated_rpm;
  r.to_rpm =
      c.overspeed && c.overspeed->to_rpm
          ? *c.overspeed->to_rpm
          : (std::isfinite(n_qs_rpm) ? std::max(2.0 * n_qs_rpm, 2.0 * rated_rpm) : 4.0 * rated_rpm);
  return r;
}

std::string FailureLine(const LimitRow& x) {
  const std::string u = x.UnitSuffix();
  const int d = DecimalsApart(x.value, x.limit, 2);
  std::string line = "limits: " + x.name + ": measured " + Fixed(x.value, d) + u + ", limit " +
                     (x.at_most ? "<= " : ">= ") + Fixed(x.limit, d) + u + ", margin " +
                     Fixed(x.margin, d) + u;
  if (!x.note.empty()) line += " (" + x.note + ")";
  return line + "; rule: " + x.source;
}

std::string ShortJumpNote(const SimulationResult& run) {
  if (!run.liftoff() || !(run.longest_jump_rad < kMinJump_rad)) return "";
  return " (a jump of " + Fixed(run.longest_jump_rad / kDeg, 3) + " deg, shorter than the " +
         Fixed(kMinJump_rad / kDeg, 1) +
         " deg that n_dyn counts: any jump fails at the rated speed)";
}

std::string BounceNote(const SimulationResult& run) {
  // A run cut short (a budget, a needle still moving) may not have shown all its episodes.
  if (run.liftoff() || (run.status != RunStatus::kComplete && run.status != RunStatus::kStopped))
    return "";
  int bounces = 0, first_cycle = 0, last_cycle = 0;
  double first_rad = 0.0, gap_m = 0.0;
  for (const Episode& e : run.episodes) {
    if (e.kind != "bounce") continue;
    if (bounces++ == 0) {
      first_rad = e.start_rad;
      first_cycle = e.cycle;
    }
    last_cycle = e.cycle;
    gap_m = std::max(gap_m, e.max_gap_m);
  }
  if (bounces == 0) return "";
  const int revolutions = last_cycle - first_cycle + 1;
  return " (the cam loses the needle in " + std::to_string(bounces) +
         (bounces == 1 ? " bounce after an impact" : " bounces after impacts") +
         (revolutions > 1 ? " over " + std::to_string(revolutions) + " revolutions" : "") +
         ", from " + Fixed(first_rad / kDeg, 2) + " deg, largest gap " + Fixed(gap_m * 1e6, 2) +
         " um: not lift-off, as none reaches the deceleration zone)";
}

std::vector<std::string> TableEndFailures(const LiftLaw& law, double top_m) {
  std::vector<std::string> failures;
  const double first = law.Lift(law.start_rad()), last = law.Lift(law.end_rad());
  // Both ends off the seat at the same lift (within 1 % of the largest): the readings may carry
  // an offset (a follower's position exported for its lift) rather than a cut.
  const bool offset = first > kOpenEndFraction * top_m && last > kOpenEndFraction * top_m &&
                      std::abs(first - last) <= 0.01 * top_m;
  for (const bool end : {false, true}) {
    const double th = end ? law.end_rad() : law.start_rad(), s = end ? last : first;
    if (top_m > 0.0 && s > kOpenEndFraction * top_m) {
      failures.push_back(std::string("lift table: undecided, it ") + (end ? "ends" : "starts") +
                         " at " + Fixed(s * 1e3, 3) + " mm (" + Fixed(100 * s / top_m, 1) +
                         " % of its largest lift) at " + Fixed(th / kDeg, 2) +
                         " deg, not on the seat: the " + (end ? "closing" : "opening") +
                         " is not in it; " +
                         (offset ? "both ends stand at this lift: if the readings carry an "
                                   "offset, take it off them, else extend"
                                 : "extend") +
                         " the table to where the lift is zero");
    }
  }
  return failures;
}

bool SurgeShowsHarm(const LimitRow& force, const LimitRow& jump, const LimitRow& stress,
                    const LimitRow& gap) {
  return force.verdict == "fail" || jump.verdict == "fail" || stress.verdict == "fail" ||
         gap.verdict == "fail";
}

namespace {

// The first surge mode's damping ratio assumed where the case states none (neither Basu nor
// EN 13906-1 gives the wire's; cases/basu-example1-surge.toml states the same 1 %).
constexpr double kAssumedSurgeDamping = 0.01;

// The scene with its helical spring as N coil masses (SurgeStudy), against the massless spring
// (left to the caller when it is the rated run: the case has no coil masses). Reads of `r` the
// spring check, the speeds and the run options only. Throws std::invalid_argument when the train
// refuses the chain (coils of 3 needle masses or more).
SurgeStudy StudySurge(const BoundCase& c, const CheckResult& r, Scene scene,
                      const CheckOptions& options) {
  const bool series = options.record_series;
  SurgeStudy s;
  const HelicalSpringCheck& h = *r.spring->helical;
  SimulationOptions sim = r.run_options;
  sim.force_dynamic = true;
  sim.record_series = false;
  TrainParameters& t = scene.train;
  t.coil_masses = 1;
  t.coil_clash = false;
  t.coil_travel_m = 0.0;
  // At f·n lift-off is judged as the sweep judges it (on the steady revolutions when asked).
  SimulationOptions over = sim;
  over.steady_state = c.overspeed && c.overspeed->steady_state;
  SimulationOptions rated = sim;
  rated.record_series = series;  // the report's surge figure
  // The rated-speed run is the massless spring's already when the case has no coil masses: the
  // caller copies it (it may be running beside this).
  if (c.spring->masses != 1) s.massless = Simulate(scene, r.speed_rpm, rated);
  // The massless spring at f·n is a note of the report only (not run for a verdict alone). The
  // chain's runs go to their end either way: a run that would not settle after the lift, and
  // the seat's landing that loads the spring and closes the coils, are the verdict's too.
  if (!options.verdict_only) s.massless_overspeed = Simulate(scene, r.overspeed_rpm, over);
  t.spring_mass_kg = ActiveSpringMassKg(*c.spring->helical);
  s.damping_assumed = !(c.spring->surge_damping_ratio > 0.0);
  s.damping_ratio = s.damping_assumed ? kAssumedSurgeDamping : c.spring->surge_damping_ratio;
  t.surge_damping_ratio = s.damping_ratio;
  t.coil_travel_m = h.length_preload_m - h.solid_length_m;
  t.coil_clash = c.spring->coil_clash;
  // The last run's two figures the study compares (its series is not copied).
  std::optional<std::array<double, 2>> before;
  for (int n : {5, 10, 20, 40}) {
    t.coil_masses = n;
    // The first N's series is the report's only where the study ends there, undecided (it
    // cannot converge at its first N): then it is run again with its series.
    SimulationOptions at_n = rated;
    if (!before) at_n.record_series = false;
    SimulationResult run = Simulate(scene, r.speed_rpm, at_n);
    if (!before && series && run.status != RunStatus::kComplete &&
        run.status != RunStatus::kStopped) {
      run = Simulate(scene, r.speed_rpm, rated);
    }
    s.masses = n;
    if (before) {
      const double force = std::abs(run.min_contact_force_ratio - (*before)[0]);
      const double peak = std::abs(run.max_spring_force_N / (*before)[1] - 1.0);
      s.change = std::isfinite(force) ? std::max(force, peak) : INFINITY;
      s.converged = s.change < kSurgeConvergence;
    }
    s.rated = std::move(run);
    if (s.converged ||
        (s.rated.status != RunStatus::kComplete && s.rated.status != RunStatus::kStopped))
      break;  // done, or undecided
    before = {s.rated.min_contact_force_ratio, s.rated.max_spring_force_N};
  }
  s.overspeed = Simulate(scene, r.overspeed_rpm, over);
  return s;
}

}  // namespace

namespace {

// A table that does not come down to the seat at an end leaves the opening or the closing (the
// lash, the seating, a lift-off near the end) to the ramps' extrapolation: the check passed a
// table cut at half its lift (issue 51's trial). Undecided, with what to change. Cut lower, it
// is taken as cut, and a warning says so (or an offset: lib/lift_data.h OffSeatEnds).
void CheckTableEnds(const LiftLaw& law, CheckResult& r) {
  std::vector<std::string> failures = TableEndFailures(law, r.kinematics.max_lift_m);
  if (const std::string off = OffSeatEnds(law); !off.empty() && failures.empty())
    r.warnings.push_back(off);
  for (std::string& line : failures) r.failing.push_back(std::move(line));
}

// "the case has no [needle] and [spring] sections": what a part of the check lacks.
std::string MissingSections(const BoundCase& c, bool train) {
  std::vector<std::string> sections;
  if (!c.needle) sections.push_back("[needle]");
  if (!c.spring) sections.push_back("[spring]");
  if (train && !c.train) sections.push_back("[train]");
  return "the case has no " + ListText(sections) + (sections.size() > 1 ? " sections" : " section");
}

// The dynamics: one run at the rated speed, the overspeed sweep and the surge study (beside
// them on a second core).
void RunDynamics(const BoundCase& c, std::shared_ptr<const LiftLaw> shared_law,
                 const CheckOptions& options, CheckResult& r) {
  const double rpm = r.speed_rpm;
  // The one scene of the check: the bound one, or one on the law asked for.
  const Scene scene = SceneFor(c, shared_law);
  r.run_options = c.run;
  // The surge study needs nothing of the rated run and the sweep: given a second core it runs
  // beside them (its runs and theirs are the same either way; the sweep keeps the other cores).
  const bool helical = r.spring && r.spring->helical;
  if (!helical) r.surge_reason = "no helical spring geometry";
  const int cores = ThreadsToUse(options.threads);
  const auto study_surge = [&c, &r, &scene, &options] {
    try {
      r.surge = StudySurge(c, r, scene, options);
    } catch (const std::invalid_argument& e) {
      r.surge_reason = e.what();
    }
  };
  std::future<void> surge;
  if (helical && cores > 1) {
    try {
      surge = std::async(std::launch::async, study_surge);
    } catch (const std::system_error&) {
      // No thread to be had: the study runs after the sweep, as on one core.
    }
  }
  SimulationOptions sim = r.run_options;
  sim.force_dynamic = true;  // the report shows the dynamic force
  sim.record_series = options.record_series;
  r.run = Simulate(scene, rpm, sim);
  if (options.rated_run_done && r.spring) options.rated_run_done(*r.spring, *r.run, r.run_options);
  if (scene.cam->play_m() == 0.0)
    r.skipped.push_back("lash analysis: no roller play ([train] play_mm = 0)");
  r.sweep_range = DefaultSweepRange(c, rpm, r.n_qs_rpm);
  // The speeds the verdict reads, from the rated speed up to f·n (1 + the separation margin),
  // are always swept: a case's [overspeed] range that leaves some out is widened (a tolerance
  // sample's or a map point's rated speed moves under a range set for the nominal one).
  const double reads_to_rpm =
      r.overspeed_rpm * (1.0 + std::max(0.0, c.limits.separation_margin_fraction));
  r.sweep_range.from_rpm = std::min(r.sweep_range.from_rpm, rpm);
  r.sweep_range.to_rpm = std::max(r.sweep_range.to_rpm, reads_to_rpm);
  OverspeedOptions os;
  os.simulation = r.run_options;
  os.simulation.steady_state = c.overspeed && c.overspeed->steady_state;
  os.from_rpm = r.sweep_range.from_rpm;
  os.to_rpm = r.sweep_range.to_rpm;
  os.threads = surge.valid() ? cores - 1 : options.threads;
  if (options.overspeed_start_rpm) {
    // On to a nearby scene's n_dyn once the scan has passed the speeds the verdict reads
    // without lift-off (up to there every speed of the scan is run as without the guess); a
    // search that does not find a bracket so is run again as any check runs it.
    OverspeedOptions hinted = os;
    hinted.start_rpm = options.overspeed_start_rpm;
    hinted.start_after_rpm = reads_to_rpm;  // the highest speed the separation row reads
    r.sweep = OverspeedSearch(scene, hinted, options.progress);
    if (r.sweep->status != "found") r.sweep = OverspeedSearch(scene, os, options.progress);
  } else {
    r.sweep = OverspeedSearch(scene, os, options.progress);
  }
  if (surge.valid()) {
    surge.get();  // rethrows what the study threw
  } else if (helical) {
    study_surge();
  }
  if (r.surge && c.spring->masses == 1) r.surge->massless = *r.run;
}

// The dynamics' verdicts: lift-off at the rated speed, a run or sweep that is undecided, n_dyn
// at or below f·n.
void JudgeDynamics(CheckResult& r) {
  const auto fail = [&r](const std::string& what) { r.failing.push_back(what); };
  const double rpm = r.speed_rpm;
  if (r.run->liftoff()) {
    fail("dynamics: the needle lifts off the cam at the rated speed " + Fixed(rpm, 0) + " rpm" +
         ShortJumpNote(*r.run));
  }
  // A run that did not end with the needle at rest is no proof of anything.
  if (r.run->status == RunStatus::kNotFollowing) {
    fail("dynamics: " + r.run->status_reason);  // a broken scene, not an undecided one
  } else if (r.run->status != RunStatus::kComplete) {
    fail("dynamics: undecided at the rated speed, the run is " + RunStatusName(r.run->status) +
         ": " + r.run->status_reason);
  }
  const OverspeedResult& s = *r.sweep;
  if (s.status == "run-budget" || s.status == "budget") {
    fail("overspeed: undecided above " + Fixed(s.scanned_to_rpm, 1) + " rpm (" +
         (s.status == "budget" ? std::string("the scan budget ended the search")
                               : std::string("the run there stopped on its budget")) +
         ")");
  }
  if (s.status == "not-following") fail("overspeed: " + OverspeedOutcome(s));
  if (s.status == "floor") {
    fail("overspeed: the needle lifts off at every speed tried down to " + Fixed(s.floor_rpm, 1) +
         " rpm");
  }
  if (s.n_dyn_rpm && *s.n_dyn_rpm <= r.overspeed_rpm) {
    fail("overspeed: n_dyn " + Fixed(*s.n_dyn_rpm, 1) + " rpm is at or below " +
         Fixed(r.overspeed_rpm, 1) + " rpm (the overspeed factor times the rated speed)");
  }
}

// The cam profile, when the case has [profile]: undercut and the contact off the face fail.
void CheckProfile(const BoundCase& c, const LiftLaw& law, CheckResult& r) {
  const auto fail = [&r](const std::string& what) { r.failing.push_back(what); };
  double& cam_zero_crank_rad = r.cam_zero_crank_rad;
  if (c.profile) {
    r.profile = MakeCaseProfile(c, law, &cam_zero_crank_rad);
    const bool flat = c.profile->follower.kind == FollowerKind::kFlat;
    const auto at = [&](double cam_rad) {
      return CamAndCrank(c, cam_zero_crank_rad, cam_rad, 1, "°");
    };
    if (r.profile->undercut) {
      fail(std::string("cam profile: the profile ") + (flat ? "has a cusp" : "undercuts") +
           ": least radius " + Fixed(r.profile->min_profile_radius_m * 1e3, 2) + " mm at " +
           at(r.profile->min_profile_radius_at_rad));
    }
    if (r.profile->off_face) {
      fail("follower face: the contact runs " + Fixed(r.profile->max_contact_offset_m * 1e3, 2) +
           " mm off the axis at " + at(r.profile->max_contact_offset_at_rad) +
           ", beyond the face half-width " + Fixed(c.profile->follower.face_half_width_m * 1e3, 2) +
           " mm");
    }
  } else {
    r.skipped.push_back("cam profile: the case has no [profile] section");
  }
}

// The last of the verdict: the warning of undamped coil masses, the spring check's failures
// first as the surge verdict (JudgeLimits) left them.
void FinishVerdict(const BoundCase& c, CheckResult& r) {
  // Undamped coils in the dynamics: every resonance of the chain with a cam harmonic is a lift-off
  // window as narrow as the run is long, which no sweep of finite steps can be sure to meet (a
  // 20-mass spring lifted off between 1259 and 1261 rpm only, undamped; not at all at 1 %).
  if (r.run && c.spring->masses > 1 && !(c.spring->surge_damping_ratio > 0.0)) {
    r.warnings.push_back("dynamics: the spring's " + std::to_string(c.spring->masses) +
                         " coil masses are undamped ([spring] surge_damping_ratio = 0): their "
                         "resonances with the cam's harmonics are lift-off windows narrower than "
                         "the sweep's steps, which it can miss; state the wire's damping (1 % is "
                         "typical)");
  }
  // A rise or return the table does not resolve: the spring check leaves the sizing undecided;
  // the runs read the law fitted there, and their rows say nothing of that unless told.
  if (r.run && r.spring && !r.spring->unresolved.empty())
    r.warnings.push_back("dynamics: the runs read the lift law fitted where " +
                         r.spring->unresolved);
  // The spring check's failures first, as the surge verdict (JudgeLimits) left them.
  if (r.spring) {
    std::vector<std::string> lines;
    for (const std::string& f : r.spring->failures) lines.push_back("spring check: " + f);
    if (!r.spring->pass && r.spring->failures.empty()) lines.push_back("spring check: fails");
    r.failing.insert(r.failing.begin(), lines.begin(), lines.end());
    for (const std::string& w : r.spring->warnings) r.warnings.push_back("spring check: " + w);
  }
}

}  // namespace

CheckResult CheckScene(const BoundCase& c, const CheckOptions& options) {
  return CheckScene(c, c.lift.law, options);
}

CheckResult CheckScene(const BoundCase& c, const LiftLaw& law, const CheckOptions& options) {
  return CheckScene(c, std::make_shared<const LiftLaw>(law), options);
}

CheckResult CheckScene(const BoundCase& c, std::shared_ptr<const LiftLaw> shared_law,
                       const CheckOptions& options) {
  const LiftLaw& law = *shared_law;
  CheckResult r;
  r.speed_rpm = options.speed_rpm.value_or(c.engine.speed_rpm);
  const double rpm = r.speed_rpm;
  r.choice = c.lift.choice;
  r.kinematics = Kinematics(law, rpm).Summarize();
  r.overspeed_rpm = rpm * (c.spring ? c.spring->overspeed_factor : 1.2);
  const auto fail = [&r](const std::string& what) { r.failing.push_back(what); };
  if (!law.HasAcceleration()) {
    r.skipped.push_back("acceleration panel and table column: the " + SplineKindName(law.kind()) +
                        " spline is C¹ only (its second derivative jumps at the knots)");
  }

  CheckTableEnds(law, r);

  // The spring check and the dynamics read the acceleration: a case that asks for them on a C¹
  // spline is undecided there, not passed.
  const std::string no_acceleration =
      "undecided, the " + SplineKindName(law.kind()) +
      " spline is C¹ only and gives no acceleration (inertia force, quasi-static lift-off, cam "
      "input); state a C² spline in [lift] spline (\"local\", \"quintic\", \"not-a-knot\") or "
      "leave it out to have it chosen from the data";
  // The spring check.
  if (!(c.needle && c.spring)) {
    r.skipped.push_back("spring check: " + MissingSections(c, false));
  } else if (!law.HasAcceleration()) {
    fail("spring check: " + no_acceleration);
  } else {
    r.spring = CheckSpring(c, law, rpm);
    r.n_qs_rpm = r.spring->liftoff_rpm_quasi_static;
  }

  // The dynamics: one run at the rated speed, and the overspeed sweep.
  if (!(c.train && c.needle && c.spring)) {
    r.skipped.push_back("dynamics and overspeed: " + MissingSections(c, true));
  } else if (!law.HasAcceleration()) {
    fail("dynamics and overspeed: " + no_acceleration);
  } else {
    RunDynamics(c, shared_law, options, r);
    JudgeDynamics(r);
  }

  CheckProfile(c, law, r);
  if (law.HasAcceleration()) JudgeLimits(c, law, r.cam_zero_crank_rad, r, !options.verdict_only);
  FinishVerdict(c, r);
  r.pass = r.failing.empty();  // one rule: a scene passes when nothing fails
  return r;
}

std::vector<FieldGroup> CheckFields(const CheckResult& r) {
  using namespace display;
  std::vector<FieldGroup> g;
  g.push_back({"kinematics",
               {{"max_lift", kMm, r.kinematics.max_lift_m, 3},
                {"open", kDegree, r.kinematics.open_rad, 2},
                {"close", kDegree, r.kinematics.close_rad, 2},
                TextField("spline_reason", r.choice.reason)}});
  if (r.spring) {
    g.push_back({"spring",
                 {{"preload", kN, r.spring->train.preload_N, 1},
                  {"gas_force", kN, r.spring->gas_force_N, 1},
                  {"basu_preload", kN, r.spring->basu_preload_N, 1},
                  FlagField("pass", r.spring->pass),
                  FlagField("preload_ok", r.spring->preload_ok),
                  FlagField("combustion_ok", r.spring->combustion_ok),
                  FlagField("basu_ok", r.spring->basu_ok)}});
  }
  if (r.run) {
    g.push_back({"dynamics",
                 {{"run_end", kDegree, r.run->run_end_rad, 2},
                  FlagField("liftoff", r.run->liftoff()),
                  TextField("status", RunStatusName(r.run->status)),
                  TextField("status_reason", r.run->status_reason),
                  CountField("episodes", static_cast<long long>(r.run->episodes.size())),
                  CountField("impacts", static_cast<long long>(r.run->impacts.size()))}});
  }
  if (r.sweep) {
    const OverspeedResult& s = *r.sweep;
    g.push_back({"overspeed",
                 {{"n_qs", kRpm, FiniteOrNone(r.n_qs_rpm), 1, "liftoff_rpm_quasi_static"},
                  {"n_dyn", kRpm, s.n_dyn_rpm, 1, "liftoff_rpm_dynamic"},
                  {"overspeed", kRpm, r.overspeed_rpm, 1},
                  {"step", kRpm, s.step_rpm, 2},
                  {"scanned_to", kRpm, s.scanned_to_rpm, 1},
                  TextField("status", s.status)}});
  }
  if (r.profile) {
    g.push_back(
        {"profile",
         {{"min_profile_radius", kMm, r.profile->min_profile_radius_m, 2},
          {"max_abs_pressure_angle", kDegree, std::abs(r.profile->max_pressure_angle_rad), 2},
          FlagField("undercut", r.profile->undercut)}});
  }
  return g;
}

std::vector<Field> LimitRowFields(const LimitRow& x) {
  return {TextField("name", x.key),
          TextField("unit", x.unit),
          FlagField("at_most", x.at_most),
          TextField("verdict", x.verdict),
          TextField("note", x.note),
          TextField("source", x.source),
          {"value", display::kNone, FiniteOrNone(x.value), 2},
          {"limit", display::kNone, FiniteOrNone(x.limit), 2},
          {"margin", display::kNone, FiniteOrNone(x.margin), 2}};
}

}  // namespace needle
