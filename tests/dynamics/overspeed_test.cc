// The overspeed search: n_dyn against n_qs, and the parallel sweep against the serial one.
#include "dynamics/overspeed.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/case/case_scene.h"
#include "spring/quasi_static.h"

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

double Nqs(const Scene& s) { return QuasiStaticLiftoffRpm(s); }

OverspeedResult Search(const Scene& s, double from, double to, int threads) {
  OverspeedOptions o;
  o.from_rpm = from;
  o.to_rpm = to;
  o.threads = threads;
  o.simulation.integrator.rtol = 1e-8;
  o.simulation.integrator.atol_m = 1e-11;
  return OverspeedSearch(s, o);
}

TEST(OverspeedTest, LightSpringLiftsOffNearItsQuasiStaticSpeed) {
  const Case c = LoadCase(kCases + "basu-cam4-light-spring.toml");
  const Scene s = MakeScene(c);
  const double n_qs = Nqs(s);
  const OverspeedResult r = Search(s, 400, 1200, 2);
  ASSERT_TRUE(r.n_dyn_rpm.has_value());
  EXPECT_LE(r.bracket_high_rpm - r.bracket_low_rpm, 0.5);
  EXPECT_LE(*r.n_dyn_rpm, n_qs * 1.02);
  EXPECT_GE(*r.n_dyn_rpm, n_qs * 0.9);
  // Every row below the bracket is free of lift-off, every row above it lifts off.
  for (const OverspeedRow& row : r.rows) {
    if (row.speed_rpm <= r.bracket_low_rpm) {
      EXPECT_FALSE(row.lifts_off) << row.speed_rpm;
    }
    if (row.speed_rpm >= r.bracket_high_rpm) {
      EXPECT_TRUE(row.lifts_off) << row.speed_rpm;
    }
  }
}

TEST(OverspeedTest, LashVibrationBringsLiftOffBelowTheQuasiStaticSpeed) {
  // Example 2's stated train (0.5 mm play on 10° ramps): the lash impact sets the train
  // ringing, and the needle leaves the cam about 2 % below n_qs.
  const Case c = LoadCase(kCases + "basu-example2.toml");
  const Scene s = MakeScene(c);
  const double n_qs = Nqs(s);
  const OverspeedResult r = Search(s, 400, 2000, 2);
  ASSERT_TRUE(r.n_dyn_rpm.has_value());
  EXPECT_LT(*r.n_dyn_rpm, n_qs * 0.99);
  EXPECT_GT(*r.n_dyn_rpm, n_qs * 0.9);
}

TEST(OverspeedTest, ParallelAndSerialSweepsAgree) {
  const Case c = LoadCase(kCases + "basu-cam4-light-spring.toml");
  const Scene s = MakeScene(c);
  const OverspeedResult a = Search(s, 500, 800, 1), b = Search(s, 500, 800, 2);
  ASSERT_TRUE(a.n_dyn_rpm && b.n_dyn_rpm);
  EXPECT_NEAR(*a.n_dyn_rpm, *b.n_dyn_rpm, 0.5);
}

TEST(OverspeedTest, EmptyRangeIsRejected) {
  const Case c = LoadCase(kCases + "basu-cam4-light-spring.toml");
  const Scene s = MakeScene(c);
  try {
    Search(s, 800, 800, 1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "overspeed: the sweep range is empty: to_rpm (800.000000) must exceed from_rpm "
                 "(800.000000)");
  }
}

TEST(OverspeedTest, SpringSurgeBringsLiftOffBelowTheOneMassSpeed) {
  // cases/basu-example1-surge.toml: the spring as 20 coil masses (1 % damping in its first
  // mode), four revolutions judged on the steady state. The coils' ringing from one event meets
  // the next and the needle leaves its cam at 611 rpm; the same scene with the massless spring
  // beside a third of its mass (masses = 1) holds to 643 rpm.
  Case c = LoadCase(kCases + "basu-example1-surge.toml");
  ASSERT_EQ(c.spring->masses, 20);
  OverspeedOptions o;
  o.from_rpm = c.overspeed->from_rpm.value();
  o.to_rpm = c.overspeed->to_rpm.value();
  o.simulation = OptionsFromCase(c);
  o.simulation.steady_state = true;
  const OverspeedResult chain = OverspeedSearch(MakeScene(c), o);
  c.spring->masses = 1;
  const OverspeedResult one = OverspeedSearch(MakeScene(c), o);
  ASSERT_TRUE(chain.n_dyn_rpm.has_value());
  ASSERT_TRUE(one.n_dyn_rpm.has_value());
  EXPECT_NEAR(*one.n_dyn_rpm, 643.1, 0.5);
  EXPECT_NEAR(*chain.n_dyn_rpm, 611.5, 0.5);
  EXPECT_LT(*chain.n_dyn_rpm, *one.n_dyn_rpm * 0.96);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

TEST(OverspeedTest, EveryBundledSceneLiftsOffAtOrBelowItsQuasiStaticSpeed) {
  // n_dyn ≤ n_qs·(1 + 2 %) on the bundled scenes with a train (the dynamics can only add to
  // the rigid train's deceleration demand here: vibration, lash).
  for (const char* name :
       {"basu-example1.toml", "basu-example2.toml", "basu-cam4-light-spring.toml"}) {
    const Case c = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/" + name);
    const Scene s = MakeScene(c);
    const double n_qs = QuasiStaticLiftoffRpm(s);
    OverspeedOptions o;
    o.from_rpm = c.overspeed->from_rpm.value();
    o.to_rpm = c.overspeed->to_rpm.value();
    o.simulation = OptionsFromCase(c);
    const OverspeedResult r = OverspeedSearch(s, o);
    ASSERT_TRUE(r.n_dyn_rpm.has_value()) << name;
    EXPECT_LE(*r.n_dyn_rpm, n_qs * 1.02) << name;
    std::printf("%s: n_qs %.1f rpm, n_dyn %.1f rpm\n", name, n_qs, *r.n_dyn_rpm);
  }
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// docs/model.md §6: n_dyn does not depend on the top of the searched range — speeds are scanned
// upward in steps of Δn from the start, whatever the end.
TEST(OverspeedScanTest, NdynDoesNotDependOnTheTopOfTheRange) {
  const Case c = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-cam4-light-spring.toml");
  const Scene s = MakeScene(c);
  OverspeedOptions o;
  o.from_rpm = 400;
  o.simulation = OptionsFromCase(c);
  std::optional<double> first;
  for (double to : {2000.0, 60000.0, 1e6}) {
    o.to_rpm = to;
    const OverspeedResult r = OverspeedSearch(s, o);
    ASSERT_TRUE(r.n_dyn_rpm) << to;
    EXPECT_EQ(r.status, "found");
    EXPECT_DOUBLE_EQ(r.step_rpm, 10.0);  // 2.5 % of 400 rpm
    EXPECT_LE(r.bracket_high_rpm - r.bracket_low_rpm, 0.5);
    if (!first) first = *r.n_dyn_rpm;
    EXPECT_DOUBLE_EQ(*r.n_dyn_rpm, *first) << to;
  }
  // Just below n_qs (639.7 rpm), as the light spring's dynamics lifts off a little early.
  EXPECT_NEAR(*first, 635.9, 0.5);
  // The scan budget ends a search that finds nothing with a status, not an error.
  o.to_rpm = 1e6;
  o.from_rpm = 400;
  o.max_speeds = 3;
  const OverspeedResult b = OverspeedSearch(s, o);
  EXPECT_FALSE(b.n_dyn_rpm);
  EXPECT_EQ(b.status, "budget");
  EXPECT_EQ(b.rows.size(), 3u);
  EXPECT_DOUBLE_EQ(b.scanned_to_rpm, b.rows.back().speed_rpm);
  EXPECT_LT(b.scanned_to_rpm, 600.0);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// Issue 12: a speed that fails must reach the caller, from whichever worker thread ran it
// (RunAll swallowing worker exceptions passed every test before).
TEST(OverspeedScanTest, AFailingSpeedReachesTheCaller) {
  const Scene s = MakeScene(LoadCase(kCases + "basu-cam4-light-spring.toml"));
  OverspeedOptions o;
  o.from_rpm = 400;
  o.to_rpm = 500;
  o.threads = 2;
  o.simulation.method = "no-such-method";
  try {
    OverspeedSearch(s, o);
    FAIL() << "the failing speeds were swallowed";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("unknown method \"no-such-method\"", 0), 0u) << e.what();
  }
}

// A run stopped by its budget is a row with that status, and the scan ends there undecided
// rather than claiming a lift-off speed above a speed it could not decide.
TEST(OverspeedScanTest, ABudgetStopIsARowStatusAndTheScanEndsUndecided) {
  const Scene s = MakeScene(LoadCase(kCases + "basu-cam4-light-spring.toml"));
  OverspeedOptions o;
  o.from_rpm = 400;
  o.to_rpm = 1200;
  o.threads = 2;
  o.simulation.integrator.max_steps = 30;
  const OverspeedResult r = OverspeedSearch(s, o);
  EXPECT_EQ(r.status, "run-budget");
  EXPECT_FALSE(r.n_dyn_rpm.has_value());
  ASSERT_FALSE(r.rows.empty());
  EXPECT_EQ(RunStatusName(r.rows.front().status), "budget");
  EXPECT_NE(r.rows.front().status_reason.find("after 30 steps"), std::string::npos);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// A light needle on a weak spring (numbers of this test's own): n_qs ≈ 822 rpm, so it lifts off
// at its rated 1000 rpm already.
const char* const kWeakSpring = R"(
[engine]
speed_rpm = 1000
cycle = "four-stroke"
[lift]
crank_deg = [-20, -14, -8, -2, 4, 10, 16, 22, 28, 34, 40]
lift_mm = [0.0, 0.12, 0.55, 1.30, 2.15, 2.70, 2.55, 1.90, 1.00, 0.30, 0.0]
spline = "not-a-knot"
resolution_mm = 0.01
[needle]
mass_kg = 0.8
[spring]
preload_N = 390
rate_N_mm = 30
[train]
contact_stiffness_N_m = 1e8
seat_stiffness_N_m = 1e8
contact_damping_ratio = 0.1
seat_damping_ratio = 0.1
play_mm = 0
)";

// The same cam, a 1.0077 kg needle on a 496.3 N preload, 0.3 mm of play on 8° ramps and a
// contact damped at 0.5 %: the lash impact sets the train ringing, and the least contact force
// dips and recovers with speed; one dip lifts the needle off (a jump of 0.1° or more) in a
// window 578.57–586.37 rpm wide, below the next lift-off at about 624.5 rpm. (The scene of issue
// 39's scan had windows at 475.8–481 rpm that were seat rebounds after closing, no lift-off since
// contract rev. 4; this one was found by a sweep of preload and mass, and its window's edges
// bisected to 0.002 rpm.)
const char* const kNarrowWindow = R"(
[engine]
speed_rpm = 400
cycle = "four-stroke"
[lift]
crank_deg = [-20, -14, -8, -2, 4, 10, 16, 22, 28, 34, 40]
lift_mm = [0.0, 0.12, 0.55, 1.30, 2.15, 2.70, 2.55, 1.90, 1.00, 0.30, 0.0]
spline = "not-a-knot"
resolution_mm = 0.01
[needle]
mass_kg = 1.0077
[spring]
preload_N = 496.3
rate_N_mm = 20
[train]
contact_stiffness_N_m = 2e7
seat_stiffness_N_m = 2e8
contact_damping_ratio = 0.005
seat_damping_ratio = 0.05
play_mm = 0.3
ramp_deg = 8
)";

// The scan the narrow-window tests run: from 200 to 700 rpm, steps of at most 15 rpm where the
// force gives no guidance.
OverspeedOptions NarrowWindowScan() {
  OverspeedOptions o;
  o.from_rpm = 200;
  o.to_rpm = 700;
  o.step_rpm = 15;
  return o;
}

// Whether one full run at n lifts off (a jump of kMinJump_rad), as the search judges.
bool LiftsOff(const Scene& s, double n) {
  SimulationOptions o;
  o.force_dynamic = true;
  return RowFromResult(Simulate(s, n, o)).lifts_off;
}

// The lowest lift-off speed on a grid from `from` in steps of `step`, up to `to`; 0: none.
double FirstLiftOff(const Scene& s, double from, double to, double step) {
  for (double n = from; n <= to; n += step) {
    if (LiftsOff(s, n)) return n;
  }
  return 0.0;
}

// Issue: n_dyn wherever it is. A design that lifts off at the start of the range has its n_dyn
// below it; the search goes down and finds it, as a fine scan does.
TEST(OverspeedDownTest, ADesignLiftingOffAtTheStartHasItsNdynFoundBelow) {
  const Scene s = MakeScene(ParseCase(kWeakSpring, "weak-spring.toml"));
  OverspeedOptions o;
  o.from_rpm = 1000;
  o.to_rpm = 3000;
  o.threads = 1;
  const OverspeedResult r = OverspeedSearch(s, o);
  EXPECT_EQ(r.status, "found");
  EXPECT_TRUE(r.lifts_off_at_start);
  ASSERT_TRUE(r.n_dyn_rpm);
  EXPECT_LE(r.bracket_high_rpm - r.bracket_low_rpm, 0.5);
  // The fine scan: no lift-off every 5 rpm from 400 rpm to just below, then the first lift-off
  // on a 0.1 rpm grid.
  const double n = *r.n_dyn_rpm;
  EXPECT_EQ(FirstLiftOff(s, 400.0, n - 2.0, 5.0), 0.0);
  const double fine = FirstLiftOff(s, n - 2.0, n + 1.0, 0.1);
  EXPECT_NEAR(fine, n, 0.5) << "search " << n << " rpm, fine scan " << fine << " rpm";
  EXPECT_LT(n, 0.9 * o.from_rpm);
}

// … and one that lifts off at every speed down to the floor says so, without a value.
TEST(OverspeedDownTest, LiftingOffDownToTheFloorIsAStatusNotAValue) {
  const Scene s = MakeScene(ParseCase(kWeakSpring, "weak-spring.toml"));
  OverspeedOptions o;
  o.from_rpm = 1000;
  o.to_rpm = 3000;
  o.floor_rpm = 900;  // n_dyn is near 811 rpm
  const OverspeedResult r = OverspeedSearch(s, o);
  EXPECT_EQ(r.status, "floor");
  EXPECT_FALSE(r.n_dyn_rpm);
  EXPECT_DOUBLE_EQ(r.floor_rpm, 900.0);
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_DOUBLE_EQ(r.rows.front().speed_rpm, 900.0);
  EXPECT_TRUE(r.rows.front().lifts_off);
}

// A run asking only "does it lift off?" gives the full run's verdict, and stops at the jump.
TEST(StopAtLiftoffTest, TheEarlyStoppedRunGivesTheFullRunsVerdict) {
  const Scene s = MakeScene(ParseCase(kWeakSpring, "weak-spring.toml"));
  for (const char* method : {"exact", "dopri5"}) {
    for (double n : {700.0, 805.0, 820.0, 1000.0}) {
      SimulationOptions o;
      o.force_dynamic = true;
      o.method = method;
      const SimulationResult full = Simulate(s, n, o);
      o.stop_at_liftoff = true;
      const SimulationResult early = Simulate(s, n, o);
      const bool lifts = RowFromResult(full).lifts_off;
      EXPECT_EQ(RowFromResult(early).lifts_off, lifts) << method << ' ' << n;
      EXPECT_EQ(lifts, n > 811.0) << method << ' ' << n;
      if (!lifts) {
        // Stopped just past the lift, its least contact force over the lift the full run's.
        EXPECT_EQ(early.status, RunStatus::kStopped);
        EXPECT_GT(early.run_end_rad, s.law->end_rad());
        EXPECT_LT(early.run_end_rad, full.run_end_rad);
        EXPECT_EQ(early.min_contact_force_during_lift_N, full.min_contact_force_during_lift_N);
        // What it reports besides: its largest lift (the not-following rule reads it) is the
        // full run's; no energy residual (the closed form integrates no W and D for it).
        EXPECT_EQ(early.max_lift_m, full.max_lift_m) << method << ' ' << n;
        EXPECT_TRUE(std::isnan(early.energy_residual)) << method << ' ' << n;
        EXPECT_FALSE(std::isnan(full.energy_residual)) << method << ' ' << n;
        EXPECT_TRUE(early.episodes.empty() || !early.episodes.back().open);
        continue;
      }
      EXPECT_EQ(early.status, RunStatus::kStopped) << method << ' ' << n;
      EXPECT_LT(early.run_end_rad, full.run_end_rad);
      // It ends in its first jump, at the end of the step (of exact: the closed-form piece) that
      // took it past kMinJump_rad, before the lift is over.
      ASSERT_FALSE(early.episodes.empty());
      const Episode& e = early.episodes.back();
      EXPECT_EQ(e.kind, "jump");
      EXPECT_GE(e.end_rad - e.start_rad, kMinJump_rad);
      EXPECT_LE(e.end_rad, early.run_end_rad);
      EXPECT_LT(early.run_end_rad - e.start_rad, 5.0 * kDeg) << method << ' ' << n;
      EXPECT_LT(early.run_end_rad, s.law->end_rad());
      EXPECT_LT(early.stats.steps, full.stats.steps);
    }
  }
}

// A lift-off window narrower than the scan step: a fixed 15 rpm scan from 200 rpm steps over it
// (575 and 590 rpm hold) and finds the next, at 635 rpm; the search led by the contact force
// finds the window.
TEST(OverspeedScanTest, TheForceLedScanFindsANarrowWindowAFixedScanMisses) {
  const Scene s = MakeScene(ParseCase(kNarrowWindow, "narrow-window.toml"));
  const double fixed = FirstLiftOff(s, 200.0, 700.0, 15.0);
  EXPECT_GT(fixed, 620.0);
  OverspeedOptions o = NarrowWindowScan();
  const OverspeedResult r = OverspeedSearch(s, o);
  ASSERT_TRUE(r.n_dyn_rpm);
  EXPECT_NEAR(*r.n_dyn_rpm, 578.57, 0.5);
  EXPECT_TRUE(LiftsOff(s, *r.n_dyn_rpm));
  EXPECT_FALSE(LiftsOff(s, r.bracket_low_rpm));
  EXPECT_FALSE(LiftsOff(s, 575.0));
  EXPECT_TRUE(LiftsOff(s, 582.5));
  EXPECT_FALSE(LiftsOff(s, 590.0));  // past the window
  // The thread count changes nothing: the same speeds, the same answer.
  o.threads = 1;
  const OverspeedResult one = OverspeedSearch(s, o);
  ASSERT_TRUE(one.n_dyn_rpm);
  EXPECT_EQ(*one.n_dyn_rpm, *r.n_dyn_rpm);
  EXPECT_EQ(one.rows.size(), r.rows.size());
}

// While the force stays at zero (the contact lost, the jumps still short of 0.1°), the scan's step
// at most doubles: with 0.8 N more preload than kNarrowWindow the contact is lost from 578.97 rpm
// and the window is 580.27–584.56 rpm wide; the scan stepped from 579.97 to 594.97 rpm over it
// and reported 624.4 rpm.
TEST(OverspeedScanTest, AScanWhereTheContactIsLostStepsNoFasterThanDoubling) {
  std::string text = kNarrowWindow;
  text.replace(text.find("preload_N = 496.3"), 17, "preload_N = 497.1");
  const Scene s = MakeScene(ParseCase(text, "narrower-window.toml"));
  OverspeedOptions o = NarrowWindowScan();
  const OverspeedResult r = OverspeedSearch(s, o);
  ASSERT_TRUE(r.n_dyn_rpm);
  EXPECT_GT(*r.n_dyn_rpm, 580.0);
  EXPECT_LT(*r.n_dyn_rpm, 584.6);
  EXPECT_TRUE(LiftsOff(s, *r.n_dyn_rpm));
  EXPECT_FALSE(LiftsOff(s, r.bracket_low_rpm));
}

// A row and the outcome as fields: SI inside (rad, m), deg and mm shown; an n_dyn not found is
// a field without a value under its published key; the columns' SI keys are Python's.
TEST(OverspeedFieldsTest, RowsAndOutcomeShowTheirUnits) {
  OverspeedRow row;
  row.speed_rpm = 812.5;
  row.jump_rad = 2.0 * kDeg;
  row.max_gap_m = 1e-4;
  row.lifts_off = true;
  const std::vector<Field> f = OverspeedRowFields(row);
  EXPECT_NEAR(*FieldAt(f, "jump_deg").Shown(), 2.0, 1e-14);
  EXPECT_NEAR(*FieldAt(f, "max_gap_mm").Shown(), 0.1, 1e-15);
  EXPECT_TRUE(FieldAt(f, "lifts_off").flag);
  EXPECT_EQ(FieldAt(f, "status").text, "complete");
  const std::vector<double> si = OverspeedRowSi(row);
  std::vector<std::string> keys;
  for (const Column& c : OverspeedColumns()) keys.push_back(c.SiKey());
  EXPECT_EQ(keys, (std::vector<std::string>{"speed_rpm", "min_contact_force_N", "jump_rad",
                                            "max_gap_m", "max_impact_speed_m_s", "lifts_off"}));
  EXPECT_EQ(si[2], row.jump_rad);
  EXPECT_EQ(si[5], 1.0);

  OverspeedResult r;
  r.status = "none";
  r.bracket_low_rpm = 900.0;
  r.bracket_high_rpm = 905.0;
  const std::vector<Field> o = OverspeedFields(r);
  EXPECT_FALSE(FieldAt(o, "liftoff_rpm_dynamic").Shown().has_value());
  EXPECT_EQ(FieldAt(o, "bracket_rpm").list_si, (std::vector<double>{900.0, 905.0}));
  EXPECT_EQ(FieldAt(o, "status").text, "none");
}

// A start guess (OverspeedOptions::start_rpm: a tolerance sample starts at its nominal's n_dyn)
// below, at and above n_dyn finds the lift-off of the scan from `from`, to its resolution, with a
// bracket run at both ends; from the guess at n_dyn in fewer runs.
TEST(OverspeedScanTest, AStartGuessFindsTheLiftOffOfTheWholeScan) {
  const Scene s = MakeScene(LoadCase(kCases + "basu-cam4-light-spring.toml"));
  OverspeedOptions o;
  o.from_rpm = 400;
  o.to_rpm = 1200;
  o.threads = 1;
  const OverspeedResult whole = OverspeedSearch(s, o);
  ASSERT_TRUE(whole.n_dyn_rpm);
  for (const double guess : {0.93 * *whole.n_dyn_rpm, *whole.n_dyn_rpm, 1.08 * *whole.n_dyn_rpm}) {
    o.start_rpm = guess;
    const OverspeedResult r = OverspeedSearch(s, o);
    ASSERT_EQ(r.status, "found") << guess;
    ASSERT_TRUE(r.n_dyn_rpm);
    EXPECT_NEAR(*r.n_dyn_rpm, *whole.n_dyn_rpm, o.resolution_rpm) << guess;
    EXPECT_LE(r.bracket_high_rpm - r.bracket_low_rpm, o.resolution_rpm);
    bool low = false, high = false;
    for (const OverspeedRow& row : r.rows) {
      if (row.speed_rpm == r.bracket_low_rpm) low = !row.lifts_off;
      if (row.speed_rpm == r.bracket_high_rpm) high = row.lifts_off;
      EXPECT_GE(row.speed_rpm, 400.0);
    }
    EXPECT_TRUE(low && high) << guess;  // both ends run: none at the low, lift-off at the high
    if (guess == *whole.n_dyn_rpm) {
      EXPECT_LT(r.rows.size(), whole.rows.size());
    }
  }
}

// What a start guess gives up: a lift-off window below the speed the scan starts from is not
// looked for (dynamics/overspeed.h). From 600 rpm the narrow-window scene's window below 587 rpm
// is not found; the scan from 200 rpm finds it.
TEST(OverspeedScanTest, AStartGuessAboveAWindowDoesNotLookBelowIt) {
  const Scene s = MakeScene(ParseCase(kNarrowWindow, "narrow-window.toml"));
  OverspeedOptions o = NarrowWindowScan();
  o.start_rpm = 600;
  const OverspeedResult r = OverspeedSearch(s, o);
  ASSERT_TRUE(r.n_dyn_rpm);
  EXPECT_GT(*r.n_dyn_rpm, 620.0);
  EXPECT_TRUE(LiftsOff(s, *r.n_dyn_rpm));
  EXPECT_FALSE(LiftsOff(s, r.bracket_low_rpm));
  o.start_rpm.reset();
  EXPECT_LT(*OverspeedSearch(s, o).n_dyn_rpm, 587.0);
}

// With start_after_rpm the scan runs from `from` as without a guess up to there: the window
// below the guess that the guess alone steps over (the test above) is found, with the same
// n_dyn and the same runs as the scan without a guess; past a window-free start_after the guess
// still saves runs and finds the same lift-off.
TEST(OverspeedScanTest, AGuessTakenOnlyPastAGivenSpeedKeepsTheScanBelowIt) {
  const Scene s = MakeScene(ParseCase(kNarrowWindow, "narrow-window.toml"));
  OverspeedOptions o = NarrowWindowScan();
  const OverspeedResult full = OverspeedSearch(s, o);
  ASSERT_TRUE(full.n_dyn_rpm);
  ASSERT_LT(*full.n_dyn_rpm, 587.0);
  o.start_rpm = 600;
  o.start_after_rpm = 590;  // the window lies below: the scan reaches it before the jump
  const OverspeedResult guarded = OverspeedSearch(s, o);
  ASSERT_TRUE(guarded.n_dyn_rpm);
  EXPECT_EQ(*guarded.n_dyn_rpm, *full.n_dyn_rpm);
  ASSERT_EQ(guarded.rows.size(), full.rows.size());
  for (size_t i = 0; i < full.rows.size(); ++i)
    EXPECT_EQ(guarded.rows[i].speed_rpm, full.rows[i].speed_rpm) << i;

  const Scene light = MakeScene(LoadCase(kCases + "basu-cam4-light-spring.toml"));
  OverspeedOptions p;
  p.from_rpm = 400;
  p.to_rpm = 1500;
  const OverspeedResult whole = OverspeedSearch(light, p);
  ASSERT_TRUE(whole.n_dyn_rpm);
  p.start_rpm = *whole.n_dyn_rpm;
  p.start_after_rpm = 410;
  const OverspeedResult jumped = OverspeedSearch(light, p);
  ASSERT_TRUE(jumped.n_dyn_rpm);
  EXPECT_NEAR(*jumped.n_dyn_rpm, *whole.n_dyn_rpm, 0.5);
  EXPECT_LT(jumped.rows.size(), whole.rows.size()) << *whole.n_dyn_rpm;
  EXPECT_TRUE(LiftsOff(light, *jumped.n_dyn_rpm));
  EXPECT_FALSE(LiftsOff(light, jumped.bracket_low_rpm));
}

// Issue 51's scene (undamped contacts, 0.38 mm of play on 12.4° ramps): the needle seats just
// before the cam's lift closes and rebounds off the undamped seat. Those rebounds begin after the
// first seating, so they are secondary openings (docs/model.md §6, contract rev. 4), not jumps:
// counted as jumps, they made lift-off windows at 116.5, 119.5, 125.5 … 139 rpm that one method's
// sweep found and another's stepped over (n_dyn 229.3 against 296.9 rpm when filed, 139.0 for
// every method before this fix, with jumps below it). Every method now gives one n_dyn, with no
// lift-off below it.
const char* const kUndampedRebound = R"(
[engine]
speed_rpm = 389.7
cycle = "four-stroke"
[lift]
crank_deg = [-29.440073006, -28.555507233, -27.67094146, -26.786375687, -25.901809914, -25.017244141, -24.132678368, -23.248112595, -22.363546822, -21.478981049, -20.594415276, -19.709849503, -18.82528373, -17.940717957, -17.056152184, -16.171586411, -15.287020638, -14.402454865, -13.517889092, -12.633323319, -11.748757546, -10.864191773, -9.979626, -9.095060227, -8.210494454, -7.325928681, -6.441362908, -5.556797135, -4.672231362, -3.787665589, -2.903099816, -2.018534043, -1.13396827, -0.249402497, 0.635163276, 1.519729049, 2.404294822, 3.288860595, 4.173426368, 5.057992141, 5.942557914, 6.827123687, 7.71168946, 8.596255233, 9.480821006, 10.365386779, 11.249952552, 12.134518325, 13.019084098, 13.903649871, 14.788215644, 15.672781417, 16.55734719, 17.441912963, 18.326478736]
lift_mm = [0, 0, 0.020998255, 0.083594947, 0.186603411, 0.328070878, 0.505315501, 0.714977192, 0.953081322, 1.215114068, 1.496107985, 1.790736173, 2.093413263, 2.398401302, 2.699918525, 2.992248965, 3.269850814, 3.527461476, 3.760197337, 3.963646342, 4.133951638, 4.267884689, 4.36290648, 4.417215648, 4.430631543, 4.430631543, 4.430631543, 4.430631543, 4.419762088, 4.376848929, 4.301961212, 4.196206718, 4.061149823, 3.898788362, 3.711524071, 3.502127065, 3.273694857, 3.029606538, 2.773472794, 2.509082491, 2.240346634, 1.971240507, 1.705744872, 1.447787083, 1.20118299, 0.969580492, 0.756405578, 0.564811646, 0.397632856, 0.257342206, 0.146014951, 0.065297902, 0.01638507, 0, 0]
spline = "not-a-knot"
breaks_deg = []
[needle]
mass_kg = 0.107216
[spring]
preload_N = 6.85769
rate_N_mm = 6.93079
[train]
contact_stiffness_N_m = 7.40699e+06
seat_stiffness_N_m = 2.26794e+07
contact_damping_ratio = 0
seat_damping_ratio = 0
play_mm = 0.382494
ramp_deg = 12.414
)";

// Whether a run at n, stopped once its verdict is final, lifts off (a jump of kMinJump_rad).
bool LiftsOffBy(const Scene& s, double n, const char* method) {
  SimulationOptions o;
  o.force_dynamic = true;
  o.stop_at_liftoff = true;
  o.method = method;
  return RowFromResult(Simulate(s, n, o)).lifts_off;
}

TEST(OverspeedMethodTest, AReboundAfterSeatingIsNoLiftOffAndEveryMethodFindsOneNdyn) {
  const Scene s = MakeScene(ParseCase(kUndampedRebound, "undamped-rebound.toml"));
  // 130 rpm: the needle seats at 17.14°, rebounds and reopens by microns before the cam closes.
  SimulationOptions full;
  full.force_dynamic = true;
  const SimulationResult at130 = Simulate(s, 130.0, full);
  EXPECT_FALSE(RowFromResult(at130).lifts_off);
  EXPECT_GT(at130.secondary_lift_m, 1e-6);
  int rebounds = 0;
  for (const Episode& e : at130.episodes) {
    EXPECT_NE(e.kind, "jump") << e.start_rad / kDeg;
    rebounds += e.kind == "rebound";
  }
  EXPECT_GT(rebounds, 0);

  std::vector<double> n_dyn;
  for (const char* method : {"exact", "dopri5", "rkf78"}) {
    OverspeedOptions o;
    o.from_rpm = 389.7;
    o.to_rpm = 782.6;
    o.simulation.method = method;
    const OverspeedResult r = OverspeedSearch(s, o);
    ASSERT_TRUE(r.n_dyn_rpm) << method;
    n_dyn.push_back(*r.n_dyn_rpm);
    EXPECT_TRUE(LiftsOffBy(s, *r.n_dyn_rpm, method)) << method;
  }
  for (double n : n_dyn) EXPECT_NEAR(n, n_dyn.front(), 0.5);
  // No lift-off below it: every rpm from 100 rpm, and each former window.
  for (double n = 100.0; n < n_dyn.front() - 0.5; n += 1.0)
    EXPECT_FALSE(LiftsOffBy(s, n, "exact")) << n;
  for (double n : {116.5, 119.5, 125.5, 127.0, 128.5, 132.0, 133.5, 135.0, 135.5, 139.0})
    EXPECT_FALSE(LiftsOffBy(s, n, "exact")) << n;
}

}  // namespace
}  // namespace needle
