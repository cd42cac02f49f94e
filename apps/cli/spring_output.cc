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

}  // namespace needle
