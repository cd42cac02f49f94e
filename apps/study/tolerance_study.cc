#include "apps/study/tolerance_study.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "apps/study/check_scene.h"
#include "lib/output.h"
#include "lib/threads.h"
#include "lib/units.h"

namespace needle {

LiftErrorModel::LiftErrorModel(const std::vector<double>& crank_rad,
                               const std::vector<bool>& varied, double sigma_m,
                               double correlation_rad)
    : size_(crank_rad.size()) {
  for (size_t i = 0; i < crank_rad.size(); ++i)
    if (varied[i]) index_.push_back(static_cast<int>(i));
  const int n = static_cast<int>(index_.size());
  root_.assign(n, std::vector<double>(n, 0.0));
  if (n == 0 || sigma_m == 0.0) return;
  if (correlation_rad == 0.0) {
    for (int i = 0; i < n; ++i) root_[i][i] = sigma_m;
    return;
  }
  Eigen::MatrixXd cov(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double d = (crank_rad[index_[i]] - crank_rad[index_[j]]) / correlation_rad;
      cov(i, j) = sigma_m * sigma_m * std::exp(-0.5 * d * d);
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
  const Eigen::VectorXd roots = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::MatrixXd a = eig.eigenvectors() * roots.asDiagonal();
  // A smooth error of the cam is zero on its base circle, where the lift is zero by definition:
  // it tapers as sin π(θ − θ_a)/(θ_b − θ_a) between the unvaried points around (θ_a, θ_b; a
  // table's end stands one spacing beyond). Untapered, the first varied point jumped off the
  // zero beside it, and the perturbed table was refused as one with an outlier.
  const int m = static_cast<int>(crank_rad.size());
  for (int i = 0; i < n; ++i) {
    int lo = index_[i], hi = index_[i];
    while (lo >= 0 && varied[lo]) --lo;
    while (hi < m && varied[hi]) ++hi;
    const double spacing = m > 1 ? crank_rad[1] - crank_rad[0] : 1.0;
    const double ta = lo >= 0 ? crank_rad[lo] : crank_rad[0] - spacing;
    const double tb = hi < m ? crank_rad[hi] : crank_rad[m - 1] + spacing;
    const double w = std::sin(kPi * (crank_rad[index_[i]] - ta) / (tb - ta));
    for (int j = 0; j < n; ++j) root_[i][j] = w * a(i, j);
  }
}

std::vector<double> LiftErrorModel::Draw(std::mt19937_64& gen) const {
  std::normal_distribution<double> normal;
  std::vector<double> z(index_.size());
  for (double& v : z) v = normal(gen);
  std::vector<double> e(size_, 0.0);
  for (size_t i = 0; i < index_.size(); ++i)
    e[index_[i]] = std::inner_product(root_[i].begin(), root_[i].end(), z.begin(), 0.0);
  return e;
}

namespace {

// The part a failing line names: up to its first colon, or its second for the spring check's
// own items ("spring check: Basu's formula").
std::string FailingItem(const std::string& line) {
  size_t colon = line.find(':');
  if (colon == std::string::npos) return line;
  if (line.compare(0, colon, "spring check") == 0) {
    const size_t second = line.find(':', colon + 1);
    if (second != std::string::npos) colon = second;
  }
  return line.substr(0, colon);
}

// The lift error's mean over the varied points and its roughness (the RMS second difference).
void RecordLiftError(const std::vector<double>& e, ToleranceSample& s) {
  double mean = 0.0, rough = 0.0;
  int varied = 0, inner = 0;
  for (size_t i = 0; i < e.size(); ++i) {
    if (e[i] != 0.0) {
      mean += e[i];
      ++varied;
    }
    if (i > 0 && i + 1 < e.size()) {
      const double d2 = e[i - 1] - 2.0 * e[i] + e[i + 1];
      rough += d2 * d2;
      ++inner;
    }
  }
  s.inputs["lift_error_mean_m"] = varied ? mean / varied : 0.0;
  s.inputs["lift_error_roughness_m"] = inner ? std::sqrt(rough / inner) : 0.0;
}

// The scalar inputs of `c` scattered by the draws z (mass, preload, rate, stiffness, play,
// speed), each recorded in s.inputs; returns the sample's speed, rpm.
double ScatterInputs(const ToleranceSection& t, const std::array<double, 6>& z, BoundCase& c,
                     ToleranceSample& s) {
  const auto [z_mass, z_preload, z_rate, z_stiffness, z_play, z_speed] = z;
  const auto scale = [](double fraction, double draw) {
    return std::max(0.0, 1.0 + fraction * draw);
  };
  if (c.needle) {
    c.needle->mass_kg *= scale(t.mass_fraction, z_mass);
    s.inputs["mass_deviation"] = t.mass_fraction * z_mass;
  }
  if (c.spring) {
    c.spring->preload_N *= scale(t.preload_fraction, z_preload);
    s.inputs["preload_deviation"] = t.preload_fraction * z_preload;
    if (c.spring->rate_N_m) {
      *c.spring->rate_N_m *= scale(t.rate_fraction, z_rate);
    } else if (c.spring->helical) {
      c.spring->helical->shear_modulus_Pa *= scale(t.rate_fraction, z_rate);  // k ∝ G
    }
    s.inputs["rate_deviation"] = t.rate_fraction * z_rate;
  }
  if (c.train) {
    c.train->contact_stiffness_N_m *= scale(t.stiffness_fraction, z_stiffness);
    c.train->seat_stiffness_N_m *= scale(t.stiffness_fraction, z_stiffness);
    s.inputs["stiffness_deviation"] = t.stiffness_fraction * z_stiffness;
    const double play = std::max(0.0, c.train->play_m + t.play_sigma_m * z_play);
    s.inputs["play_deviation_m"] = play - c.train->play_m;
    c.train->play_m = play;
  }
  s.inputs["speed_deviation"] = t.speed_fraction * z_speed;
  return c.engine.speed_rpm * scale(t.speed_fraction, z_speed);
}

// What a sample records of its check: every number of the check's fields and a few more, its
// verdict and its failing items.
void RecordCheck(const CheckResult& r, ToleranceSample& s) {
  for (const FieldGroup& group : CheckFields(r)) {
    for (const Field& f : group.fields) {
      if (f.kind != Field::Kind::kNumber || f.count) continue;  // the numbers only
      const auto v = f.Shown();
      s.outputs[group.name + "." + f.Key()] = v ? *v : NAN;
    }
  }
  if (r.spring) {
    s.outputs["spring.preload_margin_percent"] = r.spring->preload_margin_percent;
    if (r.spring->basu_preload_N) {
      s.outputs["spring.basu_deviation_percent"] =
          100.0 * (r.spring->train.preload_N - *r.spring->basu_preload_N) /
          *r.spring->basu_preload_N;
    }
    s.outputs["spring.min_quasi_static_force_N"] = r.spring->min_quasi_static.force_N;
    s.outputs["spring.liftoff_rpm_quasi_static"] = r.spring->liftoff_rpm_quasi_static;
  }
  if (r.run) {
    s.outputs["dynamics.min_contact_force_during_lift_N"] = r.run->min_contact_force_during_lift_N;
    s.outputs["dynamics.max_contact_force_N"] = r.run->max_contact_force_N;
    double impact = 0.0;
    for (const Impact& i : r.run->impacts) impact = std::max(impact, i.speed_m_s);
    s.outputs["dynamics.max_impact_speed_m_s"] = impact;
  }
  s.pass = r.pass;
  for (const std::string& line : r.failing) {
    const std::string item = FailingItem(line);
    if (std::find(s.failing.begin(), s.failing.end(), item) == s.failing.end())
      s.failing.push_back(item);
  }
}

// One sample of the case: its inputs drawn, its case changed, its check run.
ToleranceSample RunSample(const BoundCase& nominal, const ToleranceSection& t,
                          const LiftErrorModel& lift_error, const CheckOptions& base, uint64_t seed,
                          int index) {
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32),
                    static_cast<uint32_t>(index)};
  std::mt19937_64 gen(seq);
  std::normal_distribution<double> normal;
  ToleranceSample s;
  BoundCase c = nominal;
  c.scene.reset();  // built again on the sample's inputs (CheckScene)
  // The inputs, each drawn whether or not it is varied, so that a sample's draws do not shift
  // when another input's σ changes from 0.
  const std::vector<double> e = lift_error.Draw(gen);
  std::array<double, 6> z;
  for (double& zi : z) zi = normal(gen);  // mass, preload, rate, stiffness, play, speed
  LiftTable table = nominal.lift.table;
  std::vector<double>& lift = table.lift_m;
  for (size_t i = 0; i < lift.size(); ++i) lift[i] = std::max(0.0, lift[i] + e[i]);
  RecordLiftError(e, s);
  CheckOptions options = base;
  options.speed_rpm = ScatterInputs(t, z, c, s);
  // A sample the model refuses (a lift table the spline or the ramps cannot take) is a
  // result, not the end of the study: it fails as "case refused", with the reason.
  // (And the model's own refusal of a sampled value: a stiffness or a speed scattered to zero.)
  const auto refused = [&s](const std::exception& why) {
    s.pass = false;
    s.failing = {"case refused"};
    s.refused = why.what();
    return s;
  };
  try {
    c.lift = RebindLift(nominal.lift, std::move(table));
    RecordCheck(CheckScene(c, options), s);
  } catch (const CaseError& refusal) {
    return refused(refusal);
  } catch (const std::invalid_argument& refusal) {
    return refused(refusal);
  }
  return s;
}

// The options of every sample's check: one thread, no series; with `reuse`, only what the verdict
// reads (CheckOptions::verdict_only) and the nominal case's n_dyn as the overspeed scan's start.
CheckOptions SampleOptions(const BoundCase& c, bool reuse) {
  CheckOptions options;
  options.threads = 1;
  options.record_series = false;
  if (!reuse) return options;
  options.verdict_only = true;
  CheckResult nominal;
  try {
    nominal = CheckScene(c, options);
  } catch (const CaseError&) {
    return options;  // nothing to take: each sample is checked in full
  }
  if (nominal.sweep && nominal.sweep->n_dyn_rpm)
    options.overspeed_start_rpm = nominal.sweep->n_dyn_rpm;
  return options;
}

std::vector<double> Ranks(const std::vector<double>& v) {
  std::vector<size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<double> rank(v.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double mid = 0.5 * (static_cast<double>(i) + static_cast<double>(j)) + 1.0;
    for (size_t k = i; k <= j; ++k) rank[order[k]] = mid;
    i = j + 1;
  }
  return rank;
}

}  // namespace

double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> fx, fy;
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) {
      fx.push_back(x[i]);
      fy.push_back(y[i]);
    }
  }
  if (fx.size() < 3) return NAN;
  const std::vector<double> rx = Ranks(fx), ry = Ranks(fy);
  const double n = static_cast<double>(rx.size()), mean = (n + 1.0) / 2.0;
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (size_t i = 0; i < rx.size(); ++i) {
    sxy += (rx[i] - mean) * (ry[i] - mean);
    sxx += (rx[i] - mean) * (rx[i] - mean);
    syy += (ry[i] - mean) * (ry[i] - mean);
  }
  if (sxx == 0.0 || syy == 0.0) return NAN;
  return sxy / std::sqrt(sxx * syy);
}

Distribution Describe(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  Distribution d;
  d.count = static_cast<int>(v.size());
  if (v.empty()) return d;
  std::sort(v.begin(), v.end());
  const double n = static_cast<double>(v.size());
  d.mean = std::accumulate(v.begin(), v.end(), 0.0) / n;
  double ss = 0.0;
  for (double x : v) ss += (x - d.mean) * (x - d.mean);
  d.std_dev = v.size() > 1 ? std::sqrt(ss / (n - 1.0)) : 0.0;
  const auto q = [&](double p) {
    const double at = p * (n - 1.0);
    const size_t lo = static_cast<size_t>(std::floor(at));
    const size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
  };
  d.min = v.front();
  d.max = v.back();
  d.p05 = q(0.05);
  d.p50 = q(0.5);
  d.p95 = q(0.95);
  return d;
}

std::vector<ToleranceSample> RunToleranceSamples(const BoundCase& c, ToleranceOptions& options) {
  if (!(options.samples >= 1 && options.samples <= 1000000))
    throw CaseError("--samples: expected a number of samples in [1, 1000000], got " +
                    std::to_string(options.samples));
  if (!(options.first_sample >= 0 && options.first_sample <= 1000000000))
    throw CaseError("--first-sample: expected an index in [0, 1000000000], got " +
                    std::to_string(options.first_sample));
  const ToleranceSection t = EffectiveTolerance(c);
  // The lift error moves the points inside the open lift: those above zero.
  std::vector<bool> varied;
  for (double y : c.lift.table.lift_m) varied.push_back(y > 0.0);
  const LiftErrorModel lift_error(c.lift.table.crank_rad, varied, t.lift_sigma_m,
                                  t.lift_correlation_rad);
  // Without scatter every sample is the nominal case, checked in full (a map's points).
  const bool scatter = t.lift_sigma_m > 0.0 || t.mass_fraction > 0.0 || t.preload_fraction > 0.0 ||
                       t.rate_fraction > 0.0 || t.stiffness_fraction > 0.0 ||
                       t.play_sigma_m > 0.0 || t.speed_fraction > 0.0;
  const CheckOptions base = SampleOptions(c, options.reuse_nominal && scatter);
  const int threads = std::max(1, std::min(options.samples, ThreadsToUse(options.threads)));
  options.threads = threads;
  std::vector<ToleranceSample> samples(options.samples);
  std::atomic<int> next{0}, done{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    while (true) {
      const int i = next++;
      if (i >= options.samples) return;
      try {
        samples[i] = RunSample(c, t, lift_error, base, options.seed, options.first_sample + i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = options.samples;  // stop the others
      }
      ++done;
    }
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(work);
  if (options.progress) {
    // The calling thread reports progress and takes samples between reports.
    std::thread last(work);
    int reported = -1;
    while (done < options.samples && !error) {
      if (done != reported) options.progress(reported = done, options.samples);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    last.join();
  } else {
    work();
  }
  for (std::thread& th : pool) th.join();
  if (error) std::rethrow_exception(error);
  if (options.progress) options.progress(options.samples, options.samples);
  return samples;
}

ToleranceSection EffectiveTolerance(const BoundCase& c) {
  ToleranceSection t = c.tolerance.value_or(ToleranceSection{});
  if (t.lift_correlation_given) return t;
  const std::vector<double>& th = c.lift.table.crank_rad;
  const std::vector<double>& y = c.lift.table.lift_m;
  double first = 0.0, last = 0.0;
  bool any = false;
  for (size_t i = 0; i < th.size(); ++i) {
    if (!(y[i] > 0.0)) continue;
    if (!any) first = th[i];
    last = th[i];
    any = true;
  }
  t.lift_correlation_rad = kDefaultCorrelationFraction * (last - first);
  return t;
}

std::string ScatterSources(const ToleranceSection& t) {
  const std::string lift =
      "lift " + Fixed(t.lift_sigma_m * 1e3, 4) + " mm" +
      (t.lift_correlation_rad > 0.0
           ? ", correlated over " + Fixed(t.lift_correlation_rad / kDeg, 2) + " deg"
           : std::string(", independent points"));
  std::string defaults;
  if (!t.given) {
    defaults =
        " (default, no [tolerance] section: Basu's \"the cam is made to 0.01 mm\" as a "
        "smooth grinding error correlated over a quarter of the open lift)";
  } else if (!t.lift_correlation_given) {
    defaults =
        " (lift_correlation_deg not given: a smooth grinding error over a quarter of the "
        "open lift)";
  }
  const std::pair<const char*, double> others[] = {
      {"mass", t.mass_fraction}, {"preload", t.preload_fraction},
      {"rate", t.rate_fraction}, {"stiffness", t.stiffness_fraction},
      {"play", t.play_sigma_m},  {"speed", t.speed_fraction}};
  std::string none;
  for (const auto& [name, v] : others)
    if (!(v > 0.0)) none += (none.empty() ? "" : ", ") + std::string(name);
  return lift + defaults + (none.empty() ? "" : "; " + none + " not scattered");
}

std::vector<Field> ToleranceSectionFields(const ToleranceSection& t) {
  using namespace display;
  return {{"lift", kMm, t.lift_sigma_m, 4},
          {"lift_correlation", kDegree, t.lift_correlation_rad, 2},
          {"mass", kFractionPercent, t.mass_fraction, 2},
          {"preload", kFractionPercent, t.preload_fraction, 2},
          {"rate", kFractionPercent, t.rate_fraction, 2},
          {"stiffness", kFractionPercent, t.stiffness_fraction, 2},
          {"play", kMm, t.play_sigma_m, 4},
          {"speed", kFractionPercent, t.speed_fraction, 2}};
}

std::vector<Field> DistributionFields(const Distribution& d) {
  using display::kNone;
  return {CountField("count", d.count),
          {"mean", kNone, FiniteOrNone(d.mean), 4},
          {"std", kNone, FiniteOrNone(d.std_dev), 4},
          {"min", kNone, FiniteOrNone(d.min), 4},
          {"p05", kNone, FiniteOrNone(d.p05), 4},
          {"p50", kNone, FiniteOrNone(d.p50), 4},
          {"p95", kNone, FiniteOrNone(d.p95), 4},
          {"max", kNone, FiniteOrNone(d.max), 4}};
}

std::pair<double, double> WilsonInterval95(double p, double n) {
  const double z = 1.959963984540054, z2 = z * z;
  const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / (1 + z2 / n);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

ToleranceResult ReduceToleranceStudy(const BoundCase& c, const ToleranceOptions& options,
                                     std::vector<ToleranceSample> samples) {
  if (samples.empty()) throw CaseError("a tolerance study needs at least one sample");
  ToleranceResult result;
  result.tolerance = EffectiveTolerance(c);
  result.options = options;
  result.samples = std::move(samples);
  // Distributions, failure, drivers; a quantity a sample lacks (a refused sample) is NaN there.
  std::map<std::string, std::vector<double>> outputs, inputs;
  for (const ToleranceSample& s : result.samples) {
    for (const auto& [k, v] : s.outputs) outputs[k];
    for (const auto& [k, v] : s.inputs) inputs[k];
  }
  std::vector<double> fails;
  for (const ToleranceSample& s : result.samples) {
    for (auto& [k, v] : outputs) v.push_back(s.outputs.count(k) ? s.outputs.at(k) : NAN);
    for (auto& [k, v] : inputs) v.push_back(s.inputs.count(k) ? s.inputs.at(k) : NAN);
    fails.push_back(s.pass ? 0.0 : 1.0);
    for (const std::string& item : s.failing) result.failure_by_item[item] += 1.0;
  }
  const double n = static_cast<double>(result.samples.size());
  result.failure_probability = std::accumulate(fails.begin(), fails.end(), 0.0) / n;
  std::tie(result.failure_probability_low, result.failure_probability_high) =
      WilsonInterval95(result.failure_probability, n);
  for (auto& [item, count] : result.failure_by_item) count /= n;
  for (const auto& [key, values] : outputs) {
    result.distributions[key] = Describe(values);
    for (const auto& [input, x] : inputs)
      result.output_drivers[key][input] = SpearmanRho(x, values);
  }
  for (const auto& [input, x] : inputs) result.fail_drivers[input] = SpearmanRho(x, fails);
  return result;
}

ToleranceResult RunToleranceStudy(const BoundCase& c, const ToleranceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ToleranceOptions used = options;
  std::vector<ToleranceSample> samples = RunToleranceSamples(c, used);
  ToleranceResult result = ReduceToleranceStudy(c, used, std::move(samples));
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace needle
