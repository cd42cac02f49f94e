#include "spring/basu_formula.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/units.h"

namespace needle {

double BasuPreloadN(double needle_diameter_m, double injection_period_s,
                    double combustion_pressure_kg_cm2, double factor) {
  if (!(needle_diameter_m > 0.0) || !std::isfinite(needle_diameter_m)) {
    throw std::invalid_argument("Basu's formula: the needle diameter must be positive, got " +
                                std::to_string(needle_diameter_m * 1e3) + " mm");
  }
  if (!(injection_period_s > 0.0) || !std::isfinite(injection_period_s)) {
    throw std::invalid_argument("Basu's formula: the injection period must be positive, got " +
                                std::to_string(injection_period_s) + " s");
  }
  const double d_cm = needle_diameter_m * 100.0;
  const double area_cm2 = kPi * d_cm * d_cm / 4.0;  // π d²/4
  const double p_kgf = area_cm2 * combustion_pressure_kg_cm2 * factor *
                       std::pow(1.0 / injection_period_s, 0.25);  // · 35 · 1.6 · (1/t)^¼
  return p_kgf * kKgf;
}

}  // namespace needle
