#include "apps/case/case_keys.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace needle {
namespace {

using D = Dimension;

// [profile]'s and [checks]' follower keys (ReadFollowerKeys): one declaration for both lists.
// A macro: C++17 has no constexpr way to splice one array's entries into two others.
// clang-format off
#define NEEDLE_FOLLOWER_KEYS(section)                                                          \
  {section, "follower", D::kNone, "\"roller\" (default), \"flat\" or \"curved\""},             \
  {section, "roller_radius", D::kLength, "the roller's radius (a roller follower)",            \
   &kProfileLengthRange},                                                                      \
  {section, "face_radius", D::kLength, "the face's radius (a curved follower)",                \
   &kProfileLengthRange},                                                                      \
  {section, "face_half_width", D::kLength,                                                     \
   "half the face's width (flat or curved): the contact stays on it", &kProfileLengthRange},   \
  {section, "base_radius", D::kLength, "the cam's base-circle radius", &kProfileLengthRange},  \
  {section, "offset", D::kLength, "the follower's offset from the cam's centre line",          \
   &kOffsetRange}
// clang-format on

constexpr CaseKey kCaseKeys[] = {
    {"engine", "speed", D::kRotationSpeed, "rated crank speed", &kCrankSpeedRange},
    {"engine", "cycle", D::kNone,
     "\"four-stroke\" (default; the cam turns at half the crank "
     "speed) or \"two-stroke\""},

    {"lift", "crank", D::kAngle, "the table's crank angles, increasing"},
    {"lift", "lift", D::kLength, "the table's lifts, one per crank angle", &kLiftRange, true},
    {"lift", "csv", D::kNone, "a CSV file of crank_deg,lift_mm rows instead of the arrays"},
    {"lift", "normal_curve", D::kNone, "\"basu\": Basu's normal curve, scaled to max_lift_mm"},
    {"lift", "max_lift", D::kLength, "the normal curve's largest lift", &kLiftRange},
    {"lift", "spline", D::kNone, "the spline through the table (default: chosen by the table)"},
    {"lift", "resolution", D::kLength,
     "the readings' printed digit (default: read from the "
     "table)",
     &kReadingRange},
    {"lift", "noise", D::kLength, "the readings' noise σ, a measured table's", &kReadingRange},
    {"lift", "outliers", D::kNone, "\"refuse\" (default) or \"drop\" a reading that stands out"},
    {"lift", "open", D::kAngle, "where the open lift begins (default: from the table)"},
    {"lift", "close", D::kAngle, "where the open lift ends (default: from the table)"},
    {"lift", "breaks", D::kAngle, "the law's junctions, where s'' may jump"},
    {"lift", "end_slope", D::kNone, "\"natural\" or \"not-a-knot\" ends of the spline"},
    {"lift", "end_slope", D::kSlope, "the lift's slopes at the table's two ends"},
    {"lift", "smoothing", D::kNone,
     "a measured table's smoothing rule: \"discrepancy\" or "
     "\"gcv\""},

    {"needle", "mass", D::kMass, "the moving mass: needle, disks and a third of the spring",
     &kMovingMassRange},
    {"needle", "diameter", D::kLength, "the needle's seat diameter (the gas load's area)",
     &kNeedleDiameterRange},
    {"needle", "gas_force", D::kForce, "the gas load on the closed needle", &kGasForceRange},
    {"needle", "combustion_pressure", D::kPressure,
     "the pressure on the needle's area (instead "
     "of gas_force)",
     &kCombustionPressureRange},

    {"spring", "preload", D::kForce, "the installed preload P₀", &kPreloadRange},
    {"spring", "rate", D::kStiffness, "the rate k (default: from the helical geometry)",
     &kSpringRateRange},
    {"spring", "safety_factor", D::kNone, "Basu's S on the inertia force (default 1.5)",
     &kSafetyFactorRange},
    {"spring", "overspeed_factor", D::kNone,
     "f: the spring is checked at f times the rated "
     "speed (default 1.2)",
     &kOverspeedFactorRange},
    {"spring", "basu_tolerance_percent", D::kNone,
     "how far the preload may sit below Basu's "
     "formula and still agree, %"},
    {"spring", "wire", D::kLength, "the wire's diameter d (a helical spring)", &kWireRange},
    {"spring", "coil", D::kLength, "the mean coil diameter D", &kCoilRange},
    {"spring", "active_coils", D::kNone, "the active coils n", &kActiveCoilsRange},
    {"spring", "free_length", D::kLength, "the free length L₀", &kFreeLengthRange},
    {"spring", "grade", D::kNone, "an EN 10270 wire grade: its G, R_m(d) and density"},
    {"spring", "shot_peened", D::kNone, "the wire is shot-peened (fatigue strength)"},
    {"spring", "shear_modulus", D::kPressure, "G (default: the grade's)", &kShearModulusRange},
    {"spring", "density", D::kDensity, "the wire's density (default: the grade's, else steel)",
     &kDensityRange},
    {"spring", "tensile", D::kPressure, "R_m (default: the grade's at d)", &kTensileRange},
    {"spring", "ends", D::kNone,
     "\"closed-ground\" (default), \"closed\", \"open-ground\" or "
     "\"open\""},
    {"spring", "stress_correction", D::kNone,
     "\"bergstrasser\" (default), \"wahl\" or "
     "\"direct-shear\""},
    {"spring", "fatigue_criterion", D::kNone, "the fatigue criterion of the spring check"},
    {"spring", "allowable_stress_fraction", D::kNone,
     "the allowed static stress as a fraction "
     "of R_m (default 0.5)"},
    {"spring", "masses", D::kNone, "the coil masses of the dynamics (1, the default: one mass)"},
    {"spring", "surge_damping_ratio", D::kNone, "the coils' modal damping ratio",
     &kDampingRatioRange},
    {"spring", "clash", D::kNone, "model the coils' clash (coil against coil)"},
    {"spring", "clash_stiffness", D::kStiffness, "the coils' contact stiffness in a clash",
     &kContactStiffnessRange},
    {"spring", "clash_damping_ratio", D::kNone, "the clash contact's damping ratio",
     &kDampingRatioRange},

    {"train", "contact", D::kNone, "\"compliant\" (default) or \"rigid\" cam and seat contacts"},
    {"train", "contact_stiffness", D::kStiffness, "cam–roller contact stiffness (compliant)",
     &kContactStiffnessRange},
    {"train", "seat_stiffness", D::kStiffness,
     "seat contact stiffness (compliant; default: "
     "contact_stiffness's)",
     &kContactStiffnessRange},
    {"train", "contact_damping_ratio", D::kNone, "cam contact's damping ratio (compliant)",
     &kDampingRatioRange},
    {"train", "seat_damping_ratio", D::kNone, "seat contact's damping ratio (compliant)",
     &kDampingRatioRange},
    {"train", "restitution", D::kNone, "cam contact's restitution (rigid)", &kRestitutionRange},
    {"train", "seat_restitution", D::kNone, "seat's restitution (rigid)", &kRestitutionRange},
    {"train", "play", D::kLength, "the roller's play δ", &kPlayRange},
    {"train", "ramp", D::kNone, "\"tangent\" (default) ramps that take up the play"},
    {"train", "ramp", D::kAngle, "a linear ramp of this length instead", &kRampRange},

    {"solver", "method", D::kNone, "\"auto\" (default) or an integrator of the method table"},
    {"solver", "rtol", D::kNone, "relative tolerance (default 1e-8)"},
    {"solver", "atol", D::kLength, "absolute tolerance on the lift (default rtol · 1 mm)"},
    {"solver", "max_steps", D::kNone, "step budget of one run"},
    {"solver", "max_events", D::kNone, "event budget of one run"},
    {"solver", "max_seconds", D::kNone, "wall-time budget of one run, s (0: none)"},
    {"solver", "settle", D::kAngle, "how long past the window the needle may take to settle"},
    {"solver", "cycles", D::kNone, "cam revolutions run back to back (default 1)"},
    {"solver", "period_tolerance", D::kNone, "a cycle-end state repeats within this fraction"},
    {"solver", "start", D::kAngle, "the run's window start (default: the lift's)"},
    {"solver", "end", D::kAngle, "the run's window end (default: the lift's)"},

    {"overspeed", "from", D::kRotationSpeed, "the lift-off sweep's first speed", &kCrankSpeedRange},
    {"overspeed", "to", D::kRotationSpeed, "the sweep's last speed", &kCrankSpeedRange},
    {"overspeed", "steady_state", D::kNone, "judge lift-off on the steady revolutions"},

    NEEDLE_FOLLOWER_KEYS("profile"),
    {"profile", "lever_ratio", D::kNone, "the rocker's ratio λ, roller travel per needle travel"},
    {"profile", "points", D::kNone, "points over one cam revolution (default 720)"},

    {"tolerance", "lift", D::kLength, "σ of each lift-table point", &kLengthSigmaRange},
    {"tolerance", "lift_correlation", D::kAngle, "the correlation length of that error",
     &kCorrelationRange},
    {"tolerance", "mass", D::kPercent, "σ of the moving mass", &kRelativeSigmaRange},
    {"tolerance", "preload", D::kPercent, "σ of the preload", &kRelativeSigmaRange},
    {"tolerance", "rate", D::kPercent, "σ of the rate (of G when k comes from the geometry)",
     &kRelativeSigmaRange},
    {"tolerance", "stiffness", D::kPercent, "σ of the contact stiffnesses", &kRelativeSigmaRange},
    {"tolerance", "play", D::kLength, "σ of the roller play", &kLengthSigmaRange},
    {"tolerance", "speed", D::kPercent, "σ of the rated speed", &kRelativeSigmaRange},

    {"paper", "crank", D::kAngle, "angles of the published velocities"},
    {"paper", "velocity", D::kVelocity, "the published velocities there"},
    {"paper", "max_acceleration", D::kAcceleration, "the published largest acceleration"},
    {"paper", "inertia_force", D::kForce, "the published inertia force"},
    {"paper", "mean_lift", D::kLength, "the published mean lift"},
    {"paper", "spring_preload", D::kForce, "the preload Basu's formula gave"},

    {"limits", "seating_velocity", D::kVelocity, "largest landing speed on the seat",
     &kImpactSpeedLimitRange},
    {"limits", "lash_impact_velocity", D::kVelocity, "largest speed of the lash impact",
     &kImpactSpeedLimitRange},
    {"limits", "secondary_opening", D::kPercent, "largest reopening after closing, of the lift"},
    {"limits", "min_contact_force", D::kPercent,
     "least cam force over the lift, of the static "
     "load"},
    {"limits", "separation_margin", D::kPercent, "n_dyn at least (1 + this)·f·n"},
    {"limits", "hertz_stress", D::kPressure, "largest cam–roller Hertz stress",
     &kHertzStressLimitRange},
    {"limits", "contact_length", D::kLength, "the roller's width in contact", &kProfileLengthRange},
    {"limits", "elastic_modulus", D::kPressure, "E of cam and roller", &kElasticModulusRange},
    {"limits", "poisson", D::kNone, "ν of cam and roller"},
    {"limits", "fatigue_safety_factor", D::kNone, "least fatigue safety factor of the spring"},
    {"limits", "coil_gap", D::kLength, "least coil gap at full lift", &kCoilGapRange},
    {"limits", "harmonic_threshold", D::kPercent,
     "a cam harmonic's share that counts in the "
     "resonance map"},

    {"sizing", "objective", D::kNone, "\"mass\", \"height\", \"stress\" or \"diameter\""},
    {"sizing", "closed_load", D::kForce, "the spring's load closed (a textbook problem)"},
    {"sizing", "open_load", D::kForce, "its load open"},
    {"sizing", "rate", D::kStiffness, "the rate asked for (instead of the open load)"},
    {"sizing", "stroke", D::kLength, "the stroke between the two loads"},
    {"sizing", "tensile", D::kPressure, "R_m of the problem's wire"},
    {"sizing", "shear_modulus", D::kPressure, "G of the problem's wire"},
    {"sizing", "allowable_stress_fraction", D::kNone, "allowed stress as a fraction of R_m"},
    {"sizing", "stress_correction", D::kNone, "the stress factor of the problem"},
    {"sizing", "fatigue_criterion", D::kNone, "the fatigue criterion of the problem"},
    {"sizing", "grades", D::kNone, "the EN 10270 grades to size in (\"case\": the case's wire)"},
    {"sizing", "wire", D::kLength, "the wires to choose from"},
    {"sizing", "min_wire", D::kLength, "the least wire"},
    {"sizing", "max_wire", D::kLength, "the largest wire"},
    {"sizing", "installed_length", D::kLength, "the installed length, fixed"},
    {"sizing", "min_installed_length", D::kLength, "the least installed length"},
    {"sizing", "max_installed_length", D::kLength, "the largest installed length"},
    {"sizing", "max_outer_diameter", D::kLength, "the largest outer coil diameter"},
    {"sizing", "min_inner_diameter", D::kLength, "the least inner coil diameter"},
    {"sizing", "min_index", D::kNone, "the least spring index D/d"},
    {"sizing", "max_index", D::kNone, "the largest spring index D/d"},
    {"sizing", "coil_step", D::kLength, "the step of the coil diameters tried"},
    {"sizing", "min_active_coils", D::kNone, "the least active coils"},
    {"sizing", "max_active_coils", D::kNone, "the most active coils"},
    {"sizing", "active_coil_step", D::kNone, "the step of the active coils tried"},
    {"sizing", "ends", D::kNone, "the ends of the sized spring"},
    {"sizing", "free_length_step", D::kLength, "the free length's rounding (0: none)"},
    {"sizing", "mass_without_spring", D::kMass, "the moving mass less the spring's share"},
    {"sizing", "end_fixation", D::kNone, "the buckling end-fixation factor ν"},
    {"sizing", "candidates", D::kNone, "how many candidates to list"},
    {"sizing", "verify", D::kNone, "how many of them to check against the dynamics"},
};

constexpr CaseKey kCheckKeys[] = {
    NEEDLE_FOLLOWER_KEYS("checks"),
    {"checks", "min_profile_radius", D::kLength, "least radius of curvature of the profile",
     &kProfileLengthRange},
    {"checks", "min_entrainment_speed", D::kVelocity, "least entrainment speed (lubrication)"},
    {"checks", "max_pressure_angle", D::kAngle, "largest pressure angle"},
    {"checks", "spring_preload", D::kForce, "the spring's preload"},
    {"checks", "spring_rate", D::kStiffness, "the spring's rate"},
    {"checks", "moving_mass", D::kMass, "the moving mass"},
    {"checks", "min_spring_reserve", D::kNone, "least spring force over the inertia force"},
    {"checks", "contact_length", D::kLength, "the roller's width in contact"},
    {"checks", "elastic_modulus", D::kPressure, "E of cam and roller"},
    {"checks", "poisson", D::kNone, "ν of cam and roller"},
    {"checks", "max_contact_stress", D::kPressure, "largest contact stress"},
};

constexpr CaseKey kEngineKeys[] = {
    {"engine", "power", D::kPower, "the engine's power"},
    {"engine", "speed", D::kRotationSpeed, "its rated crank speed", &kCrankSpeedRange},
    {"engine", "cycle", D::kNone, "\"four-stroke\" (default) or \"two-stroke\""},
};

#undef NEEDLE_FOLLOWER_KEYS

}  // namespace

CaseKeyList CaseFileKeys() { return CaseKeyList::Of(kCaseKeys); }

CaseKeyList SynthesisCheckKeys() { return CaseKeyList::Of(kCheckKeys); }

CaseKeyList EngineFileKeys() { return CaseKeyList::Of(kEngineKeys); }

const CaseKey* FindCaseKey(CaseKeyList keys, const std::string& section, const std::string& name,
                           Dimension dimension) {
  for (const CaseKey& k : keys) {
    if (section == k.section && name == k.name && dimension == k.dimension) return &k;
  }
  return nullptr;
}

std::string CaseKeyText(const std::string& section, const std::string& name,
                        const std::string& unit) {
  for (const CaseKey& k : CaseFileKeys()) {
    if (section != k.section || name != k.name) continue;
    const std::vector<std::string> units = UnitSuffixes(k.dimension);
    if (unit.empty() && units.empty()) return name;
    if (std::find(units.begin(), units.end(), unit) != units.end()) return name + "_" + unit;
  }
  throw std::logic_error("a case writer writes [" + section + "] " + name +
                         (unit.empty() ? "" : "_" + unit) +
                         ", which apps/case/case_keys.cc does not declare");
}

std::string CaseKeysMarkdown() {
  std::string out =
      "| section | key | unit suffixes | plausible range | what it is |\n|---|---|---|---|---|\n";
  for (const CaseKey& k : CaseFileKeys()) {
    std::string suffixes;
    for (const std::string& u : UnitSuffixes(k.dimension))
      suffixes += (suffixes.empty() ? "`_" : ", `_") + u + "`";
    const std::string key = k.dimension == D::kNone ? std::string("`") + k.name + "`"
                                                    : std::string("`") + k.name + "_…`";
    const std::string range =
        k.range ? (k.upper_only ? "≤ " + ShownValue(*k.range, k.range->hi) : RangeText(*k.range))
                : "—";
    out += std::string("| [") + k.section + "] | " + key + " | " +
           (suffixes.empty() ? "—" : suffixes) + " | " + range + " | " + k.doc + " |\n";
  }
  return out;
}

}  // namespace needle
