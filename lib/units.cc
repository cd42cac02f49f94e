#include "lib/units.h"

#include <stdexcept>
#include <utility>

namespace needle {
namespace {

struct Unit {
  const char* suffix;
  double factor;  // SI value of one unit
};

// One metric horsepower in watts.
constexpr double kMetricHp = 735.49875;

std::vector<Unit> Units(Dimension dimension) {
  switch (dimension) {
    case Dimension::kNone:
      return {};
    case Dimension::kAngle:
      return {{"deg", kDeg}, {"rad", 1.0}};
    case Dimension::kLength:
      return {{"mm", 1e-3}, {"cm", 1e-2}, {"m", 1.0}, {"um", 1e-6}};
    case Dimension::kRotationSpeed:
      return {{"rpm", 1.0}};
    case Dimension::kVelocity:
      return {{"m_s", 1.0}, {"cm_s", 1e-2}, {"dcm_s", 1e-1}, {"mm_s", 1e-3}};
    case Dimension::kAcceleration:
      return {{"m_s2", 1.0}};
    case Dimension::kMass:
      return {{"kg", 1.0}, {"g", 1e-3}};
    case Dimension::kForce:
      return {{"N", 1.0}, {"kN", 1e3}, {"kgf", kKgf}};
    case Dimension::kStiffness:
      return {{"N_m", 1.0},
              {"N_mm", 1e3},
              {"kN_mm", 1e6},
              {"kgf_mm", kKgf * 1e3},
              {"kgf_cm", kKgf * 1e2}};
    case Dimension::kTime:
      return {{"s", 1.0}, {"ms", 1e-3}};
    case Dimension::kPressure:
      return {{"Pa", 1.0},  {"kPa", 1e3},      {"MPa", 1e6},           {"GPa", 1e9},
              {"bar", 1e5}, {"atm", 101325.0}, {"kgf_cm2", kKgf * 1e4}};
    case Dimension::kDensity:
      return {{"kg_m3", 1.0}, {"g_cm3", 1e3}};
    case Dimension::kSlope:
      return {{"mm_deg", 1e-3 / kDeg}, {"mm_rad", 1e-3}, {"m_rad", 1.0}};
    case Dimension::kPercent:
      return {{"percent", 1e-2}};
    case Dimension::kTemperature:
      return {{"C", 1.0}, {"K", 1.0}};
    case Dimension::kArea:
      return {{"mm2", 1e-6}, {"cm2", 1e-4}, {"m2", 1.0}};
    case Dimension::kVolume:
      return {{"cm3", 1e-6}, {"m3", 1.0}};
    case Dimension::kPower:
      return {{"hp", kMetricHp}, {"kW", 1e3}};
    case Dimension::kSpecificFuel:
      return {{"g_hp_h", 1.0}};
    case Dimension::kSlope2:
      return {{"mm_rad2", 1e-3}, {"m_rad2", 1.0}};
    case Dimension::kSlope3:
      return {{"mm_rad3", 1e-3}, {"m_rad3", 1.0}};
  }
  return {};
}

double Factor(Dimension dimension, const std::string& unit) {
  for (const Unit& u : Units(dimension)) {
    if (unit == u.suffix) return u.factor;
  }
  std::string known;
  for (const std::string& s : UnitSuffixes(dimension)) known += (known.empty() ? "" : ", ") + s;
  throw std::invalid_argument("unit '" + unit + "' is not a unit of " + DimensionName(dimension) +
                              " (known: " + known + ")");
}

}  // namespace

std::string DimensionName(Dimension dimension) {
  switch (dimension) {
    case Dimension::kNone:
      return "a dimensionless number";
    case Dimension::kAngle:
      return "angle";
    case Dimension::kLength:
      return "length";
    case Dimension::kRotationSpeed:
      return "rotation speed";
    case Dimension::kVelocity:
      return "velocity";
    case Dimension::kAcceleration:
      return "acceleration";
    case Dimension::kMass:
      return "mass";
    case Dimension::kForce:
      return "force";
    case Dimension::kStiffness:
      return "stiffness";
    case Dimension::kTime:
      return "time";
    case Dimension::kPressure:
      return "pressure";
    case Dimension::kDensity:
      return "density";
    case Dimension::kSlope:
      return "slope";
    case Dimension::kPercent:
      return "percentage";
    case Dimension::kTemperature:
      return "temperature";
    case Dimension::kArea:
      return "area";
    case Dimension::kVolume:
      return "volume";
    case Dimension::kPower:
      return "power";
    case Dimension::kSpecificFuel:
      return "specific fuel consumption";
    case Dimension::kSlope2:
      return "second derivative of lift by angle";
    case Dimension::kSlope3:
      return "third derivative of lift by angle";
  }

  return "?";
}

std::vector<std::string> UnitSuffixes(Dimension dimension) {
  std::vector<std::string> out;
  for (const Unit& u : Units(dimension)) out.emplace_back(u.suffix);
  return out;
}

SiConversion SiConversionOf(Dimension dimension, const std::string& unit) {
  // T[K] = t[°C] + 273.15
  return {Factor(dimension, unit), dimension == Dimension::kTemperature && unit == "C"};
}

double ToSi(Dimension dimension, const std::string& unit, double value) {
  return SiConversionOf(dimension, unit)(value);
}

double FromSi(Dimension dimension, const std::string& unit, double value_si) {
  const double factor = Factor(dimension, unit);
  if (dimension == Dimension::kTemperature && unit == "C") return value_si - 273.15;
  return value_si / factor;
}

}  // namespace needle
