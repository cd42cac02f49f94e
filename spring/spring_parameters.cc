#include "spring/spring_parameters.h"

#include <cmath>

#include "lib/field_error.h"

namespace needle {

void NeedleParameters::Validate() const {
  const FieldRules require{"NeedleParameters"};
  require(mass_kg > 0.0 && std::isfinite(mass_kg), "mass_kg", mass_kg, "must be positive");
  if (diameter_m)
    require(*diameter_m > 0.0 && std::isfinite(*diameter_m), "diameter_m", *diameter_m,
            "must be positive");
  require(std::isfinite(gas_force_N), "gas_force_N", gas_force_N, "must be finite");
}

void SpringParameters::Validate() const {
  const FieldRules require{"SpringParameters"};
  require(preload_N >= 0.0 && std::isfinite(preload_N), "preload_N", preload_N,
          "must not be negative");
  if (rate_N_m)
    require(*rate_N_m >= 0.0 && std::isfinite(*rate_N_m), "rate_N_m", *rate_N_m,
            "must not be negative");
  require(safety_factor >= 1.0, "safety_factor", safety_factor, "must be at least 1");
  require(overspeed_factor >= 1.0, "overspeed_factor", overspeed_factor, "must be at least 1");
  require(basu_tolerance_percent >= 0.0 && basu_tolerance_percent <= 100.0,
          "basu_tolerance_percent", basu_tolerance_percent, "must be in [0, 100]");
  require(surge_damping_ratio >= 0.0 && surge_damping_ratio <= 1.0, "surge_damping_ratio",
          surge_damping_ratio, "must be in [0, 1]");
  if (clash_stiffness_N_m)
    require(*clash_stiffness_N_m > 0.0 && std::isfinite(*clash_stiffness_N_m),
            "clash_stiffness_N_m", *clash_stiffness_N_m, "must be positive");
  if (clash_damping_ratio)
    require(*clash_damping_ratio >= 0.0 && *clash_damping_ratio <= 1.0, "clash_damping_ratio",
            *clash_damping_ratio, "must be in [0, 1]");
}

}  // namespace needle
