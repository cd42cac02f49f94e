#pragma once
/// @file
/// The needle train's force balance as a rigid body on the cam (docs/model.md §6), written
/// once for everyone who needs it (the quasi-static check, the cam synthesis' spring reserve
/// and its contact stress):
///
///     F_spring(s) = P₀ + k·s − F_g,            the spring's net closing force at lift s,
///     F_c(s, a)   = m·a + P₀ + k·s − F_g,      the cam–roller contact force, a = ω²·s''.
///
/// The needle stays on the cam while F_c ≥ 0; where it decelerates (a < 0) the spring
/// reserve K = F_spring/(m·|a|) says how many times the spring exceeds the inertia force.

namespace needle {

/// The train as the quasi-static check sees it. All SI.
struct RigidTrain {
  double mass_kg = 0.0;      ///< moving mass m, kg, > 0
  double preload_N = 0.0;    ///< spring preload P₀ at the seat, N, ≥ 0
  double rate_N_m = 0.0;     ///< spring rate k, N/m, ≥ 0
  double gas_force_N = 0.0;  ///< F_g, N, opening positive, finite

  /// Throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;

  /// P₀ + k·s − F_g in N at lift s (m).
  double SpringForceN(double lift_m) const { return preload_N + rate_N_m * lift_m - gas_force_N; }

  /// m·a + P₀ + k·s − F_g in N at lift s (m) and needle acceleration a (m/s²).
  double ContactForceN(double lift_m, double acceleration_m_s2) const {
    return mass_kg * acceleration_m_s2 + preload_N + rate_N_m * lift_m - gas_force_N;
  }

  /// K = F_spring(s)/(m·|a|) where a < 0, dimensionless; +∞ where a ≥ 0.
  double SpringReserve(double lift_m, double acceleration_m_s2) const;
};

}  // namespace needle
