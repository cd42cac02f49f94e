#pragma once
/// @file
/// Basu's empirical valve-spring preload (NACA TM 477; docs/model.md §7):
///
///     P = (π d²/4) · p_c · 1.6 · (1/t)^(1/4)   [kgf],
///
/// d the needle diameter in cm, p_c = 35 kg/cm² the combustion pressure, t the injection
/// period in seconds (lift duration in crank degrees over 6n). The first factor holds the
/// needle shut against combustion; 1.6·t^(−1/4) stands for the inertia of needle and disks.

namespace needle {

/// Combustion pressure of the formula, kg/cm² (Basu: 35).
constexpr double kBasuCombustionPressureKgCm2 = 35.0;
/// Safety factor of the formula (Basu: 1.6).
constexpr double kBasuFactor = 1.6;

/// Basu's preload in N. needle_diameter_m > 0, injection_period_s > 0 (throws
/// std::invalid_argument naming the value otherwise).
double BasuPreloadN(double needle_diameter_m, double injection_period_s,
                    double combustion_pressure_kg_cm2 = kBasuCombustionPressureKgCm2,
                    double factor = kBasuFactor);

}  // namespace needle
