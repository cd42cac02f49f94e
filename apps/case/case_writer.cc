#include "apps/case/case_writer.h"

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "apps/case/case_keys.h"
#include "lib/engine_cycle.h"
#include "lib/follower.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/wire_material.h"

namespace needle {
std::string ExactDecimal(double v) {
  for (int digits = 6; digits <= 17; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << v;
    if (std::stod(out.str()) == v) return out.str();
  }
  return std::to_string(v);
}

namespace {

// A key of `section` as written, with its unit suffix: declared in the one list (case_keys.h).
struct Keys {
  const char* section;
  std::string operator()(const std::string& name, const std::string& unit = "") const {
    return CaseKeyText(section, name, unit);
  }
};
constexpr Keys kEngine{"engine"}, kLift{"lift"}, kNeedle{"needle"}, kSpring{"spring"},
    kTrain{"train"}, kProfile{"profile"};

// The assumed stiff steel train of a written case: contacts and seat of stiffness `k_N_m` and
// damping ratio `zeta`, no roller play.
std::string AssumedTrain(const std::string& k_N_m, const std::string& zeta) {
  return "[train]\n" + kTrain("contact_stiffness", "N_m") + " = " + k_N_m + "\n" +
         kTrain("contact_damping_ratio") + " = " + zeta + "\n" + kTrain("seat_stiffness", "N_m") +
         " = " + k_N_m + "\n" + kTrain("seat_damping_ratio") + " = " + zeta + "\n" +
         kTrain("play", "mm") + " = 0\n";
}

}  // namespace

std::string DesignCaseText(const DesignInputs& in, const DesignResult& r) {
  std::ostringstream c;
  c.precision(10);
  c << "# Written by `needle design " << in.path << " --case`: Basu's design chain (NACA TM 477).\n"
    << "# Values marked ASSUMED are not computed by the chain; replace them with your own.\n"
    << "title = \"" << (in.title.empty() ? std::string("designed valve") : in.title)
    << " (designed)\"\n\n[engine]\n"
    << kEngine("speed", "rpm") << " = " << in.speed_rpm << "\n"
    << kEngine("cycle") << " = \"" << EngineCycleName(in.cycle)
    << "\"\n\n# The normal curve scaled to the maximum lift " << r.max_lift_m * 1e3
    << " mm.\n[lift]\n"
    << kLift("crank", "deg") << " = [";
  for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i)
    c << (i ? ", " : "") << r.lift_table.crank_rad[i] / kDeg;
  c << "]\n" << kLift("lift", "mm") << " = [";
  for (size_t i = 0; i < r.lift_table.lift_m.size(); ++i)
    c << (i ? ", " : "") << r.lift_table.lift_m[i] * 1e3;
  c << "]\n\n[needle]\n";
  if (in.moving_mass_kg) {
    c << kNeedle("mass", "kg") << " = " << *in.moving_mass_kg << "  # [design] moving_mass_kg\n";
  } else {
    // Basu's Example 1: 11.5 kg of needle and disks with a 31 mm needle.
    const double m = 11.5 * std::pow(r.needle_diameter_m / 31e-3, 3);
    c << kNeedle("mass", "kg") << " = " << m
      << "  # ASSUMED: Basu's Example 1 (11.5 kg at a 31 mm needle) scaled by the needle "
         "diameter cubed; weigh yours or give [design] moving_mass_kg\n";
  }
  c << kNeedle("diameter", "mm") << " = " << r.needle_diameter_m * 1e3
    << "  # the gas load defaults to Basu's 35 kg/cm2 on it\n\n[spring]\n"
    << kSpring("preload", "N") << " = " << r.spring_preload_N << "  # Basu's formula\n"
    << kSpring("rate", "N_mm") << " = " << 0.1 * r.spring_preload_N / r.max_lift_m * 1e-3
    << "  # ASSUMED: 10 % more force at full lift\n\n"
    << "# ASSUMED: a stiff steel roller-on-cam contact and seat, no roller play.\n"
    << AssumedTrain("1e9", "0.05") << "\n"
    << "# The cam disk and roller of the chain; a radial roller follower.\n[profile]\n"
    << kProfile("base_radius", "mm") << " = " << r.cam_disk_m * 1e3 / 2 << "\n"
    << kProfile("roller_radius", "mm") << " = " << r.roller_m * 1e3 / 2 << "\n"
    << kProfile("offset", "mm") << " = 0\n";
  return c.str();
}

std::string SynthesizedCaseText(const SynthesisFile& f, const SynthesizedLaw& law) {
  const double mm = 1e3;
  // Every 10th step (and the last), as crank angles: ×2 for a four-stroke cam.
  const double k = CrankTurnsPerCycle(f.cycle);
  std::ostringstream c, angles, lifts;
  angles.precision(10);
  lifts.precision(10);
  for (size_t i = 0; i < law.phi.size(); i += 10) {
    angles << (i ? ", " : "") << (f.crank_start_rad + k * law.phi[i]) / kDeg;
    lifts << (i ? ", " : "") << std::max(0.0, law.s[i]) * mm;
  }
  if ((law.phi.size() - 1) % 10 != 0) {
    angles << ", " << (f.crank_start_rad + k * law.phi.back()) / kDeg;
    lifts << ", " << std::max(0.0, law.s.back()) * mm;
  }
  c << "# Written by `needle synth " << f.path << "`.\n"
    << "title = \"" << (f.title.empty() ? "synthesized law" : f.title) << "\"\n\n[engine]\n"
    << kEngine("speed", "rpm") << " = " << f.speed_rpm << "\n"
    << kEngine("cycle") << " = \"" << EngineCycleName(f.cycle) << "\"\n\n[lift]\n"
    << kLift("crank", "deg") << " = [" << angles.str() << "]\n"
    << kLift("lift", "mm") << " = [" << lifts.str() << "]\n"
    << kLift("spline") << " = \"not-a-knot\"\n"
    << kLift("resolution", "mm") << " = 0.000001\n";
  if (f.base_radius_m) {
    const FollowerGeometry& g = f.follower;
    c << "\n[profile]\n"
      << kProfile("follower") << " = \"" << FollowerKindName(g.kind) << "\"\n"
      << kProfile("base_radius", "mm") << " = " << *f.base_radius_m * mm;
    if (g.kind == FollowerKind::kRoller)
      c << "\n" << kProfile("roller_radius", "mm") << " = " << g.roller_radius_m * mm;
    if (g.face_radius_m > 0.0)
      c << "\n" << kProfile("face_radius", "mm") << " = " << g.face_radius_m * mm;
    if (g.face_half_width_m > 0.0)
      c << "\n" << kProfile("face_half_width", "mm") << " = " << g.face_half_width_m * mm;
    c << "\n" << kProfile("offset", "mm") << " = " << f.offset_m * mm << "\n";
  }
  // Every [checks] input the synthesis used goes on into the case, so that `needle check` on
  // it runs the spring check and the dynamics. What the synthesis file does not say and the
  // dynamics needs is stated as an assumption, marked as such.
  if (f.moving_mass_kg && f.spring_preload_N) {
    std::ostringstream v;
    v.precision(12);
    v << "\n[needle]\n"
      << kNeedle("mass", "kg") << " = " << *f.moving_mass_kg << "\n"
      << kNeedle("gas_force", "N") << " = 0  # ASSUMED: the synthesis file states no gas load\n"
      << "\n[spring]\n"
      << kSpring("preload", "N") << " = " << *f.spring_preload_N << "\n"
      << kSpring("rate", "N_mm") << " = " << f.spring_rate_N_m.value_or(0.0) * 1e-3 << "\n"
      << "\n# ASSUMED (not in the synthesis file): a stiff steel roller-on-cam contact and "
         "seat,\n"
         "# no roller play. State your own train before trusting the dynamics.\n"
      << AssumedTrain("2e8", "0.1");
    c << v.str();
  }
  return c.str();
}

// A length in mm as written: whole nanometres when that reads back to the same metres (a
// stated 13 mm wire is 13, not 13.000000000000002), else the exact digits.
namespace {
std::string Millimetres(double m) {
  const double mm = std::round(m * 1e9) / 1e6;
  return ToSi(Dimension::kLength, "mm", mm) == m ? ExactDecimal(mm) : ExactDecimal(m * 1e3);
}
}  // namespace

std::string SizedCaseText(const std::string& original, double needle_mass_kg, const SizedSpring& s,
                          const SizingSpace& space) {
  const HelicalGeometry& g = s.geometry;
  const SizingWire& w = space.wires.at(s.wire_index);
  std::ostringstream keys;
  keys << "# sized by `needle size` (" << w.label << "): the spring's lines below replace "
       << "the case's\n";
  keys << kSpring("preload", "N") << " = " << Fixed(s.preload_N, 1) << '\n';
  keys << kSpring("wire", "mm") << " = " << Millimetres(g.wire_m) << '\n';
  keys << kSpring("coil", "mm") << " = " << Millimetres(g.coil_m) << '\n';
  keys << kSpring("active_coils") << " = " << ExactDecimal(g.active_coils) << '\n';
  // Up to the next 1e-6 mm: the installed length never shorter than sized
  // (less 1e-12 m of round-off: the sized L₁ has 1e-9 m to spare, kLengthSlack_m)
  keys << kSpring("free_length", "mm") << " = "
       << ExactDecimal(std::ceil(g.free_length_m * 1e9 - 1e-3) / 1e6) << '\n';
  if (w.grade) {  // R_m(d) and G of the grade
    keys << kSpring("grade") << " = \"" << WireGradeName(*w.grade) << "\"\n";
  } else {
    keys << kSpring("shear_modulus", "GPa") << " = " << ExactDecimal(g.shear_modulus_Pa * 1e-9)
         << '\n';
    keys << kSpring("tensile", "MPa") << " = " << ExactDecimal(g.tensile_Pa * 1e-6) << '\n';
  }
  keys << kSpring("density", "kg_m3") << " = " << ExactDecimal(g.density_kg_m3) << '\n';
  keys << kSpring("ends") << " = \"" << SpringEndsName(g.ends) << "\"\n";
  if (g.stress_factor != StressFactor::kBergstrasser)
    keys << kSpring("stress_correction") << " = \"" << StressFactorName(g.stress_factor) << "\"\n";
  if (g.fatigue_criterion != FatigueCriterion::kGoodmanZimmerli)
    keys << kSpring("fatigue_criterion") << " = \"" << CriterionInfo(g.fatigue_criterion).name
         << "\"\n";
  if (g.shot_peened) keys << kSpring("shot_peened") << " = true\n";
  if (g.allowable_fraction != 0.5)
    keys << kSpring("allowable_stress_fraction") << " = " << ExactDecimal(g.allowable_fraction)
         << '\n';

  static const std::regex header(R"(^\s*\[\s*([A-Za-z0-9_]+)\s*\]\s*(#.*)?$)");
  static const std::regex key(R"(^\s*([A-Za-z0-9_]+)\s*=)");
  static const std::regex spring_key(
      R"(^(preload_|rate_|wire_|coil_|active_coils$|free_length_|shear_modulus_|density_|tensile_|grade$|ends$|stress_correction$|fatigue_criterion$|shot_peened$|allowable_stress_fraction$).*)");
  std::istringstream in(original);
  std::ostringstream out;
  std::string line, section;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, header)) {
      section = m[1];
      out << line << '\n';
      if (section == "spring") out << keys.str();
      continue;
    }
    if (std::regex_search(line, m, key)) {
      const std::string k = m[1];
      if (section == "spring" && std::regex_match(k, spring_key)) continue;
      if (section == "needle" && k.rfind("mass_", 0) == 0) {
        out << kNeedle("mass", "kg") << " = " << ExactDecimal(needle_mass_kg)
            << "  # the needle's parts and a third of the sized spring's active coils\n";
        continue;
      }
    }
    out << line << '\n';
  }
  return out.str();
}

}  // namespace needle
