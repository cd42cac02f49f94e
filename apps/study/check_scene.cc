#include "apps/study/check_scene.h"

#include <algorithm>
#include <cmath>

#include "apps/scene/case_profile.h"
#include "apps/scene/case_scene.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/quasi_static.h"
#include "spring/resonance.h"

namespace needle {

SweepRange DefaultSweepRange(const Case& c, double rated_rpm, double n_qs_rpm) {
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
  std::string line = "limits: " + x.name + ": measured " + Fixed(x.value, 2) + u + ", limit " +
                     (x.at_most ? "<= " : ">= ") + Fixed(x.limit, 2) + u + ", margin " +
                     Fixed(x.margin, 2) + u;
  if (!x.note.empty()) line += " (" + x.note + ")";
  return line + "; rule: " + x.source;
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

// The limits table (docs/springs.md "The limits table"): one row per limit, judged where the scene
// has what it needs, else "not judged" with the reason.
void JudgeLimits(const Case& c, const LiftLaw& law, double cam_zero_crank_rad, CheckResult& r) {
  const LimitsSection& l = c.limits;
  const double crank_turns = CrankTurnsPerCycle(c.engine.cycle);  // per cam turn
  const auto row = [&](std::string key, std::string name, std::string unit, bool at_most,
                       double limit, std::string source) {
    LimitRow x;
    x.key = std::move(key);
    x.name = std::move(name);
    x.unit = std::move(unit);
    x.at_most = at_most;
    x.limit = limit;
    x.source = std::move(source);
    x.verdict = "not judged";
    return x;
  };
  const auto judge = [](LimitRow& x, double value, std::string note) {
    x.value = value;
    x.margin = x.at_most ? x.limit - value : value - x.limit;
    x.verdict = x.margin >= 0.0 ? "pass" : "fail";
    x.note = std::move(note);
  };
  // A contact force of zero is a loss of contact, whatever the limit (a limit of 0 %, or an
  // overspeed factor of 1, would otherwise pass it).
  const auto judge_force = [&judge](LimitRow& x, double value, std::string note) {
    judge(x, value, std::move(note));
    if (!(value > 0.0) && x.verdict != "fail") {
      x.verdict = "fail";
      x.note += "; a contact force of 0 fails whatever the limit";
    }
  };
  const LimitsSection d;  // the defaults, to name where a limit came from
  const auto from = [](bool set, const std::string& key, const std::string& cited) {
    return set ? "[limits] " + key : cited;
  };

  LimitRow seat = row("seating_velocity", "seating velocity", "m/s", true, l.seating_velocity_m_s,
                      from(l.seating_velocity_m_s != d.seating_velocity_m_s, "seating_velocity",
                           "Blair: optimum ramp velocity 1.0-1.5 m/s"));
  LimitRow lash =
      row("lash_impact_speed", "cam impact speed (lash and recontacts)", "m/s", true,
          l.lash_impact_velocity_m_s,
          from(l.lash_impact_velocity_m_s != d.lash_impact_velocity_m_s, "lash_impact_velocity",
               "Blair: optimum ramp velocity 1.0-1.5 m/s (the opening ramp)"));
  // Least contact force while the cam lifts the needle, against the static load holding it
  // there: at f·n the inertia grows by f², so a share 1 − 1/f² of that load must remain.
  const double f_over = c.spring ? c.spring->overspeed_factor : 1.2;
  const double force_limit = l.min_contact_force_fraction.value_or(1.0 - 1.0 / (f_over * f_over));
  LimitRow force = row("min_contact_force",
                       "least contact force while the cam lifts the needle, % of P0 + k y - F_g",
                       "%", false, 100 * force_limit,
                       l.min_contact_force_fraction
                           ? "[limits] min_contact_force_percent"
                           : "overspeed factor f = " + Fixed(f_over, 2) +
                                 ": 1 - 1/f^2 of the holding load left for f n's inertia");
  if (r.run && c.spring) {
    const SimulationResult& run = *r.run;
    double landing = 0.0;
    std::string where = "no landing on the seat in the run";
    for (const Impact& i : run.impacts) {
      if (i.kind.rfind("seat", 0) == 0 && i.kind != "seat-sticking" && i.speed_m_s >= landing) {
        landing = i.speed_m_s;
        where = i.kind + " at " + Fixed(i.crank_rad / kDeg, 2) + " deg";
      }
    }
    judge(seat, landing, where);
    if (c.train && c.train->play_m > 0.0) {
      // Every strike of the cam on the roller: the lash, and a recontact after a bounce or a
      // jump (where the cam already touched when the run began, the first strike is one).
      double strike = 0.0;
      std::string at = "the cam never struck the roller";
      for (const Impact& i : run.impacts) {
        if ((i.kind == "lash" || i.kind == "recontact") && i.speed_m_s >= strike) {
          strike = i.speed_m_s;
          at = i.kind + " at " + Fixed(i.crank_rad / kDeg, 2) + " deg";
        }
      }
      judge(lash, strike,
            at + "; peak contact force in the run " + Fixed(run.max_contact_force_N, 0) + " N");
    } else {
      lash.note = "no roller play ([train] play_mm = 0): no lash to take up";
    }
    if (std::isfinite(run.min_contact_force_ratio)) {
      judge_force(force, 100 * run.min_contact_force_ratio,
                  Fixed(run.min_contact_force_ratio_force_N, 1) + " N at " +
                      Fixed(run.min_contact_force_ratio_rad / kDeg, 2) + " deg");
    } else {
      judge_force(force, 0.0, "the cam never lifted the needle off its seat");
    }
  } else {
    seat.note = lash.note = force.note = "no dynamics ([train] missing)";
  }

  LimitRow sep = row("separation_margin", "separation margin n_dyn/(f n) - 1", "%", false,
                     100 * l.separation_margin_fraction,
                     from(l.separation_margin_fraction != d.separation_margin_fraction,
                          "separation_margin_percent", "model: n_dyn > f n"));
  if (r.sweep && r.sweep->status != "run-budget" && r.sweep->status != "budget" &&
      r.sweep->status != "floor" && r.sweep->status != "not-following") {
    if (r.sweep->n_dyn_rpm) {
      judge(sep, 100 * (*r.sweep->n_dyn_rpm / r.overspeed_rpm - 1),
            "n_dyn " + Fixed(*r.sweep->n_dyn_rpm, 1) + " rpm, f n " + Fixed(r.overspeed_rpm, 1) +
                " rpm");
    } else {
      judge(sep, 100 * (r.sweep->scanned_to_rpm / r.overspeed_rpm - 1),
            "no lift-off up to " + Fixed(r.sweep->scanned_to_rpm, 1) + " rpm (a lower bound)");
    }
  } else {
    sep.note = r.sweep ? "the sweep is undecided (" + r.sweep->status + ")"
                       : "no overspeed sweep ([train] missing)";
  }

  LimitRow hertz =
      row("hertz_stress", "Hertz stress cam-roller", "MPa", true, l.hertz_stress_Pa * 1e-6,
          from(l.hertz_stress_Pa != d.hertz_stress_Pa, "hertz_stress_MPa",
               "ISO 6336-5 case-hardened MQ, 1500 MPa"));
  if (r.profile && r.spring && l.contact_length_m) {
    const FollowerGeometry& g = c.profile->follower;
    const RigidTrain& t = r.spring->train;
    const double omega = OmegaFromRpm(r.speed_rpm), k = crank_turns;
    const double play = c.train ? c.train->play_m : 0.0;
    double worst = 0.0, at = 0.0;
    for (const ProfilePoint& q : r.profile->points) {
      const double th = cam_zero_crank_rad + k * q.cam_rad;
      const bool open = th >= law.start_rad() && th <= law.end_rad();
      const double f_needle = open ? QuasiStaticForce(law, t, omega, th)
                                   : (play > 0 ? 0.0 : t.preload_N - t.gas_force_N);  // base circle
      const double stress = ContactStress(g, q, std::max(0.0, f_needle) / g.lever_ratio,
                                          l.elastic_modulus_Pa, l.poisson, *l.contact_length_m);
      if (stress > worst) {
        worst = stress;
        at = q.cam_rad;
      }
    }
    judge(hertz, worst * 1e-6,
          "quasi-static force at " + Fixed(r.speed_rpm, 0) + " rpm, worst at cam " +
              Fixed(at / kDeg, 1) + " deg");
  } else {
    hertz.note = !r.profile  ? "no [profile] (the cam's radius)"
                 : !r.spring ? "no spring check (the contact force)"
                             : "no [limits] contact_length_mm (the roller's width)";
  }

  const HelicalSpringCheck* helical = r.spring && r.spring->helical ? &*r.spring->helical : nullptr;
  LimitRow fatigue = row("fatigue_safety_factor", "spring fatigue safety factor (Goodman)", "",
                         false, l.fatigue_safety_factor,
                         from(l.fatigue_safety_factor != d.fatigue_safety_factor,
                              "fatigue_safety_factor", "Shigley 10-12: design factor 1.5"));
  LimitRow gap = row("coil_gap", "coil gap at full lift", "mm", false, NAN,
                     l.coil_gap_m ? "[limits] coil_gap_mm" : "EN 13906-1: S_a");
  // Surge by its effect, with the spring as coil masses (SurgeStudy): the least contact force,
  // lift-off at f·n and the spring's stress with the coils' inertia.
  LimitRow surge_force =
      row("surge_contact_force", "least contact force with the coils' surge, % of P0 + k y - F_g",
          "%", false, force.limit, force.source);
  LimitRow surge_jump = row("surge_overspeed_jump", "longest jump at f n with the coils' surge",
                            "deg", true, kMinJump_rad / kDeg,
                            "model: lift-off is a jump of 0.1 deg or more (§6), none at f n (§8)");
  LimitRow surge_stress =
      row("surge_spring_stress", "spring shear stress at the surge's peak force", "MPa", true, NAN,
          "the helical check's allowable stress");
  LimitRow ratio = row("surge_frequency_ratio", "first surge mode over the cam frequency f_1/f_cam",
                       "", false, kMinSurgeRatio,
                       "spring makers' screen f_1 >= 13 f (Rockford Spring, 'Dynamic loading of "
                       "springs'; Shigley 10-9 asks 15-20); a warning where the coils' dynamics "
                       "show no harm");
  const std::string no_helical = "no helical spring geometry ([spring] wire_mm …)";
  if (helical) {
    const HelicalSpringCheck& h = *helical;
    if (h.fatigue_judged) {
      judge(fatigue, h.fatigue.goodman_safety_factor,
            "tau " + Fixed(h.stress_preload_Pa * 1e-6, 0) + "-" +
                Fixed(h.stress_full_lift_Pa * 1e-6, 0) + " MPa, " +
                (c.spring->helical->shot_peened ? "shot-peened" : "unpeened") + " (Zimmerli)");
    } else {
      fatigue.note = "wire " + Fixed(c.spring->helical->wire_m * 1e3, 1) +
                     " mm: Zimmerli's data cover wire below 10 mm";
    }
    gap.limit = (l.coil_gap_m ? *l.coil_gap_m : h.min_clearance_m) * 1e3;
    const SimulationResult* chain = r.surge && r.surge->rated.status == RunStatus::kComplete
                                        ? &r.surge->rated
                                        : (r.run && r.run->min_coil_gap_m ? &*r.run : nullptr);
    if (chain && chain->min_coil_gap_m) {
      // A chain of coil masses: the least gap in the run at the rated speed, where surge may
      // close one segment well before the static full lift closes them all.
      const int n = r.surge ? r.surge->masses : c.spring->masses;
      gap.name = "coil gap in the run (worst segment x N)";
      judge(gap, *chain->min_coil_gap_m * 1e3,
            "at " + Fixed(r.speed_rpm, 0) + " rpm with " + std::to_string(n) + " coil masses, " +
                std::to_string(chain->coil_clashes) + " clashes; " +
                Fixed(h.clearance_full_lift_m * 1e3, 2) + " mm at full lift statically");
    } else {
      judge(gap, h.clearance_full_lift_m * 1e3, "");
    }
    // The modes j·f_e of the spring held at both ends (spring/resonance.h), f_e the check's: the
    // resonance map's lines (information).
    for (int j = 1; j <= 3; ++j) r.surge_modes_hz.push_back(j * h.surge_hz);
    r.harmonics = LiftHarmonics(law, 2 * kPi * crank_turns, 1000, l.harmonic_threshold);
    const auto undecided = [](const SimulationResult& run) {
      return run.status != RunStatus::kComplete;
    };
    if (r.surge && (undecided(r.surge->rated) || undecided(r.surge->overspeed))) {
      const SimulationResult& bad = undecided(r.surge->rated) ? r.surge->rated : r.surge->overspeed;
      const std::string why = "undecided: the run with " + std::to_string(r.surge->masses) +
                              " coil masses at " + Fixed(bad.speed_rpm, 1) + " rpm is " +
                              RunStatusName(bad.status) + ": " + bad.status_reason;
      surge_force.note = surge_jump.note = surge_stress.note = why;
      r.failing.push_back("surge: " + why);
    } else if (r.surge) {
      const SurgeStudy& s = *r.surge;
      const std::string with = std::to_string(s.masses) + " coil masses, zeta " +
                               Fixed(100 * s.damping_ratio, 1) + " %" +
                               (s.damping_assumed ? " (assumed)" : "") + ", converged to " +
                               Fixed(100 * s.change, 2) + " %" + (s.converged ? "" : " (NOT)");
      judge_force(surge_force,
                  std::isfinite(s.rated.min_contact_force_ratio)
                      ? 100 * s.rated.min_contact_force_ratio
                      : 0.0,
                  "with " + with + "; massless spring " +
                      Fixed(100 * s.massless.min_contact_force_ratio, 2) + " %");
      judge(surge_jump, s.overspeed.longest_jump_rad / kDeg,
            "at " + Fixed(r.overspeed_rpm, 1) + " rpm with " + with + "; massless spring " +
                Fixed(s.massless_overspeed.longest_jump_rad / kDeg, 2) + " deg");
      // τ grows with the force (τ = k 8 F D / π d³): the full-lift stress scaled by the peak.
      const double f_full = r.spring->train.preload_N + r.spring->train.rate_N_m * law.Max(0).value;
      surge_stress.limit = h.allowable_stress_Pa * 1e-6;
      judge(surge_stress, h.stress_full_lift_Pa * 1e-6 * s.rated.max_spring_force_N / f_full,
            "peak spring force " + Fixed(s.rated.max_spring_force_N, 0) + " N with the coils, " +
                Fixed(s.massless.max_spring_force_N, 0) + " N massless (" +
                Fixed(100 * (s.rated.max_spring_force_N / s.massless.max_spring_force_N - 1), 1) +
                " %)");
    } else {
      surge_force.note = surge_jump.note = surge_stress.note =
          r.run ? "the coils' dynamics could not be run: " + r.surge_reason
                : "no dynamics ([train] missing)";
    }
    judge(ratio, h.surge_ratio,
          "f_1 " + Fixed(h.surge_hz, 1) + " Hz, cam " + Fixed(h.cam_hz, 2) + " Hz");
    if (ratio.verdict == "fail" && r.surge) {
      if (!SurgeShowsHarm(surge_force, surge_jump, surge_stress, gap)) {
        ratio.verdict = "warning";
        ratio.note += "; the coils' dynamics show no harm";
        // The spring check's own screen (the same f_1/f_cam >= 13) warns with it: its failures
        // are those of its other sub-checks (CheckScene lists them after the limits).
        r.spring->failures = SpringFailures(*r.spring, /*surge_screen=*/false);
        r.spring->pass = r.spring->failures.empty();
      } else {
        ratio.note += "; the coils' dynamics show harm (the surge rows)";
      }
    }
  } else {
    fatigue.note = gap.note = ratio.note = no_helical;
    surge_force.note = surge_jump.note = surge_stress.note = no_helical;
  }
  r.limits = {seat, lash,        force,      sep,          hertz, fatigue,
              gap,  surge_force, surge_jump, surge_stress, ratio};
  for (const LimitRow& x : r.limits) {
    if (x.verdict == "warning") r.warnings.push_back(FailureLine(x));
    if (x.verdict == "fail") {
      r.failing.push_back(FailureLine(x));
    }
  }
  // The rows not judged, in one line grouped by reason.
  std::vector<std::pair<std::string, std::string>> by_reason;  // reason, names
  for (const LimitRow& x : r.limits) {
    if (x.verdict != "not judged") continue;
    auto it = std::find_if(by_reason.begin(), by_reason.end(),
                           [&](const auto& p) { return p.first == x.note; });
    if (it == by_reason.end()) {
      by_reason.push_back({x.note, x.name});
    } else {
      it->second += ", " + x.name;
    }
  }
  if (!by_reason.empty()) {
    std::string line = "limits not judged: ";
    for (size_t i = 0; i < by_reason.size(); ++i) {
      line += (i ? "; " : "") + by_reason[i].second + " (" + by_reason[i].first + ")";
    }
    r.skipped.push_back(line);
  }
}

// The scene with its helical spring as N coil masses (SurgeStudy), against the massless spring.
// Throws std::invalid_argument when the train refuses the chain (coils of 3 needle masses or
// more).
SurgeStudy StudySurge(const Case& c, const CheckResult& r, bool series) {
  SurgeStudy s;
  Scene scene = MakeScene(c);
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
  // The rated-speed run is the massless spring's already when the case has no coil masses.
  s.massless = c.spring->masses == 1 && r.run ? *r.run : Simulate(scene, r.speed_rpm, rated);
  s.massless_overspeed = Simulate(scene, r.overspeed_rpm, over);
  t.spring_mass_kg = ActiveSpringMassKg(*c.spring->helical);
  s.damping_assumed = !(c.spring->surge_damping_ratio > 0.0);
  s.damping_ratio = s.damping_assumed ? kAssumedSurgeDamping : c.spring->surge_damping_ratio;
  t.surge_damping_ratio = s.damping_ratio;
  t.coil_travel_m = h.length_preload_m - h.solid_length_m;
  t.coil_clash = c.spring->coil_clash;
  std::optional<SimulationResult> before;
  for (int n : {5, 10, 20, 40}) {
    t.coil_masses = n;
    SimulationResult run = Simulate(scene, r.speed_rpm, rated);
    s.masses = n;
    if (before) {
      const double force = std::abs(run.min_contact_force_ratio - before->min_contact_force_ratio);
      const double peak = std::abs(run.max_spring_force_N / before->max_spring_force_N - 1.0);
      s.change = std::isfinite(force) ? std::max(force, peak) : INFINITY;
      s.converged = s.change < kSurgeConvergence;
    }
    s.rated = std::move(run);
    if (s.converged || s.rated.status != RunStatus::kComplete) break;  // done, or undecided
    before = s.rated;
  }
  s.overspeed = Simulate(scene, r.overspeed_rpm, over);
  return s;
}

}  // namespace

CheckResult CheckScene(const Case& c, const LiftLaw& law, const CheckOptions& options) {
  CheckResult r;
  r.speed_rpm = options.speed_rpm.value_or(c.engine.speed_rpm);
  const double rpm = r.speed_rpm;
  r.choice = CaseLiftChoice(c);
  r.kinematics = Kinematics(law, rpm).Summarize();
  r.overspeed_rpm = rpm * (c.spring ? c.spring->overspeed_factor : 1.2);
  const auto fail = [&r](const std::string& what) { r.failing.push_back(what); };
  if (!law.HasAcceleration()) {
    r.skipped.push_back("acceleration panel and table column: the " + SplineKindName(law.kind()) +
                        " spline is C¹ only (its second derivative jumps at the knots)");
  }

  // The spring check.
  if (c.needle && c.spring && law.HasAcceleration()) {
    r.spring = CheckSpring(c, law, rpm);
    r.n_qs_rpm = r.spring->liftoff_rpm_quasi_static;
  } else {
    r.skipped.push_back(!law.HasAcceleration()
                            ? "spring check: the spline is C¹ only (no acceleration)"
                            : "spring check: the case has no [needle] and [spring] sections");
  }

  // The dynamics: one run at the rated speed, and the overspeed sweep.
  if (c.train && c.needle && c.spring && law.HasAcceleration()) {
    const Scene scene = MakeScene(c);
    r.run_options = OptionsFromCase(c);
    SimulationOptions sim = r.run_options;
    sim.force_dynamic = true;  // the report shows the dynamic force
    sim.record_series = options.record_series;
    r.run = Simulate(scene, rpm, sim);
    if (scene.cam->play_m() == 0.0)
      r.skipped.push_back("lash analysis: no roller play ([train] play_mm = 0)");
    r.sweep_range = DefaultSweepRange(c, rpm, r.n_qs_rpm);
    OverspeedOptions os;
    os.simulation = r.run_options;
    os.simulation.steady_state = c.overspeed && c.overspeed->steady_state;
    os.from_rpm = r.sweep_range.from_rpm;
    os.to_rpm = r.sweep_range.to_rpm;
    os.threads = options.threads;
    r.sweep = OverspeedSearch(scene, os, options.progress);
    if (r.spring && r.spring->helical) {
      try {
        r.surge = StudySurge(c, r, options.record_series);
      } catch (const std::invalid_argument& e) {
        r.surge_reason = e.what();
      }
    } else {
      r.surge_reason = "no helical spring geometry";
    }

    if (r.run->liftoff()) {
      fail("dynamics: the needle lifts off the cam at the rated speed " + Fixed(rpm, 0) + " rpm");
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
  } else {
    r.skipped.push_back(
        "dynamics and overspeed: the case has no [train] section (contact stiffness, play)");
  }

  // The cam profile, when the case has [profile].
  double cam_zero_crank_rad = 0.0;
  if (c.profile) {
    r.profile = MakeCaseProfile(c, law, &cam_zero_crank_rad);
    const bool flat = c.profile->follower.kind == FollowerKind::kFlat;
    if (r.profile->undercut) {
      fail(std::string("cam profile: the profile ") + (flat ? "has a cusp" : "undercuts") +
           " (least radius " + Fixed(r.profile->min_profile_radius_m * 1e3, 2) + " mm at cam " +
           Fixed(r.profile->min_profile_radius_at_rad / kDeg, 1) + "°)");
    }
    if (r.profile->off_face) {
      fail("follower face: the contact runs " + Fixed(r.profile->max_contact_offset_m * 1e3, 2) +
           " mm off the axis at cam " + Fixed(r.profile->max_contact_offset_at_rad / kDeg, 1) +
           "°, beyond the face half-width " +
           Fixed(c.profile->follower.face_half_width_m * 1e3, 2) + " mm");
    }
  } else {
    r.skipped.push_back("cam profile: the case has no [profile] section");
  }
  if (law.HasAcceleration()) JudgeLimits(c, law, cam_zero_crank_rad, r);
  // The spring check's failures first, as the surge verdict (JudgeLimits) left them.
  if (r.spring) {
    std::vector<std::string> lines;
    for (const std::string& f : r.spring->failures) lines.push_back("spring check: " + f);
    if (!r.spring->pass && r.spring->failures.empty()) lines.push_back("spring check: fails");
    r.failing.insert(r.failing.begin(), lines.begin(), lines.end());
  }
  r.pass = r.failing.empty();  // one rule: a scene passes when nothing fails
  return r;
}

std::vector<FieldGroup> CheckFields(const CheckResult& r) {
  using namespace display;
  const auto finite = [](double v) {
    return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
  };
  std::vector<FieldGroup> g;
  g.push_back({"kinematics",
               {{"max_lift", kMm, r.kinematics.max_lift_m, 3},
                {"open", kDegree, r.kinematics.open_rad, 2},
                {"close", kDegree, r.kinematics.close_rad, 2}}});
  if (r.spring) {
    g.push_back({"spring",
                 {{"preload", kN, r.spring->train.preload_N, 1},
                  {"gas_force", kN, r.spring->gas_force_N, 1},
                  {"basu_preload", kN, r.spring->basu_preload_N, 1}}});
  }
  if (r.run) g.push_back({"dynamics", {{"run_end", kDegree, r.run->run_end_rad, 2}}});
  if (r.sweep) {
    const OverspeedResult& s = *r.sweep;
    g.push_back({"overspeed",
                 {{"n_qs", kRpm, finite(r.n_qs_rpm), 1, "liftoff_rpm_quasi_static"},
                  {"n_dyn", kRpm, s.n_dyn_rpm, 1, "liftoff_rpm_dynamic"},
                  {"overspeed", kRpm, r.overspeed_rpm, 1},
                  {"step", kRpm, s.step_rpm, 2},
                  {"scanned_to", kRpm, s.scanned_to_rpm, 1}}});
  }
  if (r.profile) {
    g.push_back(
        {"profile",
         {{"min_profile_radius", kMm, r.profile->min_profile_radius_m, 2},
          {"max_abs_pressure_angle", kDegree, std::abs(r.profile->max_pressure_angle_rad), 2}}});
  }
  return g;
}

}  // namespace needle
