// What spring computes and prints: ComputeSpring (spring_command.h).
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli/cli_checks.h"
#include "apps/cli/command_output.h"
#include "apps/cli/output_paths.h"
#include "apps/cli/result_writers.h"
#include "apps/cli/spring_command.h"
#include "apps/scene/case_file.h"
#include "apps/scene/case_scene.h"
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
  const double a_abs = check.max_abs_acceleration_m_s2;
  const double a_deg = check.max_abs_acceleration_rad / kDeg;
  const double inertia_N = check.inertia_force_N;
  const ForceMinimum& fmin = check.min_quasi_static;
  const double n_qs = check.liftoff_rpm_quasi_static;
  const double required_N = check.required_preload_N;
  const double margin = check.preload_margin_percent;
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
    j["basu_preload_kgf"] = basu_N ? nlohmann::json(*basu_N / kKgf) : nlohmann::json(nullptr);
    j["actual_preload_kgf"] = train.preload_N / kKgf;
    j["deviation_percent"] = basu_N ? nlohmann::json(100.0 * (train.preload_N - *basu_N) / *basu_N)
                                    : nlohmann::json(nullptr);
    j["max_abs_acceleration_m_s2"] = a_abs;
    j["max_abs_acceleration_deg"] = a_deg;
    j["inertia_force_kgf"] = inertia_N / kKgf;
    j["spring_rate_N_mm"] = train.rate_N_m * 1e-3;
    j["min_quasi_static_force_N"] = fmin.force_N;
    j["min_quasi_static_force_deg"] = fmin.crank_rad / kDeg;
    j["liftoff_rpm_quasi_static"] = Finite(n_qs);
    j["safety_factor"] = c.spring->safety_factor;
    j["overspeed_factor"] = c.spring->overspeed_factor;
    j["required_preload_N"] = required_N;
    j["required_preload_kgf"] = required_N / kKgf;
    j["preload_margin_percent"] = Finite(margin);
    j["gas_force_N"] = check.gas_force_N;
    j["gas_source"] = check.gas_source;
    j["combustion_ok"] = check.combustion_ok;
    j["combustion_margin_percent"] = Finite(check.combustion_margin_percent);
    j["basu_tolerance_percent"] = check.basu_tolerance_percent;
    j["basu_ok"] = check.basu_ok;
    j["preload_ok"] = preload_ok;
    j["failures"] = check.failures;
    j["pass"] = ok;
    if (helical) {
      const auto& h = *helical;
      j["helical"] = {{"rate_N_mm", h.rate_N_m * 1e-3},
                      {"index", h.index},
                      {"stress_correction", h.wahl ? "wahl" : "bergstrasser"},
                      {"correction_factor", h.correction_factor},
                      {"stress_preload_MPa", h.stress_preload_Pa * 1e-6},
                      {"stress_full_lift_MPa", h.stress_full_lift_Pa * 1e-6},
                      {"allowable_stress_MPa", h.allowable_stress_Pa * 1e-6},
                      {"total_coils", h.total_coils},
                      {"solid_length_mm", h.solid_length_m * 1e3},
                      {"length_preload_mm", h.length_preload_m * 1e3},
                      {"length_full_lift_mm", h.length_full_lift_m * 1e3},
                      {"clearance_full_lift_mm", h.clearance_full_lift_m * 1e3},
                      {"min_clearance_mm", h.min_clearance_m * 1e3},
                      {"surge_hz", h.surge_hz},
                      {"cam_hz", h.cam_hz},
                      {"surge_ratio", h.surge_ratio},
                      {"stress_ok", h.stress_ok},
                      {"clearance_ok", h.clearance_ok},
                      {"surge_ok", h.surge_ok},
                      {"pass", h.pass()}};
    }
    result.json = std::move(j);
  } else {
    out << (c.title.empty() ? c.path : c.title) << '\n';
    out << "speed " << Fixed(speed, 1) << " rpm, spline " << SplineKindName(law.kind())
        << ", injection period " << Fixed(sum.injection_period_s, 4) << " s\n\n";
    if (basu_N) {
      out << "Basu's formula (d = " << Fixed(*c.needle->diameter_m * 1e3, 1)
          << " mm): " << Fixed(*basu_N / kKgf, 1) << " kgf; the case's spring "
          << Fixed(train.preload_N / kKgf, 1) << " kgf ("
          << Fixed(100.0 * (train.preload_N - *basu_N) / *basu_N, 1) << " %; tolerance "
          << Fixed(check.basu_tolerance_percent, 1) << " %) -> " << PassFail(check.basu_ok) << '\n';
    }
    out << "combustion load F_g = " << Fixed(check.gas_force_N / kKgf, 1) << " kgf ("
        << check.gas_source << "); preload against S x F_g: margin "
        << (std::isfinite(check.combustion_margin_percent)
                ? Fixed(check.combustion_margin_percent, 1) + " %"
                : std::string("unbounded"))
        << " -> " << PassFail(check.combustion_ok) << '\n';
    out << "inertia force m*max|a| = " << Fixed(train.mass_kg, 2) << " kg x " << Fixed(a_abs, 2)
        << " m/s^2 (at " << Fixed(a_deg, 1) << " deg) = " << Fixed(inertia_N / kKgf, 2) << " kgf\n";
    out << "quasi-static contact force: min " << Fixed(fmin.force_N, 1) << " N at "
        << Fixed(fmin.crank_rad / kDeg, 2) << " deg (spring rate "
        << Fixed(train.rate_N_m * 1e-3, 2) << " N/mm)\n";
    out << "quasi-static lift-off speed n_qs = "
        << (std::isfinite(n_qs) ? Fixed(n_qs, 1) + " rpm (" + Fixed(n_qs / speed, 2) + " x rated)"
                                : "none (never decelerates)")
        << '\n';
    out << "required preload (S = " << Fixed(c.spring->safety_factor, 2) << " at "
        << Fixed(c.spring->overspeed_factor, 2) << " x " << Fixed(speed, 0)
        << " rpm): " << Fixed(required_N, 1) << " N = " << Fixed(required_N / kKgf, 2)
        << " kgf; margin of the case's spring "
        << (std::isfinite(margin) ? Fixed(margin, 1) + " %" : "unbounded") << " -> "
        << PassFail(preload_ok) << '\n';
    if (helical) {
      const auto& h = *helical;
      out << "\nhelical spring (" << (h.wahl ? "Wahl" : "Bergstrasser") << " correction "
          << Fixed(h.correction_factor, 3) << ")\n"
          << "  rate " << Fixed(h.rate_N_m * 1e-3, 2) << " N/mm, index D/d " << Fixed(h.index, 2)
          << ", total coils " << Fixed(h.total_coils, 1) << '\n'
          << "  shear stress " << Fixed(h.stress_preload_Pa * 1e-6, 0) << " MPa at preload, "
          << Fixed(h.stress_full_lift_Pa * 1e-6, 0) << " MPa at full lift, allowable "
          << Fixed(h.allowable_stress_Pa * 1e-6, 0) << " MPa -> " << PassFail(h.stress_ok) << '\n'
          << "  length " << Fixed(h.length_preload_m * 1e3, 1) << " mm at preload, "
          << Fixed(h.length_full_lift_m * 1e3, 1) << " mm at full lift, solid "
          << Fixed(h.solid_length_m * 1e3, 1) << " mm; coil gaps "
          << Fixed(h.clearance_full_lift_m * 1e3, 2) << " mm against S_a "
          << Fixed(h.min_clearance_m * 1e3, 2) << " mm -> " << PassFail(h.clearance_ok) << '\n'
          << "  surge " << Fixed(h.surge_hz, 1) << " Hz, cam " << Fixed(h.cam_hz, 3)
          << " Hz, ratio " << Fixed(h.surge_ratio, 1) << " (>= 13) -> " << PassFail(h.surge_ok)
          << '\n';
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
    j["power_hp"] = in.power_W / 735.49875;
    j["speed_rpm"] = in.speed_rpm;
    j["atomizer"] = in.atomizer;
    j["fuel_per_cycle_g"] = r.fuel_per_cycle_g;
    j["fuel_per_cycle_cm3"] = r.fuel_per_cycle_cm3;
    j["mixing_ratio"] = r.mixing_ratio;
    j["air_per_cycle_cm3"] = r.air_per_cycle_cm3;
    j["air_expanded_cm3"] = r.air_expanded_cm3;
    j["mixture_cm3"] = r.mixture_cm3;
    j["injection_period_s"] = r.injection_period_s;
    j["pressure_ratio"] = r.pressure_ratio;
    j["air_velocity_m_s"] = r.air_velocity_m_s;
    j["mean_cross_section_mm2"] = r.mean_cross_section_m2 * 1e6;
    nlohmann::json trials = nlohmann::json::array();
    for (const auto& t : r.trials) {
      trials.push_back({{"discharge_passage_mm", t.passage_m * 1e3},
                        {"mean_lift_mm", Finite(t.mean_lift_m * 1e3)},
                        {"max_lift_mm", Finite(t.max_lift_m * 1e3)},
                        {"accepted", t.accepted}});
    }
    j["passage_trials"] = trials;
    j["discharge_passage_mm"] = r.discharge_passage_m * 1e3;
    j["mean_lift_mm"] = r.mean_lift_m * 1e3;
    j["max_lift_mm"] = r.max_lift_m * 1e3;
    nlohmann::json table = nlohmann::json::array();
    for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i) {
      table.push_back({{"crank_deg", r.lift_table.crank_rad[i] / kDeg},
                       {"lift_mm", r.lift_table.lift_m[i] * 1e3}});
    }
    j["lift_table"] = table;
    j["cam_disk_computed_mm"] = r.cam_disk_computed_m * 1e3;
    j["cam_disk_mm"] = r.cam_disk_m * 1e3;
    j["roller_mm"] = r.roller_m * 1e3;
    j["passage_height_mm"] = r.passage_height_m * 1e3;
    j["needle_diameter_suggested_mm"] = r.needle_diameter_suggested_m * 1e3;
    j["needle_diameter_mm"] = r.needle_diameter_m * 1e3;
    j["cage_diameter_mm"] = r.cage_diameter_m * 1e3;
    j["spring_preload_kgf"] = r.spring_preload_N / kKgf;
    j["spring_preload_N"] = r.spring_preload_N;
    j["max_lift_cross_section_mm2"] = r.max_lift_cross_section_m2 * 1e6;
    j["nozzle_cross_section_mm2"] = r.nozzle_cross_section_m2 * 1e6;
    j["nozzle_holes"] = r.nozzle_holes;
    j["nozzle_hole_mm"] = r.nozzle_hole_m * 1e3;
    result.json = std::move(j);
  } else {
    out << (in.title.empty() ? in.path : in.title) << '\n'
        << Fixed(in.power_W / 735.49875, 1) << " HP_i per cylinder, " << Fixed(in.speed_rpm, 1)
        << " rpm, " << EngineCycleName(in.cycle) << ", " << in.atomizer << " atomizer\n\n"
        << "fuel per working cycle      " << Fixed(r.fuel_per_cycle_g, 3)
        << " g = " << Fixed(r.fuel_per_cycle_cm3, 3) << " cm3\n"
        << "mixing ratio                " << Fixed(r.mixing_ratio, 2)
        << (r.mixing_ratio_from_line ? " (Basu's line)" : " (given)") << '\n'
        << "injection air (p1, T1)      " << Fixed(r.air_per_cycle_cm3, 1) << " cm3\n"
        << "expanded to p0              " << Fixed(r.air_expanded_cm3, 1) << " cm3; mixture "
        << Fixed(r.mixture_cm3, 1) << " cm3\n"
        << "outflow velocity w0         " << Fixed(r.air_velocity_m_s, 1)
        << " m/s (p0/p1 = " << Fixed(r.pressure_ratio, 4) << ")\n"
        << "injection period            " << Fixed(r.injection_period_s, 4) << " s\n"
        << "mean cross-section          " << Fixed(r.mean_cross_section_m2 * 1e6, 2) << " mm2\n";
    for (const auto& t : r.trials) {
      out << "  passage " << Fixed(t.passage_m * 1e3, 1) << " mm: ";
      if (std::isnan(t.mean_lift_m)) {
        out << "its largest cross-section is below the mean -> rejected\n";
        continue;
      }
      out << "mean lift " << Fixed(t.mean_lift_m * 1e3, 3) << " mm, max lift "
          << Fixed(t.max_lift_m * 1e3, 3) << " mm -> " << (t.accepted ? "taken" : "rejected")
          << '\n';
    }
    out << "maximum lift (rho " << Fixed(in.rho, 2) << ")        " << Fixed(r.max_lift_m * 1e3, 3)
        << " mm\n"
        << "lift table (normal curve)  ";
    for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i) {
      out << ' ' << Fixed(r.lift_table.crank_rad[i] / kDeg, 0) << ":"
          << Fixed(r.lift_table.lift_m[i] * 1e3, 3);
    }
    out << "\ncam disk                    " << Fixed(r.cam_disk_computed_m * 1e3, 1)
        << " mm computed, " << Fixed(r.cam_disk_m * 1e3, 1) << " mm adopted; roller "
        << Fixed(r.roller_m * 1e3, 1) << " mm\n"
        << "discharge passage height    " << Fixed(r.passage_height_m * 1e3, 2) << " mm\n"
        << "needle diameter             " << Fixed(r.needle_diameter_m * 1e3, 2)
        << " mm (2d = " << Fixed(r.needle_diameter_suggested_m * 1e3, 1) << " mm); cage "
        << Fixed(r.cage_diameter_m * 1e3, 1) << " mm\n"
        << "spring preload (formula)    " << Fixed(r.spring_preload_N / kKgf, 1)
        << " kgf = " << Fixed(r.spring_preload_N, 0) << " N\n"
        << "cross-section at max lift   " << Fixed(r.max_lift_cross_section_m2 * 1e6, 2) << " mm2\n"
        << "nozzle cross-section        " << Fixed(r.nozzle_cross_section_m2 * 1e6, 2) << " mm2 in "
        << r.nozzle_holes << " holes of " << Fixed(r.nozzle_hole_m * 1e3, 3) << " mm\n";
    if (o.case_out) out << "case written: " << *o.case_out << '\n';
  }
  if (o.case_out) result.case_file = DesignCase(in, r);
  result.text = out.str();
  return result;
}

}  // namespace needle
