// The engine file of `needle design`: [engine] and [design].
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
using case_internal::OptionalCount;
using case_internal::OptionalPositive;
using case_internal::ParseToml;
using case_internal::Positive;
using case_internal::Section;
using case_internal::SectionReader;

namespace {

// A power in W shown in the key's horsepower (metric, as the case file reads "hp").
double HpPerWatt() { return 1.0 / ToSi(Dimension::kPower, "hp", 1.0); }

}  // namespace

DesignInputs ParseDesignInputs(const std::string& text, const std::string& path) {
  const toml::table root = ParseToml(text, path);
  for (const auto& [k, node] : root) {
    const std::string key(k.str());
    if (key == "title" || key == "engine" || key == "design") continue;
    throw CaseError(path + ": " + key + ": unknown " + (node.is_table() ? "section" : "key") +
                    " (known: title, [engine], [design])");
  }
  DesignInputs d;
  d.path = path;
  d.title = root["title"].value_or(std::string());
  SectionReader e(Section(root, path, "engine"), path, "engine", EngineFileKeys());
  if (!e.present())
    e.Fail("power_hp", "section [engine] is missing; it needs power_hp and speed_rpm");
  d.power_W = Positive(e, "power", Dimension::kPower, HpPerWatt(), "power_hp");
  d.speed_rpm = Positive(e, "speed", Dimension::kRotationSpeed, 1.0, "speed_rpm");
  if (auto cycle = case_internal::OptionalCycle(e)) d.cycle = *cycle;
  e.Finish();
  SectionReader r(Section(root, path, "design"), path, "design");
  r.Declare("fuel_density");
  auto positive = [&](const std::string& name, Dimension dim, double shown, const std::string& key,
                      double& into) {
    if (auto v = OptionalPositive(r, name, dim, shown, key)) into = *v;
  };
  auto number = [&](const std::string& key, double lo, double& into) {
    if (auto v = r.OptionalNumber(key)) {
      if (!(*v > lo)) r.Fail(key, "must be above " + Number(lo) + ", got " + Number(*v));
      into = *v;
    }
  };
  if (auto v = r.OptionalQuantity("fuel", Dimension::kSpecificFuel)) {
    if (!(*v > 0.0)) r.Fail("fuel_g_hp_h", "must be positive, got " + Number(*v));
    d.fuel_g_hp_h = *v;
  }
  positive("fuel_density", Dimension::kDensity, 1e-3, "fuel_density_g_cm3", d.fuel_density_kg_m3);
  positive("injection_crank", Dimension::kAngle, 180.0 / kPi, "injection_crank_deg",
           d.injection_crank_rad);
  positive("injection_air_pressure", Dimension::kPressure, 1.0 / 101325.0,
           "injection_air_pressure_atm", d.injection_air_pressure_Pa);
  positive("cylinder_pressure", Dimension::kPressure, 1.0 / 101325.0, "cylinder_pressure_atm",
           d.cylinder_pressure_Pa);
  if (auto t = r.OptionalQuantity("air_temperature", Dimension::kTemperature)) {
    if (!(*t > 0.0)) r.Fail("air_temperature", "must be above absolute zero");
    d.air_temperature_K = *t;
  }
  number("velocity_coefficient", 0.0, d.velocity_coefficient);
  if (d.velocity_coefficient > 1.0) {
    r.Fail("velocity_coefficient", "must be at most 1, got " + Number(d.velocity_coefficient));
  }
  if (auto a = r.OptionalString("atomizer")) {
    if (*a != "disk" && *a != "sleeve")
      r.Fail("atomizer", "expected \"disk\" or \"sleeve\", got \"" + *a + "\"");
    d.atomizer = *a;
  }
  if (auto ratio = r.OptionalString("pressure_ratio")) {
    if (*ratio != "absolute" && *ratio != "gauge") {
      r.Fail("pressure_ratio", "expected \"absolute\" or \"gauge\", got \"" + *ratio + "\"");
    }
    d.gauge_ratio = *ratio == "gauge";
  }
  if (auto m = r.OptionalNumber("mixing_ratio")) {
    if (!(*m > 0.0)) r.Fail("mixing_ratio", "must be positive, got " + Number(*m));
    d.mixing_ratio = *m;
  }
  positive("cam_peripheral_velocity", Dimension::kVelocity, 1.0, "cam_peripheral_velocity_m_s",
           d.cam_peripheral_velocity_m_s);
  number("disk_to_roller", 1.0, d.disk_to_roller);
  // Checked as an integer in range before the cast (3e9 printed "−2147483648 holes").
  if (auto holes = OptionalCount(r, "nozzle_holes", 1000.0, "1000"))
    d.nozzle_holes = static_cast<int>(*holes);
  if (auto v = r.OptionalQuantity("discharge_passage", Dimension::kLength)) {
    if (!(*v > 0.0)) r.Fail("discharge_passage_mm", "must be positive, got " + Number(*v * 1e3));
    d.discharge_passage_m = *v;
  }
  positive("max_lift_limit", Dimension::kLength, 1e3, "max_lift_limit_mm", d.max_lift_limit_m);
  if (auto list = r.OptionalQuantityArray("passage_candidates", Dimension::kLength)) {
    if (list->empty()) r.Fail("passage_candidates_mm", "must not be empty");
    for (double v : *list) {
      if (!(v > 0.0)) r.Fail("passage_candidates_mm", "every diameter must be positive");
    }
    d.passage_candidates_m = *list;
  }
  if (auto v = r.OptionalQuantity("needle_diameter", Dimension::kLength)) {
    if (!(*v > 0.0)) r.Fail("needle_diameter_mm", "must be positive, got " + Number(*v * 1e3));
    d.needle_diameter_m = *v;
  }
  if (auto v = r.OptionalQuantity("cam_disk", Dimension::kLength)) {
    if (!(*v > 0.0)) r.Fail("cam_disk_mm", "must be positive, got " + Number(*v * 1e3));
    d.cam_disk_m = *v;
  }
  if (auto m = r.OptionalQuantity("moving_mass", Dimension::kMass)) {
    if (!(*m > 0.0 && *m <= 1e4))
      r.Fail("moving_mass_kg", "must be in (0, 1e4] kg, got " + Number(*m));
    d.moving_mass_kg = *m;
  }
  number("rho", 1.0, d.rho);
  number("nozzle_ratio", 0.0, d.nozzle_ratio);
  r.Finish();
  return d;
}

DesignInputs LoadDesignInputs(const std::string& path) {
  return ParseDesignInputs(ReadInputFile(path, "engine file"), path);
}

}  // namespace needle
