#include "lib/rigid_train.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace needle {

void RigidTrain::Validate() const {
  if (!(mass_kg > 0.0) || !std::isfinite(mass_kg)) {
    throw std::invalid_argument("mass must be positive, got " + std::to_string(mass_kg) + " kg");
  }
  if (!(preload_N >= 0.0) || !std::isfinite(preload_N)) {
    throw std::invalid_argument("preload must not be negative, got " + std::to_string(preload_N) +
                                " N");
  }
  if (!(rate_N_m >= 0.0) || !std::isfinite(rate_N_m)) {
    throw std::invalid_argument("spring rate must not be negative, got " +
                                std::to_string(rate_N_m) + " N/m");
  }
  if (!std::isfinite(gas_force_N)) throw std::invalid_argument("gas force must be finite");
}

double RigidTrain::SpringReserve(double lift_m, double acceleration_m_s2) const {
  if (!(acceleration_m_s2 < 0.0)) return std::numeric_limits<double>::infinity();
  return SpringForceN(lift_m) / (mass_kg * -acceleration_m_s2);
}

}  // namespace needle
