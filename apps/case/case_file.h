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
///               stress_correction = "bergstrasser" | "wahl", allowable_stress_fraction = 0.5,
///               grade = "SH" | "DH" | "VDC" | "VDCrV" | "VDSiCr" (R_m and G), shot_peened = false;
///               in the dynamics (helical only): masses = 1 (coil masses), surge_damping_ratio = 0,
///               clash = false, clash_stiffness_N_m (= k_c), clash_damping_ratio (= ζ_c)
///     [train]   contact = "compliant" | "rigid"; compliant: contact_stiffness_N_m (k_c),
///               contact_damping_ratio = 0.05, seat_stiffness_N_m (= k_c), seat_damping_ratio =
///               0.05; rigid: restitution = 0, seat_restitution = 0; play_mm = 0,
///               ramp = "tangent" | ramp_deg
///     [solver]  method = "auto" | "dopri5" | "cvode-bdf" | "cvode-adams", rtol = 1e-8, atol_mm,
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

#include "apps/case/sizing_section.h"
#include "lib/case_error.h"
#include "lib/engine_cycle.h"
#include "lib/follower.h"
#include "lib/lift_data.h"
#include "lib/lift_law.h"
#include "lib/spline.h"
#include "spring/design_chain.h"
#include "spring/spring_parameters.h"

namespace needle {

struct EngineSection {
  double speed_rpm = 0.0;                        ///< rated crank speed, rpm, > 0
  EngineCycle cycle = EngineCycle::kFourStroke;  ///< the crank-to-cam rule (lib/engine_cycle.h)
};

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

struct PaperSection {
  std::vector<double> crank_rad;     ///< angles of the published velocities, rad
  std::vector<double> velocity_m_s;  ///< published velocity magnitudes, m/s
  std::optional<double> max_acceleration_m_s2;
  std::optional<double> inertia_force_N;
  std::optional<double> mean_lift_m;
  std::optional<double> spring_preload_N;  ///< the preload Basu's formula gave
};

/// [train]: contacts and roller play of the dynamic model (docs/model.md §3–4).
struct TrainSection {
  double contact_stiffness_N_m = 0.0;   ///< k_c, > 0 (required when compliant)
  double contact_damping_ratio = 0.05;  ///< ζ_c, ≥ 0
  double seat_stiffness_N_m = 0.0;      ///< k_s, > 0 (default: k_c)
  double seat_damping_ratio = 0.05;     ///< ζ_s, ≥ 0
  bool rigid = false;                   ///< contact = "rigid" (else "compliant")
  double restitution = 0.0;             ///< e of the rigid cam contact, [0, 1]
  double seat_restitution = 0.0;        ///< e_s of the rigid seat, [0, 1]
  double play_m = 0.0;                  ///< roller play δ, ≥ 0
  bool linear_ramp = false;             ///< `ramp_deg` given (else tangent ramps)
  double ramp_rad = 0.0;                ///< ramp length when linear
};

/// [solver]: how the dynamics is integrated.
struct SolverSection {
  std::string method = "auto";               ///< "auto", "dopri5", "cvode-bdf", "cvode-adams"
  double rtol = 1e-8;                        ///< relative tolerance
  std::optional<double> atol_m;              ///< absolute tolerance (default rtol·1 mm)
  long max_steps = 2000000;                  ///< step budget
  long max_events = 100000;                  ///< event budget
  double max_seconds = 60.0;                 ///< wall-time budget of one run, s; 0: none
  std::optional<double> start_rad, end_rad;  ///< window override
  /// Past the window's end, at most this much more while the needle settles (docs/model.md §5)
  double settle_limit_deg = 3600.0;
  int cycles = 1;                  ///< cam revolutions run back to back, [1, 1000]
  double period_tolerance = 1e-6;  ///< a cycle-end state repeats within this fraction, (0, 1e-2]
};

/// [overspeed]: the lift-off sweep.
struct OverspeedSection {
  std::optional<double> from_rpm, to_rpm;
  bool steady_state = false;  ///< judge lift-off on the steady revolutions (needs cycles ≥ 2)
};

/// [tolerance]: how the inputs scatter in a tolerance study (`needle tolerance`): each is one
/// standard deviation of a normal scatter about the nominal value; 0 leaves the input alone.
struct ToleranceSection {
  /// lift_mm: the error of each lift-table point inside the open lift, m (default 0.01 mm:
  /// Basu, NACA TM 477, "the cam is made to 0.01 mm"); [0, 1 mm].
  double lift_sigma_m = 1e-5;
  /// lift_correlation_deg: correlation length of that error along the crank angle, rad (a
  /// Gaussian kernel exp(−Δθ²/2ℓ²), tapering to zero where the lift is zero); 0: independent
  /// points; [0, 360°]. Not given: a quarter of the open lift (EffectiveTolerance), a smooth
  /// grinding error.
  double lift_correlation_rad = 0.0;
  bool lift_correlation_given = false;  ///< `lift_correlation_deg` stated
  bool given = false;                   ///< the case has the section
  double mass_fraction = 0.0;           ///< mass_percent: the moving mass, [0, 50 %]
  double preload_fraction = 0.0;        ///< preload_percent: P₀, [0, 50 %]
  double rate_fraction = 0.0;           ///< rate_percent: k (G, when k comes from the geometry)
  double stiffness_fraction = 0.0;      ///< stiffness_percent: k_c and k_s, [0, 50 %]
  double play_sigma_m = 0.0;            ///< play_mm: the roller play, m (a play below 0 is 0)
  double speed_fraction = 0.0;          ///< speed_percent: the rated speed, [0, 50 %]
};

/// [profile]: the cam that drives the needle, for `needle profile`.
struct ProfileSection {
  /// `follower` (roller, flat or curved), base_radius, roller_radius or face_radius,
  /// face_half_width, offset, lever_ratio: the library's geometry, validated as read.
  FollowerGeometry follower;
  int points = 720;  ///< points over one cam revolution
};

/// [limits]: the design limits `needle check` judges, one row each (docs/springs.md "The limits
/// table" gives the source of every default).
struct LimitsSection {
  /// Largest landing speed of the needle on its seat, m/s: the top of Blair's optimum ramp
  /// velocity range, 1.0–1.5 m/s at the highest operating speed.
  double seating_velocity_m_s = 1.5;
  /// Largest speed at which the cam strikes the roller as it takes up the play (the lash
  /// impact), m/s: the opening ramp's velocity, the same Blair range as the seating velocity.
  double lash_impact_velocity_m_s = 1.5;
  /// Largest secondary opening after closing (the needle seats, rebounds and reopens: a
  /// secondary injection), as a fraction of the largest lift.
  double secondary_opening_fraction = 0.01;
  /// Least cam contact force while the cam lifts the needle, as a fraction of the static load
  /// holding it on the cam there (P₀ + k y − F_g); absent: 1 − 1/f², f = [spring]
  /// overspeed_factor (the share the inertia of f·n would take, so at least 30.6 % at f = 1.2).
  std::optional<double> min_contact_force_fraction;
  /// n_dyn at least (1 + this)·f·n (0: the model contract's passing check, n_dyn > f·n).
  double separation_margin_fraction = 0.0;
  /// Largest Hertz stress cam–roller, Pa: ISO 6336-5's σ_Hlim of case-hardened steel, MQ.
  double hertz_stress_Pa = 1500e6;
  std::optional<double> contact_length_m;  ///< the roller's width in contact (needs [profile])
  double elastic_modulus_Pa = 210e9;       ///< E of cam and roller (steel)
  double poisson = 0.3;                    ///< ν (steel)
  /// Least Goodman–Zimmerli fatigue safety factor of the spring: the design factor of
  /// Shigley's fatigue-design example (§10-12), 1.5.
  double fatigue_safety_factor = 1.5;
  /// Least coil gap at full lift, m; absent: EN 13906-1's S_a of the spring.
  std::optional<double> coil_gap_m;
  /// A cam harmonic is significant when its acceleration reaches this fraction of the largest
  /// (the resonance map's orders; information, no verdict).
  double harmonic_threshold = 0.05;
};

/// The case's [needle] and [spring] are the spring module's parameters.
using NeedleSection = NeedleParameters;
using SpringSection = SpringParameters;

struct Case {
  std::string path;   ///< the file it came from, for messages
  std::string title;  ///< optional one-line description
  EngineSection engine;
  LiftSection lift;
  std::optional<NeedleSection> needle;
  std::optional<SpringSection> spring;
  std::optional<TrainSection> train;
  std::optional<SolverSection> solver;
  std::optional<OverspeedSection> overspeed;
  std::optional<ProfileSection> profile;
  std::optional<ToleranceSection> tolerance;
  std::optional<PaperSection> paper;
  LimitsSection limits;                 ///< [limits], defaults when absent
  std::optional<SizingSection> sizing;  ///< [sizing] (`needle size`, sizing_section.h)
};

/// A synthesis specification (`needle synth SPEC.toml`): [rise] angle_deg, lift_mm, step_deg;
/// [limits] speed_mm_rad, acceleration_mm_rad2, deceleration_mm_rad2, jerk_mm_rad3;
/// [checks] base_radius_mm, roller_radius_mm, offset_mm, max_pressure_angle_deg,
/// min_profile_radius_mm (the last two steer every step; offset must then be 0);

/// [output] fall = "mirror" | "none", crank_start_deg, speed_rpm, cycle (for --case).
struct SynthesisFile {
  std::string path, title;
  double rise_rad = 0.0, height_m = 0.0, step_rad = 0.0;
  double speed_limit = 1e300, accel_limit = 0.0, decel_limit = 0.0, jerk_limit = 1e300;
  FollowerKind follower = FollowerKind::kRoller;  ///< [checks] follower
  std::optional<double> base_radius_m, roller_radius_m;
  std::optional<double> face_radius_m;      ///< curved face
  std::optional<double> face_half_width_m;  ///< flat or curved face: caps S' (flat) or φ (curved)
  /// Lubrication: the least entrainment velocity at [output] speed_rpm, m/s (steers S'').
  std::optional<double> min_entrainment_m_s;
  double offset_m = 0.0;
  std::optional<double> max_pressure_angle_rad;
  std::optional<double> min_profile_radius_m;  ///< steer S'' so the profile keeps this radius
  /// Spring reserve (steers S'' on the decelerating side) and contact stress (checked):
  std::optional<double> spring_preload_N, spring_rate_N_m, moving_mass_kg, min_spring_reserve;
  std::optional<double> contact_length_m;  ///< roller width in contact, for Hertz stress
  double elastic_modulus_Pa = 210e9, poisson = 0.3;
  std::optional<double> max_contact_stress_Pa;

  bool mirror_fall = true;
  double crank_start_rad = 0.0;
  double speed_rpm = 1000.0;
  EngineCycle cycle = EngineCycle::kFourStroke;
};
SynthesisFile LoadSynthesisFile(const std::string& path);
/// The same from text; `path` names it in messages.
SynthesisFile ParseSynthesisFile(const std::string& text, const std::string& path);

/// Reads an engine file for the design chain; throws CaseError like LoadCase.

DesignInputs LoadDesignInputs(const std::string& path);
DesignInputs ParseDesignInputs(const std::string& text, const std::string& path);

/// Reads and validates a case file. Throws CaseError (one line) on any problem: unreadable
/// file, malformed TOML, missing or unknown keys, unknown unit suffixes, wrong types,
/// non-increasing angles, NaN, negative lift, too few points for the spline kind.
Case LoadCase(const std::string& path);

/// As LoadCase, from text already in memory; `path` is used in messages only.
Case ParseCase(const std::string& text, const std::string& path);

/// The published velocity magnitude at `crank_rad` (m/s), when the case's [paper] gives one there.
std::optional<double> PaperVelocityAt(const Case& c, double crank_rad);

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
