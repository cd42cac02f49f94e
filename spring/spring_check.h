#pragma once
/// @file
/// The spring check of a case at one speed (what `needle spring` prints and `needle check`
/// reports): Basu's formula beside the case's spring, the inertia force m·max|a|, the
/// quasi-static contact force and lift-off speed, the preload sizing, the helical check.
///
/// A passing check means all of (docs/model.md §7): the preload withstands the combustion load
/// with the safety factor, P₀ ≥ S·F_g; the preload is not below Basu's formula by more than
/// `basu_tolerance_percent` (10 % by default: Basu found built springs within 3 % of it, and his
/// own Example 2 adopts 176 kgf against the formula's 185 kgf, −5 %, so a tolerance must allow
/// the paper's own design, with a margin, and no more); the inertia sizing P₀ ≥ P₀,req; and the
/// helical checks.

#include <optional>
#include <string>
#include <vector>

#include "lib/case_error.h"
#include "lib/kinematics.h"
#include "spring/helical_spring.h"
#include "spring/quasi_static.h"
#include "spring/spring_parameters.h"

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
  /// n_qs's 95 % band from the lift table's accuracy (QuasiStaticLiftoffBand), rpm.
  std::optional<ExtremumBand> liftoff_rpm_quasi_static_band;
  double required_preload_N = 0.0;
  /// P₀,req at the acceleration band's unsafe end (RequiredPreloadUnsafeN), N: the inertia
  /// sizing is judged there, and undecided where the preload lies between the two.
  std::optional<double> required_preload_unsafe_N;
  double preload_margin_percent = 0.0;  ///< +∞ when nothing is required
  /// 100·(P₀ − P₀,req at the unsafe end)/P₀,req there, %: the margin the verdict reads; none
  /// without a band or where nothing is required there.
  std::optional<double> preload_margin_unsafe_percent;
  bool preload_ok = false;
  /// Whether the lift decelerates anywhere (s'' < 0): a table that never does (it stops before
  /// the lift's top, or holds two readings) leaves the inertia sizing undecided, and failed.
  bool decelerates = false;
  /// UnresolvedSides of the lift table (lib/lift_data.h): a rise or return of too few readings
  /// to resolve its acceleration leaves the inertia sizing undecided, and failed. Empty if none.
  std::string unresolved;
  double gas_force_N = 0.0;                ///< F_g, the combustion load
  std::string gas_source;                  ///< where F_g comes from
  double combustion_margin_percent = 0.0;  ///< 100·(P₀ − S·F_g)/(S·F_g); +∞ when F_g ≤ 0
  bool combustion_ok = true;               ///< P₀ ≥ S·F_g
  double safety_factor = 1.5;              ///< S of the combustion load and the sizing
  std::optional<double> basu_deviation_percent;  ///< 100·(P₀ − P_Basu)/P_Basu
  double basu_tolerance_percent = 10.0;
  bool basu_ok = true;  ///< deviation ≥ −tolerance (true without a diameter)
  std::optional<HelicalSpringCheck> helical;
  std::vector<std::string> failures;  ///< one line per failing sub-check, with its margin
  /// Inputs that look like a slip of unit, one line each (PreloadSlip); they judge nothing.
  std::vector<std::string> warnings;
  bool pass = false;
};

/// Whether the inertia sizing is undecided within the table's accuracy: the lift decelerates,
/// every side of it is resolved, and the preload meets the fitted lift's requirement but not the
/// one at its acceleration band's unsafe end.
bool UndecidedWithinAccuracy(const SpringCheckResult& r);

/// What the preload's margin over the fitted lift's need leaves out: " of a lift the table does
/// not resolve" (UnresolvedSides), or where the sizing is undecided within the table's accuracy
/// " of the fitted lift, -1.4 % at its acceleration band's unsafe end"; empty otherwise.
std::string PreloadMarginNote(const SpringCheckResult& r);

/// A preload above 3 times the largest rule that asks for one (Basu's formula, the combustion
/// load's S·F_g, the inertia sizing's P₀,req) is most often a slip of unit: the warning names
/// the ratio and, where dividing by it brings the preload within 3 times of that rule, the slip
/// ("9.81×: kgf for N?", kN for N, lbf for N). nullopt below 3 times, or with no rule.
std::optional<std::string> PreloadSlip(const SpringCheckResult& r);

/// The failing sub-checks of `r`, one line each with its margin, from its sub-verdicts. With
/// `surge_screen` false the helical check's f_e/f_cam ≥ 13 item is left out: a caller that has
/// judged surge by its effect in the dynamics (apps/study/check_scene.h) makes it a warning.
std::vector<std::string> SpringFailures(const SpringCheckResult& r, bool surge_screen = true);

/// The check as fields (lib/result_fields.h): Basu's preload and the case's (kgf) and their
/// deviation (%), the largest |a| and where, the inertia force (kgf), the rate (N/mm), the
/// least quasi-static force and where, n_qs (none when the needle never decelerates), the
/// required preload (N and kgf) and the margins (%; none when unbounded), the combustion load,
/// each sub-verdict and the whole. The helical check's are HelicalFields.
std::vector<Field> SpringCheckFields(const SpringCheckResult& r);

/// The check at `speed_rpm` of `spring` on `needle` driven by `law` (C²), the cam at half
/// crank speed when `four_stroke`. Throws CaseError prefixed with `where` (the case file) when
/// the law has no acceleration, the helical geometry is impossible or a quantity overflows.
SpringCheckResult CheckSpring(const NeedleParameters& needle, const SpringParameters& spring,
                              const LiftLaw& law, double speed_rpm, EngineCycle cycle,
                              const std::string& where);

}  // namespace needle
