// [needle], [spring] and [limits] (section_reader.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "apps/case/plausible_ranges.h"
#include "apps/case/section_reader.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle::case_internal {

NeedleSection ReadNeedle(SectionReader r) {
  NeedleSection n;
  n.mass_kg = r.Quantity("mass", Dimension::kMass);
  n.diameter_m = r.OptionalQuantity("diameter", Dimension::kLength);
  // The gas load (docs/model.md §4): stated, or a combustion pressure on the needle's area, by
  // default Basu's 35 kg/cm² ("the spring must be strong enough to withstand the combustion
  // pressure"); 0 without a diameter.
  const auto gas = r.OptionalQuantity("gas_force", Dimension::kForce);
  const std::string gas_key = gas ? r.last_key() : "";
  const auto pressure = r.OptionalQuantity("combustion_pressure", Dimension::kPressure);
  if (gas && pressure) {
    r.Fail(gas_key, "give gas_force or combustion_pressure, not both");
  }
  if (pressure && !(*pressure >= 0.0)) {
    r.Fail(r.last_key(), "must not be negative, got " + Number(*pressure) + " Pa");
  }
  if (pressure && !n.diameter_m) {
    r.Fail(r.last_key(), "needs diameter_mm (the load is the pressure on the needle's area)");
  }
  const double area = n.diameter_m ? kPi * *n.diameter_m * *n.diameter_m / 4.0 : 0.0;
  if (gas) {
    n.gas_force_N = *gas;
    n.gas_source = "stated";
  } else if (pressure) {
    n.gas_force_N = *pressure * area;
    n.gas_source = "combustion pressure " + Number(*pressure * 1e-5) + " bar on the needle";
  } else if (n.diameter_m) {
    n.gas_force_N = 35.0 * kKgf * 1e4 * area;  // 35 kg/cm² on π d²/4
    n.gas_source = "Basu's 35 kg/cm2 on the needle";
  } else {
    n.gas_force_N = 0.0;
    n.gas_source = "none (no needle diameter)";
  }
  r.Validated([&n] { n.Validate(); });  // the needle's one rule (spring/spring_parameters.h)
  r.Finish();
  return n;
}

HelicalGeometry ReadHelical(SectionReader& r) {
  HelicalGeometry g;
  g.wire_m = Positive(r, "wire", Dimension::kLength, 1e3, "wire_mm");
  g.coil_m = Positive(r, "coil", Dimension::kLength, 1e3, "coil_mm");
  const auto coils = r.OptionalNumber("active_coils");
  if (!coils) r.Fail("active_coils", "missing; the helical check needs the number of active coils");
  if (!(*coils >= 2.0))
    r.Fail("active_coils", "must be at least 2 (EN 13906-1), got " + Number(*coils));
  g.active_coils = *coils;
  g.free_length_m = Positive(r, "free_length", Dimension::kLength, 1e3, "free_length_mm");
  if (auto grade = r.OptionalString("grade")) {
    g.grade = ParseWireGrade(*grade);
    if (!g.grade)
      r.Fail("grade", "expected one of " + WireGradeList() + ", got \"" + *grade + "\"");
  }
  if (auto peened = r.OptionalBool("shot_peened")) g.shot_peened = *peened;
  if (g.grade && !r.FindQuantity("shear_modulus", Dimension::kPressure)) {
    g.shear_modulus_Pa = GradeData(*g.grade).shear_modulus_Pa;  // EN 13906-1's G of the grade
  } else {
    g.shear_modulus_Pa =
        Positive(r, "shear_modulus", Dimension::kPressure, 1e-9, "shear_modulus_GPa");
  }
  if (auto rho = r.OptionalQuantity("density", Dimension::kDensity)) {
    if (!(*rho > 0.0)) r.Fail("density_kg_m3", "must be positive, got " + Number(*rho));
    g.density_kg_m3 = *rho;
  }
  if (g.grade && !r.FindQuantity("tensile", Dimension::kPressure)) {
    try {
      g.tensile_Pa = TensileStrengthPa(*g.grade, g.wire_m);  // R_m(d) of the grade
    } catch (const std::invalid_argument& e) {
      r.Fail("grade", e.what());
    }
  } else {
    g.tensile_Pa = Positive(r, "tensile", Dimension::kPressure, 1e-6, "tensile_MPa");
  }
  const double index = g.coil_m / g.wire_m;
  if (index < 4.0 || index > 20.0) {
    r.Fail("coil_mm", "spring index D/d = " + Number(index) +
                          " is outside 4…20 (EN 13906-1); change the wire or the coil diameter");
  }
  if (auto ends = r.OptionalString("ends")) {
    const std::optional<SpringEnds> e = ParseSpringEnds(*ends);
    if (!e) r.Fail("ends", "expected " + SpringEndsList() + ", got \"" + *ends + "\"");
    g.ends = *e;
  }
  if (auto corr = r.OptionalString("stress_correction")) {
    const std::optional<StressFactor> f = ParseStressFactor(*corr);
    if (!f)
      r.Fail("stress_correction", "expected " + StressFactorChoice() + ", got \"" + *corr + "\"");
    g.stress_factor = *f;
  }
  if (auto name = r.OptionalString("fatigue_criterion")) {
    const std::optional<FatigueCriterion> c = ParseFatigueCriterion(*name);
    if (!c) {
      r.Fail("fatigue_criterion",
             "expected " + FatigueCriterionChoice() + ", got \"" + *name + "\"");
    }
    g.fatigue_criterion = *c;
    if (*c == FatigueCriterion::kBhandari && g.shot_peened) {
      r.Fail("fatigue_criterion",
             "\"bhandari\" takes unpeened wire's endurance (S'se = 0.22 S_ut); with "
             "shot_peened = true use a Zimmerli criterion (\"goodman-zimmerli\", \"gerber\", "
             "\"asme-elliptic\" or \"sines\")");
    }
  }
  if (auto f = r.OptionalNumber("allowable_stress_fraction")) {
    if (!(*f > 0.0 && *f <= 1.0)) {
      r.Fail("allowable_stress_fraction", "must be in (0, 1], got " + Number(*f));
    }
    g.allowable_fraction = *f;
  }
  return g;
}

SpringSection ReadSpring(SectionReader r) {
  SpringSection sp;
  sp.preload_N = r.Quantity("preload", Dimension::kForce);
  sp.rate_N_m = r.OptionalQuantity("rate", Dimension::kStiffness);
  for (auto [key, into] : {std::pair<const char*, double*>{"safety_factor", &sp.safety_factor},
                           {"overspeed_factor", &sp.overspeed_factor},
                           {"basu_tolerance_percent", &sp.basu_tolerance_percent}}) {
    if (auto v = r.OptionalNumber(key)) *into = *v;
  }
  if (r.FindQuantity("wire", Dimension::kLength)) {
    // One rate: a stated one beside the geometry's was taken by the quasi-static check while
    // the helical check printed the geometry's (issue 51).
    if (sp.rate_N_m) {
      r.Fail(r.FindQuantity("rate", Dimension::kStiffness)->first,
             "the helical geometry (wire, coil, active_coils) sets the rate; give the rate or "
             "the geometry, not both");
    }
    sp.helical = ReadHelical(r);
  }
  if (!sp.helical) {
    // The helical check's keys without its geometry: say what they need, not "unknown key".
    for (const char* key : {"fatigue_criterion", "stress_correction", "ends", "grade",
                            "shot_peened", "allowable_stress_fraction", "active_coils"}) {
      if (r.Has(key))
        r.Fail(key,
               "needs the helical geometry (wire_mm, coil_mm, active_coils, free_length_mm "
               "…): it is a setting of the helical spring check");
    }
  }
  if (!sp.rate_N_m && !sp.helical) {
    r.Fail("rate", "missing; give rate_N_mm (or rate_N_m, rate_kgf_mm …) or the helical geometry");
  }
  if (auto n = OptionalCount(r, "masses", kMaxCoilMasses, std::to_string(kMaxCoilMasses))) {
    if (*n > 1 && !sp.helical)
      r.Fail("masses",
             "needs the helical geometry (wire_mm, coil_mm, active_coils …): the coil "
             "masses are the active coils' mass");
    sp.masses = static_cast<int>(*n);
  }
  if (auto z = r.OptionalNumber("surge_damping_ratio")) {
    if (!sp.helical)  // with masses = 1 it is the check's surge study's (apps/study/check_scene.h)
      r.Fail("surge_damping_ratio",
             "needs the helical geometry (wire_mm, coil_mm, active_coils …): the coils it damps");
    sp.surge_damping_ratio = *z;
  }
  if (auto clash = r.OptionalBool("clash")) {
    if (*clash && sp.masses == 1)
      r.Fail("clash", "needs masses of at least 2 (the coils that meet)");
    sp.coil_clash = *clash;
  }
  if (auto k = r.OptionalQuantity("clash_stiffness", Dimension::kStiffness)) {
    if (!sp.coil_clash) r.Fail(r.last_key(), "needs clash = true");
    sp.clash_stiffness_N_m = *k;
  }
  if (auto z = r.OptionalNumber("clash_damping_ratio")) {
    if (!sp.coil_clash) r.Fail("clash_damping_ratio", "needs clash = true");
    sp.clash_damping_ratio = *z;
  }
  r.Validated([&sp] { sp.Validate(); });  // the spring's one rule (spring/spring_parameters.h)
  r.Finish();
  return sp;
}

LimitsSection ReadLimits(SectionReader r) {
  LimitsSection l;
  const auto optional_fraction = [&r](const std::string& name, double low) {
    const std::optional<double> v = r.OptionalQuantity(name, Dimension::kPercent);
    if (v && !(*v >= low && *v <= 1.0))
      r.Fail(r.last_key(), "must be in " + Number(low * 100) + "…100 %, got " + Number(*v * 100));
    return v;
  };
  const auto fraction = [&](const std::string& name, double low, double& into) {
    if (auto v = optional_fraction(name, low)) into = *v;
  };
  if (auto v = OptionalPositive(r, "seating_velocity", Dimension::kVelocity, 1.0,
                                "seating_velocity_m_s", "m/s"))
    l.seating_velocity_m_s = *v;
  if (auto v = OptionalPositive(r, "lash_impact_velocity", Dimension::kVelocity, 1.0,
                                "lash_impact_velocity_m_s", "m/s"))
    l.lash_impact_velocity_m_s = *v;
  fraction("secondary_opening", 0.0, l.secondary_opening_fraction);
  l.min_contact_force_fraction = optional_fraction("min_contact_force", 0.0);
  fraction("separation_margin", -1.0, l.separation_margin_fraction);
  if (auto v = OptionalPositive(r, "hertz_stress", Dimension::kPressure, 1e-6, "hertz_stress_MPa",
                                "MPa"))
    l.hertz_stress_Pa = *v;
  l.contact_length_m =
      OptionalPositive(r, "contact_length", Dimension::kLength, 1e3, "contact_length_mm", "mm");
  if (auto v = OptionalPositive(r, "elastic_modulus", Dimension::kPressure, 1e-9,
                                "elastic_modulus_GPa", "GPa"))
    l.elastic_modulus_Pa = *v;
  if (auto nu = r.OptionalNumber("poisson")) {
    if (!(*nu >= 0.0 && *nu < 0.5)) r.Fail("poisson", "must be in [0, 0.5), got " + Number(*nu));
    l.poisson = *nu;
  }
  if (auto f = r.OptionalNumber("fatigue_safety_factor")) {
    if (!(*f >= 1.0 && *f <= 10.0))
      r.Fail("fatigue_safety_factor", "must be in 1…10, got " + Number(*f));
    l.fatigue_safety_factor = *f;
  }
  l.coil_gap_m = OptionalPositive(r, "coil_gap", Dimension::kLength, 1e3, "coil_gap_mm", "mm");
  fraction("harmonic_threshold", 0.001, l.harmonic_threshold);
  if (!(l.harmonic_threshold < 1.0)) r.Fail("harmonic_threshold_percent", "must be below 100 %");
  r.Finish();
  return l;
}

}  // namespace needle::case_internal
