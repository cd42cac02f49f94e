#include "apps/scene/check_scene.h"

#include <algorithm>
#include <cmath>

#include "apps/scene/case_profile.h"
#include "apps/scene/case_scene.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/quasi_static.h"

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

namespace {

// The limits table (README "The limits table"): one row per limit, judged where the scene has
// what it needs, else "not judged" with the reason.
void JudgeLimits(const Case& c, const LiftLaw& law, double cam_zero_crank_rad, CheckResult& r) {
  const LimitsSection& l = c.limits;
  const bool four = c.engine.cycle == "four-stroke";
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
  const LimitsSection d;  // the defaults, to name where a limit came from
  const auto from = [](bool set, const std::string& key, const std::string& cited) {
    return set ? "[limits] " + key : cited;
  };

  LimitRow seat = row("seating_velocity", "seating velocity", "m/s", true, l.seating_velocity_m_s,
                      from(l.seating_velocity_m_s != d.seating_velocity_m_s, "seating_velocity",
                           "Blair: optimum ramp velocity 1.0-1.5 m/s"));
  LimitRow force = row("min_contact_force", "least contact force in the lift", "% of P0", false,
                       100 * l.min_contact_force_fraction,
                       from(l.min_contact_force_fraction != d.min_contact_force_fraction,
                            "min_contact_force_percent", "model: F_c > 0 (no lift-off)"));
  if (r.run && c.spring) {
    double landing = 0.0;
    std::string where = "no landing on the seat in the run";
    for (const Impact& i : r.run->impacts) {
      if (i.kind.rfind("seat", 0) == 0 && i.kind != "seat-sticking" && i.speed_m_s >= landing) {
        landing = i.speed_m_s;
        where = i.kind + " at " + Fixed(i.crank_rad / kDeg, 2) + " deg";
      }
    }
    judge(seat, landing, where);
    judge(force, 100 * r.run->min_contact_force_during_lift_N / c.spring->preload_N,
          Fixed(r.run->min_contact_force_during_lift_N, 1) + " N of P0 " +
              Fixed(c.spring->preload_N, 1) + " N");
  } else {
    seat.note = force.note = "no dynamics ([train] missing)";
  }

  LimitRow sep = row("separation_margin", "separation margin n_dyn/(f n) - 1", "%", false,
                     100 * l.separation_margin_fraction,
                     from(l.separation_margin_fraction != d.separation_margin_fraction,
                          "separation_margin_percent", "model: n_dyn > f n"));
  if (r.sweep && r.sweep->status != "run-budget" && r.sweep->status != "budget" &&
      r.sweep->status != "floor") {
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
    const double omega = OmegaFromRpm(r.speed_rpm), k = four ? 2.0 : 1.0;
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
  LimitRow res = row("resonance_margin", "first surge mode above the cam's harmonics", "%", false,
                     100 * l.resonance_margin_fraction,
                     from(l.resonance_margin_fraction != d.resonance_margin_fraction,
                          "resonance_margin_percent", "no significant harmonic at the mode"));
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
    if (r.run && r.run->min_coil_gap_m) {
      // A chain of coil masses: the least gap in the run at the rated speed, where surge may
      // close one segment well before the static full lift closes them all.
      gap.name = "coil gap in the run (worst segment x N)";
      judge(gap, *r.run->min_coil_gap_m * 1e3,
            "at " + Fixed(r.speed_rpm, 0) + " rpm with " + std::to_string(c.spring->masses) +
                " coil masses, " + std::to_string(r.run->coil_clashes) + " clashes; " +
                Fixed(h.clearance_full_lift_m * 1e3, 2) + " mm at full lift statically");
    } else {
      judge(gap, h.clearance_full_lift_m * 1e3, "");
    }
    // The modes j·f_e of the spring held at both ends (spring/resonance.h), f_e the check's.
    for (int j = 1; j <= 3; ++j) r.surge_modes_hz.push_back(j * h.surge_hz);
    r.harmonics = LiftHarmonics(law, four ? 4 * kPi : 2 * kPi, 1000, l.harmonic_threshold);
    const int top = r.harmonics->highest_significant_order;
    const double f_top = top * h.cam_hz;
    judge(res, 100 * (r.surge_modes_hz[0] / f_top - 1),
          "f_1 " + Fixed(r.surge_modes_hz[0], 1) + " Hz, order " + std::to_string(top) + " at " +
              Fixed(f_top, 1) + " Hz");
  } else {
    fatigue.note = gap.note = res.note = "no helical spring geometry ([spring] wire_mm …)";
  }
  r.limits = {seat, force, sep, hertz, fatigue, gap, res};
  for (const LimitRow& x : r.limits) {
    if (x.verdict == "fail") {
      r.failing.push_back("limits: " + x.name + " " + Fixed(x.value, 2) + x.UnitSuffix() +
                          (x.at_most ? " above " : " below ") + Fixed(x.limit, 2) + x.UnitSuffix() +
                          " (" + x.source + ")");
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
    for (const std::string& f : r.spring->failures) fail("spring check: " + f);
    if (!r.spring->pass && r.spring->failures.empty()) fail("spring check: fails");
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

    if (r.run->liftoff()) {
      fail("dynamics: the needle lifts off the cam at the rated speed " + Fixed(rpm, 0) + " rpm");
    }
    // A run that did not end with the needle at rest is no proof of anything.
    if (r.run->status != RunStatus::kComplete) {
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
