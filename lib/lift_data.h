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
/// where the fitted curve exceeds h), and readings down to −4σ (more in a table of over 316
/// readings: TailSigmas) are accepted as noise of a seated needle. A reading that stands far
/// out of its neighbourhood (FindOutliers) is an outlier of measured data: listed, and left out
/// when the case says so. A sparse table is exact (the paper's: read from a drawing, rounded to
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
/// Readings down to −kNegativeSigmas·σ (at least; TailSigmas scales it with the number of
/// readings) are accepted as the noise of a seated needle.
constexpr double kNegativeSigmas = 4.0;
/// An outlier of measured data stands more than kOutlierSigmas robust σ (at least; TailSigmas
/// scales it with the number of readings) from what its neighbours give ...
constexpr double kOutlierSigmas = 5.0;
/// ... and more than this fraction of the table's largest |lift|, so that the corners of an
/// exact dense table, where s''' or s'' jumps, are no outliers (with 30 readings over the event
/// they stand up to ~5e-4 of the lift from the cubic through their neighbours).
constexpr double kOutlierFloorFraction = 1e-3;
/// FindOutliers stops after this many: a table with more is not a few bad readings.
constexpr int kMaxOutliers = 20;

/// How many σ from zero a Gaussian reading must stand to be an error among `readings` of them:
/// the level that one table in 100 of as many honest readings passes, one-sided
/// (P(Z > z) = 1/(100 readings)), and at least `floor_sigmas` (4σ is that level at 316
/// readings; 200 000 readings give 5.3σ).
double TailSigmas(long readings, double floor_sigmas);

/// σ̂ of the readings (see the file comment), m; 0 when the table has fewer than five points
/// or no window that is not flat.
double EstimateNoise(const std::vector<double>& crank_rad, const std::vector<double>& lift_m);

/// The robust σ̂: 1.4826 times the median |e| of the same pseudo-residuals as EstimateNoise
/// (their median absolute deviation from zero; for Gaussian noise, σ). A few bad readings move
/// it by their few windows' share, where they inflate the RMS without bound. m; 0 as
/// EstimateNoise.
double EstimateNoiseRobust(const std::vector<double>& crank_rad, const std::vector<double>& lift_m);

/// A reading of measured data that stands out of its neighbourhood.
struct LiftOutlier {
  size_t index = 0;         ///< entry of the table
  double lift_m = 0.0;      ///< the reading, m
  double expected_m = 0.0;  ///< the cubic through its four nearest neighbours, at its angle, m
  double sigmas = 0.0;      ///< its pseudo-residual over the robust σ̂
};

/// Outliers of a measured table, in table order. Reading i's pseudo-residual is the least |e| of
/// the (up to three) windows of five consecutive readings that hold it in their middle three
/// places: a single bad reading of error δ stands at least 4δ/√70 out in all of them, each
/// neighbour at most δ/√70 in one. An outlier's exceeds both TailSigmas(N, kOutlierSigmas) (with
/// 2N: two-sided) times `robust_sigma_m` and kOutlierFloorFraction of the largest |lift|. Found
/// one at a time, the worst first, each left out before the next is sought (so that a bad
/// reading neither hides nor accuses its neighbours), at most kMaxOutliers.
std::vector<LiftOutlier> FindOutliers(const std::vector<double>& crank_rad,
                                      const std::vector<double>& lift_m, double robust_sigma_m);

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
  /// Outliers of measured data are left out of the fit (and of σ̂); otherwise they are only
  /// listed in LiftLawChoice::outliers, for the caller to refuse the table.
  bool drop_outliers = false;
};

/// The law chosen for a table, and why.
struct LiftLawChoice {
  LiftLawOptions law;                       ///< what the LiftLaw is built with
  bool measured = false;                    ///< measured data (closed level 3σ) or an exact table
  double noise_m = 0.0;                     ///< σ used, m
  std::string noise_source;                 ///< "stated", "estimated" or "rounding"
  std::optional<double> estimated_noise_m;  ///< σ̂ when estimated
  std::string reason;                       ///< one line: which spline and why
  /// Measured data's outliers (FindOutliers with EstimateNoiseRobust), in table order.
  std::vector<LiftOutlier> outliers;
  double robust_noise_m = 0.0;  ///< the robust σ̂ they were sought with, m (measured data)
  /// The table the law is built on: the given one, less the outliers when they are dropped.
  LiftTable table;
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
/// `lines`, when given, gets the file's line number of each reading (for messages).
LiftTable ReadLiftCsv(const std::string& path, bool four_stroke, std::vector<int>* lines = nullptr);

/// As ReadLiftCsv, from text already in memory; `path` is used in messages only.
LiftTable ParseLiftCsv(const std::string& text, const std::string& path, bool four_stroke,
                       std::vector<int>* lines = nullptr);

}  // namespace needle
