#include "apps/study/spring_sizing_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <regex>
#include <sstream>

#include "apps/study/size_candidates.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/basu_formula.h"
#include "spring/quasi_static.h"
#include "spring/resonance.h"

namespace needle {
namespace {

using sizing_internal::Mm;
using sizing_internal::Seconds;

// The default range of the case's own wire: a third to twice its diameter (R40 sizes inside).
constexpr double kCaseWireLo = 1.0 / 3.0, kCaseWireHi = 2.0;

}  // namespace

BoundCase CaseWithSpring(const BoundCase& c, const SizedSpring& s, const SizingSpace& space,
                         double mass_without_spring_kg) {
  BoundCase out = c;
  out.scene.reset();  // the check builds it on the sized spring
  SpringParameters& p = *out.spring;
  p.preload_N = s.preload_N;
  p.rate_N_m.reset();
  p.helical = s.geometry;
  (void)space;
  out.needle->mass_kg = mass_without_spring_kg + s.active_mass_kg / 3.0;
  return out;
}

namespace {

// The valve-spring grades a rate-only spring is sized in by default (EN 10270-2).
const char* const kValveGrades[] = {"VDC", "VDCrV", "VDSiCr"};

// The default bounds of a spring the case gives by its rate alone, from the needle's diameter
// d_n: the coil passes over the needle (ID ≥ d_n), OD ≤ 4 d_n, installed length ≤ 10 d_n
// (Basu's examples: ID 2.4–2.6 d_n, OD 3.4–3.7 d_n, L₁ 2.5–6.8 d_n).
constexpr double kNeedleInner = 1.0, kNeedleOuter = 4.0, kNeedleInstalled = 10.0;

// The wires of the space: [sizing]'s grades or stated wire, else the case's wire or grade
// family, else (a rate-only spring) the valve grades.
void AddWires(const BoundCase& c, const SizingSection& z, SizingSpace& sp,
              std::vector<std::string>& notes, const std::string& fail_where) {
  const std::optional<HelicalGeometry>& own = c.spring->helical;
  std::vector<std::string> grades = z.grades;
  if (grades.empty()) {
    if (z.tensile_Pa) {
      grades = {"stated"};
    } else if (own && own->grade) {
      const std::string family = GradeData(*own->grade).standard;
      for (WireGrade g : AllWireGrades())
        if (GradeData(g).standard == family) grades.push_back(WireGradeName(g));
      notes.push_back("grades " + family + " (the case's " + WireGradeName(*own->grade) + ")");
    } else if (own) {
      grades = {"case"};
    } else {
      grades.assign(std::begin(kValveGrades), std::end(kValveGrades));
      notes.push_back(
          "grades VDC, VDCrV, VDSiCr (default: EN 10270-2 valve spring wire; the "
          "case's spring has no geometry)");
    }
  }
  for (const std::string& name : grades) {
    const std::optional<WireGrade> grade = ParseWireGrade(name);
    const bool stated = name == "stated" || (name == "case" && z.tensile_Pa);
    if (!grade && !stated && !own)
      throw CaseError(fail_where +
                      "grades: \"case\" needs the case's helical spring (its wire) or [sizing] "
                      "tensile_MPa and shear_modulus_GPa");
    const double d_ref = own ? own->wire_m : 0.0;
    double lo = z.min_wire_m.value_or(grade ? GradeData(*grade).min_wire_m : kCaseWireLo * d_ref);
    double hi = z.max_wire_m.value_or(grade ? GradeData(*grade).max_wire_m : kCaseWireHi * d_ref);
    if (grade) {
      lo = std::max(lo, GradeData(*grade).min_wire_m);
      hi = std::min(hi, GradeData(*grade).max_wire_m);
    }
    if (stated && z.wire_m.empty() && !(z.min_wire_m && z.max_wire_m))
      throw CaseError(fail_where +
                      "wire_mm: a stated wire needs the diameters to try (wire_mm, "
                      "or min_wire_mm and max_wire_mm)");
    for (double d : z.wire_m.empty() ? PreferredWireDiameters(lo, hi) : z.wire_m) {
      if (stated) {
        if (d < z.min_wire_m.value_or(0.0) * (1 - 1e-12) ||
            d > z.max_wire_m.value_or(INFINITY) * (1 + 1e-12))
          continue;
      } else if (!z.wire_m.empty() && (d < lo * (1 - 1e-12) || d > hi * (1 + 1e-12))) {
        continue;
      }
      SizingWire w;
      w.wire_m = d;
      w.density_kg_m3 = own ? own->density_kg_m3 : 7850.0;
      if (grade) {
        w.label = name;
        w.grade = grade;
        w.tensile_Pa = TensileStrengthPa(*grade, d);
        w.shear_modulus_Pa = GradeData(*grade).shear_modulus_Pa;
      } else {
        w.label = stated ? "stated wire" : "case wire";
        w.tensile_Pa = stated ? *z.tensile_Pa : own->tensile_Pa;
        w.shear_modulus_Pa = stated ? *z.shear_modulus_Pa : own->shear_modulus_Pa;
      }
      sp.wires.push_back(w);
    }
    if (!grade) {
      const double rm = stated ? *z.tensile_Pa : own->tensile_Pa;
      const double shear = stated ? *z.shear_modulus_Pa : own->shear_modulus_Pa;
      notes.push_back(std::string(stated ? "the stated wire" : "the case's wire") + " (R_m " +
                      Fixed(rm * 1e-6, 0) + " MPa, G " + Fixed(shear * 1e-9, 1) +
                      " GPa) at every diameter");
    }
  }
  if (sp.wires.empty())
    throw CaseError(fail_where + (z.wire_m.empty() ? "grades" : "wire_mm") +
                    ": no wire diameter lies in the grades' tabulated ranges");
  notes.push_back(std::to_string(sp.wires.size()) + " wires (" +
                  (z.wire_m.empty() ? "ISO 3 R40 preferred sizes" : "[sizing] wire_mm") + ")");
}

// The diameters and lengths the spring must fit: [sizing]'s, else the case's spring's, else
// (a rate-only spring) the needle's defaults; and the rules' settings.
void SetBounds(const BoundCase& c, const SizingSection& z, SizeResult& r,
               std::vector<std::string>& notes, const std::string& fail_where) {
  SizingSpace& sp = r.space;
  const std::optional<HelicalGeometry>& own = c.spring->helical;
  sp.min_index = z.min_index.value_or(4.0);
  sp.max_index = z.max_index.value_or(20.0);
  sp.coil_step_m = z.coil_step_m;
  notes.push_back("D/d " + Fixed(sp.min_index, 1) + "..." + Fixed(sp.max_index, 1) + ", D by " +
                  Mm(sp.coil_step_m, 1));
  std::optional<double> outer, inner, installed;
  std::string from = "the case's spring";
  if (own) {
    outer = own->coil_m + own->wire_m;
    inner = own->coil_m - own->wire_m;
    const HelicalSpringCheck check = CheckHelicalSpring(*own, c.spring->preload_N, r.stroke_m,
                                                        c.engine.speed_rpm, c.engine.cycle);
    installed = check.length_preload_m;
    r.case_spring_mass_kg = own->density_kg_m3 * kPi * kPi * own->wire_m * own->wire_m *
                            own->coil_m * check.total_coils / 4.0;
  } else if (c.needle->diameter_m && !z.max_outer_m && !z.min_inner_m && !z.max_installed_m) {
    const double dn = *c.needle->diameter_m;
    outer = kNeedleOuter * dn;
    inner = kNeedleInner * dn;
    installed = kNeedleInstalled * dn;
    from = "default from the needle's " + Fixed(dn * 1e3, 1) + " mm diameter";
  }
  const auto bound = [&](const std::optional<double>& stated, std::optional<double> from_case,
                         const std::string& what) -> std::optional<double> {
    if (stated) {
      notes.push_back(what + Mm(*stated) + " ([sizing])");
      return stated;
    }
    if (from_case) notes.push_back(what + Mm(*from_case) + " (" + from + ")");
    return from_case;
  };
  sp.max_outer_m = bound(z.max_outer_m, outer, "OD <= ");
  sp.min_inner_m = bound(z.min_inner_m, inner, "ID >= ");
  if (z.min_installed_m) {
    sp.min_installed_m = *z.min_installed_m;
    notes.push_back("installed length >= " + Mm(sp.min_installed_m) + " ([sizing])");
  }
  if (auto v = bound(z.max_installed_m, installed, "installed length <= ")) sp.max_installed_m = *v;
  if (!sp.max_outer_m || (!z.max_installed_m && !installed))
    throw CaseError(fail_where +
                    (sp.max_outer_m ? "max_installed_length_mm" : "max_outer_diameter_mm") +
                    ": the space needs a bound (the case's spring has no helical geometry and "
                    "[needle] no diameter_mm to derive one from)");
  sp.min_active_coils = z.min_active_coils.value_or(2.0);
  sp.max_active_coils = z.max_active_coils.value_or(30.0);
  sp.active_coil_step = z.active_coil_step;
  notes.push_back(Fixed(sp.min_active_coils, 1) + "..." + Fixed(sp.max_active_coils, 1) +
                  " active coils by " + Fixed(sp.active_coil_step, 2));
  sp.free_length_step_m = z.free_length_step_m;
  sp.ends = z.ends ? ParseSpringEnds(*z.ends).value_or(SpringEnds::kClosedGround)
                   : (own ? own->ends : SpringEnds::kClosedGround);
  sp.stress_factor = z.stress_factor.value_or(own ? own->stress_factor : sp.stress_factor);
  sp.fatigue_criterion =
      z.fatigue_criterion.value_or(own ? own->fatigue_criterion : sp.fatigue_criterion);
  sp.shot_peened = own && own->shot_peened;
  if (sp.shot_peened && sp.fatigue_criterion == FatigueCriterion::kBhandari)
    throw CaseError(fail_where +
                    "fatigue_criterion: \"bhandari\" takes unpeened wire's endurance (S'se = "
                    "0.22 S_ut) and the case's spring is shot-peened; use a Zimmerli criterion");
  sp.allowable_fraction = z.allowable_fraction.value_or(own ? own->allowable_fraction : 0.5);
  sp.end_fixation = z.end_fixation;
  notes.push_back(std::string(SpringEndsName(sp.ends)) + " ends");
  if (z.stress_factor || z.fatigue_criterion || z.allowable_fraction) {
    notes.push_back(std::string("stress_correction ") + StressFactorName(sp.stress_factor) +
                    ", tau <= " + Fixed(sp.allowable_fraction, 2) + " R_m, fatigue_criterion " +
                    CriterionInfo(sp.fatigue_criterion).name);
  }
}

// The duty of the sizing (spring/spring_sizing.h): the stroke, the rated speed, the limits, and
// the least preload of a spring of rate k and active coil mass m_s (S·F_g, Basu's formula less
// its tolerance, the inertia sizing with m₀ + m_s/3; or a stated P₁ judged against those).
SizingDuty MakeDuty(const BoundCase& c, const SizingSection& z, const LiftLaw& law,
                    const KinematicsSummary& sum, const SizeResult& r) {
  const double rpm = c.engine.speed_rpm;
  const EngineCycle cycle = c.engine.cycle;
  SizingDuty duty;
  duty.stroke_m = r.stroke_m;
  duty.speed_rpm = rpm;
  duty.cycle = cycle;
  duty.min_fatigue_factor = c.limits.fatigue_safety_factor;
  duty.min_gap_m = c.limits.coil_gap_m;
  if (z.open_load_N) duty.rate_N_m = (*z.open_load_N - *z.closed_load_N) / r.stroke_m;
  if (z.rate_N_m) duty.rate_N_m = z.rate_N_m;
  const SpringParameters& spring = *c.spring;
  const double gas = c.needle->gas_force_N, m0 = r.mass_without_spring_kg;
  const std::optional<double> basu =
      c.needle->diameter_m
          ? std::optional<double>(BasuPreloadN(*c.needle->diameter_m, sum.injection_period_s))
          : std::nullopt;
  duty.preload_floor_N =
      std::max(spring.safety_factor * gas,
               basu ? *basu * (1.0 - spring.basu_tolerance_percent / 100.0) : 0.0);
  const double omega = OmegaFromRpm(rpm);
  duty.preload = [&law, &spring, gas, m0, basu, omega](double rate, double spring_mass) {
    PreloadNeed need;
    const auto take = [&need](double preload_N, const char* rule) {
      need.preload_N = preload_N;
      need.rule = rule;
    };
    take(spring.safety_factor * gas, "combustion load S F_g");
    if (basu) {
      const double b = *basu * (1.0 - spring.basu_tolerance_percent / 100.0);
      if (b > need.preload_N) take(b, "Basu's formula less its tolerance");
    }
    RigidTrain t;
    t.mass_kg = m0 + spring_mass / 3.0;
    t.rate_N_m = rate;
    t.gas_force_N = gas;
    const double inertia =
        RequiredPreloadN(law, t, omega, spring.safety_factor, spring.overspeed_factor);
    if (inertia > need.preload_N) take(inertia, "inertia sizing");
    return need;
  };
  if (z.closed_load_N) {  // a textbook problem: P₁ is stated, and judged against the duty's
    const double p1 = *z.closed_load_N;
    duty.preload_floor_N = p1;
    duty.closed_load_N = p1;
    duty.open_load_N = z.open_load_N;
    duty.preload = [p1, need = duty.preload](double rate, double spring_mass) {
      const PreloadNeed duty_need = need(rate, spring_mass);
      return PreloadNeed{p1, "stated closed load P1", duty_need.preload_N, duty_need.rule};
    };
  }
  return duty;
}

}  // namespace

SizeResult SizeCase(const BoundCase& c, const LiftLaw& law, const SizeOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!c.needle || !c.spring)
    throw CaseError(c.path +
                    ": [spring]: needle size needs [needle] and [spring] (the moving mass, "
                    "the safety and overspeed factors)");
  RequireAcceleration(law);
  const SizingSection z = c.sizing.value_or(SizingSection{});
  const std::optional<HelicalGeometry>& own = c.spring->helical;
  const std::string fail_where = c.path + ": [sizing] ";
  SizeResult r;
  r.objective = z.objective;
  const double rpm = c.engine.speed_rpm;
  const KinematicsSummary sum = Kinematics(law, rpm).Summarize();
  r.stroke_m = z.stroke_m.value_or(sum.max_lift_m);
  // 1 % below the lift passes: a table's stated peak may sit a spline's overshoot under it.
  if (z.stroke_m && *z.stroke_m < 0.99 * sum.max_lift_m)
    throw CaseError(fail_where + "stroke_mm: " + Fixed(*z.stroke_m * 1e3, 3) +
                    " mm is below the lift's largest, " + Fixed(sum.max_lift_m * 1e3, 3) +
                    " mm, which `needle check` of the sized case judges; give at least that");
  if (z.stroke_m) {
    r.stroke_note = "[sizing] stroke_mm; the case's lift peaks at " + Mm(sum.max_lift_m, 3) +
                    ", which `needle check` of the sized case judges";
  }

  // The space.
  SizingSpace& sp = r.space;
  std::vector<std::string> notes;
  AddWires(c, z, sp, notes, fail_where);
  SetBounds(c, z, r, notes, fail_where);
  for (size_t i = 0; i < notes.size(); ++i) r.space_note += (i ? "; " : "") + notes[i];

  // The duty: the moving mass without the spring, the preload rules.
  if (z.mass_without_spring_kg) {
    r.mass_without_spring_kg = *z.mass_without_spring_kg;
    r.mass_note = "[sizing] mass_without_spring_kg";
  } else if (own) {
    r.mass_without_spring_kg = c.needle->mass_kg - ActiveSpringMassKg(*own) / 3.0;
    r.mass_note = "[needle] mass_kg less a third of the case's active coils";
  } else {
    r.mass_without_spring_kg = c.needle->mass_kg;
    r.mass_note = "[needle] mass_kg (the case's spring has no geometry to take out)";
  }
  const SizingDuty duty = MakeDuty(c, z, law, sum, r);

  // Stage 1: the closed form.
  SizingOptions so;
  so.objective = z.objective == "height"     ? SizingObjective::kHeight
                 : z.objective == "stress"   ? SizingObjective::kStress
                 : z.objective == "diameter" ? SizingObjective::kDiameter
                                             : SizingObjective::kMass;
  so.keep = z.candidates;
  so.front = true;
  r.closed_form = SizeSpring(sp, duty, so);
  if (r.closed_form.groups == 0 && r.closed_form.rate_misses > 0)
    throw CaseError(fail_where + (z.open_load_N ? "open_load_N" : "rate_N_mm") +
                    ": no (wire, D) of the space reaches the rate " +
                    Fixed(*duty.rate_N_m * 1e-3, 2) + " N/mm with " +
                    Fixed(sp.min_active_coils, 1) + "..." + Fixed(sp.max_active_coils, 1) +
                    " active coils (" + std::to_string(r.closed_form.rate_misses) +
                    " pairs tried); widen min_/max_active_coils or the wires");
  if (r.closed_form.groups == 0)
    throw CaseError(fail_where +
                    "max_outer_diameter_mm: no coil diameter of any wire fits the "
                    "space (" +
                    r.space_note + ")");
  SizeStage closed{"closed form", r.closed_form.candidates,
                   static_cast<long>(r.closed_form.best.size()), Seconds(t0), ""};
  closed.note = std::to_string(r.closed_form.groups) + " (wire, D) groups; " +
                std::to_string(r.closed_form.evaluated) + " springs evaluated, " +
                std::to_string(r.closed_form.passed) + " passed; the best of " +
                std::to_string(r.closed_form.best.size()) + " groups kept; the front scanned " +
                std::to_string(r.closed_form.front_evaluated) + " springs";
  r.stages.push_back(closed);
  if (r.closed_form.best.empty()) {
    std::ostringstream m;
    if (r.closed_form.binding && r.closed_form.closest) {
      const SizingRule& b = *r.closed_form.binding;
      const SizedSpring& s = *r.closed_form.closest;
      const std::string u = b.unit.empty() ? "" : " " + b.unit;
      m << "no spring in the space (" << r.space_note << ") reaches the " << b.name << " of "
        << (b.at_most ? "at most " : "at least ") << Fixed(b.limit, 2) << u << "; best "
        << Fixed(b.value, 2) << u << " (short by " << Fixed(-b.margin, 2) << u << ") at "
        << sp.wires[s.wire_index].label << " d = " << Mm(s.geometry.wire_m)
        << ", D = " << Mm(s.geometry.coil_m, 1) << ", " << Fixed(s.geometry.active_coils, 1)
        << " active coils";
    } else {
      m << "no spring in the space (" << r.space_note << ")";
    }
    r.no_fit = m.str();
  }

  // Stage 2: the candidates, checked end to end, until one passes.
  VerifyCandidates(c, law, z, duty, options, r);
  return r;
}

std::vector<Field> SizeStageFields(const SizeStage& s) {
  return {TextField("name", s.name),
          CountField("in", s.in),
          CountField("kept", s.kept),
          {"seconds", display::kNone, s.seconds, 3},
          TextField("note", s.note)};
}

}  // namespace needle
