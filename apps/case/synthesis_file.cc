// The synthesis file of `needle synth`.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "apps/case/case_file.h"
#include "apps/case/plausible_ranges.h"
#include "apps/case/section_reader.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle {

using case_internal::Number;
using case_internal::ParseToml;
using case_internal::Positive;
using case_internal::ReadFollowerKeys;
using case_internal::Section;
using case_internal::SectionReader;
using case_internal::SignedLength;

SynthesisFile LoadSynthesisFile(const std::string& path) {
  return ParseSynthesisFile(ReadInputFile(path, "synthesis file"), path);
}

namespace {

// [rise]: its angle and lift, and the step of the synthesis (ranges that keep it finite).
void ParseRise(const toml::table& root, const std::string& path, SynthesisFile& f) {
  SectionReader rise(Section(root, path, "rise"), path, "rise");
  if (!rise.present())
    rise.Fail("angle_deg", "section [rise] is missing; it needs angle_deg and lift_mm");
  // Ranges that keep the synthesis finite and its memory bounded (a lift of 3e305 mm made the
  // speed search loop forever; a step of 1e-7° asked for 5.7 GB).
  f.rise.rise_rad = Positive(rise, "angle", Dimension::kAngle, 180.0 / kPi, "angle_deg");
  if (!(f.rise.rise_rad <= 2 * kPi))
    rise.Fail(rise.last_key(),
              "must be at most 360 deg of cam, got " + Number(f.rise.rise_rad / kDeg));
  f.rise.height_m = Positive(rise, "lift", Dimension::kLength, 1e3, "lift_mm");
  if (!(f.rise.height_m <= 1.0))
    rise.Fail(rise.last_key(),
              "must be at most 1000 mm, got " + Number(f.rise.height_m * 1e3) + " mm");
  if (auto st = rise.OptionalQuantity("step", Dimension::kAngle)) {
    if (!(*st > 0.0 && *st < f.rise.rise_rad / 10))
      rise.Fail(rise.last_key(), "must be positive and below a tenth of the rise");
    if (!(*st >= f.rise.rise_rad / 1e6))
      rise.Fail(rise.last_key(), "must be at least a millionth of the rise (" +
                                     Number(f.rise.rise_rad / kDeg / 1e6) +
                                     " deg): at most 1e6 steps");
    f.rise.step_rad = *st;
  }
  rise.Finish();
}

// [limits]: the derivative limits the law is synthesized under.
void ParseSynthesisLimits(const toml::table& root, const std::string& path, SynthesisFile& f) {
  SectionReader lim(Section(root, path, "limits"), path, "limits");
  if (!lim.present())
    lim.Fail("acceleration", "section [limits] is missing; it needs acceleration and deceleration");
  if (auto v = lim.OptionalQuantity("speed", Dimension::kSlope)) {
    if (!(*v > 0.0 && *v < 1e6)) lim.Fail(lim.last_key(), "must be positive and finite");
    f.rise.speed_limit = *v;
  }
  f.rise.accel_limit =
      Positive(lim, "acceleration", Dimension::kSlope2, 1e3, "acceleration_mm_rad2");
  f.rise.decel_limit =
      Positive(lim, "deceleration", Dimension::kSlope2, 1e3, "deceleration_mm_rad2");
  if (!(f.rise.accel_limit < 1e12)) lim.Fail("acceleration", "must be finite (below 1e15 mm/rad2)");
  if (!(f.rise.decel_limit < 1e12)) lim.Fail("deceleration", "must be finite (below 1e15 mm/rad2)");
  if (auto v = lim.OptionalQuantity("jerk", Dimension::kSlope3)) {
    if (!(*v > 0.0 && *v < 1e15)) lim.Fail(lim.last_key(), "must be positive and finite");
    f.rise.jerk_limit = *v;
  }
  lim.Finish();
}

// [checks]: the follower and the checks of the synthesized cam (profile, spring, contact).
void ParseChecks(const toml::table& t, const std::string& path, SynthesisFile& f) {
  SectionReader ch(&t, path, "checks", SynthesisCheckKeys());
  // Each value is checked as it is read, so a failure names the key as written.
  auto length = [&](const std::string& name, bool positive) {
    return SignedLength(ch, name, positive);
  };
  f.follower = ReadFollowerKeys(ch);
  f.base_radius_m = length("base_radius", true);
  const FollowerKind kind = f.follower.kind;
  if ((kind != FollowerKind::kRoller || f.follower.face_half_width_m > 0.0) && !f.base_radius_m)
    ch.Fail("base_radius",
            "a " + std::string(FollowerKindName(kind)) + " follower needs base_radius_mm");
  if (auto u = ch.OptionalQuantity("min_entrainment_speed", Dimension::kVelocity)) {
    if (!(*u > 0.0 && *u <= 1e3))
      ch.Fail(ch.last_key(), "must be in (0, 1000] m/s, got " + Number(*u) + " m/s");
    if (!f.base_radius_m) ch.Fail("base_radius", "the lubrication limit needs base_radius_mm");
    f.min_entrainment_m_s = *u;
  }
  f.offset_m = ch.OptionalQuantity("offset", Dimension::kLength).value_or(0.0);
  if (f.base_radius_m) {  // the follower's one rule (lib/follower.h), as [profile]'s
    FollowerGeometry g = f.follower;
    g.base_radius_m = *f.base_radius_m;
    g.offset_m = f.offset_m;
    ch.Validated([&g] { g.Validate(); });
  }
  f.max_pressure_angle_rad = ch.OptionalQuantity("max_pressure_angle", Dimension::kAngle);
  if (f.max_pressure_angle_rad &&
      !(*f.max_pressure_angle_rad > 0.0 && *f.max_pressure_angle_rad < kPi / 2))
    ch.Fail(ch.last_key(),
            "must be in (0, 90) deg, got " + Number(*f.max_pressure_angle_rad / kDeg) + " deg");
  f.min_profile_radius_m = length("min_profile_radius", false);
  if (f.min_profile_radius_m && !f.base_radius_m) {
    ch.Fail("base_radius", "the curvature limit needs base_radius_mm");
  }
  f.spring_preload_N = ch.OptionalQuantity("spring_preload", Dimension::kForce);
  if (f.spring_preload_N && !(*f.spring_preload_N >= 0.0 && *f.spring_preload_N <= 1e7))
    ch.Fail(ch.last_key(), "must be in [0, 1e7] N, got " + Number(*f.spring_preload_N) + " N");
  f.spring_rate_N_m = ch.OptionalQuantity("spring_rate", Dimension::kStiffness);
  if (f.spring_rate_N_m && !(*f.spring_rate_N_m >= 0.0 && *f.spring_rate_N_m <= 1e12))
    ch.Fail(ch.last_key(),
            "must be in [0, 1e9] N/mm, got " + Number(*f.spring_rate_N_m * 1e-3) + " N/mm");
  f.moving_mass_kg = ch.OptionalQuantity("moving_mass", Dimension::kMass);
  if (f.moving_mass_kg && !(*f.moving_mass_kg > 0.0 && *f.moving_mass_kg <= 1e4))
    ch.Fail(ch.last_key(), "must be in (0, 1e4] kg, got " + Number(*f.moving_mass_kg) + " kg");
  f.min_spring_reserve = ch.OptionalNumber("min_spring_reserve");
  if (f.min_spring_reserve && !(f.spring_preload_N && f.moving_mass_kg)) {
    ch.Fail("min_spring_reserve",
            "needs spring_preload_N (or _kgf), moving_mass_kg and [output] speed_rpm");
  }
  if (f.min_spring_reserve && !(*f.min_spring_reserve > 0.0 && *f.min_spring_reserve <= 1e6))
    ch.Fail("min_spring_reserve", "must be in (0, 1e6]");
  f.contact_length_m = length("contact_length", true);
  if (auto e = ch.OptionalQuantity("elastic_modulus", Dimension::kPressure)) {
    if (!(*e > 0.0 && *e <= 1e13))
      ch.Fail(ch.last_key(), "must be in (0, 1e4] GPa, got " + Number(*e * 1e-9) + " GPa");
    f.elastic_modulus_Pa = *e;
  }
  if (auto nu = ch.OptionalNumber("poisson")) {
    if (!(*nu >= 0.0 && *nu < 0.5)) ch.Fail("poisson", "must be in [0, 0.5), got " + Number(*nu));
    f.poisson = *nu;
  }
  f.max_contact_stress_Pa = ch.OptionalQuantity("max_contact_stress", Dimension::kPressure);
  if (f.max_contact_stress_Pa &&
      !(*f.max_contact_stress_Pa > 0.0 && *f.max_contact_stress_Pa <= 1e13))
    ch.Fail(ch.last_key(),
            "must be in (0, 1e7] MPa, got " + Number(*f.max_contact_stress_Pa * 1e-6) + " MPa");
  if (f.max_contact_stress_Pa &&
      !(f.contact_length_m && f.spring_preload_N && f.moving_mass_kg && f.base_radius_m)) {
    ch.Fail("max_contact_stress",
            "needs contact_length_mm, spring_preload, moving_mass_kg and base_radius_mm");
  }

  if (f.max_pressure_angle_rad && !f.base_radius_m)
    ch.Fail("base_radius", "the pressure-angle check needs base_radius_mm");
  ch.Finish();
}

// [output]: the fall, the crank angle of the rise's start, the speed and the cycle.
void ParseOutput(const toml::table& t, const std::string& path, SynthesisFile& f) {
  SectionReader o(&t, path, "output");
  if (auto fall = o.OptionalString("fall")) {
    if (*fall != "mirror" && *fall != "none") o.Fail("fall", "expected \"mirror\" or \"none\"");
    f.mirror_fall = *fall == "mirror";
  }
  f.crank_start_rad = o.OptionalQuantity("crank_start", Dimension::kAngle).value_or(0.0);
  if (auto n = o.OptionalQuantity("speed", Dimension::kRotationSpeed)) {
    if (!(*n > 0.0 && *n <= 1e6)) o.Fail("speed_rpm", "must be in (0, 1e6] rpm, got " + Number(*n));
    f.speed_rpm = *n;
  }
  if (auto cycle = case_internal::OptionalCycle(o)) f.cycle = *cycle;
  o.Finish();
}

}  // namespace

SynthesisFile ParseSynthesisFile(const std::string& text, const std::string& path) {
  const toml::table root = ParseToml(text, path);
  for (const auto& [k, node] : root) {
    const std::string key(k.str());
    if (key == "title" || key == "rise" || key == "limits" || key == "checks" || key == "output")
      continue;
    throw CaseError(path + ": " + key + ": unknown " + (node.is_table() ? "section" : "key") +
                    " (known: title, [rise], [limits], [checks], [output])");
  }
  SynthesisFile f;
  f.path = path;
  f.title = root["title"].value_or(std::string());
  ParseRise(root, path, f);
  ParseSynthesisLimits(root, path, f);
  if (const toml::table* t = Section(root, path, "checks")) ParseChecks(*t, path, f);
  if (const toml::table* t = Section(root, path, "output")) ParseOutput(*t, path, f);
  return f;
}

}  // namespace needle
