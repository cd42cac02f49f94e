#pragma once
/// @file
/// Units at the edges of needle. Everything inside is SI (m, s, kg, N, rad); case-file
/// keys carry their unit as a suffix (`lift_mm`, `preload_kgf`) and are converted here:
///
///     value_SI = value_in_unit · factor(unit),   e.g. 1 kgf = 9.80665 N, 1 deg = π/180 rad.

#include <string>
#include <vector>

namespace needle {

/// Standard gravity, m/s² (defines the kilogram-force: 1 kgf = kStandardGravity N).
constexpr double kStandardGravity = 9.80665;
/// One kilogram-force in newtons.
constexpr double kKgf = kStandardGravity;
constexpr double kPi = 3.14159265358979323846;
/// Radians per degree.
constexpr double kDeg = kPi / 180.0;

/// Crank angular speed ω in rad/s from a speed in rpm: ω = 2πn/60. Valid for n ≥ 0.
inline double OmegaFromRpm(double speed_rpm) { return 2.0 * kPi * speed_rpm / 60.0; }

/// The physical dimension a case-file quantity has; each has its own unit suffixes.
enum class Dimension {
  kNone,           ///< dimensionless, key without suffix
  kAngle,          ///< deg, rad
  kLength,         ///< m, cm, mm, um
  kRotationSpeed,  ///< rpm
  kVelocity,       ///< m_s, cm_s, dcm_s, mm_s
  kAcceleration,   ///< m_s2
  kMass,           ///< kg, g
  kForce,          ///< N, kN, kgf
  kStiffness,      ///< N_m, N_mm, kN_mm, kgf_mm, kgf_cm
  kTime,           ///< s, ms
  kPressure,       ///< Pa, kPa, MPa, GPa, bar, atm, kgf_cm2
  kDensity,        ///< kg_m3, g_cm3
  kSlope,          ///< length per crank angle: mm_deg, mm_rad, m_rad
  kPercent,        ///< percent (converted to a fraction)
  kTemperature,    ///< C, K (converted to kelvin)
  kArea,           ///< mm2, cm2, m2
  kVolume,         ///< cm3, m3
  kPower,          ///< hp (metric horsepower, 735.49875 W), kW
  kSpecificFuel,   ///< g_hp_h (grams per metric horsepower-hour), kept in g/(hp·h)
  kSlope2,         ///< length per angle²: mm_rad2, m_rad2 (a cam law's S'')
  kSlope3,         ///< length per angle³: mm_rad3, m_rad3 (a cam law's S''')

};

/// Name of a dimension for messages ("length", "force", …).
std::string DimensionName(Dimension dimension);

/// The unit suffixes a dimension accepts, in the order shown to users.
std::vector<std::string> UnitSuffixes(Dimension dimension);

/// Converts `value` given in `unit` of `dimension` to SI. Throws std::invalid_argument
/// when the unit is not one of UnitSuffixes(dimension). Temperatures in C gain 273.15.
double ToSi(Dimension dimension, const std::string& unit, double value);

/// ToSi for many values of one unit, the unit looked up once: (*this)(v) is ToSi's bits.
struct SiConversion {
  double factor = 1.0;   ///< SI per unit
  bool celsius = false;  ///< a temperature in C: v + 273.15 instead
  double operator()(double value) const { return celsius ? value + 273.15 : value * factor; }
};
/// The conversion of `unit` of `dimension` (throws as ToSi).
SiConversion SiConversionOf(Dimension dimension, const std::string& unit);

/// Converts an SI value back to `unit` (inverse of ToSi).
double FromSi(Dimension dimension, const std::string& unit, double value_si);

}  // namespace needle
