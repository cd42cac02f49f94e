#pragma once
/// @file
/// A Monte-Carlo tolerance study: the case checked (CheckScene) on N samples of its inputs,
/// each input scattered as the case's [tolerance] section says (ToleranceSection: normal, σ
/// about the nominal value), to give the distributions of what `check` reports (n_qs, n_dyn,
/// the spring's margins, the forces), the probability that the check fails, by failing item,
/// and the inputs that drive each (Spearman rank correlation).
///
/// Sample i draws its inputs from its own generator, seeded by (seed, i): a study is the same
/// for a seed whatever the number of threads, and shards of it (first_sample) are its parts. The
/// lift-table error is drawn on the points inside the open lift (the seated points are the base
/// circle), with covariance σ² exp(−(θ_i − θ_j)²/2ℓ²) (Cholesky), independent when ℓ = 0.

#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "apps/case/bound_case.h"

namespace needle {

/// Options of a study; every field has a default.
struct ToleranceOptions {
  int samples = 1000;  ///< N, [1, 1e6]
  uint64_t seed = 1;   ///< the study's seed: the same seed, the same samples
  /// The index of the first sample: a study of samples [first, first + N) of a larger one
  /// (a shard on another machine), [0, 1e9].
  int first_sample = 0;
  int threads = 0;  ///< 0: all cores; each sample is checked on one thread
  /// Check the nominal case once, and check each sample for its verdict only, its overspeed scan
  /// started at the nominal's n_dyn (CheckOptions::verdict_only, overspeed_start_rpm). Off, or a
  /// section without scatter (every sample is then the nominal case): each sample a full check.
  /// What it changes, measured: docs/commands.md, "What a sample takes from the nominal".
  bool reuse_nominal = true;
  /// Called after each sample (done, N), from the calling thread; may be empty.
  std::function<void(int, int)> progress;
};

/// One sample: the inputs drawn and what the check reported.
struct ToleranceSample {
  /// The inputs as drawn, relative to nominal: mass, preload, rate, stiffness, speed (fractions,
  /// "mass_deviation" …), play (m), and two summaries of the lift error: its mean over the
  /// open lift (m) and the RMS of its second difference (m), which drives the acceleration.
  std::map<std::string, double> inputs;
  /// Every number the check reports (the `check --json` keys, "overspeed.liftoff_rpm_dynamic"…)
  /// and the spring's margins; NaN where the sample has none (no lift-off in the range).
  std::map<std::string, double> outputs;
  bool pass = true;
  /// The failing items, each named by its part ("spring check: Basu's formula", "overspeed");
  /// "case refused" when the sample's case could not be checked (then `refused` says why).
  std::vector<std::string> failing;
  std::string refused;
};

/// The spread of one quantity over the samples where it is finite.
struct Distribution {
  int count = 0;  ///< finite samples
  double mean = NAN, std_dev = NAN, min = NAN, p05 = NAN, p50 = NAN, p95 = NAN, max = NAN;
};

/// How strongly each input moves a quantity: Spearman's ρ over the samples, by input.
using Drivers = std::map<std::string, double>;

struct ToleranceResult {
  ToleranceSection tolerance;                         ///< the scatter used
  ToleranceOptions options;                           ///< samples, seed, threads (the count used)
  std::vector<ToleranceSample> samples;               ///< in sample order
  std::map<std::string, Distribution> distributions;  ///< every output
  double failure_probability = 0.0;                   ///< the fraction of samples whose check fails
  /// Its 95 % Wilson interval (WilsonInterval95).
  double failure_probability_low = 0.0, failure_probability_high = 1.0;
  std::map<std::string, double> failure_by_item;  ///< the fraction failing each item
  Drivers fail_drivers;  ///< ρ of each input with failing (1) or passing (0)
  std::map<std::string, Drivers> output_drivers;  ///< ρ of each input with each output
  double seconds = 0.0;                           ///< wall time of the study
};

/// The scatter as fields: lift σ (mm) and its correlation length (deg), the fractions in %,
/// the play σ (mm).
std::vector<Field> ToleranceSectionFields(const ToleranceSection& t);

/// The scatter a study of `c` applies: its [tolerance] section, or the defaults without one
/// (ToleranceSection's: Basu's 0.01 mm on the lift table, nothing else). Where the lift error's
/// correlation is not stated it is a smooth grinding error, correlated over a quarter of the
/// open lift (kDefaultCorrelationFraction of the span of the table's points above zero):
/// independent points at 0.01 mm move s'' by σ/h², which failed a passing 0.35 mm design in
/// every sample (issue 51).
ToleranceSection EffectiveTolerance(const BoundCase& c);
inline constexpr double kDefaultCorrelationFraction = 0.25;

/// Which scatter each input got, and which are the defaults, in one line: "lift 0.0100 mm,
/// correlated over 13.75 deg (default: …); mass, … not scattered".
std::string ScatterSources(const ToleranceSection& t);

/// A distribution as fields: its count and its moments and quantiles (none when not finite).
std::vector<Field> DistributionFields(const Distribution& d);

/// The 95 % Wilson score interval of a fraction `p` of `n` trials:
///   (p + z²/2n ± z·√(p(1−p)/n + z²/4n²)) / (1 + z²/n),  z = 1.95996…,
/// clipped to [0, 1].
std::pair<double, double> WilsonInterval95(double p, double n);

/// The study of case `c` (its [tolerance] section, or the defaults without one). Throws
/// CaseError on a case that cannot be checked.
ToleranceResult RunToleranceStudy(const BoundCase& c, const ToleranceOptions& options);

/// The samples alone, [first_sample, first_sample + samples) in order (a shard of a study, as a
/// worker elsewhere computes it); `options.threads` becomes the count used. Throws CaseError
/// as RunToleranceStudy does; a sample the model refuses is a sample ("case refused").
std::vector<ToleranceSample> RunToleranceSamples(const BoundCase& c, ToleranceOptions& options);

/// The study of samples already computed (gathered from shards, in sample order): what
/// RunToleranceStudy reports of them, by the same code, bit for bit; `seconds` is left 0.
/// Throws CaseError when `samples` is empty.
ToleranceResult ReduceToleranceStudy(const BoundCase& c, const ToleranceOptions& options,
                                     std::vector<ToleranceSample> samples);

/// The lift-table error: normal, σ at each point where `varied` is true (0 elsewhere), with
/// covariance σ² exp(−(θ_i − θ_j)²/2ℓ²) between them (ℓ = 0: independent). The covariance is
/// factored once (an eigen-decomposition, which a near-singular kernel does not break).
class LiftErrorModel {
 public:
  LiftErrorModel(const std::vector<double>& crank_rad, const std::vector<bool>& varied,
                 double sigma_m, double correlation_rad);
  /// One draw, m, at every point of the table.
  std::vector<double> Draw(std::mt19937_64& gen) const;

 private:
  std::vector<int> index_;                 // the varied points
  std::vector<std::vector<double>> root_;  // A with A Aᵀ = the covariance (rows: varied points)
  size_t size_;
};

/// Spearman's rank correlation of x and y (mid-ranks for ties); NaN when either is constant or
/// they hold fewer than 3 finite pairs.
double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y);

/// The distribution of the finite values of `v` (quantiles by linear interpolation).
Distribution Describe(std::vector<double> v);

}  // namespace needle
