// The tolerance study: its statistics on known data, the lift error's covariance, the failure
// probability against the normal law's closed form, and the same study for a seed whatever
// the thread count.
#include "apps/study/tolerance_study.h"

#include <gtest/gtest.h>

#include <cmath>

#include "apps/case/case_file.h"
#include "apps/study/check_scene.h"
#include "lib/units.h"

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

// Example 1's spring check alone (no [train], no [profile]: a sample takes a millisecond), its
// lift and preload scattered by these σ.
Case SpringCheckOnly(double lift_sigma_m, double preload_fraction) {
  Case c = LoadCase(kCases + "basu-example1.toml");
  c.train.reset();
  c.profile.reset();
  c.tolerance = ToleranceSection{};
  c.tolerance->lift_sigma_m = lift_sigma_m;
  c.tolerance->preload_fraction = preload_fraction;
  return c;
}

TEST(ToleranceStudyTest, SpearmanOnKnownData) {
  EXPECT_DOUBLE_EQ(SpearmanRho({1, 2, 3, 4, 5}, {1, 8, 27, 64, 125}), 1.0);  // monotone
  EXPECT_DOUBLE_EQ(SpearmanRho({1, 2, 3, 4, 5}, {5, 4, 3, 2, 1}), -1.0);
  // Ties take mid-ranks: x ranks 1, 2.5, 2.5, 4 against 1, 2, 3, 4: ρ = 4.5/√(4.5·5).
  EXPECT_NEAR(SpearmanRho({1, 2, 2, 3}, {1, 2, 3, 4}), 4.5 / std::sqrt(22.5), 1e-15);
  EXPECT_TRUE(std::isnan(SpearmanRho({1, 1, 1}, {1, 2, 3})));  // a constant input
  EXPECT_TRUE(std::isnan(SpearmanRho({1, 2}, {1, 2})));
  // Non-finite pairs are left out.
  EXPECT_DOUBLE_EQ(SpearmanRho({1, 2, NAN, 3}, {2, 4, 5, 6}), 1.0);
}

TEST(ToleranceStudyTest, DescribeOnKnownData) {
  std::vector<double> v;
  for (int i = 101; i >= 1; --i) v.push_back(i);
  v.push_back(NAN);
  const Distribution d = Describe(v);
  EXPECT_EQ(d.count, 101);
  EXPECT_DOUBLE_EQ(d.mean, 51.0);
  EXPECT_NEAR(d.std_dev, std::sqrt(101.0 * 102.0 / 12.0), 1e-12);  // 1..n: n(n+1)/12
  EXPECT_DOUBLE_EQ(d.p05, 6.0);
  EXPECT_DOUBLE_EQ(d.p50, 51.0);
  EXPECT_DOUBLE_EQ(d.p95, 96.0);
  EXPECT_EQ(d.min, 1.0);
  EXPECT_EQ(d.max, 101.0);
}

TEST(ToleranceStudyTest, TheLiftErrorHasItsCovariance) {
  const std::vector<double> crank = {0.0, 0.01, 0.02, 0.03, 0.04};
  const std::vector<bool> varied = {false, true, true, true, false};
  const double sigma = 1e-5, ell = 0.02;
  for (double length : {0.0, ell}) {
    const LiftErrorModel model(crank, varied, sigma, length);
    std::mt19937_64 gen(7);
    const int n = 20000;
    double s11 = 0, s12 = 0, s13 = 0;
    for (int k = 0; k < n; ++k) {
      const std::vector<double> e = model.Draw(gen);
      ASSERT_EQ(e[0], 0.0);  // the seated points stay
      ASSERT_EQ(e[4], 0.0);
      s11 += e[1] * e[1];
      s12 += e[1] * e[2];
      s13 += e[1] * e[3];
    }
    // Variance σ² within 4 standard errors (σ²·√(2/n) = 1 %); correlations
    // exp(−h²/2ℓ²) = e^(−1/8) and e^(−1/2) at h = ℓ/2 and ℓ, or 0, within 4/√n. A correlated
    // error tapers as w = sin π(θ − θ_a)/(θ_b − θ_a) between the zeros at 0 and 0.04: w = 0.707,
    // 1, 0.707 at the three points, so Var e₁ = σ²/2, and Cov = w_i w_j σ² k_ij.
    const double w1 = length > 0 ? std::sin(kPi / 4) : 1.0, w2 = 1.0, w3 = w1;
    EXPECT_NEAR(s11 / n / (sigma * sigma), w1 * w1, 0.04) << length;
    const double r12 = s12 / s11, r13 = s13 / s11;
    EXPECT_NEAR(r12, length > 0 ? std::exp(-0.125) * w2 / w1 : 0.0, 0.03) << length;
    EXPECT_NEAR(r13, length > 0 ? std::exp(-0.5) * w3 / w1 : 0.0, 0.03) << length;
  }
}

// Example 1's spring check alone with the preload scattered by 5 %: Basu's formula fails where P₀ <
// 0.9·812.2 kgf, that is z below (0.9·812.2/790 − 1)/0.05 = −1.494: Φ(−1.494) = 6.76 % of the
// samples.
TEST(ToleranceStudyTest, TheFailureProbabilityIsTheNormalLaws) {
  const Case c = SpringCheckOnly(0.0, 0.05);
  ToleranceOptions o;
  o.samples = 2000;
  o.seed = 42;
  const ToleranceResult r = RunToleranceStudy(Bind(c), o);
  const CheckResult nominal = CheckScene(Bind(c));
  const double basu_N = *nominal.spring->basu_preload_N;
  const double z = (0.9 * basu_N / c.spring->preload_N - 1.0) / 0.05;
  const double p = 0.5 * std::erfc(-z / std::sqrt(2.0));
  EXPECT_NEAR(p, 0.0676, 5e-4);
  const double se = std::sqrt(p * (1 - p) / o.samples);
  EXPECT_NEAR(r.failure_by_item.at("spring check: Basu's formula"), p, 4 * se);
  EXPECT_GE(r.failure_probability, r.failure_by_item.at("spring check: Basu's formula"));
  // The study carries the Wilson interval of its own failure fraction.
  const auto [p_low, p_high] = WilsonInterval95(r.failure_probability, o.samples);
  EXPECT_EQ(r.failure_probability_low, p_low);
  EXPECT_EQ(r.failure_probability_high, p_high);
  EXPECT_LT(p_low, r.failure_probability);
  EXPECT_GT(p_high, r.failure_probability);
  // The preload drives the failing, against it; nothing else moves.
  EXPECT_LT(r.fail_drivers.at("preload_deviation"), -0.3);
  EXPECT_TRUE(std::isnan(r.fail_drivers.at("mass_deviation")));
  // n_qs² ∝ P₀ + k s − F_g at the critical angle: its spread is the preload's times
  // d ln n_qs / d ln P₀ = ½ P₀ / (P₀ + k s − F_g) (0.70 here: F_g = 2590 N of 7747), taken by a
  // central difference on the nominal case, to first order in σ.
  const auto nqs_at = [&](double factor) {
    Case v = c;
    v.spring->preload_N *= factor;
    return CheckScene(Bind(v)).n_qs_rpm;
  };
  const double slope = std::log(nqs_at(1.001) / nqs_at(0.999)) / std::log(1.001 / 0.999);
  EXPECT_NEAR(slope, 0.70, 0.02);
  const Distribution& nqs = r.distributions.at("spring.liftoff_rpm_quasi_static");
  EXPECT_NEAR(nqs.std_dev / nqs.mean / (slope * 0.05), 1.0, 0.05);
  EXPECT_GT(r.output_drivers.at("spring.liftoff_rpm_quasi_static").at("preload_deviation"), 0.99);
}

TEST(ToleranceStudyTest, WithoutScatterEverySampleIsTheNominalCase) {
  const Case c = SpringCheckOnly(0.0, 0.0);
  ToleranceOptions o;
  o.samples = 5;
  const ToleranceResult r = RunToleranceStudy(Bind(c), o);
  const CheckResult nominal = CheckScene(Bind(c));
  for (const ToleranceSample& s : r.samples) {
    EXPECT_EQ(s.outputs.at("spring.liftoff_rpm_quasi_static"), nominal.n_qs_rpm);
    EXPECT_EQ(s.pass, nominal.pass);
  }
  EXPECT_EQ(r.distributions.at("spring.liftoff_rpm_quasi_static").std_dev, 0.0);
}

// The whole check on every sample (Example 2 with its [tolerance]: the dynamics and the sweep),
// on one thread and on two: the same samples, bit for bit; another seed, other samples.
TEST(ToleranceStudyTest, ASeedGivesTheSameStudyWhateverTheThreads) {
  const Case c = LoadCase(kCases + "basu-example2.toml");
  ASSERT_TRUE(c.tolerance.has_value());
  ToleranceOptions o;
  o.samples = 4;
  o.seed = 2026;
  o.threads = 1;
  const ToleranceResult one = RunToleranceStudy(Bind(c), o);
  o.threads = 2;
  const ToleranceResult two = RunToleranceStudy(Bind(c), o);
  ASSERT_EQ(one.samples.size(), 4u);
  for (size_t i = 0; i < one.samples.size(); ++i) {
    EXPECT_EQ(one.samples[i].inputs, two.samples[i].inputs) << i;
    const auto& a = one.samples[i].outputs;
    const auto& b = two.samples[i].outputs;
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [key, v] : a) {
      if (std::isnan(v)) {
        EXPECT_TRUE(std::isnan(b.at(key))) << key;
      } else {
        EXPECT_EQ(v, b.at(key)) << key;
      }
    }
    EXPECT_EQ(one.samples[i].failing, two.samples[i].failing);
  }
  o.seed = 2027;
  o.samples = 1;
  const ToleranceResult other = RunToleranceStudy(Bind(c), o);
  EXPECT_NE(other.samples[0].inputs, one.samples[0].inputs);
}

// A shard [first, first + N) of a study is that part of the whole: what a worker on another
// machine computes.
TEST(ToleranceStudyTest, ShardsAreThePartsOfTheStudy) {
  const Case c = SpringCheckOnly(ToleranceSection{}.lift_sigma_m, 0.05);
  ToleranceOptions o;
  o.samples = 5;
  o.seed = 9;
  const ToleranceResult whole = RunToleranceStudy(Bind(c), o);
  o.first_sample = 3;
  o.samples = 2;
  const ToleranceResult shard = RunToleranceStudy(Bind(c), o);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(shard.samples[i].inputs, whole.samples[3 + i].inputs) << i;
    EXPECT_EQ(shard.samples[i].outputs.at("spring.liftoff_rpm_quasi_static"),
              whole.samples[3 + i].outputs.at("spring.liftoff_rpm_quasi_static"));
  }
  EXPECT_NE(shard.samples[0].inputs, whole.samples[0].inputs);
}

// A sample whose case the model refuses (here a lift table scattered by 0.5 mm, whose tangent
// ramps cannot take up the play) is a failing sample with its reason, not the study's end.
TEST(ToleranceStudyTest, ARefusedSampleIsAResult) {
  Case c = LoadCase(kCases + "basu-example1.toml");
  c.tolerance = ToleranceSection{};
  c.tolerance->lift_sigma_m = 5e-4;
  ToleranceOptions o;
  o.samples = 3;
  const ToleranceResult r = RunToleranceStudy(Bind(c), o);
  ASSERT_GT(r.failure_by_item.count("case refused"), 0u);
  int refused = 0;
  for (const ToleranceSample& s : r.samples) {
    if (s.refused.empty()) continue;
    ++refused;
    EXPECT_FALSE(s.pass);
    EXPECT_EQ(s.refused.rfind(kCases + "basu-example1.toml: ", 0), 0u) << s.refused;
  }
  EXPECT_DOUBLE_EQ(r.failure_by_item.at("case refused"), refused / 3.0);
  EXPECT_EQ(r.distributions.at("kinematics.max_lift_mm").count, 3 - refused);
}

// A sampled value the model itself refuses (a contact stiffness scattered below zero, held at
// zero) is a refused sample with the model's reason, not the study's end (it ended the study
// with exit 2 before: found by trying stiffness_percent = 50 as a user would).
TEST(ToleranceStudyTest, AValueTheModelRefusesIsARefusedSample) {
  Case c = LoadCase(kCases + "basu-example2.toml");
  c.tolerance->stiffness_fraction = 0.5;
  ToleranceOptions o;
  o.samples = 3;
  o.seed = 6;
  const ToleranceResult r = RunToleranceStudy(Bind(c), o);
  for (int i : {0, 1}) {  // scattered by more than −100 %
    EXPECT_LT(r.samples[i].inputs.at("stiffness_deviation"), -1.0);
    EXPECT_EQ(r.samples[i].refused,
              "TrainParameters.contact_stiffness_N_m = 0.000000: must be positive");
    EXPECT_FALSE(r.samples[i].pass);
  }
  EXPECT_TRUE(r.samples[2].refused.empty());
  EXPECT_DOUBLE_EQ(r.failure_by_item.at("case refused"), 2.0 / 3.0);
}

TEST(ToleranceStudyTest, BadSampleCountsAreRefused) {
  const Case c = LoadCase(kCases + "basu-example2.toml");
  ToleranceOptions o;
  o.samples = 0;
  try {
    RunToleranceStudy(Bind(c), o);
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_STREQ(e.what(), "--samples: expected a number of samples in [1, 1000000], got 0");
  }
}

// Samples that take from the nominal's check (ToleranceOptions::reuse_nominal: its n_dyn as the
// scan's start, the verdict's work only) say what a full check of each says: the same verdict and
// failing items, every output the same but n_dyn (within the search's resolution, 0.5 rpm: both
// brackets are run at both ends) and the speed the scan reached.
TEST(ToleranceStudyTest, ASampleTakingFromTheNominalHasItsFullChecksVerdict) {
  const Case c = LoadCase(kCases + "basu-example2.toml");
  ToleranceOptions o;
  o.samples = 6;
  o.seed = 33;
  o.threads = 2;
  const std::vector<ToleranceSample> reused = RunToleranceSamples(Bind(c), o);
  o.reuse_nominal = false;
  const std::vector<ToleranceSample> full = RunToleranceSamples(Bind(c), o);
  ASSERT_EQ(reused.size(), full.size());
  for (size_t i = 0; i < full.size(); ++i) {
    EXPECT_EQ(reused[i].pass, full[i].pass) << i;
    EXPECT_EQ(reused[i].failing, full[i].failing) << i;
    ASSERT_EQ(reused[i].outputs.size(), full[i].outputs.size());
    for (const char* words : {"dynamics.status", "dynamics.impacts", "spring.pass"})
      EXPECT_EQ(full[i].outputs.count(words), 0u) << words;  // the check's numbers only
    for (const auto& [key, v] : full[i].outputs) {
      const double w = reused[i].outputs.at(key);
      if (key == "overspeed.liftoff_rpm_dynamic") {
        EXPECT_NEAR(w, v, 0.5) << i;
      } else if (key != "overspeed.scanned_to_rpm") {
        EXPECT_TRUE(w == v || (std::isnan(w) && std::isnan(v))) << i << ' ' << key;
      }
    }
  }
}

// A check for its verdict only, its scan going on from the nominal's n_dyn past f·n (what a
// tolerance sample runs), judges every limit as the full check of the same perturbed case, with
// the same numbers: the surge study's chain runs are the full check's, to their end.
TEST(ToleranceStudyTest, AVerdictOnlyCheckJudgesEveryLimitAsTheFullCheck) {
  const Case nominal = LoadCase(kCases + "basu-example2.toml");
  CheckOptions options;
  options.threads = 1;
  options.record_series = false;
  const CheckResult first = CheckScene(Bind(nominal), options);
  ASSERT_TRUE(first.surge && first.sweep && first.sweep->n_dyn_rpm);
  Case c = nominal;
  c.spring->preload_N *= 0.94;
  c.needle->mass_kg *= 1.03;
  const CheckResult full = CheckScene(Bind(c), options);
  CheckOptions asked = options;
  asked.overspeed_start_rpm = first.sweep->n_dyn_rpm;
  asked.verdict_only = true;
  const CheckResult r = CheckScene(Bind(c), asked);
  EXPECT_EQ(r.surge->rated.status, full.surge->rated.status);
  EXPECT_EQ(r.surge->rated.run_end_rad, full.surge->rated.run_end_rad);
  EXPECT_EQ(r.surge->masses, full.surge->masses);
  EXPECT_EQ(r.pass, full.pass);
  EXPECT_EQ(r.failing, full.failing);
  ASSERT_EQ(r.limits.size(), full.limits.size());
  for (size_t i = 0; i < r.limits.size(); ++i) {
    const LimitRow &a = r.limits[i], &b = full.limits[i];
    EXPECT_EQ(a.verdict, b.verdict) << a.key;
    if (a.key != "separation_margin") {
      EXPECT_TRUE(a.value == b.value || (std::isnan(a.value) && std::isnan(b.value))) << a.key;
    }
  }
  EXPECT_NEAR(*r.sweep->n_dyn_rpm, *full.sweep->n_dyn_rpm, 0.5);
  EXPECT_LT(r.sweep->rows.size(), full.sweep->rows.size());
  EXPECT_FALSE(r.harmonics);  // report-only: not computed
}

}  // namespace
}  // namespace needle

// The Wilson score interval against values worked by hand from its formula: 50 of 100 gives
// 0.5 ± 0.0962 (centre 0.5), 0 of 10 gives [0, 0.2775] (the lower end clipped at 0), 10 of 10
// the mirror image; a study's result carries the interval of its own failure fraction.
TEST(WilsonInterval, MatchesTheScoreIntervalWorkedByHand) {
  const auto [lo, hi] = needle::WilsonInterval95(0.5, 100);
  EXPECT_NEAR(lo, 0.403832, 1e-6);
  EXPECT_NEAR(hi, 0.596168, 1e-6);
  const auto [lo0, hi0] = needle::WilsonInterval95(0.0, 10);
  EXPECT_EQ(lo0, 0.0);
  EXPECT_NEAR(hi0, 0.277533, 1e-6);
  const auto [lo1, hi1] = needle::WilsonInterval95(1.0, 10);
  EXPECT_NEAR(lo1, 1.0 - 0.277533, 1e-6);
  EXPECT_NEAR(hi1, 1.0, 1e-12);
}

namespace needle {
namespace {

// Issue 51: without a [tolerance] section Basu's 0.01 mm was put on every table point
// independently: s'' moves by σ/h², and a small injector's passing design (0.35 mm of harmonic
// lift over 40°, 6 g, 300 N) failed in all 200 samples, the output not saying the scatter was a
// default. The default is now a smooth grinding error, correlated over a quarter of the open lift
// and zero where the lift is, stated as the default.
TEST(ToleranceStudyTest, TheDefaultLiftErrorIsASmoothGrindingErrorAndSaysSo) {
  std::string crank = "crank_deg = [", lift = "lift_mm = [";
  for (int i = 0; i <= 40; ++i) {
    crank += (i ? ", " : "") + std::to_string(i - 20);
    char v[32];
    std::snprintf(v, sizeof v, "%.4f", 0.35 * (1 - std::cos(2 * kPi * i / 40.0)) / 2);
    lift += (i ? ", " : "") + std::string(v);
  }
  const std::string text = "[engine]\nspeed_rpm = 1500\ncycle = \"four-stroke\"\n[lift]\n" + crank +
                           "]\n" + lift +
                           "]\n[needle]\nmass_kg = 0.006\ndiameter_mm = 4\n[spring]\n"
                           "preload_N = 300\nrate_N_mm = 40\n[train]\ncontact_stiffness_N_m = "
                           "5e7\n";
  const Case c = ParseCase(text, "small.toml");
  ASSERT_TRUE(CheckScene(Bind(c)).pass);
  const ToleranceSection t = EffectiveTolerance(Bind(c));
  EXPECT_NEAR(t.lift_correlation_rad / kDeg, 0.25 * 38.0, 1e-9);  // points above zero: −19…19°
  EXPECT_EQ(ScatterSources(t),
            "lift 0.0100 mm, correlated over 9.50 deg (default, no [tolerance] section: Basu's "
            "\"the cam is made to 0.01 mm\" as a smooth grinding error correlated over a quarter "
            "of the open lift); mass, preload, rate, stiffness, play, speed not scattered");
  ToleranceOptions o;
  o.samples = 200;
  o.seed = 1;
  EXPECT_LT(RunToleranceStudy(Bind(c), o).failure_probability, 0.02);
  // Independent points, as stated: the old default's harshness, every sample failing.
  const Case independent = ParseCase(text + "[tolerance]\nlift_correlation_deg = 0\n", "s.toml");
  EXPECT_EQ(ScatterSources(EffectiveTolerance(Bind(independent))),
            "lift 0.0100 mm, independent points; mass, preload, rate, stiffness, play, speed not "
            "scattered");
  EXPECT_GT(RunToleranceStudy(Bind(independent), o).failure_probability, 0.95);
}

}  // namespace
}  // namespace needle
