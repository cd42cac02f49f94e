#pragma once
/// @file
/// Lift data as engineers have it (docs/model.md §2): exact tables like the paper's and
/// measured tables with noise, read from TOML or CSV, and the choice of the spline and of the
/// open-lift rule that fits them.
///
/// Noise. The standard deviation σ of the readings is estimated from the data by a difference
/// estimator: for every five consecutive points the fourth divided difference
/// D = Σ_j w_j s_j, w_j = 1/Π_{l≠j}(θ_j − θ_l), annihilates any cubic, so for a smooth law
/// D ≈ s⁗/24 (negligible on a dense table) and for noise Var(D) = σ² Σ w_j². The pseudo-residual
/// e = D/√(Σ w_j²) therefore has variance σ², and σ̂ = √(mean e²) over all windows that are not
/// exactly flat (a zero-padded zone reads the same value and says nothing about the noise).
///
/// Choice. A stated spline is used as stated. Otherwise a table is measured when it is dense
/// (at least kDenseTablePoints points) or its noise is stated (`noise_mm`); measured data gets
/// the smoothing spline with σ (stated, else estimated), the closed level h = 3σ (open lift
/// where the fitted curve exceeds h), and readings down to −4σ are accepted as noise of a seated
/// needle. A sparse table is exact (the paper's: read from a drawing, rounded to
/// `resolution_mm`): when it starts and ends at zero lift it gets the clamped cubic at rest at
/// both ends (the evidence is in README: Basu's velocity tables and the closed-form laws),
/// otherwise not-a-knot.

#include <optional>
#include <string>
#include <vector>

#include "lib/lift_law.h"
#include "lib/spline.h"

namespace needle {

/// Plausible readings of a lift table; a value outside is refused before any fit, naming its
/// row and column (a typo such as 1e300, or a unit mix-up). A lift within ±1 m: needle lifts are
/// millimetres and cam lifts centimetres (the largest bundled table, the Siconos cam's, 154 mm),
/// and a lift written in µm under `lift_mm` (1.7 mm as 1700) lands beyond it.
constexpr double kMaxLiftM = 1.0;
/// A crank angle within ±720°, rad: a four-stroke cycle either side of dead centre, so a table
/// written from −360° to 360° or from 0° to 720° (cam angles 0…360° of a four-stroke) fits.
constexpr double kMaxCrankRad = 4.0 * 3.14159265358979323846;

/// A table with at least this many points is dense: taken as measured data, smoothed.
constexpr int kDenseTablePoints = 30;
/// Closed level of measured data, in σ: the needle is open where the fitted lift exceeds 3σ.
constexpr double kClosedLevelSigmas = 3.0;
/// Readings down to −4σ are accepted as the noise of a seated needle.
constexpr double kNegativeSigmas = 4.0;

/// σ̂ of the readings (see the file comment), m; 0 when the table has fewer than five points
/// or no window that is not flat.
double EstimateNoise(const std::vector<double>& crank_rad, const std::vector<double>& lift_m);

/// What a case says about its lift data. Every field has a default (nothing stated).
struct LiftDataOptions {
  std::optional<SplineKind> kind;             ///< stated spline kind
  SplineOptions spline;                       ///< end slopes and smoothing rule (kind ignored)
  std::optional<double> noise_m;              ///< stated σ of the readings, m, > 0
  std::optional<double> resolution_m;         ///< stated rounding of the readings, m, > 0
  std::optional<double> open_rad, close_rad;  ///< stated θ_open, θ_close
  /// Stated angles where s'' jumps, rad (LiftLawOptions::breaks_rad): the table is then a
  /// designed cam's exact lift however dense, with a not-a-knot cubic on each piece by default.
  std::vector<double> breaks_rad;
};

/// The law chosen for a table, and why.
struct LiftLawChoice {
  LiftLawOptions law;                       ///< what the LiftLaw is built with
  bool measured = false;                    ///< measured data (closed level 3σ) or an exact table
  double noise_m = 0.0;                     ///< σ used, m
  std::string noise_source;                 ///< "stated", "estimated" or "rounding"
  std::optional<double> estimated_noise_m;  ///< σ̂ when estimated
  std::string reason;                       ///< one line: which spline and why
};

/// Decides the spline, σ and the open-lift rule for `table` (see the file comment).
LiftLawChoice ChooseLiftLaw(const LiftTable& table, const LiftDataOptions& options);

}  // namespace needle

namespace needle {

/// Reads a lift table from CSV: `#` comment lines and blank lines skipped; a header naming two
/// columns with their units — the angle `crank_deg` or `cam_deg` (cam angles are turned into
/// crank angles: ×2 when `four_stroke`, else ×1) and the lift `lift_mm`, `lift_um`, `lift_in`
/// or `lift_m` — then one row per reading. Spreadsheet output is read as written: a UTF-8
/// byte-order mark, CRLF line ends and double-quoted fields are accepted, and the separator is
/// taken from the header: ',' (decimal mark '.'), or ';' when the header has ';' and no ','
/// (decimal mark ',', as a spreadsheet writes in a German or other European locale: `12,5`); a
/// '.' in such a table is refused (it may be a thousands separator). Angles must increase
/// strictly, every value be a finite number, and there be at least two rows. Throws CaseError
/// naming the file, the line and the column ("FILE:LINE:COLUMN: what").
LiftTable ReadLiftCsv(const std::string& path, bool four_stroke);

/// As ReadLiftCsv, from text already in memory; `path` is used in messages only.
LiftTable ParseLiftCsv(const std::string& text, const std::string& path, bool four_stroke);

}  // namespace needle
