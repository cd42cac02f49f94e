#pragma once
/// @file
/// Basu's design chain (NACA TM 477, Examples 1 and 2), from engine data to cam and valve:
///
///     fuel per cycle      G = N_i · b · c / (60 n)       (c = 2 four-stroke, 1 two-stroke) [g]
///     mixing ratio        ν(n): least-squares line through (125, 15), (300, 21.5), (400, 25)
///     injection air       V_a = ν · G/γ  at p₁, T₁;   expanded V_e = V_a · p₁/p₀ (isothermal)
///     mixture             V = V_e + G/γ
///     injection period    t = Δθ_deg / (6 n)
///     outflow velocity    w₀ = 44.8 φ √(T₁ [1 − (p₀/p₁)^0.286])            [m/s]
///     mean cross-section  q̄ = V / (w₀ t)
///     cross-section curve q(h, d) = (d − 0.354 h) · π · 0.3827 h   (45° seat)
///     mean lift           h̄ = q⁻¹(q̄, d);   maximum lift h_max = ρ h̄ (ρ = 2.12)
///     cam disk            D_c = v_c · 60 · 2 / (π n)   (four-stroke: cam at n/2); roller D_c/ratio
///     passage height      1.25 d;  needle ≈ 2 d;  cage ≈ 2.25 · needle
///     spring preload      Basu's formula with the needle diameter and t
///     nozzle              A = 0.95 · q(h_max, d);  hole diameter √(4A/(π z))
///
/// The discharge-passage diameter d, when not given, is the smallest candidate whose
/// maximum lift stays within the limit (Basu: the lift "should not exceed" 4 mm; he rejects
/// d = 10 mm for Example 1 because it needs 6.34 mm).

#include <optional>
#include <string>
#include <vector>

#include "lib/engine_cycle.h"
#include "lib/lift_law.h"
#include "lib/result_fields.h"
#include "lib/units.h"

namespace needle {

/// The engine data of Basu's design chain (`needle design ENGINE.toml`), SI except where a
/// unit is named. Defaults are Basu's.
struct DesignInputs {
  std::string path;
  std::string title;
  double power_W = 0.0;  ///< indicated power per cylinder (case: power_hp)
  double speed_rpm = 0.0;
  EngineCycle cycle = EngineCycle::kFourStroke;
  double fuel_g_hp_h = 145.0;  ///< specific fuel consumption, g per metric hp·h
  double fuel_density_kg_m3 = 860.0;
  double injection_crank_rad = 55.0 * kPi / 180.0;
  double injection_air_pressure_Pa = 61.0 * 101325.0;  ///< p1, absolute (Basu: 60 atg)
  double cylinder_pressure_Pa = 36.0 * 101325.0;       ///< p0, absolute (Basu: 35 atg)
  bool gauge_ratio = false;  ///< use (p0 − 1 atm)/(p1 − 1 atm) in w0, as Basu's arithmetic did
  double air_temperature_K = 293.15;
  double velocity_coefficient = 0.8;   ///< φ
  std::string atomizer = "disk";       ///< "disk" or "sleeve"
  std::optional<double> mixing_ratio;  ///< ν; from Basu's line through his three points if absent
  double cam_peripheral_velocity_m_s = 1.5;
  double disk_to_roller = 5.0;
  int nozzle_holes = 1;
  std::optional<double> discharge_passage_m;  ///< chosen d; by the rule when absent
  double max_lift_limit_m = 4e-3;             ///< the rule rejects passages needing more lift
  std::vector<double> passage_candidates_m = {6e-3, 10e-3, 16e-3, 20e-3, 25e-3, 30e-3};
  std::optional<double> needle_diameter_m;  ///< adopted; 2·d when absent
  std::optional<double> cam_disk_m;         ///< adopted (built) disk; computed when absent
  double rho = 2.12;                        ///< max/mean lift of the normal curve
  double nozzle_ratio = 0.95;               ///< nozzle / valve cross-section at max lift
  /// Needle and disks, for `design --case` (the chain does not need it); when absent the case
  /// gets an assumption, marked as such
  std::optional<double> moving_mass_kg;
};

/// q(h, d) = (d − 0.354 h)·π·0.3827 h, SI (m, m²). Throws std::invalid_argument for h < 0,
/// d ≤ 0, or h beyond the curve's crest h = d/0.708 where q stops growing.
double SeatCrossSection(double lift_m, double passage_m);

/// The lift h with q(h, d) = q (the rising branch). Throws std::invalid_argument when q
/// exceeds the curve's largest value for this d.
double LiftForCrossSection(double area_m2, double passage_m);

/// ν at `speed_rpm` on the least-squares line through Basu's three points.
double BasuMixingRatio(double speed_rpm);

/// w₀ = 44.8 φ √(T₁ [1 − r^0.286]) in m/s, r = p₀/p₁ the pressure ratio (0 < r < 1).
double OutflowVelocity(double velocity_coefficient, double temperature_K, double pressure_ratio);

/// One candidate passage diameter tried by the rule.
struct PassageTrial {
  double passage_m = 0.0;
  double mean_lift_m = 0.0;
  double max_lift_m = 0.0;
  bool accepted = false;
};

struct DesignResult {
  double fuel_per_cycle_g = 0.0;
  double fuel_per_cycle_cm3 = 0.0;
  double mixing_ratio = 0.0;
  bool mixing_ratio_from_line = false;
  double air_per_cycle_cm3 = 0.0;
  double air_expanded_cm3 = 0.0;
  double mixture_cm3 = 0.0;
  double injection_period_s = 0.0;
  double pressure_ratio = 0.0;  ///< p₀/p₁ used in w₀
  double air_velocity_m_s = 0.0;
  double mean_cross_section_m2 = 0.0;
  std::vector<PassageTrial> trials;  ///< the rule's trail (one entry when d was given)
  double discharge_passage_m = 0.0;
  double mean_lift_m = 0.0;
  double max_lift_m = 0.0;
  LiftTable lift_table;
  double cam_disk_computed_m = 0.0;
  double cam_disk_m = 0.0;  ///< adopted (given) or computed
  double roller_m = 0.0;
  double passage_height_m = 0.0;
  double needle_diameter_suggested_m = 0.0;  ///< 2 d
  double needle_diameter_m = 0.0;            ///< adopted or 2 d
  double cage_diameter_m = 0.0;
  double spring_preload_N = 0.0;
  double max_lift_cross_section_m2 = 0.0;
  double nozzle_cross_section_m2 = 0.0;
  int nozzle_holes = 0;
  double nozzle_hole_m = 0.0;
};

/// The chain's results as fields (lib/result_fields.h), each in the unit Basu's tables use
/// (g, cm³, mm, mm², kgf). The passage trials and the lift table are listed apart.
std::vector<Field> DesignFields(const DesignResult& r);

/// One passage trial as fields: the passage (mm), its mean and maximum lift (mm; none when its
/// largest cross-section is below the mean) and whether it was taken.
std::vector<Field> PassageTrialFields(const PassageTrial& t);

/// The lift table's columns: crank (deg), lift (mm).
const std::vector<Column>& DesignLiftColumns();

/// Runs the whole chain. Throws std::invalid_argument when no candidate passage keeps the
/// maximum lift within the limit, or a step's input is out of its formula's range.
DesignResult RunDesignChain(const DesignInputs& in);

}  // namespace needle
