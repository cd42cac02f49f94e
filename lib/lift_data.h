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
/// Choice. A stated spline is used as stated. A dense table (at least kDenseTablePoints
/// readings) with neither its noise nor its breaks stated is read for what it holds
/// (docs/lift-data.md, "Reading a table"): its breaks are sought (FindBreaks), then ReadTable
/// tells an exact export from a rounded one and from a measurement by what the residual between
/// the breaks is, not by its size, and each piece between the breaks and the seat is fitted from
/// its own readings by the local fit (lib/local_fit.h) with the σ the table's kind gives: its
/// rounding q/√12, or the measurement's noise (then the closed level h = 3σ, readings down to
/// −4σ and more accepted as a seated needle's noise: TailSigmas, and outliers sought:
/// FindOutliers). A table whose noise is stated is measured data, fitted whole by the local fit.
/// A sparse table is exact (the paper's: read from a drawing, rounded to `resolution_mm`): when
/// it starts and ends at zero lift it gets the clamped cubic at rest at both ends (the evidence
/// is in docs/lift-data.md and docs/validation.md: Basu's velocity tables), otherwise not-a-knot.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lib/engine_cycle.h"
#include "lib/lift_law.h"
#include "lib/result_fields.h"
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

/// A table with at least this many points is dense: read for what it holds (ReadTable).
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

/// Break detection (docs/model.md §2). A table exported from CAD of a cam drawn from arcs or
/// joined laws is exact, but its s'' jumps at every junction; a spline across a junction smears
/// the jump (and a dense table with jumps looks noisy to EstimateNoise). FindBreaks looks for
/// them in the table alone: the second divided differences (≈ s'') of kBreakSideWindows windows
/// on each side of every interval are fitted with a line each and extrapolated to the interval;
/// the difference Ĵ of the two is s'''s jump there. An interval holds a break when |Ĵ| stands
///  - above TailSigmas(N, kBreakSigmas) times its own noise (σ times the norm of its weights on
///    the readings): the table's rounding or noise cannot make it, and
///  - above kBreakOverSmooth times the median of |Ĵ| at the eight intervals kBreakSideWindows
///    + 2 … + 5 away on either side (clear of this interval's windows): the extrapolation error
///    of a smooth law changes slowly along the table, a jump stands alone.
/// A corner (s' jumps by K) shows in the two windows across the interval instead (K/h each):
/// their excess Ĉ over the two lines is tested the same way. A candidate is kept when the two
/// sides' cubics (below) fit their readings kBreakOverSmooth times better than one cubic fits
/// them all: a jump, not a steep but smooth change over a few readings.
/// The break is then located to a fraction of the grid step: cubics fitted by least squares to
/// kBreakFitPoints readings on each side meet there with equal slopes (s'' jumps: the root of
/// the difference of their slopes) or, where their slopes never meet near the interval, with a
/// corner (s' jumps: the root of the difference of their lifts).

/// Breaks are also sought on means of bins of 2, 4, 8, … consecutive readings while there are at
/// least this many bins (ChooseLiftLaw): the noise of neighbouring readings' s'' grows as 1/h².
constexpr size_t kBreakLeastBins = 60;
/// The readings of each side's quintic in FindJunctions.
constexpr int kJunctionSide = 7;
/// FindJunctions is run on tables of at most this many readings (a coarse table's; a dense
/// one's junctions show among bins).
constexpr size_t kJunctionsAtMost = 5000;

/// Fewer windows of s'' on a side than this and the extrapolation is not checked.
constexpr int kBreakSideWindows = 4;
/// Readings of each side's cubic that locates a break: two more than a cubic needs.
constexpr int kBreakFitPoints = 6;
/// Least |Ĵ| over its noise, in σ (TailSigmas raises it with the number of intervals): far out
/// of what the table's rounding or noise gives at any interval.
constexpr double kBreakSigmas = 6.0;
/// Least |Ĵ| over the smooth-law level around it: a jump stands ten times above the slowly
/// changing extrapolation error of the law beside it.
constexpr double kBreakOverSmooth = 10.0;
/// An s'' jump's two measures, Ĵ and the jump of the located cubics' s'', agree within this
/// fraction of Ĵ (within 0.5 % on exact tables at 0.1…0.5°); where s''' jumps instead (a
/// cycloidal or 3-4-5 law's junction, s'' continuous), Ĵ sees J₃·h and the cubics nothing, so they
/// disagree by all of it: no break.
constexpr double kBreakJumpAgreement = 0.05;
/// A break found within this fraction of the grid step of a reading is put at the reading (no
/// knot a hair's breadth from another; the lift moves by J·(0.02 h)²/2 there, far below 1e-9 m
/// on any grid of a degree or less).
constexpr double kBreakSnapFraction = 0.02;
/// ... or, for an s'' jump J, within the δ at which a reading's lift on the far side's curve
/// moves by |J|·δ²/2 = this many times the sides' fit error (their RMS residual, at least σ):
/// the readings cannot tell the break from the reading, and a knot that near one makes a sliver
/// whose s'' is that lift error over δ² (a harmonic's end at 12° found at 11.989° on a 0.5°
/// table: s'' 1.9 % off beside it). Never past a quarter of the step.
constexpr double kBreakSnapResiduals = 3.0;
/// An exact table: the RMS of its sixth differences' pseudo-residuals, the windows across the
/// breaks left out, is at most this many times the σ of its printed digits' rounding (q/√12):
/// twice allows for the law's own sixth derivative and the rounding of the angles.
constexpr double kExactDigitsFactor = 3.0;

/// ... or at most this fraction of the largest |lift|, whichever is larger: a table printed to
/// all of a double's digits (1e-12 mm on a 154 mm cam) is exact where its law's own sixth
/// differences and the last digits' rounding leave ~1e-14 of the lift; no measurement comes
/// near (the finest gauges read 1e-6 of their range).
constexpr double kExactRelativeFloor = 1e-13;

/// What a table holds (ReadTable).
enum class TableKind {
  kExact,     ///< a law's exact values, printed to q: the residual is the law's own, smooth
  kRounded,   ///< a law's values rounded to q: a white residual at the rounding's level
  kMeasured,  ///< a measurement: a white residual above the rounding's level
};

/// "exact", "rounded" or "measured".
std::string TableKindName(TableKind kind);

/// Halved, a smooth law's normalised fourth differences grow 2⁴ = 16 times, white noise's not at
/// all: a residual growing less than this is white (noise at least 4× the law's own residual).
constexpr double kWhiteHalvingRatio = 4.0;
/// White noise's neighbouring fourth differences share four readings: their correlation is
/// −56/70 = −0.8 wherever the noise is, even in one part of the table or in one outlier. A smooth
/// law the readings do not resolve (a C∞ bump's feet at 1°, s'' rising from nothing within a
/// step or two) has a residual that hardly shrinks when halved but varies slowly: +0.7. A rise
/// resolved in two to four readings leaves a residual of alternating sign in a few windows that
/// hardly shrinks when halved either: −0.02 to −0.59 on 9 random exact exports that a
/// threshold of 0 read as measured (5 refused as outliers); all but the −0.59 are above this.
/// Measured tables (1-5 µm, steps 0.1-1°): −0.65 to −0.84. A residual is white only when this
/// correlation is below this, ...
constexpr double kWhiteLagCorrelation = -0.5;
/// ... over at least this many windows. On few windows the correlation of white noise scatters
/// toward 0 (simulated, 20 000 draws: median −0.67 on 8 windows, −0.71 on 12, −0.75 on 20; at or
/// above −0.5 in 20 % of draws on 8, 9 % on 12, 4 % on 16, 2 % on 20, 0.3 % on 30), and a coarse
/// rise's lands on either side of −0.5 (two exports of 30-31 readings, a return over about 5° in
/// two of them, read −0.52 on 7 and 8 windows, as measured; one refused). Below this the table is
/// read as exact: a measured table is then fitted at its rounding's σ, its noise lifting |s''| (the
/// safe side), where an exact one read as measured had its peaks smoothed away or was refused.
constexpr long kWhiteLeastWindows = 12;
/// A white residual up to this many times the rounding's σ (q/√12) is the rounding.
constexpr double kRoundingNoiseFactor = 2.0;

/// The reading of a table (ReadTable).
struct TableReading {
  TableKind kind = TableKind::kExact;
  double sigma_m = 0.0;             ///< σ of a reading: the rounding's, or the measurement's, m
  double rounding_sigma_m = 0.0;    ///< q/√12 (or 1e-13 of the largest lift, q unknown) with
                                    ///< the angles' printing (AngleRoundingSigma), m
  std::optional<double> printed_m;  ///< q, the printed resolution (stated or read), m
  double residual_m = 0.0;          ///< RMS normalised fourth difference between the cuts, m
  double halving_ratio = 0.0;       ///< the same on every other reading, over it (of the
                                    ///< pieces between cuts long enough to hold a halved window)
  double lag_correlation = 0.0;     ///< Σ e_i e_{i+1} / Σ e_i² of neighbouring windows
  long windows = 0;                 ///< the windows of five readings the residual is over
  bool staircase = false;           ///< most steps between readings are at most q
};

/// Reads readings first … last of (x, y) for what they hold, the windows across `cuts` (breaks
/// and the seat, rad) left out: the RMS normalised fourth divided difference over the table and
/// over its two half-density subsamples. A smooth law's grows 16× when halved, white noise's
/// not; a white residual within kRoundingNoiseFactor of q/√12 is the rounding.
TableReading ReadTable(const std::vector<double>& crank_rad, const std::vector<double>& lift_m,
                       size_t first, size_t last, const std::vector<double>& cuts,
                       std::optional<double> resolution_m);

/// A place where a derivative of the lift jumps.
struct LiftBreak {
  double crank_rad = 0.0;  ///< where, rad (between readings, or at one)
  int order = 2;           ///< the derivative that jumps: 2 (s'', a junction) or 1 (s', a corner)
  double jump = 0.0;       ///< its jump, right minus left, m/rad^order
  double lift_m = 0.0;     ///< the lift there, m (the two sides' cubics, averaged)
  size_t index = 0;        ///< the reading at or just before it
  /// How far it may lie from crank_rad, rad: 0 when found among the readings, the bins' width
  /// when found among bins of several readings (lift_choice.cc SeekBreaks).
  double uncertainty_rad = 0.0;
};

/// How far the breaks used, `used_rad` (each an angle of `found`), may lie from where they are
/// put, rad: the largest LiftBreak::uncertainty_rad among them (0: none found among bins).
double BreakUncertainty(const std::vector<LiftBreak>& found, const std::vector<double>& used_rad);

/// Breaks of a table (see above), increasing; `sigma_m` is the σ of its readings (the robust
/// σ̂: a few jumps do not move it), m, ≥ 0.
std::vector<LiftBreak> FindBreaks(const std::vector<double>& crank_rad,
                                  const std::vector<double>& lift_m, double sigma_m);

/// Dwells of an exact or rounded table inside its open lift, readings [first, last]: runs of at
/// least kDwellLeastReadings equal readings above 0, the readings beside each lower (a top) or
/// higher, where one quintic fitted by least squares to the run and kDwellSide readings on each
/// side misfits some reading by more than kDwellMisfits printed digits q (√12 `sigma_m`): a
/// smooth top rounded flat fits (at most 1.14 q on 1349 such runs of harmonic, cycloidal, 3-4-5,
/// 4-5-6-7, modified sine and trapezoid and cubic B-spline tops, 0.05-10 mm, 0.05-2°, to 1e-3 mm,
/// 1e-4 mm or 9 decimals), a dwell between two s'' jumps does not; and where s'' jumps at one
/// of its ends at least (a dwell its sides meet with s'' at 0 is read across as before: the
/// pieces' one-sided ends overshot a trapezoidal law's ramp there). Increasing.
std::vector<LiftDwell> FindDwells(const std::vector<double>& crank_rad,
                                  const std::vector<double>& lift_m, size_t first, size_t last,
                                  double sigma_m);
/// The dwells a local fit of an exact or rounded table reads (ChooseLiftLaw): FindDwells' on its
/// printed digit q, but those whose junctions were both found among `inside` (each at the run's
/// end reading or up to two readings outside it; on a side whose s'' jumps into the dwell, only
/// in the gap beside it: the dwell's piece between them is its lift already), and those whose
/// sides would keep fewer than kDwellSideReadings readings. A break closer than that to a side
/// whose s'' jumps into the dwell, jumping the same way, is that junction misplaced: not counted
/// against the side. The breaks within two readings of a dwell kept, and the misplaced ones, are
/// dropped from `inside` (its ends are its junctions).
std::vector<LiftDwell> SeekDwells(const std::vector<double>& crank_rad,
                                  const std::vector<double>& lift_m, size_t first, size_t last,
                                  double q, SplineKind kind, std::vector<const LiftBreak*>* inside);
/// `law` with `dwells`: each one's ends among its breaks (readings, not estimates), in order.
void AddDwells(const std::vector<LiftDwell>& dwells, LiftLawOptions* law);
/// FindDwells' least run, its readings either side, and its misfit in printed digits.
constexpr size_t kDwellLeastReadings = 3;
constexpr size_t kDwellSide = 4;
constexpr double kDwellMisfits = 3.0;
/// The least readings of each side SeekDwells takes a dwell with: enough for DwellTrim (lib/
/// lift_pieces.cc) to leave the dwell's reading out of the side's fit.
constexpr size_t kDwellSideReadings = 2 * kLocalMinimumPoints + 2;
/// The readings of a dwell's side that tell whether s'' jumps where it meets the dwell, and the
/// misfit ratio and the least s''(ξ), in h/β², that say it does (lib/lift_dwells.cc
/// JumpsIntoDwell).
constexpr size_t kJumpReadings = 8;
constexpr double kJumpSquares = 4.0;
constexpr double kJumpScale = 2.0;

/// Junctions of an exact table too coarse for FindBreaks' lines of s'' (a harmonic rise over 30
/// readings): at each reading the quintics fitted to the 7 readings ending there and the 7
/// beginning there give s''; where they differ by kBreakOverSmooth times the median difference
/// 8 to 13 readings away and by TailSigmas(N, kBreakSigmas) times its noise (σ ‖w_R − w_L‖),
/// s'' jumps: at the reading when it alone stands out, between it and the next when both do
/// (where the two sides' slopes meet). A located jump that differs from the one seen by more
/// than a quarter (a kink of s'') is none. Order-2 breaks only, increasing.
std::vector<LiftBreak> FindJunctions(const std::vector<double>& crank_rad,
                                     const std::vector<double>& lift_m, double sigma_m);

/// Whether the quintics through the readings on either side of a break found among bins see its
/// s'' jump there (within half of it): 7 readings a side, doubled while their noise σ‖w‖ is
/// not under a tenth of the jump and they reach no further than `reach_rad`. Where they can
/// tell, a kink of s'' that the bins' lines took for a jump is refused; elsewhere true.
bool JumpConfirmed(const std::vector<double>& crank_rad, const std::vector<double>& lift_m,
                   const LiftBreak& b, double sigma_m, double reach_rad);

/// A break found among bins of width `width_rad`, located again on the readings (x, y): cubics
/// fitted to each side's readings from one to twelve widths away meet as in FindBreaks, within a
/// width of where it was found; unchanged when they do not.
LiftBreak RefineBreak(const std::vector<double>& crank_rad, const std::vector<double>& lift_m,
                      const LiftBreak& found, double width_rad);

/// An inch in mm (a lift table's lift_in column).
constexpr double kInchMm = 25.4;

/// The rounding of the readings, m: the largest 10^-k mm or 10^-k in (k = 0…12) of which every
/// lift is a multiple (to 1e-6 of it), or, where the lifts are printed to significant digits (%g),
/// the digit of their highest decade of 8 distinct readings or more; nullopt when none is (lifts
/// not written in decimal mm or inches).
std::optional<double> PrintedResolution(const std::vector<double>& lift_m);

/// Whether the digit q (m) is 10^-k in rather than 10^-k mm.
bool InchDigit(double q_m);

/// An angle whose printed digit is below this share of the grid's step was rounded to it; a
/// digit at the step's own scale (0.1° steps printing 0.1°) is a computed grid's, exact.
constexpr double kAngleDigitOfStep = 1e-3;

/// The lift noise, m, that printing the angles makes in readings from … to of (x, y): a reading
/// taken at θ and printed at θ + δ misses the law at the printed angle by s'·δ, δ uniform over
/// the angle's printed digit q_θ (the finest among it and its four nearest neighbours of the
/// largest 10^-k deg, k = 0…12, of which each is a multiple) where q_θ is below
/// kAngleDigitOfStep of the step, else 0, and at most the grid's unevenness as fourth
/// differences see it (σ̂ of θ against the row index: a uniform grid's rounding errors follow the
/// step's residue modulo the digit, correlated, below q_θ/√12); RMS over the readings. (Angles
/// printed "%.10g", 7 decimals from 100°, on a harmonic 6 mm rise over 60° of crank: 7e-10 mm,
/// 2.5× a 9-decimal table's lift rounding.) A cam-degree column doubled to crank degrees reads
/// as half its digit.
double AngleRoundingSigma(const std::vector<double>& crank_rad, const std::vector<double>& lift_m,
                          size_t from, size_t to);

/// σ̂ of the readings from sixth divided differences (blind to quintics), leaving out every
/// window that is flat or holds one of `breaks_rad` strictly inside; m, 0 when none is left.
double EstimateNoiseBetweenBreaks(const std::vector<double>& crank_rad,
                                  const std::vector<double>& lift_m,
                                  const std::vector<double>& breaks_rad);

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
  /// Breaks are sought in the table (FindBreaks) when none are stated and the noise is not
  /// stated; false (`breaks_deg = []`) switches that off.
  bool find_breaks = true;
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
  /// Breaks found in the table (FindBreaks), s'' jumps only; empty when stated or not sought.
  /// Those strictly inside the open lift are the law's breaks when the table is judged exact.
  std::vector<LiftBreak> breaks_found;
  /// How far a break used may lie from where it is put, rad: 0 when each was found among the
  /// readings, else the widest bins' width among those used (kBreakLeastBins); a break found and
  /// then left out (too few readings beside it) does not count.
  double break_uncertainty_rad = 0.0;
  /// What a dense table was read to hold (ReadTable); none for a stated reading or a sparse table.
  std::optional<TableReading> reading;
  /// The first corner (s' jumps) found: the table cannot be differentiated there. ChooseLiftLaw
  /// leaves the refusal to the caller, who knows the file.
  std::optional<LiftBreak> corner;
  /// The table the law is built on: the given one, less the outliers when they are dropped,
  /// plus a reading at each break found between readings (its lift from the sides' cubics).
  LiftTable table;
};

/// Decides the spline, σ and the open-lift rule for `table` (see the file comment).
LiftLawChoice ChooseLiftLaw(const LiftTable& table, const LiftDataOptions& options);

/// A side of the lift (the rise before its first largest reading, the return after its last)
/// holding fewer than this many readings above the seat does not resolve its acceleration: a
/// harmonic rise of 8° read every 3° (2 readings) gave a_max 5.4 m/s² against the law's 1113,
/// its band [5.2, 483] (bench/export_trial.py: beyond the unsafe end at 5-6 % of the extremes of
/// pieces under 4 steps, 2-2.7 % of the others).
constexpr size_t kResolvedSideReadings = 3;
/// A warning where the table's rise or return, from a seat reading to the top, holds fewer than
/// kResolvedSideReadings readings above the seat ("the return from 25.6 to 33.1 deg holds 2
/// readings above the seat: …"); empty otherwise. A side the table cuts (no seat reading
/// beyond it) is not given, which is another matter, and not warned of.
std::string UnresolvedSides(const LiftTable& table);

/// A table whose first or last lift is above this fraction of its largest does not reach the
/// seat there: the check is undecided (apps/study/check_scene.h TableEndFailures; a table cut
/// just above zero is taken, its ramps bring it down).
inline constexpr double kOpenEndFraction = 0.05;
/// Where the law's open lift begins (ends) at the table's first (last) reading, above the seat
/// there (an exact table's reading above 0; measured data's fit above its closed level, 3σ): the
/// table stops above the seat, and the runs carry the cam on from that end (docs/model.md §3) —
/// a table cut there, or readings carrying an offset, which the table cannot tell apart ("the
/// lift table starts at 0.012 mm (-6.00 deg) and ends at 0.012 mm (70.00 deg), above the seat:
/// …"); empty otherwise.
std::string OffSeatEnds(const LiftLaw& law);

/// Whether the law's dip below the seat (LiftLaw::undershoot_m) is more than the readings can
/// hold: above half their printed digit (√3 σ) when rounded, above the closed level (3σ) for
/// measured data. A dip within it is the rounding's or the noise's (a 3-4-5 rise exported to
/// 1e-3 mm dipped 0.0003 mm at its first reading, and was told to try another spline kind).
bool DipBeyondReadings(const LiftLawChoice& choice, const LiftLaw& law);

/// The choice as fields (lib/result_fields.h): the spline's reason, σ (mm) and its source,
/// whether the table is measured, and the breaks found in the table (deg; only when some were).
std::vector<Field> LiftChoiceFields(const LiftLawChoice& choice);

}  // namespace needle

namespace needle {

/// Reads a lift table from CSV: `#` comment lines and blank lines skipped; a header naming two
/// columns with their units — the angle `crank_deg` or `cam_deg` (cam angles are turned into
/// crank angles by CrankTurnsPerCycle(cycle): ×2 four-stroke, ×1 two-stroke) and the lift
/// `lift_mm`, `lift_um`, `lift_in` or `lift_m` — then one row per reading. Spreadsheet output is
/// read as written: a UTF-8 byte-order mark, CRLF line ends and double-quoted fields are accepted,
/// and the separator is taken from the header: ',' (decimal mark '.'), or ';' when the header has
/// ';' and no ',' (decimal mark ',', as a spreadsheet writes in a German or other European locale:
/// `12,5`); a
/// '.' in such a table is refused (it may be a thousands separator). Angles must increase
/// strictly, every value be a finite number, and there be at least two rows. Throws CaseError
/// naming the file, the line and the column ("FILE:LINE:COLUMN: what").
/// `lines`, when given, gets the file's line number of each reading (for messages). `time_s`,
/// when given, lets the table have a third column, `time_s` or `time_ms` (a measured trace's
/// clock, `needle fit`), and gets its readings in s (empty when the column is absent).
LiftTable ReadLiftCsv(const std::string& path, EngineCycle cycle, std::vector<int>* lines = nullptr,
                      std::vector<double>* time_s = nullptr);

/// As ReadLiftCsv, from text already in memory; `path` is used in messages only.
LiftTable ParseLiftCsv(const std::string& text, const std::string& path, EngineCycle cycle,
                       std::vector<int>* lines = nullptr, std::vector<double>* time_s = nullptr);

/// A lift step larger than this fraction of the table's largest lift (or than its printed digit)
/// at a break placed between readings drops the break (BuildChosenLaw): 0.3 um on a 3 mm lift.
inline constexpr double kBreakStepOfLift = 1e-4;
/// The law on `choice` (its table and options). Where it steps in lift at a break found between
/// readings (each side fitted from its own readings and extrapolated to it) by more than the
/// printed digit or kBreakStepOfLift of the largest lift, the two sides do not meet as a cam's
/// do: that break is dropped, with the reading added there, and the law built again (one fit
/// across it), until none steps; the reason says so.
std::shared_ptr<const LiftLaw> BuildChosenLaw(LiftLawChoice* choice);

}  // namespace needle
