// The spring check's fields: the preloads in kgf as Basu reads them, n_qs and the margins
// without a value where they are unbounded, the verdicts as yes/no.
#include "spring/spring_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "lib/units.h"

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

TEST(SpringCheckTest, FieldsShowTheCheckInKgfAndPercent) {
  const Case c = LoadCase(kCases + "basu-example1.toml");
  const LiftLaw law = MakeLiftLaw(c);
  SpringCheckResult r = CheckSpring(c, law, c.engine.speed_rpm);
  std::vector<Field> f = SpringCheckFields(r);
  EXPECT_EQ(*FieldAt(f, "actual_preload_kgf").Shown(), r.train.preload_N / kKgf);
  ASSERT_TRUE(r.basu_preload_N.has_value());
  EXPECT_EQ(*FieldAt(f, "deviation_percent").Shown(), *r.basu_deviation_percent);
  EXPECT_EQ(*FieldAt(f, "spring_rate_N_mm").Shown(), r.train.rate_N_m * 1e-3);
  EXPECT_EQ(*FieldAt(f, "liftoff_rpm_quasi_static").Shown(), r.liftoff_rpm_quasi_static);
  EXPECT_EQ(FieldAt(f, "pass").flag, r.pass);
  EXPECT_EQ(FieldAt(f, "gas_source").text, r.gas_source);
  // Unbounded: a needle that never decelerates has no n_qs, nothing required has no margin.
  r.liftoff_rpm_quasi_static = INFINITY;
  r.preload_margin_percent = INFINITY;
  f = SpringCheckFields(r);
  EXPECT_FALSE(FieldAt(f, "liftoff_rpm_quasi_static").Shown().has_value());
  EXPECT_FALSE(FieldAt(f, "preload_margin_percent").Shown().has_value());
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// Issue 51: a preload typed in kgf for N (900 "kgf" where 900 N was meant) passes every rule
// that asks for a large enough preload. Above 3 times the largest rule it is a warning that
// names the ratio and the slip that brings it back within 3 times of the rule.
TEST(SpringCheckTest, APreloadFarAboveEveryRuleIsAWarningNamingTheLikelySlip) {
  SpringCheckResult r;
  r.basu_preload_N = 770.0;
  r.safety_factor = 1.5;
  r.gas_force_N = 100.0;  // S·F_g = 150 N
  r.required_preload_N = 300.0;
  r.train.preload_N = 900.0 * 9.80665;
  ASSERT_TRUE(PreloadSlip(r));
  EXPECT_EQ(*PreloadSlip(r),
            "the preload 8826 N is 11.5× the largest rule (Basu's formula, 770 N); 9.81×: kgf for "
            "N?");
  r.train.preload_N = 2000.0;  // 2.6×: a stiff design, no warning
  EXPECT_FALSE(PreloadSlip(r));
  r.train.preload_N = 2400.0;  // 3.1×: lbf for N brings it to 1.4×, kgf to 0.32 (3.1 off)
  EXPECT_EQ(*PreloadSlip(r),
            "the preload 2400 N is 3.1× the largest rule (Basu's formula, 770 N); 4.45×: lbf for "
            "N?");
  r.train.preload_N = 9e5;  // 1169×: kN for N
  EXPECT_EQ(*PreloadSlip(r),
            "the preload 900000 N is 1168.8× the largest rule (Basu's formula, 770 N); 1000×: kN "
            "for N?");
  r.basu_preload_N.reset();  // the inertia sizing is then the largest rule
  r.train.preload_N = 1e5;   // 333×: no slip brings it within 3×
  EXPECT_EQ(*PreloadSlip(r),
            "the preload 100000 N is 333.3× the largest rule (the inertia sizing, "
            "300 N)");
  r.required_preload_N = r.gas_force_N = 0.0;  // no rule asks for a preload
  EXPECT_FALSE(PreloadSlip(r));
  // … nor one that asks for 3e-8 N (a user's trial: "10771019217.3× the largest rule (the
  // inertia sizing, 0 N)"): no slip is read from it.
  r.required_preload_N = 2.8e-8;
  r.train.preload_N = 300.0;
  EXPECT_FALSE(PreloadSlip(r));
}

// The same on a case: an 8 mm needle at 1500 rpm (Basu's formula asks 987 N) with 3500 N, which
// is 688 bar on the needle's area (within the plausible range): the check warns, and judges.
TEST(SpringCheckTest, TheCheckCarriesThePreloadSlipWarning) {
  const Case c = ParseCase(R"(
[engine]
speed_rpm = 1500
[lift]
crank_deg = [-15, -10, -5, 0, 5, 10, 15, 20, 25, 30, 35, 40]
lift_mm = [0, 0.073, 0.29, 0.77, 1.54, 2.49, 3.38, 3.67, 3.22, 2.12, 0.954, 0]
[needle]
mass_kg = 0.05
diameter_mm = 8
[spring]
preload_N = 3500
rate_N_mm = 50
)",
                           "t.toml");
  const SpringCheckResult r = CheckSpring(c, MakeLiftLaw(c), c.engine.speed_rpm);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0],
            "the preload 3500 N is 3.5× the largest rule (Basu's formula, 987 N); 4.45×: lbf for "
            "N?");
  EXPECT_TRUE(r.pass);
}

// A table of two readings (a straight rise, a user's trial) never decelerates: n_qs is none,
// and the spring passed with nothing limiting its preload. Its inertia sizing is undecided now.
// So does a straight rise of eight readings, whose fitted s'' is a round-off's −1e-16 of the
// lift's scale (a review: the first rule, s'' < 0, let it pass with n_qs 2e11 rpm).
TEST(SpringCheckTest, ATableThatNeverDeceleratesLeavesTheInertiaSizingUndecided) {
  for (const char* lift : {"crank_deg = [0, 10]\nlift_mm = [0, 1]",
                           "crank_deg = [0, 10, 20, 30, 40, 50, 60, 70]\n"
                           "lift_mm = [0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]"}) {
    const Case c = ParseCase(std::string("[engine]\nspeed_rpm = 600\n[lift]\n") + lift +
                                 "\n[needle]\nmass_kg = 0.05\n[spring]\npreload_N = 100\n"
                                 "rate_N_mm = 5\n",
                             "t.toml");
    const SpringCheckResult r = CheckSpring(c, MakeLiftLaw(c), c.engine.speed_rpm);
    EXPECT_FALSE(r.decelerates) << lift;
    EXPECT_FALSE(r.preload_ok);
    EXPECT_FALSE(r.pass);
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0],
              "inertia sizing: undecided: the lift table never decelerates (a lift that returns "
              "to its seat must), so it does not hold the lift's top; give the whole lift");
  }
}

// A rise of two readings above the seat (a harmonic rise of 8.1° every 3°: a_max 5.4 m/s²
// against the law's 1113) passed the inertia sizing on its band; the table does not resolve it,
// so the sizing is undecided, and failed, however large the preload.
TEST(SpringCheckTest, AnUnresolvedRiseLeavesTheInertiaSizingUndecided) {
  const Case c = ParseCase(
      "[engine]\nspeed_rpm = 1000\n[lift]\ncrank_deg = [0, 3, 6, 9, 12, 15, 18, 21, 24, 27, "
      "30]\nlift_mm = [0, 0.1241, 0.3463, 0.4102, 0.4091, 0.4066, 0.3, 0.2, 0.1, 0.03, 0]\n"
      "[needle]\nmass_kg = 0.05\n[spring]\npreload_N = 5000\nrate_N_mm = 5\n",
      "t.toml");
  const SpringCheckResult r = CheckSpring(c, MakeLiftLaw(c), c.engine.speed_rpm);
  EXPECT_TRUE(r.decelerates);
  EXPECT_GT(r.train.preload_N, r.required_preload_unsafe_N.value_or(0.0));
  EXPECT_FALSE(r.preload_ok);
  EXPECT_FALSE(r.pass);
  ASSERT_EQ(r.failures.size(), 1u);
  EXPECT_EQ(r.failures[0],
            "inertia sizing: undecided: the rise from 0 to 9 deg holds 2 readings above the seat: "
            "too few to resolve its acceleration, which may lie beyond its band; export the "
            "table finer there");
}

// n_qs's band where every deceleration's band reaches zero: its upper end unbounded, given as
// such (JSON null), not left out.
TEST(SpringCheckTest, AnUnboundedNqsBandIsGiven) {
  SpringCheckResult r;
  r.liftoff_rpm_quasi_static = 5224.8;
  r.liftoff_rpm_quasi_static_band = ExtremumBand{2883.8, INFINITY};
  const std::vector<Field> fields = SpringCheckFields(r);
  const Field& band = FieldAt(fields, "liftoff_rpm_quasi_static_band");
  ASSERT_EQ(band.list_si.size(), 2u);
  EXPECT_NEAR(band.list_si[0], 2883.8, 1e-9);
  EXPECT_TRUE(std::isinf(band.list_si[1]));
}

}  // namespace
}  // namespace needle
