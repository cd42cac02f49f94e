#pragma once
/// @file
/// Calibration of a case from measured lift traces (`needle fit`, docs/fit.md). The unknowns q,
/// named as case keys (`train.play_mm`, `spring.preload_N`, …), minimise
///
///   Σ_traces Σ_i ρ(r_i²),   r_i = (y(θ_i + Δθ; q, n) + Δs − ŷ_i) / σ,
///
/// where ŷ_i is the lift measured at crank angle θ_i of a trace recorded at speed n, y the needle
/// lift the model gives there (dynamics/simulation.h, the case's method: `exact` for linear
/// contacts), Δθ and Δs the trace's crank-angle and sensor offsets (`trace.offset_deg`,
/// `trace.offset_mm`, shared by the traces: one encoder, one sensor), σ the trace's noise
/// estimated from its own readings (lib/lift_data.h EstimateNoiseRobust) and ρ Huber's loss,
/// quadratic up to `huber_sigmas` and linear beyond (outliers weigh as |r|, not r²). Ceres
/// Solver's trust region minimises it from several starts (events make the cost non-smooth),
/// parameters that span decades in logs. The 95 % intervals are the linearised ones: covariance
/// s²(JᵀWJ)⁻¹ at the optimum, W Huber's weights, s² = max(1, (1.4826·median|r|)²) (a fit worse than
/// the noise widens them; the robust scale, 1.4826 times the median |r|, so that outliers do
/// not), mapped through the log where a parameter is in logs, then widened to
/// hold every value a scan of the cost along that unknown finds to fit as well (within
/// ½·3.84·s² of the optimum: the likelihood-ratio level, where the slope at the optimum
/// misleads). n_dyn's interval is the 2.5–97.5 % range of the overspeed search over draws from
/// that normal approximation (an unknown the scan widened or found not identified drawn flat
/// over its interval).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "apps/case/measured_trace.h"
#include "lib/units.h"

namespace needle {

/// One unknown as named on the command line: `section.stem_unit` (`train.play_mm`) or
/// `section.stem` for a dimensionless key (`train.contact_damping_ratio`).
struct FitKey {
  std::string name;     ///< as given
  std::string section;  ///< "needle", "spring", "train" or "trace"
  std::string stem;     ///< "mass", "preload", …
  std::string unit;     ///< the unit suffix ("" for a dimensionless key)
  Dimension dimension = Dimension::kNone;
  bool log_scale = false;  ///< fitted in logs (a positive value that may span decades)
};

/// Parses `name` as a key `needle fit` can free; throws CaseError naming `option` and listing
/// the keys it can (FitKeyList).
FitKey ParseFitKey(const std::string& name, const std::string& option = "--free");

/// The keys that can be freed, with their units: "needle.mass_kg, spring.preload_N, …".
std::string FitKeyList();

/// A bound stated for one unknown (`--bounds KEY=LOW:HIGH`), in the key's unit.
struct FitBound {
  FitKey key;
  double low = 0.0, high = 0.0;
};

/// Parses `KEY=LOW:HIGH`; throws CaseError naming `option`.
FitBound ParseFitBound(const std::string& text, const std::string& option = "--bounds");

/// How a fit is made. Every field has a default but `free`.
struct FitOptions {
  std::vector<FitKey> free;      ///< the unknowns, at least one, each once
  std::vector<FitBound> bounds;  ///< stated bounds (else the plausible ranges, docs/ranges.md)
  /// Starts of the local search, [1, 64]: the case's values, then the best points of a screen;
  /// each searched a few iterations, the three best on to convergence (FitCase).
  int starts = 12;
  double huber_sigmas = 3.0;    ///< the robust loss's knee, in σ, (0, 100]
  int max_iterations = 100;     ///< of each start's trust region, [1, 10000]
  bool predict_liftoff = true;  ///< n_dyn of the fitted case with its interval
  int liftoff_draws = 60;       ///< draws of the parameters for n_dyn's interval, [10, 10000]
  uint64_t seed = 1;            ///< of the draws and the starts after the first
  bool suggest_speed = true;    ///< for a pair the traces do not separate, the speed that would
};

/// One fitted unknown, in its key's unit.
struct FittedValue {
  FitKey key;
  double start = 0.0;            ///< the case's value (offsets: 0)
  double value = 0.0;            ///< fitted
  double low = 0.0, high = 0.0;  ///< its 95 % interval
  double lower_bound = 0.0, upper_bound = 0.0;
  bool at_bound = false;  ///< the optimum sits on a bound
  /// false: the traces do not pin it down (a bound fits as well as the optimum, or the curvature
  /// there is nil): the interval reaches that bound.
  bool identified = true;
  /// The linearised interval was widened to hold values the cost's scan found to fit as well
  /// (a flat or many-valleyed cost, FitCase).
  bool widened = false;
  std::string note;  ///< why it is not identified, when it is not
};

/// A pair of unknowns the traces do not separate (|correlation| > kUnseparatedCorrelation).
struct UnseparatedPair {
  int a = 0, b = 0;  ///< indices into FitResult::parameters
  double correlation = 0.0;
  /// The speed whose trace, added, would narrow the two intervals most (at least 4 times
  /// together), rpm; none: no speed tried does.
  std::optional<double> separating_rpm;
  double correlation_with = 0.0;                ///< the correlation with that trace added
  double narrowing_a = 1.0, narrowing_b = 1.0;  ///< how many times narrower each interval gets
};

/// Correlation above which two unknowns are called not separated.
constexpr double kUnseparatedCorrelation = 0.95;

/// One trace against the fitted model.
struct TraceFit {
  std::string path;
  double speed_rpm = 0.0;
  int readings = 0;      ///< in the file
  int used = 0;          ///< inside the run window (the rest: the needle seated before and after)
  double noise_m = 0.0;  ///< σ estimated from the trace
  double rms_m = 0.0;    ///< residual RMS of the used readings
  double runs_z = 0.0;   ///< the residual signs' runs test (Wald–Wolfowitz): ≪ 0 structured
  double worst_from_rad = 0.0, worst_to_rad = 0.0;  ///< where the residual is largest (5 % window)
  double worst_rms_m = 0.0;                         ///< its RMS there
  std::vector<double> crank_rad, measured_m, fitted_m;  ///< the used readings, fitted at each
};

/// n_dyn of the fitted case with its interval, rpm.
struct LiftoffPrediction {
  std::optional<double> value;  ///< at the fitted values (none: no lift-off in the sweep)
  /// 2.5 and 97.5 % of the draws, a draw without lift-off in the sweep counted as lifting off
  /// beyond it (high = +∞: above the sweep's end, to_rpm).
  double low = 0.0, high = 0.0;
  int draws = 0, draws_without = 0;  ///< draws run, and those without lift-off in the sweep
  int draws_refused = 0;             ///< draws the model refused (not in the quantiles)
  std::string status;                ///< the search's status at the fitted values
  double to_rpm = 0.0;               ///< the sweep's end
};

struct FitResult {
  std::vector<FittedValue> parameters;
  std::vector<std::vector<double>> correlation;  ///< P × P
  std::vector<UnseparatedPair> unseparated;
  std::vector<TraceFit> traces;
  double chi2_reduced = 0.0;  ///< Σ w r² / (N − P)
  /// The intervals' scale s², max(1, (1.4826 · median |r|)²): the residual's robust scale
  /// against the noise, which a few outliers do not move.
  double scale2 = 1.0;
  int restarts = 0;                ///< searches restarted where the scan found a lower cost
  std::vector<std::string> notes;  ///< what the fit leaves out of the case (its [solver] cycles)
  bool model_misses = false;       ///< the residual is well above the noise and structured
  std::string model_note;          ///< what and where, when it does
  /// When the residual exceeds the noise by more than noise alone explains (3 standard
  /// deviations of χ²/ν) without the structure of a missing effect: a local minimum or a model
  /// that misses something, said so.
  std::string residual_note;
  std::optional<LiftoffPrediction> liftoff;
  double cost = 0.0;                ///< the best start's final cost, ½ Σ ρ
  std::vector<double> start_costs;  ///< each start's final cost (NaN: it failed)
  int iterations = 0;               ///< the best start's
  int model_runs = 0;               ///< simulations over the whole fit
  std::string termination;          ///< Ceres's message for the best start
  double seconds = 0.0;
  BoundCase fitted;  ///< the case with the fitted values
};

/// Fits `b`'s unknowns to `traces` (each checked by CheckMeasuredTrace). Throws CaseError on a
/// key the case cannot free (a rate that comes from a geometry, a section the case lacks), a bound
/// outside the plausible range, an option out of its range, or no start the model runs from.
FitResult FitCase(const BoundCase& b, const std::vector<MeasuredTrace>& traces,
                  const FitOptions& options);

/// The fitted values as the case file's overrides, {section: {key: value}}, in the keys' units
/// (offsets left out: they belong to the traces).
std::vector<std::pair<std::string, std::pair<std::string, double>>> FittedOverrides(
    const FitResult& r);

}  // namespace needle
