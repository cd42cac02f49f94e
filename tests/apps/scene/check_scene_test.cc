// "Check a scene" as a library function: the pass/fail policy on scenes that must pass, that
// must fail and that lack parts, and the one default sweep range both commands use.
#include "apps/scene/check_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

bool Contains(const std::vector<std::string>& lines, const std::string& start) {
  for (const std::string& l : lines)
    if (l.rfind(start, 0) == 0) return true;
  return false;
}

const std::string kSmall = R"(
title = "small"
[engine]
speed_rpm = 400
[lift]
crank_deg = [-10, 0, 10, 20, 30]
lift_mm = [0, 1, 2, 1, 0]
)";

TEST(DefaultSweepRangeTest, TwiceTheLargerOfNqsAndTheRatedSpeed) {
  const Case c = ParseCase(kSmall, "t.toml");
  EXPECT_EQ(DefaultSweepRange(c, 400, 900).from_rpm, 400);
  EXPECT_EQ(DefaultSweepRange(c, 400, 900).to_rpm, 1800);
  // n_qs below the rated speed: the sweep still reaches past the rated speed (the overspeed
  // command used to stop at 2·n_qs and refuse an empty range).
  EXPECT_EQ(DefaultSweepRange(c, 400, 150).to_rpm, 800);
  EXPECT_EQ(DefaultSweepRange(c, 400, INFINITY).to_rpm, 1600);
}

TEST(DefaultSweepRangeTest, TheCaseSectionWins) {
  const Case c = ParseCase(kSmall + "[overspeed]\nfrom_rpm = 500\nto_rpm = 700\n", "t.toml");
  EXPECT_EQ(DefaultSweepRange(c, 400, 900).from_rpm, 500);
  EXPECT_EQ(DefaultSweepRange(c, 400, 900).to_rpm, 700);
}

// Basu's Example 1 passes every part; the numbers are README's.
TEST(CheckSceneTest, BasuExampleOnePasses) {
  const Case c = LoadCase(kCases + "basu-example1.toml");
  const CheckResult r = CheckScene(c, MakeLiftLaw(c));
  EXPECT_TRUE(r.pass);
  EXPECT_TRUE(r.failing.empty());
  ASSERT_TRUE(r.spring && r.run && r.sweep);
  EXPECT_NEAR(r.n_qs_rpm, 649.5, 0.05);
  ASSERT_TRUE(r.sweep->n_dyn_rpm);
  EXPECT_NEAR(*r.sweep->n_dyn_rpm, 650.7, 0.05);
  EXPECT_EQ(r.sweep_range.from_rpm, 125);  // its [overspeed] section
  EXPECT_EQ(r.sweep_range.to_rpm, 1000);
  EXPECT_EQ(r.overspeed_rpm, 1.2 * r.speed_rpm);
}

// The JSON's numbers come from one field table per part, in display units, under the keys
// the JSON has always had.
TEST(CheckSceneTest, FieldsDescribeTheNumbersOnce) {
  const Case c = LoadCase(kCases + "basu-example1.toml");
  const CheckResult r = CheckScene(c, MakeLiftLaw(c));
  const std::vector<FieldGroup> g = CheckFields(r);
  ASSERT_EQ(g.size(), 5u);  // kinematics, spring, dynamics, overspeed, profile
  EXPECT_EQ(g[0].name, "kinematics");
  EXPECT_EQ(g[0].fields[0].Key(), "max_lift_mm");
  EXPECT_EQ(*g[0].fields[0].Shown(), r.kinematics.max_lift_m * 1e3);
  EXPECT_EQ(g[3].name, "overspeed");
  EXPECT_EQ(g[3].fields[0].Key(), "liftoff_rpm_quasi_static");
  EXPECT_EQ(*g[3].fields[0].Shown(), r.n_qs_rpm);
  EXPECT_EQ(g[3].fields[1].Key(), "liftoff_rpm_dynamic");
  EXPECT_EQ(*g[3].fields[1].Shown(), *r.sweep->n_dyn_rpm);
}

// The spring 80 % below Basu's formula fails, named as the spring check's.
TEST(CheckSceneTest, AWeakSpringFailsAndIsNamed) {
  const Case c = LoadCase(kCases + "new-engine-weak-spring.toml");
  const CheckResult r = CheckScene(c, MakeLiftLaw(c));
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(Contains(r.failing, "spring check: ")) << r.failing.size();
  EXPECT_TRUE(Contains(r.skipped, "dynamics and overspeed: the case has no [train] section"));
  EXPECT_TRUE(Contains(r.skipped, "cam profile: the case has no [profile] section"));
}

// Above n_dyn the run at the rated speed lifts off, and the sweep starts above f·n's
// threshold: both are failures, with the speed in the line.
TEST(CheckSceneTest, LiftOffAtTheRatedSpeedFails) {
  const Case c = LoadCase(kCases + "basu-example1.toml");
  CheckOptions o;
  o.speed_rpm = 700;
  const CheckResult r = CheckScene(c, MakeLiftLaw(c), o);
  EXPECT_FALSE(r.pass);
  ASSERT_TRUE(r.run);
  EXPECT_TRUE(r.run->liftoff());
  EXPECT_TRUE(
      Contains(r.failing, "dynamics: the needle lifts off the cam at the rated speed 700 rpm"));
  EXPECT_TRUE(Contains(r.failing, "overspeed: n_dyn "));
  EXPECT_TRUE(Contains(r.failing, "spring check: "));  // 700 rpm needs more preload too
}

// Only kinematics: nothing to fail, and every part that was not run is named.
TEST(CheckSceneTest, AKinematicsOnlySceneSaysWhatItSkipped) {
  const Case c = ParseCase(kSmall, "t.toml");
  const CheckResult r = CheckScene(c, MakeLiftLaw(c));
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.skipped.size(), 4u);
  // The limits table names what it could not judge, in one line grouped by what is missing.
  EXPECT_TRUE(Contains(r.skipped,
                       "limits not judged: seating velocity, least contact force in "
                       "the lift (no dynamics ([train] missing)); separation margin"));
  EXPECT_EQ(r.limits.size(), 7u);
  for (const LimitRow& x : r.limits) EXPECT_EQ(x.verdict, "not judged") << x.key;
  EXPECT_TRUE(std::isnan(r.n_qs_rpm));
  EXPECT_FALSE(r.spring || r.run || r.sweep || r.profile);
}

// Basu's Example 2 with its stated helical spring: the limits table judges six rows and fails
// two, each named with its value, limit and source.
TEST(CheckSceneTest, TheLimitsTableOfExample2) {
  const Case c = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example2.toml");
  CheckOptions o;
  o.record_series = false;
  const CheckResult r = CheckScene(c, MakeLiftLaw(c), o);
  ASSERT_EQ(r.limits.size(), 7u);
  const auto row = [&](const std::string& key) {
    for (const LimitRow& x : r.limits)
      if (x.key == key) return x;
    return LimitRow{};
  };
  EXPECT_EQ(row("hertz_stress").verdict, "not judged");
  EXPECT_EQ(row("hertz_stress").note, "no [profile] (the cam's radius)");
  const LimitRow f = row("fatigue_safety_factor");
  EXPECT_EQ(f.verdict, "fail");
  EXPECT_NEAR(f.value, 1.462, 1e-3);  // τ 642 → 689 MPa, R_m 1600 MPa, unpeened
  EXPECT_DOUBLE_EQ(f.limit, 1.5);
  EXPECT_NEAR(f.margin, f.value - 1.5, 1e-12);
  EXPECT_EQ(row("resonance_margin").verdict, "fail");  // 194.6 Hz under order 90 (300 Hz)
  EXPECT_EQ(row("coil_gap").verdict, "pass");
  EXPECT_EQ(row("seating_velocity").verdict, "pass");
  EXPECT_EQ(row("separation_margin").verdict, "pass");
  EXPECT_NEAR(row("separation_margin").value, 100 * (r.sweep->n_dyn_rpm.value() / 480 - 1), 1e-9);
  EXPECT_TRUE(Contains(r.failing,
                       "limits: spring fatigue safety factor (Goodman) 1.46 below "
                       "1.50 (Shigley 10-12: design factor 1.5)"));
  EXPECT_FALSE(r.pass);
  ASSERT_EQ(r.surge_modes_hz.size(), 3u);
  EXPECT_NEAR(r.surge_modes_hz[1], 2 * r.surge_modes_hz[0], 1e-9);
}

}  // namespace
}  // namespace needle
