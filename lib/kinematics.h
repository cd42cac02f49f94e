#pragma once
/// @file
/// Needle kinematics at a crank speed n (docs/model.md §1–2), with ω = 2πn/60 rad/s:
///
///     t = (θ − θ_open)/ω,   v = ω·ds/dθ,   a = ω²·d²s/dθ²,   j = ω³·d³s/dθ³,
///     injection period T = (θ_close − θ_open)/ω  (= open lift in degrees / (6n)),
///     mean lift s̄ = (1/(θ_close − θ_open))∫s dθ,  ρ = s_max / s̄  (Basu: 2.12),
///
/// every extreme taken over the open lift [θ_open, θ_close] only (lib/lift_law.h).

#include <optional>
#include <string>
#include <vector>

#include "lib/lift_law.h"
#include "lib/result_fields.h"

namespace needle {

/// One row of a kinematics table (SI).
struct KinematicsPoint {
  double crank_rad = 0.0;     ///< θ, rad
  double time_s = 0.0;        ///< t = (θ − θ_open)/ω, s
  double lift_m = 0.0;        ///< s(θ), m
  double velocity_m_s = 0.0;  ///< ω s'(θ), m/s
  /// ω² s''(θ), m/s²; empty for C¹ splines (pchip, makima).
  std::optional<double> acceleration_m_s2;
  /// ω³ s'''(θ), m/s³ (piecewise constant for cubics); empty for C¹ splines.
  std::optional<double> jerk_m_s3;
};

/// The whole-lift quantities of `needle kinematics --json`.
struct KinematicsSummary {
  double speed_rpm = 0.0;
  double open_rad = 0.0;   ///< θ_open, rad
  double close_rad = 0.0;  ///< θ_close, rad
  double injection_period_s = 0.0;
  double max_lift_m = 0.0;
  double max_lift_rad = 0.0;
  double mean_lift_m = 0.0;
  double rho = 0.0;  ///< max lift / mean lift
  double max_velocity_m_s = 0.0;
  double max_velocity_rad = 0.0;
  double min_velocity_m_s = 0.0;
  double min_velocity_rad = 0.0;
  std::optional<double> max_acceleration_m_s2, max_acceleration_rad;
  std::optional<double> min_acceleration_m_s2, min_acceleration_rad;
  /// 95 % bands of the two extremes from the table's accuracy (LiftLaw::AccelerationBand), m/s².
  std::optional<ExtremumBand> max_acceleration_band_m_s2, min_acceleration_band_m_s2;
};

/// The band around `value`, `decimals` after the point: " ± h" when its two ends are as far
/// from it ("a_max 535 ± 6 m/s²"), else " +a/-b", the reach above and below ("51.96 +0.00/-32.17":
/// the JSON's [19.79, 51.96]); empty without a band.
std::string PlusMinus(double value, const std::optional<ExtremumBand>& band, int decimals);

/// The decimals the two acceleration extremes print with: 2, or as many as show the larger one
/// to 2 significant digits (a table run at 1 rpm read "0.00 ± 0.00 m/s^2").
int AccelerationDecimals(const KinematicsSummary& s);

class Kinematics {
 public:
  /// `law` must outlive this object. speed_rpm must be positive and finite
  /// (throws std::invalid_argument otherwise).
  Kinematics(const LiftLaw& law, double speed_rpm);

  KinematicsPoint At(double crank_rad) const;
  KinematicsSummary Summarize() const;

  double speed_rpm() const { return speed_rpm_; }
  /// ω, rad/s.
  double omega() const { return omega_; }
  const LiftLaw& law() const { return law_; }

 private:
  const LiftLaw& law_;
  double speed_rpm_;
  double omega_;
};

/// The summary as fields (lib/result_fields.h): open and close (deg), the injection period (s),
/// the lift's, velocity's and acceleration's extremes and where they are, ρ. Every writer's
/// JSON keys (`max_lift_mm`, `max_lift_deg`, …) and text values come from here; the bands
/// (`max_acceleration_band_m_s2` = [low, high]) only where the law has them.
std::vector<Field> KinematicsFields(const KinematicsSummary& s);

/// The lift law's own fields beside the summary: its spline's name, its closed level (mm) and the
/// spline's largest dip below the seat inside the open lift (mm) and where (deg; none without a
/// dip).
std::vector<Field> LiftLawFields(const LiftLaw& law);

/// The table's columns: crank (deg), time (s), lift (mm), velocity (m/s), acceleration
/// (m/s²), jerk (m/s³).
const std::vector<Column>& KinematicsColumns();

/// One row's SI values in KinematicsColumns()' order; NaN where a derivative is missing.
std::vector<double> KinematicsRowSi(const KinematicsPoint& p);

}  // namespace needle
