#include "dynamics/model/contact_law.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace needle {

double ContactLaw::GatedForce(double g, double g_rate) const {
  return g > 0.0 ? std::max(0.0, Force(g, g_rate)) : 0.0;  // max(0, F) for g > 0
}

CompliantContact::CompliantContact(double stiffness_N_m, double damping_ratio, double mass_kg)
    : k_(stiffness_N_m), c_(2.0 * damping_ratio * std::sqrt(stiffness_N_m * mass_kg)) {
  if (!(stiffness_N_m > 0.0) || !(damping_ratio >= 0.0) || !(mass_kg > 0.0)) {
    throw std::invalid_argument("CompliantContact: stiffness " + std::to_string(stiffness_N_m) +
                                " N/m, damping ratio " + std::to_string(damping_ratio) + ", mass " +
                                std::to_string(mass_kg) +
                                " kg: stiffness and mass must be positive, ζ ≥ 0");
  }
}

double CompliantContact::Potential(double g) const {
  const double gp = std::max(0.0, g);
  return 0.5 * k_ * gp * gp;
}

RigidContact::RigidContact(double restitution) : e_(restitution) {
  if (!(restitution >= 0.0 && restitution <= 1.0)) {
    throw std::invalid_argument("RigidContact: restitution " + std::to_string(restitution) +
                                ": must be in [0, 1]");
  }
}

}  // namespace needle
