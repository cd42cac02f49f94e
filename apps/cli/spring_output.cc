// What spring computes and prints: ComputeSpring (spring_command.h).
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/spring_command.h"
#include "apps/report/command_output.h"
#include "apps/report/output_paths.h"
#include "apps/report/result_writers.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/basu_formula.h"
#include "spring/design_chain.h"
#include "spring/helical_spring.h"
#include "spring/quasi_static.h"
#include "spring/spring_check.h"

namespace needle {

namespace {

std::string PassFail(bool ok) { return ok ? "pass" : "FAIL"; }

}  // namespace

CommandOutput ComputeSpring(const Case& c, const SpringCommandOptions& o) {
  RequireSpeed(o.speed_rpm);
  const double speed = o.speed_rpm.value_or(c.engine.speed_rpm);
  const LiftLaw law = MakeLiftLaw(c);
  const SpringCheckResult check = CheckSpring(c, law, speed);
  const KinematicsSummary& sum = check.kinematics;
  const RigidTrain& train = check.train;
  const std::optional<HelicalSpringCheck>& helical = check.helical;
  const std::optional<double>& basu_N = check.basu_preload_N;
  const double n_qs = check.liftoff_rpm_quasi_static;
  const bool preload_ok = check.preload_ok;
  const bool ok = check.pass;

  CommandOutput result;
  result.status = ok ? 0 : 1;
  std::ostringstream out;
  if (o.json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["speed_rpm"] = speed;
    j["spline"] = SplineKindName(law.kind());
    j["injection_period_s"] = sum.injection_period_s;
    PutFields(j, SpringCheckFields(check));
    j["safety_factor"] = c.spring->safety_factor;
    j["overspeed_factor"] = c.spring->overspeed_factor;
    j["failures"] = check.failures;
    if (helical) PutFields(j["helical"], HelicalFields(*helical));
    result.json = std::move(j);
  } else {
    const std::vector<Field> fields = SpringCheckFields(check);
    const auto t = [&](const char* key) { return FieldText(FieldAt(fields, key)); };
    const auto or_unbounded = [&](const char* key) {
      return FieldAt(fields, key).si ? t(key) : std::string("unbounded");
    };
    out << (c.title.empty() ? c.path : c.title) << '\n';
    out << "speed " << Fixed(speed, 1) << " rpm, spline " << SplineKindName(law.kind())
        << ", injection period " << Fixed(sum.injection_period_s, 4) << " s\n\n";
    if (basu_N) {
      out << "Basu's formula (d = " << Fixed(*c.needle->diameter_m * 1e3, 1)
          << " mm): " << t("basu_preload_kgf") << "; the case's spring " << t("actual_preload_kgf")
          << " (" << t("deviation_percent") << "; tolerance " << t("basu_tolerance_percent")
          << ") -> " << PassFail(check.basu_ok) << '\n';
    }
    out << "combustion load F_g = "
        << FieldText({"gas_force", display::kKgForce, check.gas_force_N, 1}) << " ("
        << check.gas_source << "); preload against S x F_g: margin "
        << or_unbounded("combustion_margin_percent") << " -> " << PassFail(check.combustion_ok)
        << '\n';
    out << "inertia force m*max|a| = " << Fixed(train.mass_kg, 2) << " kg x "
        << t("max_abs_acceleration_m_s2") << " (at " << t("max_abs_acceleration_deg")
        << ") = " << t("inertia_force_kgf") << '\n';
    out << "quasi-static contact force: min " << t("min_quasi_static_force_N") << " at "
        << t("min_quasi_static_force_deg") << " (spring rate " << t("spring_rate_N_mm") << ")\n";
    out << "quasi-static lift-off speed n_qs = "
        << (std::isfinite(n_qs)
                ? t("liftoff_rpm_quasi_static") + " (" + Fixed(n_qs / speed, 2) + " x rated)"
                : "none (never decelerates)")
        << '\n';
    out << "required preload (S = " << Fixed(c.spring->safety_factor, 2) << " at "
        << Fixed(c.spring->overspeed_factor, 2) << " x " << Fixed(speed, 0)
        << " rpm): " << t("required_preload_N") << " = " << t("required_preload_kgf")
        << "; margin of the case's spring " << or_unbounded("preload_margin_percent") << " -> "
        << PassFail(preload_ok) << '\n';
    if (helical) {
      const std::vector<Field> hf = HelicalFields(*helical);
      const auto ht = [&](const char* key) { return FieldText(FieldAt(hf, key)); };
      const auto pf = [&](const char* key) { return PassFail(FieldAt(hf, key).flag); };
      out << "\nhelical spring (" << (helical->wahl ? "Wahl" : "Bergstrasser") << " correction "
          << ht("correction_factor") << ")\n"
          << "  rate " << ht("rate_N_mm") << ", index D/d " << ht("index") << ", total coils "
          << ht("total_coils") << '\n'
          << "  shear stress " << ht("stress_preload_MPa") << " at preload, "
          << ht("stress_full_lift_MPa") << " at full lift, allowable " << ht("allowable_stress_MPa")
          << " -> " << pf("stress_ok") << '\n'
          << "  length " << ht("length_preload_mm") << " at preload, " << ht("length_full_lift_mm")
          << " at full lift, solid " << ht("solid_length_mm") << "; coil gaps "
          << ht("clearance_full_lift_mm") << " against S_a " << ht("min_clearance_mm") << " -> "
          << pf("clearance_ok") << '\n'
          << "  surge " << ht("surge_hz") << ", cam " << ht("cam_hz") << ", ratio "
          << ht("surge_ratio") << " (>= 13) -> " << pf("surge_ok") << '\n';
    }
    out << "\nspring check: " << (ok ? "pass" : "FAIL") << '\n';
    for (const std::string& f : check.failures) out << "  fails: " << f << '\n';
  }
  result.text = out.str();
  return result;
}

namespace {

// The case `design --case` writes (issue 11): what the chain computed, and what it does not
// compute (moving mass, spring rate, contact train) as assumptions marked ASSUMED.
std::string DesignCase(const DesignInputs& in, const DesignResult& r) {
  std::ostringstream c;
  c.precision(10);
  c << "# Written by `needle design " << in.path << " --case`: Basu's design chain (NACA TM 477).\n"
    << "# Values marked ASSUMED are not computed by the chain; replace them with your own.\n"
    << "title = \"" << (in.title.empty() ? std::string("designed valve") : in.title)
    << " (designed)\"\n\n[engine]\nspeed_rpm = " << in.speed_rpm << "\ncycle = \""
    << EngineCycleName(in.cycle) << "\"\n\n# The normal curve scaled to the maximum lift "
    << r.max_lift_m * 1e3 << " mm.\n[lift]\ncrank_deg = [";
  for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i)
    c << (i ? ", " : "") << r.lift_table.crank_rad[i] / kDeg;
  c << "]\nlift_mm = [";
  for (size_t i = 0; i < r.lift_table.lift_m.size(); ++i)
    c << (i ? ", " : "") << r.lift_table.lift_m[i] * 1e3;
  c << "]\n\n[needle]\n";
  if (in.moving_mass_kg) {
    c << "mass_kg = " << *in.moving_mass_kg << "  # [design] moving_mass_kg\n";
  } else {
    // Basu's Example 1: 11.5 kg of needle and disks with a 31 mm needle.
    const double m = 11.5 * std::pow(r.needle_diameter_m / 31e-3, 3);
    c << "mass_kg = " << m
      << "  # ASSUMED: Basu's Example 1 (11.5 kg at a 31 mm needle) scaled by the needle "
         "diameter cubed; weigh yours or give [design] moving_mass_kg\n";
  }
  c << "diameter_mm = " << r.needle_diameter_m * 1e3
    << "  # the gas load defaults to Basu's 35 kg/cm2 on it\n\n[spring]\npreload_N = "
    << r.spring_preload_N
    << "  # Basu's formula\nrate_N_mm = " << 0.1 * r.spring_preload_N / r.max_lift_m * 1e-3
    << "  # ASSUMED: 10 % more force at full lift\n\n"
    << "# ASSUMED: a stiff steel roller-on-cam contact and seat, no roller play.\n"
    << "[train]\ncontact_stiffness_N_m = 1e9\ncontact_damping_ratio = 0.05\n"
       "seat_stiffness_N_m = 1e9\nseat_damping_ratio = 0.05\nplay_mm = 0\n\n"
    << "# The cam disk and roller of the chain; a radial roller "
       "follower.\n[profile]\nbase_radius_mm = "
    << r.cam_disk_m * 1e3 / 2 << "\nroller_radius_mm = " << r.roller_m * 1e3 / 2
    << "\noffset_mm = 0\n";
  return c.str();
}

}  // namespace

CommandOutput ComputeDesign(const DesignInputs& in, const DesignCommandOptions& o) {
  CommandOutput result;
  DesignResult r;
  try {
    r = RunDesignChain(in);
  } catch (const std::invalid_argument& e) {
    throw CaseError(in.path + ": [design]: " + e.what());
  }
  std::ostringstream out;
  if (o.json) {
    nlohmann::json j;
    j["engine"] = in.path;
    PutFields(j, {{"power", display::kHp, in.power_W}});
    j["speed_rpm"] = in.speed_rpm;
    j["atomizer"] = in.atomizer;
    PutFields(j, DesignFields(r));
    j["passage_trials"] = RecordList(r.trials, PassageTrialFields);
    nlohmann::json table = nlohmann::json::array();
    for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i)
      table.push_back(
          RowObject(DesignLiftColumns(), {r.lift_table.crank_rad[i], r.lift_table.lift_m[i]}));
    j["lift_table"] = table;
    result.json = std::move(j);
  } else {
    const std::vector<Field> fields = DesignFields(r);
    const auto t = [&](const char* key) { return FieldText(FieldAt(fields, key)); };
    const auto v = [&](const char* key) { return ValueText(FieldAt(fields, key)); };
    out << (in.title.empty() ? in.path : in.title) << '\n'
        << ValueText({"power", display::kHp, in.power_W, 1}) << " HP_i per cylinder, "
        << Fixed(in.speed_rpm, 1) << " rpm, " << EngineCycleName(in.cycle) << ", " << in.atomizer
        << " atomizer\n\n"
        << "fuel per working cycle      " << t("fuel_per_cycle_g") << " = "
        << t("fuel_per_cycle_cm3") << '\n'
        << "mixing ratio                " << v("mixing_ratio")
        << (r.mixing_ratio_from_line ? " (Basu's line)" : " (given)") << '\n'
        << "injection air (p1, T1)      " << t("air_per_cycle_cm3") << '\n'
        << "expanded to p0              " << t("air_expanded_cm3") << "; mixture "
        << t("mixture_cm3") << '\n'
        << "outflow velocity w0         " << t("air_velocity_m_s")
        << " (p0/p1 = " << v("pressure_ratio") << ")\n"
        << "injection period            " << t("injection_period_s") << '\n'
        << "mean cross-section          " << t("mean_cross_section_mm2") << '\n';
    for (const PassageTrial& trial : r.trials) {
      const std::vector<Field> tf = PassageTrialFields(trial);
      out << "  passage " << FieldText(FieldAt(tf, "discharge_passage_mm")) << ": ";
      if (!FieldAt(tf, "mean_lift_mm").si) {
        out << "its largest cross-section is below the mean -> rejected\n";
        continue;
      }
      out << "mean lift " << FieldText(FieldAt(tf, "mean_lift_mm")) << ", max lift "
          << FieldText(FieldAt(tf, "max_lift_mm")) << " -> "
          << (trial.accepted ? "taken" : "rejected") << '\n';
    }
    out << "maximum lift (rho " << Fixed(in.rho, 2) << ")        " << t("max_lift_mm") << '\n'
        << "lift table (normal curve)  ";
    for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i) {
      out << ' ' << Fixed(r.lift_table.crank_rad[i] / kDeg, 0) << ":"
          << Fixed(r.lift_table.lift_m[i] * 1e3, 3);
    }
    out << "\ncam disk                    " << v("cam_disk_computed_mm") << " mm computed, "
        << t("cam_disk_mm") << " adopted; roller " << t("roller_mm") << '\n'
        << "discharge passage height    " << t("passage_height_mm") << '\n'
        << "needle diameter             " << t("needle_diameter_mm")
        << " (2d = " << t("needle_diameter_suggested_mm") << "); cage " << t("cage_diameter_mm")
        << '\n'
        << "spring preload (formula)    " << t("spring_preload_kgf") << " = "
        << t("spring_preload_N") << '\n'
        << "cross-section at max lift   " << t("max_lift_cross_section_mm2") << '\n'
        << "nozzle cross-section        " << t("nozzle_cross_section_mm2") << " in "
        << v("nozzle_holes") << " holes of " << t("nozzle_hole_mm") << '\n';
    if (o.case_out) out << "case written: " << *o.case_out << '\n';
  }
  if (o.case_out) result.case_file = DesignCase(in, r);
  result.text = out.str();
  return result;
}

}  // namespace needle
