#include "lib/kinematics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "lib/output.h"
#include "lib/units.h"

namespace needle {

Kinematics::Kinematics(const LiftLaw& law, double speed_rpm)
    : law_(law), speed_rpm_(speed_rpm), omega_(OmegaFromRpm(speed_rpm)) {
  if (!(speed_rpm > 0.0) || !std::isfinite(speed_rpm)) {
    throw std::invalid_argument("speed must be a positive number of rpm, got " +
                                std::to_string(speed_rpm));
  }
}

KinematicsPoint Kinematics::At(double crank_rad) const {
  KinematicsPoint p;
  p.crank_rad = crank_rad;
  p.time_s = (crank_rad - law_.start_rad()) / omega_;  // t = (θ − θ_open)/ω
  std::array<double, 4> s{};
  law_.Derivatives(crank_rad, law_.HasAcceleration() ? 4 : 2, s.data());
  p.lift_m = s[0];                 // s
  p.velocity_m_s = omega_ * s[1];  // v = ω s'
  if (law_.HasAcceleration()) {
    p.acceleration_m_s2 = omega_ * omega_ * s[2];   // a = ω² s''
    p.jerk_m_s3 = omega_ * omega_ * omega_ * s[3];  // j = ω³ s'''
  }
  return p;
}

KinematicsSummary Kinematics::Summarize() const {
  KinematicsSummary s;
  s.speed_rpm = speed_rpm_;
  s.open_rad = law_.start_rad();
  s.close_rad = law_.end_rad();
  s.injection_period_s = (law_.end_rad() - law_.start_rad()) / omega_;  // T = Δθ/ω
  const Extremum lift = law_.Max(0);
  s.max_lift_m = lift.value;
  s.max_lift_rad = lift.crank_rad;
  s.mean_lift_m = law_.MeanLift();
  s.rho = s.max_lift_m / s.mean_lift_m;  // ρ = s_max / s̄
  const Extremum vmax = law_.Max(1), vmin = law_.Min(1);
  s.max_velocity_m_s = omega_ * vmax.value;
  s.max_velocity_rad = vmax.crank_rad;
  s.min_velocity_m_s = omega_ * vmin.value;
  s.min_velocity_rad = vmin.crank_rad;
  if (law_.HasAcceleration()) {
    const Extremum amax = law_.Max(2), amin = law_.Min(2);
    s.max_acceleration_m_s2 = omega_ * omega_ * amax.value;
    s.max_acceleration_rad = amax.crank_rad;
    s.min_acceleration_m_s2 = omega_ * omega_ * amin.value;
    s.min_acceleration_rad = amin.crank_rad;
    const double w2 = omega_ * omega_;
    if (const auto band = law_.AccelerationBand(true)) {
      s.max_acceleration_band_m_s2 = ExtremumBand{w2 * band->low, w2 * band->high};
    }
    if (const auto band = law_.AccelerationBand(false)) {
      s.min_acceleration_band_m_s2 = ExtremumBand{w2 * band->low, w2 * band->high};
    }
  }
  return s;
}

std::string PlusMinus(double value, const std::optional<ExtremumBand>& band, int decimals) {
  if (!band) return "";
  std::ostringstream up, down;
  up << std::fixed << std::setprecision(decimals) << std::max(0.0, band->high - value);
  down << std::fixed << std::setprecision(decimals) << std::max(0.0, value - band->low);
  // The band as the JSON gives it: symmetric as "± h", else its two reaches, "+a/-b".
  if (up.str() == down.str()) return " ± " + up.str();
  return " +" + up.str() + "/-" + down.str();
}

int AccelerationDecimals(const KinematicsSummary& s) {
  if (!s.max_acceleration_m_s2) return 2;
  return DecimalsFor(
      std::max(std::abs(*s.max_acceleration_m_s2), std::abs(*s.min_acceleration_m_s2)), 2, 2);
}

std::vector<Field> KinematicsFields(const KinematicsSummary& s) {
  using namespace display;
  std::vector<Field> fields = {
      {"open", kDegree, s.open_rad, 2},
      {"close", kDegree, s.close_rad, 2},
      {"injection_period", kS, s.injection_period_s, 5},
      {"max_lift", kMm, s.max_lift_m, 3},
      {"max_lift", kDegree, s.max_lift_rad, 2},
      {"mean_lift", kMm, s.mean_lift_m, 3},
      {"rho", kNone, s.rho, 3},
      {"max_velocity", kMPerS, s.max_velocity_m_s, 3},
      {"max_velocity", kDegree, s.max_velocity_rad, 2},
      {"min_velocity", kMPerS, s.min_velocity_m_s, 3},
      {"min_velocity", kDegree, s.min_velocity_rad, 2},
      {"max_acceleration", kMPerS2, s.max_acceleration_m_s2, 2},
      {"max_acceleration", kDegree, s.max_acceleration_rad, 2},
      {"min_acceleration", kMPerS2, s.min_acceleration_m_s2, 2},
      {"min_acceleration", kDegree, s.min_acceleration_rad, 2},
  };
  const std::pair<const char*, const std::optional<ExtremumBand>*> bands[] = {
      {"max_acceleration_band", &s.max_acceleration_band_m_s2},
      {"min_acceleration_band", &s.min_acceleration_band_m_s2}};
  for (const auto& [name, band] : bands) {
    if (!*band) continue;
    fields.push_back(ListField(name, kMPerS2, {(*band)->low, (*band)->high}));
    fields.back().decimals = 2;
  }
  return fields;
}

std::vector<Field> LiftLawFields(const LiftLaw& law) {
  using namespace display;
  const bool dips = law.undershoot_m() > 0;
  return {
      TextField("spline", SplineKindName(law.kind())),
      {"closed_level", kMm, law.closed_level_m(), 4},
      {"undershoot", kMm, law.undershoot_m(), 4},
      {"undershoot", kDegree, dips ? std::optional<double>(law.undershoot_rad()) : std::nullopt, 2},
  };
}

const std::vector<Column>& KinematicsColumns() {
  using namespace display;
  static const std::vector<Column> columns = {
      {"crank", kDegree},        {"time", kS},      {"lift", kMm}, {"velocity", kMPerS},
      {"acceleration", kMPerS2}, {"jerk", kMPerS3},
  };
  return columns;
}

std::vector<double> KinematicsRowSi(const KinematicsPoint& p) {
  return {p.crank_rad,
          p.time_s,
          p.lift_m,
          p.velocity_m_s,
          p.acceleration_m_s2.value_or(NAN),
          p.jerk_m_s3.value_or(NAN)};
}

}  // namespace needle
