#include "apps/cli/spring_command.h"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli/cli_checks.h"
#include "apps/cli/command_output.h"
#include "apps/cli/output_paths.h"
#include "apps/cli/result_writers.h"
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

CLI::App* AddSpringCommand(CLI::App& app, SpringCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "spring",
      "Spring check: Basu's formula, quasi-static lift-off, preload sizing, helical spring");
  cmd->add_option("CASE", o.case_path, "case file (TOML) with [needle] and [spring]")->required();
  cmd->add_option("--rpm", o.speed_rpm, "crank speed in rpm (default: [engine] speed_rpm)")
      ->check(SpeedRpm());
  cmd->add_flag("--json", o.json, "print one JSON object");
  return cmd;
}

int RunSpringCommand(const SpringCommandOptions& o) {
  return Emit(ComputeSpring(LoadCase(o.case_path), o), o.format, std::nullopt);
}

CLI::App* AddDesignCommand(CLI::App& app, DesignCommandOptions& o) {
  CLI::App* cmd =
      app.add_subcommand("design", "Basu's design chain from engine data to cam, valve and spring");
  cmd->add_option("ENGINE", o.engine_path, "engine file (TOML) with [engine] and [design]")
      ->required();
  cmd->add_flag("--json", o.json, "print one JSON object, every quantity with its unit in the key");
  cmd->add_option("--case", o.case_out,
                  "write a complete case for `needle check`: the normal-curve lift, the needle, "
                  "Basu's spring, the cam profile, and each assumption marked as such");
  return cmd;
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

int RunDesignCommand(const DesignCommandOptions& o) {
  const DesignInputs in = LoadDesignInputs(o.engine_path);
  if (o.case_out) CheckOutputPaths({{"--case", *o.case_out}}, {in.path});
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
    out << FormatObject(j, o.format);
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
  if (o.case_out) WriteOutput({"--case", *o.case_out}, DesignCase(in, r));
  std::cout << out.str() << std::flush;
  return 0;
}

}  // namespace needle
