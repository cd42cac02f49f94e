#pragma once
/// @file
/// Case files: one scene per TOML file, every dimensional key carrying its unit as a
/// suffix (`speed_rpm`, `lift_mm`, `crank_deg`, `preload_kgf` or `preload_N`, …).
/// Values are converted to SI on reading (lib/units.h); nothing downstream sees units.
///
///     title = "…"                      optional
///     [engine]  speed_rpm, cycle = "four-stroke" | "two-stroke"
///     [lift]    crank_deg + lift_mm  |  csv = "file.csv"  |  normal_curve = "basu" + max_lift_mm
///               spline = natural | not-a-knot | clamped | quintic | pchip | makima | smoothing
///                        (default: chosen from the data, lib/lift_data.h)
///               noise_mm (σ of the readings; estimated for a dense table when absent)
///               resolution_mm = 0.01 (table rounding; σ = resolution/√12 for smoothing)
///               open_deg, close_deg (the open lift; detected when absent)
///               end_slope = "at-rest" | end_slope_mm_deg = [start, end]   (clamped only)
///               smoothing = "discrepancy" (default) | "gcv"              (smoothing only)
///               outliers = "refuse" (default) | "drop"   (dense measured data: a reading far out
///               of
///                        its neighbourhood refuses the case, or is left out with a warning)
///     [needle]  mass_kg, diameter_mm, gas_force_N | combustion_pressure_bar (or _kgf_cm2, _MPa…);
///               default gas load: Basu's 35 kg/cm² on the needle diameter, 0 without one
///     [spring]  preload_kgf | preload_N, rate_N_mm (or from the geometry), safety_factor = 1.5,
///               overspeed_factor = 1.2; helical geometry: wire_mm, coil_mm (mean),
///               active_coils, free_length_mm, shear_modulus_GPa, density_kg_m3 = 7850,
///               tensile_MPa, ends = "closed-ground" | "closed" | "open-ground" | "open",
///               stress_correction = "bergstrasser" | "wahl" | "direct-shear",
///               fatigue_criterion = "goodman-zimmerli" | "gerber" | "asme-elliptic" | "sines" |
///               "bhandari", allowable_stress_fraction = 0.5,
///               grade = "SH" | "DH" | "VDC" | "VDCrV" | "VDSiCr" (R_m and G), shot_peened = false;
///               in the dynamics (helical only): masses = 1 (coil masses), surge_damping_ratio = 0,
///               clash = false, clash_stiffness_N_m (= k_c), clash_damping_ratio (= ζ_c)
///     [train]   contact = "compliant" | "rigid"; compliant: contact_stiffness_N_m (k_c),
///               contact_damping_ratio = 0.05, seat_stiffness_N_m (= k_c), seat_damping_ratio =
///               0.05; rigid: restitution = 0, seat_restitution = 0; play_mm = 0,
///               ramp = "tangent" | ramp_deg
///     [solver]  method = "auto" | a method of the method table (MethodList()), rtol = 1e-8,
///     atol_mm,
///               max_steps = 2e6, max_events = 1e5, max_seconds = 60 (0: none), start_deg,
///               end_deg (window),
///               settle_deg = 3600 (past the window, the most run while the needle settles),
///               cycles = 1 (cam revolutions back to back), period_tolerance = 1e-6
///     [overspeed] from_rpm, to_rpm, steady_state = false (judge the revolutions after the
///               first: needs cycles ≥ 2)
///     [tolerance] lift_mm = 0.01, lift_correlation_deg = 0, mass_percent, preload_percent,
///               rate_percent, stiffness_percent, play_mm, speed_percent (all 0 but the lift):
///               one standard deviation of each input's scatter (`needle tolerance`)
///     [paper]   published values to compare with: crank_deg + velocity_dcm_s (magnitudes),
///               max_acceleration_m_s2, inertia_force_kgf, mean_lift_mm
///
/// Every problem is reported as one CaseError line: "FILE: [section] key: what was expected".
/// Every physical key has a plausible range (apps/case/plausible_ranges.h, docs/ranges.md),
/// checked as its section is finished.

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/case/case_sections.h"
#include "apps/case/sizing_section.h"
#include "apps/case/synthesis_file.h"
#include "dynamics/simulation.h"
#include "lib/case_error.h"
#include "lib/engine_cycle.h"
#include "lib/follower.h"
#include "lib/lift_data.h"
#include "lib/lift_law.h"
#include "lib/spline.h"
#include "spring/design_chain.h"
#include "spring/spring_parameters.h"

namespace needle {

struct LiftSection {
  LiftTable table;       ///< the lift table in SI (from crank_deg/lift_mm, csv or the normal curve)
  SplineOptions spline;  ///< spline kind and its options
  bool spline_given = false;      ///< `spline` stated (else chosen from the data: lib/lift_data.h)
  double resolution_m = 1e-5;     ///< rounding of the table's lifts, m (paper: 0.01 mm)
  bool resolution_given = false;  ///< `resolution_mm` stated
  std::optional<double> noise_m;  ///< `noise_mm`: σ of the readings, m
  std::optional<double> open_rad, close_rad;  ///< `open_deg`, `close_deg`: the open lift
  std::vector<double> breaks_rad;  ///< `breaks_deg`: where s'' jumps (a cam of arcs), rad
  /// `breaks_deg` stated (also as []): the breaks are not sought in the table (FindBreaks).
  bool breaks_given = false;
  std::string source;  ///< "table", "csv FILE" or "basu normal curve"
  /// `outliers = "drop"`: outliers of measured data are left out with a warning (default
  /// "refuse": the case is refused naming the first; lib/lift_data.h FindOutliers).
  bool drop_outliers = false;
  std::string csv_path;    ///< the CSV file the table was read from (empty: not from a CSV)
  std::vector<int> lines;  ///< the CSV file's line of each reading (empty: not from a CSV)
  std::string lift_key = "lift_mm";  ///< the key of the lifts, as written (`lift_um`, …)
};

/// [solver]: how the dynamics is integrated, read straight into the run options
/// (dynamics/simulation.h: method, rtol, atol, the budgets, settle, cycles, the period
/// tolerance; the defaults are theirs), and the window override.
struct SolverSection {
  /// atol_m: atol_mm's, else DefaultAtol(rtol), set by the reader (a caller that changes rtol
  /// in code sets atol_m too).
  SimulationOptions run;
  bool atol_given = false;                   ///< atol_mm stated
  std::optional<double> start_rad, end_rad;  ///< window override
};

/// The case's [needle] and [spring] are the spring module's parameters.
using NeedleSection = NeedleParameters;
using SpringSection = SpringParameters;

/// The file model: the sections as read (CaseSections), the lift table and its rule, and
/// [solver].
struct Case : CaseSections {
  LiftSection lift;
  std::optional<SolverSection> solver;
};

/// Reads an engine file for the design chain; throws CaseError like LoadCase.
DesignInputs LoadDesignInputs(const std::string& path);
DesignInputs ParseDesignInputs(const std::string& text, const std::string& path);

/// Reads and validates a case file. Throws CaseError (one line) on any problem: unreadable
/// file, malformed TOML, missing or unknown keys, unknown unit suffixes, wrong types,
/// non-increasing angles, NaN, negative lift, too few points for the spline kind.
Case LoadCase(const std::string& path);

/// As LoadCase, from text already in memory; `path` is used in messages only.
Case ParseCase(const std::string& text, const std::string& path);

/// The spline, noise and open-lift rule for the case's lift data (lib/lift_data.h).
LiftLawChoice CaseLiftChoice(const Case& c);

/// True when `path` ends in ".csv" (any case): a bare lift table rather than a case file.
bool IsCsvPath(const std::string& path);

/// A case made of a bare CSV lift table (ReadLiftCsv) and nothing else: speed 0 (the caller
/// states it), `cycle` as given, the spline chosen from the data.
Case CaseFromLiftCsv(const std::string& path, EngineCycle cycle);

/// A case's lift resolved once: the spline, noise and open-lift rule chosen for its data, and
/// the law built on that choice (what a job needs of [lift]).
struct CaseLift {
  LiftLawChoice choice;
  std::shared_ptr<const LiftLaw> law;
};

/// The choice (CaseLiftChoice) made once and the law built from it, turning
/// spline-construction failures into CaseError.
CaseLift ResolveLift(const Case& c);

/// Builds the lift law of a case: ResolveLift's law.
LiftLaw MakeLiftLaw(const Case& c);

/// Checks that `kind` can be built on the case's table (enough points); throws CaseError
/// naming `where` (e.g. "--spline" or "[lift] spline") otherwise.
void CheckSplineFits(const Case& c, SplineKind kind, const std::string& where);

}  // namespace needle
