#pragma once
/// @file
/// A case's [sizing] section (`needle size`, issue 35): what the spring may be and what it must
/// fit. Every key is optional; what is absent comes from the case's own spring
/// (apps/study/spring_sizing_scene.h says how). Read by ReadSizing (sizing_section.cc) with the
/// key reader of every section; keys that contradict each other (a minimum above its maximum,
/// installed_length_mm beside its range, one wire, index and coil count: nothing to choose) are
/// refused naming the key.
///
///     [sizing]
///     grades = ["VDC", "VDSiCr"]    wire grades (spring/wire_material.h), or "case" for the
///                                   case's own wire (its R_m and G at every diameter)
///     wire_mm = [4, 4.5, 5]         wire diameters; default ISO 3's R40 preferred sizes within
///                                   each grade's table range and min_wire_mm…max_wire_mm
///     min_wire_mm, max_wire_mm
///     installed_length_mm           L₁, the length at the seated preload, exactly; or
///     min_installed_length_mm, max_installed_length_mm
///     max_outer_diameter_mm, min_inner_diameter_mm
///     min_index = 4, max_index = 20 D/d (EN 13906-1)
///     coil_step_mm = 0.5            mean coil diameters on multiples of this
///     min_active_coils = 2, max_active_coils = 30, active_coil_step = 0.5
///     ends = "closed-ground" | "closed" | "open-ground" | "open"
///     objective = "mass" | "height" | "stress" | "diameter" (least outer diameter)
///
///   A textbook design problem (Bhandari Ex. 10.4: "150 N closed, 300 N open over 5 mm"):
///     closed_load_N                 P₁ at the installed length: the preload, stated
///     open_load_N                   P₂ after the stroke: the rate (P₂ − P₁)/stroke; or
///     rate_N_mm                     the rate itself (each (wire, D) takes the fewest coils
///                                   whose rate is at most it: the books round n up)
///     stroke_mm                     the stroke (default: the lift's largest)
///     tensile_MPa, shear_modulus_GPa  a stated wire: this R_m and G at every diameter
///                                   (grades default to it)
///     allowable_stress_fraction     τ at full lift ≤ this × R_m (default: the case's, 0.5)
///     stress_correction, fatigue_criterion  as in [spring] (default: the case's)
///     free_length_step_mm = 0.1     the free length rounded up to this (0: not rounded)
///     mass_without_spring_kg        the moving mass less a third of the active coils
///     end_fixation = 0.5            ν of EN 13906-1's buckling (0.5: both ends fixed)
///     candidates = 5                the best springs listed
///     verify = 10                   at most this many checked end to end (the best, then the
///                                   mass-fatigue front), then the case's own spring

#include <optional>
#include <string>
#include <vector>

#include "spring/spring_parameters.h"
#include "spring/wire_material.h"

namespace needle {

struct SizingSection {
  std::vector<std::string> grades;  ///< grade names or "case"; empty: the case's (see file)
  std::vector<double> wire_m;       ///< stated wire diameters; empty: R40 preferred sizes
  std::optional<double> min_wire_m, max_wire_m;
  std::optional<double> min_installed_m, max_installed_m;  ///< equal for installed_length_mm
  std::optional<double> max_outer_m, min_inner_m;
  std::optional<double> min_index, max_index;
  double coil_step_m = 0.5e-3;
  std::optional<double> min_active_coils, max_active_coils;
  double active_coil_step = 0.5;
  std::optional<std::string> ends;  ///< as written; checked against the end types
  std::string objective = "mass";
  double free_length_step_m = 1e-4;
  std::optional<double> mass_without_spring_kg;
  double end_fixation = 0.5;
  int candidates = 5;
  int verify = 10;
  std::optional<double> closed_load_N, open_load_N;    ///< P₁, P₂
  std::optional<double> rate_N_m;                      ///< or the rate
  std::optional<double> stroke_m;                      ///< default: the lift's largest
  std::optional<double> tensile_Pa, shear_modulus_Pa;  ///< a stated wire
  std::optional<double> allowable_fraction;
  std::optional<StressFactor> stress_factor;
  std::optional<FatigueCriterion> fatigue_criterion;
};

}  // namespace needle
