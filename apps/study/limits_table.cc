// The limits table (limits_table.h): a function per row or group of rows; JudgeLimits is the
// table of them.
#include "apps/study/limits_table.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "apps/case/case_profile.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/quasi_static.h"
#include "spring/resonance.h"

namespace needle {

namespace {

// What every row reads: the case, its law, the check's results so far, the limits and their
// defaults (to name where a limit came from).
struct Judging {
  const BoundCase& c;
  const LiftLaw& law;
  double cam_zero_crank_rad;
  CheckResult& r;
  bool report_notes;
  const LimitsSection& l;
  LimitsSection d;
  double crank_turns;  // per cam turn
};

LimitRow row(std::string key, std::string name, std::string unit, bool at_most, double limit,
             std::string source) {
  return VerdictRow::Unjudged(std::move(key), std::move(name), std::move(unit), at_most, limit,
                              std::move(source));
}

void judge(LimitRow& x, double value, std::string note) { x.Judge(value, std::move(note)); }

// A contact force of zero is a loss of contact, whatever the limit (a limit of 0 %, or an
// overspeed factor of 1, would otherwise pass it).
void judge_force(LimitRow& x, double value, std::string note) {
  judge(x, value, std::move(note));
  if (!(value > 0.0) && x.verdict != "fail") {
    x.verdict = "fail";
    x.note += "; a contact force of 0 fails whatever the limit";
  }
}

std::string from(bool set, const std::string& key, const std::string& cited) {
  return set ? "[limits] " + key : cited;
}

// A chain run decided: complete, or stopped past the lift or at its first lift-off when only the
// verdict was asked (CheckOptions::verdict_only).
bool Decided(const SimulationResult& run) {
  return run.status == RunStatus::kComplete || run.status == RunStatus::kStopped;
}

// The rows of the rated run: the seating velocity, the secondary opening, the cam's strikes on
// the roller and the least contact force while the cam lifts the needle.
struct RunRows {
  LimitRow seat, reopen, lash, force;
};

RunRows UnjudgedRunRows(const Judging& j) {
  LimitRow seat = row("seating_velocity", "seating velocity", "m/s", true, j.l.seating_velocity_m_s,
                      from(j.l.seating_velocity_m_s != j.d.seating_velocity_m_s, "seating_velocity",
                           "Blair: optimum ramp velocity 1.0-1.5 m/s"));
  LimitRow lash =
      row("lash_impact_speed", "cam impact speed (lash and recontacts)", "m/s", true,
          j.l.lash_impact_velocity_m_s,
          from(j.l.lash_impact_velocity_m_s != j.d.lash_impact_velocity_m_s, "lash_impact_velocity",
               "Blair: optimum ramp velocity 1.0-1.5 m/s (the opening ramp)"));
  LimitRow reopen = row("secondary_opening", "secondary opening after closing", "um", true,
                        1e6 * j.l.secondary_opening_fraction * j.r.kinematics.max_lift_m,
                        from(j.l.secondary_opening_fraction != j.d.secondary_opening_fraction,
                             "secondary_opening_percent",
                             "1 % of the largest lift: a reopening is a secondary injection"));
  // Least contact force while the cam lifts the needle, against the static load holding it
  // there: at f·n the inertia grows by f², so a share 1 − 1/f² of that load must remain.
  const double f_over = j.c.spring ? j.c.spring->overspeed_factor : 1.2;
  const double force_limit = j.l.min_contact_force_fraction.value_or(1.0 - 1.0 / (f_over * f_over));
  LimitRow force = row("min_contact_force",
                       "least contact force while the cam lifts the needle, % of P0 + k y - F_g",
                       "%", false, 100 * force_limit,
                       j.l.min_contact_force_fraction
                           ? "[limits] min_contact_force_percent"
                           : "overspeed factor f = " + Fixed(f_over, 2) +
                                 ": 1 - 1/f^2 of the holding load left for f n's inertia");
  return {seat, reopen, lash, force};
}

RunRows JudgeRunRows(const Judging& j) {
  RunRows x = UnjudgedRunRows(j);
  LimitRow &seat = x.seat, &reopen = x.reopen, &lash = x.lash, &force = x.force;
  if (j.r.run && j.c.spring) {
    const SimulationResult& run = *j.r.run;
    double landing = 0.0;
    std::string where = "no landing on the seat in the run";
    for (const Impact& i : run.impacts) {
      if (i.kind.rfind("seat", 0) == 0 && i.kind != "seat-sticking" && i.speed_m_s >= landing) {
        landing = i.speed_m_s;
        where = i.kind + " at " + Fixed(i.crank_rad / kDeg, 2) + " deg";
      }
    }
    judge(seat, landing, where);
    const auto seated = std::find_if(run.impacts.begin(), run.impacts.end(), [&](const Impact& i) {
      return i.kind.rfind("seat", 0) == 0 && i.crank_rad > j.r.kinematics.max_lift_rad;
    });
    if (run.secondary_lift_m > 0.0) {
      judge(reopen, 1e6 * run.secondary_lift_m,
            Fixed(1e3 * run.secondary_lift_m, 4) + " mm at " +
                Fixed(run.secondary_lift_rad / kDeg, 2) + " deg, open " +
                Fixed(run.secondary_open_rad / kDeg, 2) + " deg");
    } else {
      judge(reopen, 0.0,
            seated == run.impacts.end()
                ? "the needle did not seat in the run"
                : "no reopening after it seated at " + Fixed(seated->crank_rad / kDeg, 2) + " deg");
    }
    if (j.c.train && j.c.train->play_m > 0.0) {
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
    seat.note = reopen.note = lash.note = force.note = "no dynamics ([train] missing)";
  }
  return x;
}

// n_dyn against f·n (1 + the separation margin).
LimitRow SeparationRow(const Judging& j) {
  LimitRow sep = row("separation_margin", "separation margin n_dyn/(f n) - 1", "%", false,
                     100 * j.l.separation_margin_fraction,
                     from(j.l.separation_margin_fraction != j.d.separation_margin_fraction,
                          "separation_margin_percent", "model: n_dyn > f n"));
  if (j.r.sweep && j.r.sweep->status != "run-budget" && j.r.sweep->status != "budget" &&
      j.r.sweep->status != "floor" && j.r.sweep->status != "not-following") {
    if (j.r.sweep->n_dyn_rpm) {
      judge(sep, 100 * (*j.r.sweep->n_dyn_rpm / j.r.overspeed_rpm - 1),
            "n_dyn " + Fixed(*j.r.sweep->n_dyn_rpm, 1) + " rpm, f n " +
                Fixed(j.r.overspeed_rpm, 1) + " rpm");
    } else {
      judge(sep, 100 * (j.r.sweep->scanned_to_rpm / j.r.overspeed_rpm - 1),
            "no lift-off up to " + Fixed(j.r.sweep->scanned_to_rpm, 1) + " rpm (a lower bound)");
    }
  } else {
    sep.note = j.r.sweep ? "the sweep is undecided (" + j.r.sweep->status + ")"
                         : "no overspeed sweep ([train] missing)";
  }
  return sep;
}

// The largest Hertz stress cam–roller under the quasi-static force.
LimitRow HertzRow(const Judging& j) {
  LimitRow hertz =
      row("hertz_stress", "Hertz stress cam-roller", "MPa", true, j.l.hertz_stress_Pa * 1e-6,
          from(j.l.hertz_stress_Pa != j.d.hertz_stress_Pa, "hertz_stress_MPa",
               "ISO 6336-5 case-hardened MQ, 1500 MPa"));
  if (j.r.profile && j.r.spring && j.l.contact_length_m && j.r.profile->undercut) {
    // Hertz's formula needs a convex cam: an undercut profile's radius passes through zero (the
    // check fails on the undercut itself).
    hertz.note = "the cam profile is undercut (no convex radius to press on)";
  } else if (j.r.profile && j.r.spring && j.l.contact_length_m) {
    const FollowerGeometry& g = j.c.profile->follower;
    const RigidTrain& t = j.r.spring->train;
    const double omega = OmegaFromRpm(j.r.speed_rpm), k = j.crank_turns;
    const double play = j.c.train ? j.c.train->play_m : 0.0;
    double worst = 0.0, at = 0.0;
    for (const ProfilePoint& q : j.r.profile->points) {
      const double th = j.cam_zero_crank_rad + k * q.cam_rad;
      const bool open = th >= j.law.start_rad() && th <= j.law.end_rad();
      const double f_needle = open ? QuasiStaticForce(j.law, t, omega, th)
                                   : (play > 0 ? 0.0 : t.preload_N - t.gas_force_N);  // base circle
      const double stress =
          ContactStress(g, q, std::max(0.0, f_needle) / g.lever_ratio, j.l.elastic_modulus_Pa,
                        j.l.poisson, *j.l.contact_length_m);
      if (stress > worst) {
        worst = stress;
        at = q.cam_rad;
      }
    }
    judge(hertz, worst * 1e-6,
          "quasi-static force at " + Fixed(j.r.speed_rpm, 0) + " rpm, worst at " +
              CamAndCrank(j.c, j.cam_zero_crank_rad, at, 1, " deg"));
  } else {
    hertz.note = !j.r.profile  ? "no [profile] (the cam's radius)"
                 : !j.r.spring ? "no spring check (the contact force)"
                               : "no [limits] contact_length_mm (the roller's width)";
  }
  return hertz;
}

// The spring's rows: fatigue, the coil gap, surge judged by its effect (the least contact force,
// lift-off at f·n and the stress with the coils' inertia) and the surge frequency screen.
struct SpringRows {
  LimitRow fatigue, gap, surge_force, surge_jump, surge_stress, ratio;
};

SpringRows UnjudgedSpringRows(const Judging& j, const LimitRow& force) {
  SpringRows x;
  const FatigueCriterion criterion = j.c.spring && j.c.spring->helical
                                         ? j.c.spring->helical->fatigue_criterion
                                         : FatigueCriterion::kGoodmanZimmerli;
  x.fatigue =
      row("fatigue_safety_factor",
          std::string("spring fatigue safety factor (") + CriterionInfo(criterion).title + ")", "",
          false, j.l.fatigue_safety_factor,
          from(j.l.fatigue_safety_factor != j.d.fatigue_safety_factor, "fatigue_safety_factor",
               "Shigley 10-12: design factor 1.5"));
  x.gap = row("coil_gap", "coil gap at full lift", "mm", false, NAN,
              j.l.coil_gap_m ? "[limits] coil_gap_mm" : "EN 13906-1: S_a");
  // Surge by its effect, with the spring as coil masses (SurgeStudy).
  x.surge_force =
      row("surge_contact_force", "least contact force with the coils' surge, % of P0 + k y - F_g",
          "%", false, force.limit, force.source);
  x.surge_jump = row("surge_overspeed_jump", "longest jump at f n with the coils' surge", "deg",
                     true, kMinJump_rad / kDeg,
                     "model: lift-off is a jump of 0.1 deg or more (§6), none at f n (§8)");
  x.surge_stress = row("surge_spring_stress", "spring shear stress at the surge's peak force",
                       "MPa", true, NAN, "the helical check's allowable stress");
  x.ratio = row("surge_frequency_ratio", "first surge mode over the cam frequency f_1/f_cam", "",
                false, kMinSurgeRatio,
                "spring makers' screen f_1 >= 13 f (Rockford Spring, 'Dynamic loading of "
                "springs'; Shigley 10-9 asks 15-20); a warning where the coils' dynamics "
                "show no harm");
  return x;
}

void JudgeFatigueAndGap(const Judging& j, const HelicalSpringCheck& h, SpringRows& x) {
  const HelicalGeometry& wire = *j.c.spring->helical;
  if (h.fatigue_judged) {
    const FatigueCheck& f = h.fatigue;
    const std::string basis =
        f.criterion == FatigueCriterion::kBhandari
            ? "tau_m " + Fixed(f.stress_mean_Pa * 1e-6, 0) + " MPa (K_s), tau_a " +
                  Fixed(f.stress_amplitude_Pa * 1e-6, 0) + " MPa (Wahl), S'se " +
                  Fixed(f.endurance_Pa * 1e-6, 0) + " MPa, S_sy " + Fixed(f.yield_Pa * 1e-6, 0) +
                  " MPa"
            : std::string(wire.shot_peened ? "shot-peened" : "unpeened") + " (Zimmerli)";
    judge(x.fatigue, f.safety_factor,
          "tau " + Fixed(h.stress_preload_Pa * 1e-6, 0) + "-" +
              Fixed(h.stress_full_lift_Pa * 1e-6, 0) + " MPa, " + basis);
  } else {
    x.fatigue.note =
        "wire " + Fixed(wire.wire_m * 1e3, 1) + " mm: Zimmerli's data cover wire below 10 mm";
  }
  x.gap.limit = (j.l.coil_gap_m ? *j.l.coil_gap_m : h.min_clearance_m) * 1e3;
  const CheckResult& r = j.r;
  const SimulationResult* chain = r.surge && Decided(r.surge->rated)
                                      ? &r.surge->rated
                                      : (r.run && r.run->min_coil_gap_m ? &*r.run : nullptr);
  if (chain && chain->min_coil_gap_m) {
    // A chain of coil masses: the least gap in the run at the rated speed, where surge may
    // close one segment well before the static full lift closes them all.
    const int n = r.surge ? r.surge->masses : j.c.spring->masses;
    x.gap.name = "coil gap in the run (worst segment x N)";
    judge(x.gap, *chain->min_coil_gap_m * 1e3,
          "at " + Fixed(r.speed_rpm, 0) + " rpm with " + std::to_string(n) + " coil masses, " +
              std::to_string(chain->coil_clashes) + " clashes; " +
              Fixed(h.clearance_full_lift_m * 1e3, 2) + " mm at full lift statically");
  } else {
    judge(x.gap, h.clearance_full_lift_m * 1e3, "");
  }
}

void JudgeSurge(const Judging& j, const HelicalSpringCheck& h, SpringRows& x) {
  CheckResult& r = j.r;
  const auto undecided = [](const SimulationResult& run) { return !Decided(run); };
  if (r.surge && (undecided(r.surge->rated) || undecided(r.surge->overspeed))) {
    const SimulationResult& bad = undecided(r.surge->rated) ? r.surge->rated : r.surge->overspeed;
    const std::string why = "undecided: the run with " + std::to_string(r.surge->masses) +
                            " coil masses at " + Fixed(bad.speed_rpm, 1) + " rpm is " +
                            RunStatusName(bad.status) + ": " + bad.status_reason;
    x.surge_force.note = x.surge_jump.note = x.surge_stress.note = why;
    r.failing.push_back("surge: " + why);
  } else if (r.surge) {
    const SurgeStudy& s = *r.surge;
    const std::string with = std::to_string(s.masses) + " coil masses, zeta " +
                             Fixed(100 * s.damping_ratio, 1) + " %" +
                             (s.damping_assumed ? " (assumed)" : "") + ", converged to " +
                             Fixed(100 * s.change, 2) + " %" + (s.converged ? "" : " (NOT)");
    judge_force(x.surge_force,
                std::isfinite(s.rated.min_contact_force_ratio)
                    ? 100 * s.rated.min_contact_force_ratio
                    : 0.0,
                "with " + with + "; massless spring " +
                    Fixed(100 * s.massless.min_contact_force_ratio, 2) + " %");
    judge(x.surge_jump, s.overspeed.longest_jump_rad / kDeg,
          "at " + Fixed(r.overspeed_rpm, 1) + " rpm with " + with +
              (j.report_notes ? "; massless spring " +
                                    Fixed(s.massless_overspeed.longest_jump_rad / kDeg, 2) + " deg"
                              : std::string()));
    // τ grows with the force (τ = k 8 F D / π d³): the full-lift stress scaled by the peak.
    const double f_full = r.spring->train.preload_N + r.spring->train.rate_N_m * j.law.Max(0).value;
    x.surge_stress.limit = h.allowable_stress_Pa * 1e-6;
    judge(x.surge_stress, h.stress_full_lift_Pa * 1e-6 * s.rated.max_spring_force_N / f_full,
          "peak spring force " + Fixed(s.rated.max_spring_force_N, 0) + " N with the coils, " +
              Fixed(s.massless.max_spring_force_N, 0) + " N massless (" +
              Fixed(100 * (s.rated.max_spring_force_N / s.massless.max_spring_force_N - 1), 1) +
              " %)");
  } else {
    x.surge_force.note = x.surge_jump.note = x.surge_stress.note =
        r.run ? "the coils' dynamics could not be run: " + r.surge_reason
              : "no dynamics ([train] missing)";
  }
}

// The surge screen f_1/f_cam: a warning where the coils' dynamics show no harm.
void JudgeSurgeRatio(const Judging& j, const HelicalSpringCheck& h, SpringRows& x) {
  CheckResult& r = j.r;
  judge(x.ratio, h.surge_ratio,
        "f_1 " + Fixed(h.surge_hz, 1) + " Hz, cam " + Fixed(h.cam_hz, 2) + " Hz");
  if (x.ratio.verdict != "fail" || !r.surge) return;
  if (!SurgeShowsHarm(x.surge_force, x.surge_jump, x.surge_stress, x.gap)) {
    x.ratio.verdict = "warning";
    x.ratio.note += "; the coils' dynamics show no harm";
    // The spring check's own screen (the same f_1/f_cam >= 13) warns with it: its failures
    // are those of its other sub-checks (CheckScene lists them after the limits).
    r.spring->failures = SpringFailures(*r.spring, /*surge_screen=*/false);
    r.spring->pass = r.spring->failures.empty();
  } else {  // name the rows that fail (the coil gap alone was once called "the surge rows")
    std::vector<std::string> rows;
    for (const LimitRow* row : {&x.surge_force, &x.surge_jump, &x.surge_stress, &x.gap})
      if (row->verdict == "fail") rows.push_back(row->name);
    x.ratio.note += "; the coils' dynamics show harm (" + ListText(rows) + ")";
  }
}

SpringRows JudgeSpringRows(const Judging& j, const LimitRow& force) {
  SpringRows x = UnjudgedSpringRows(j, force);
  CheckResult& r = j.r;
  if (!(r.spring && r.spring->helical)) {
    const std::string no_helical = "no helical spring geometry ([spring] wire_mm …)";
    x.fatigue.note = x.gap.note = x.ratio.note = no_helical;
    x.surge_force.note = x.surge_jump.note = x.surge_stress.note = no_helical;
    return x;
  }
  const HelicalSpringCheck& h = *r.spring->helical;
  JudgeFatigueAndGap(j, h, x);
  // The modes m·f_e of the spring held at both ends (spring/resonance.h), f_e the check's: the
  // resonance map's lines (information).
  for (int m = 1; m <= 3; ++m) r.surge_modes_hz.push_back(m * h.surge_hz);
  if (j.report_notes)
    r.harmonics = LiftHarmonics(j.law, 2 * kPi * j.crank_turns, 1000, j.l.harmonic_threshold);
  JudgeSurge(j, h, x);
  JudgeSurgeRatio(j, h, x);
  return x;
}

// The rows not judged, in one line grouped by reason (r.not_judged, and a skipped line).
void SummarizeNotJudged(CheckResult& r) {
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
  r.not_judged.clear();
  for (size_t i = 0; i < by_reason.size(); ++i) {
    r.not_judged += (i ? "; " : "") + by_reason[i].second + " (" + by_reason[i].first + ")";
  }
  if (!r.not_judged.empty()) r.skipped.push_back("limits not judged: " + r.not_judged);
}

}  // namespace

// The limits table (docs/springs.md "The limits table"): one row per limit, judged where the scene
// has what it needs, else "not judged" with the reason.
void JudgeLimits(const BoundCase& c, const LiftLaw& law, double cam_zero_crank_rad, CheckResult& r,
                 bool report_notes) {
  const Judging j{c,
                  law,
                  cam_zero_crank_rad,
                  r,
                  report_notes,
                  c.limits,
                  LimitsSection{},
                  CrankTurnsPerCycle(c.engine.cycle)};
  const RunRows run = JudgeRunRows(j);
  const LimitRow sep = SeparationRow(j);
  const LimitRow hertz = HertzRow(j);
  const SpringRows spring = JudgeSpringRows(j, run.force);
  r.limits = {run.seat,
              run.reopen,
              run.lash,
              run.force,
              sep,
              hertz,
              spring.fatigue,
              spring.gap,
              spring.surge_force,
              spring.surge_jump,
              spring.surge_stress,
              spring.ratio};
  for (const LimitRow& x : r.limits) {
    if (x.verdict == "warning") r.warnings.push_back(FailureLine(x));
    if (x.verdict == "fail") r.failing.push_back(FailureLine(x));
  }
  SummarizeNotJudged(r);
}

}  // namespace needle
