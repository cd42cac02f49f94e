#pragma once
/// @file
/// The spring check of a case at one speed (what `needle spring` prints and `needle check`
/// reports): Basu's formula beside the case's spring, the inertia force m·max|a|, the
/// quasi-static contact force and lift-off speed, the preload sizing, the helical check.

#include <optional>

#include "lib/case_file.h"
#include "lib/kinematics.h"
#include "spring/helical_spring.h"
#include "spring/quasi_static.h"

namespace needle {

struct SpringCheckResult {
  double speed_rpm = 0.0;
  KinematicsSummary kinematics;
  double max_abs_acceleration_m_s2 = 0.0, max_abs_acceleration_rad = 0.0;
  double inertia_force_N = 0.0;
  std::optional<double> basu_preload_N;  ///< when [needle] gives the diameter
  RigidTrain train;                      ///< rate from [spring] or the helical geometry
  ForceMinimum min_quasi_static;
  double liftoff_rpm_quasi_static = 0.0;  ///< +∞ when the needle never decelerates
  double required_preload_N = 0.0;
  double preload_margin_percent = 0.0;  ///< +∞ when nothing is required
  bool preload_ok = false;
  std::optional<HelicalSpringCheck> helical;
  bool pass = false;
};

/// Needs [needle] and [spring] and a C² lift law; throws CaseError naming what is missing.
SpringCheckResult CheckSpring(const Case& c, const LiftLaw& law, double speed_rpm);

}  // namespace needle
