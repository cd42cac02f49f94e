// Cam-law synthesis with a constant-maximum-speed section (MATEC 2018).
#include "lib/cam_synthesis.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lib/units.h"

namespace needle {
namespace {

// The paper's case: 8 mm in 63° of cam, S'max = 7.6 mm/rad. The paper gives no limits on
// S'' and S'''; 250 mm/rad² and 20 000 mm/rad³ are ours (stated in cases/matec-2018-synth.toml).
SynthesisSpec Paper() {
  SynthesisSpec s;
  s.rise_rad = 63.0 * kDeg;
  s.height_m = 8e-3;
  s.speed_limit = 7.6e-3;
  s.accel_limit = 0.25;
  s.decel_limit = 0.25;
  s.jerk_limit = 20.0;
  return s;
}

void ExpectWithinLimits(const SynthesizedLaw& law, const SynthesisSpec& s) {
  for (size_t i = 0; i < law.phi.size(); ++i) {
    EXPECT_LE(law.s1[i], s.speed_limit * (1 + 1e-12)) << i;
    EXPECT_GE(law.s1[i], -1e-15) << i;
    EXPECT_LE(law.s2[i], s.accel_limit * (1 + 1e-12)) << i;
    EXPECT_GE(law.s2[i], -s.decel_limit * (1 + 1e-12)) << i;
    // Every step, the junction of the two sides too (issue 11: it used to be let off).
    if (i > 0) {
      EXPECT_LE(std::abs(law.s3[i]), s.jerk_limit * (1 + 1e-9)) << i;
    }
    if (i > 0) {
      EXPECT_GT(law.phi[i], law.phi[i - 1]);
    }
  }
}

TEST(CamSynthesisTest, PaperCaseHasAConstantSpeedSectionAtSmax) {
  const SynthesisSpec s = Paper();
  const SynthesizedLaw law = SynthesizeRise(s);
  ExpectWithinLimits(law, s);
  EXPECT_TRUE(law.speed_limit_active);
  EXPECT_NEAR(law.phi.back(), s.rise_rad, 1e-15);
  EXPECT_NEAR(law.s.back(), s.height_m, 1e-15);
  EXPECT_EQ(law.s1.front(), 0.0);
  EXPECT_NEAR(law.s1.back(), 0.0, 1e-12);
  // On the section S' = S'max to rounding, S'' = 0, and φ₀ = ΔS/S'max.
  int inside = 0;
  for (size_t i = 0; i < law.phi.size(); ++i) {
    if (law.phi[i] > law.constant_start_rad + 1e-9 && law.phi[i] < law.constant_end_rad - 1e-9) {
      EXPECT_NEAR(law.s1[i], s.speed_limit, 1e-12 * s.speed_limit);
      EXPECT_EQ(law.s2[i], 0.0);
      ++inside;
    }
  }
  EXPECT_GT(inside, 100);
  const double s_start = law.s[law.junction];
  double s_end = 0;
  for (size_t i = 0; i < law.phi.size(); ++i) {
    if (std::abs(law.phi[i] - law.constant_end_rad) < 1e-12) s_end = law.s[i];
  }
  EXPECT_NEAR(law.constant_length_rad(), (s_end - s_start) / s.speed_limit, 1e-9);
  std::printf("paper case: constant-speed section %.3f..%.3f deg (%.3f deg), limits used %.4f\n",
              law.constant_start_rad / kDeg, law.constant_end_rad / kDeg,
              law.constant_length_rad() / kDeg, law.scale);
}

TEST(CamSynthesisTest, WithoutAnActiveSpeedLimitTheSidesMeetWithinTheJerkLimit) {
  SynthesisSpec s = Paper();
  s.speed_limit = 1e300;  // the earlier scheme [3, 4]
  const SynthesizedLaw law = SynthesizeRise(s);
  ExpectWithinLimits(law, s);
  EXPECT_FALSE(law.speed_limit_active);
  // The sides would meet with S'' = ±a (a step of 2a in one step: S''' ≈ 2a/Δφ, far over the
  // limit). They are made to meet at the speed V* both reach with S'' back at 0: a
  // constant-speed stretch of at most two steps at V*, S'' = 0 at both its ends.
  EXPECT_GT(law.meet_speed, 0.0);
  EXPECT_LE(law.constant_length_rad(), 2.0 * s.rise_rad / 4000.0 * (1 + 1e-9));
  EXPECT_NEAR(law.s2[law.junction], 0.0, 1e-12);
  EXPECT_NEAR(law.s1[law.junction], law.s1[law.junction + 1], 1e-12);
  // Equal limits on both sides: the junction (S'' changes sign) at half the rise, and S' peaks
  // there.
  EXPECT_NEAR(law.phi[law.junction], s.rise_rad / 2, 2 * s.rise_rad / 4000);
  size_t peak = 0;
  for (size_t i = 0; i < law.s1.size(); ++i) {
    if (law.s1[i] > law.s1[peak]) peak = i;
  }
  EXPECT_NEAR(law.phi[peak], s.rise_rad / 2, 2 * s.rise_rad / 4000);
  EXPECT_GT(law.s1[peak], 7.6e-3);  // faster than the limit the other case imposes
}

TEST(CamSynthesisTest, InfeasibleSpecIsRefusedWithTheLeastSmaxThatWorks) {
  SynthesisSpec s = Paper();
  s.speed_limit = 7.2e-3;  // 7.2 mm/rad × 63° = 7.92 mm < 8 mm
  try {
    SynthesizeRise(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind(
                  "infeasible: S'max × rise angle = 7.916813 mm is not more than the "
                  "displacement 8.000000 mm; the least S'max that fits",
                  0),
              0u)
        << e.what();
  }
  const double least = LeastSpeedLimit(s);
  EXPECT_GT(least, 8e-3 / s.rise_rad);
  s.speed_limit = least * 1.001;
  EXPECT_NO_THROW(SynthesizeRise(s));
  s.speed_limit = least * 0.999;
  EXPECT_THROW(SynthesizeRise(s), std::invalid_argument);
}

TEST(CamSynthesisTest, SpecIsValidated) {
  SynthesisSpec s = Paper();
  s.accel_limit = 0.0;
  try {
    SynthesizeRise(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "SynthesisSpec.accel_limit = 0.000000: must be positive");
  }
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

TEST(CamSynthesisStepLimitsTest, CurvatureLimitSteersEveryStepAndAvoidsTheUndercut) {
  // Radial roller follower r_r = 8.25 mm. On the paper's 10 mm base circle the law undercuts;
  // with the curvature limit steering each step (profile radius ≥ 0) the paper's 63° become
  // infeasible, and the message names the least S'max that would fit.
  SynthesisSpec s = Paper();
  s.follower.base_radius_m = 0.010;
  s.follower.roller_radius_m = 0.00825;
  s.follower_limits.min_profile_radius_m = 0.0;
  try {
    SynthesizeRise(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the least S'max that fits is 7.94"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(
                  "with the limits of the cam and its roller follower; the least base radius"),
              std::string::npos);
  }
  // On a 30 mm base circle it fits; the cap binds near the crest, and every convex step keeps
  // a profile radius ≥ 0 while the derivative limits still hold.
  s.follower.base_radius_m = 0.030;
  const SynthesizedLaw law = SynthesizeRise(s);
  EXPECT_TRUE(law.curvature_limited);
  ExpectWithinLimits(law, s);
  double min_radius = 1e9;
  for (size_t i = 0; i < law.phi.size(); ++i) {
    if (law.s2[i] >= 0.0) continue;
    const double r = s.follower.base_radius_m + s.follower.roller_radius_m + law.s[i],
                 v = law.s1[i];
    min_radius =
        std::min(min_radius, std::pow(r * r + v * v, 1.5) / (r * r + 2 * v * v - r * law.s2[i]) -
                                 s.follower.roller_radius_m);
  }
  EXPECT_GE(min_radius, -1e-9);
  EXPECT_LT(min_radius, 1e-5);  // and it is the binding limit: the radius comes down to it
}

TEST(CamSynthesisStepLimitsTest, PressureAngleLimitSteersEveryStep) {
  SynthesisSpec s = Paper();
  s.follower.base_radius_m = 0.030;
  s.follower.roller_radius_m = 0.00825;
  s.follower_limits.max_pressure_angle_rad = 11.0 * kDeg;  // the unsteered law reaches 11.19°
  const SynthesizedLaw law = SynthesizeRise(s);
  EXPECT_TRUE(law.pressure_angle_limited);
  double worst = 0;
  for (size_t i = 0; i < law.phi.size(); ++i) {
    worst = std::max(worst, std::atan(law.s1[i] / (s.follower.base_radius_m +
                                                   s.follower.roller_radius_m + law.s[i])));
  }
  EXPECT_LE(worst, 11.0 * kDeg + 1e-12);
  EXPECT_GT(worst, 10.99 * kDeg);
  ExpectWithinLimits(law, s);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

TEST(CamSynthesisStepLimitsTest, SpringReserveSteersTheDeceleration) {
  // A fuel-pump plunger of 0.2 kg on a 500 N, 20 N/mm spring at 1000 rpm of cam: with
  // K = 1.5 the decelerating side keeps (P₀ + kS) ≥ 1.5·m·ω²·|S''| at every step.
  SynthesisSpec s = Paper();
  s.min_spring_reserve = 1.5;
  s.train.preload_N = 500;
  s.train.rate_N_m = 20e3;
  s.train.mass_kg = 0.2;
  s.cam_omega = OmegaFromRpm(1000);
  const SynthesizedLaw law = SynthesizeRise(s);
  EXPECT_TRUE(law.spring_reserve_limited);
  double worst = INFINITY;
  for (size_t i = 0; i < law.phi.size(); ++i) {
    if (law.s2[i] < 0.0) {
      worst =
          std::min(worst, (500 + 20e3 * law.s[i]) / (0.2 * s.cam_omega * s.cam_omega * -law.s2[i]));
    }
  }
  EXPECT_GE(worst, 1.5 * (1 - 1e-9));
  EXPECT_LT(worst, 1.51);  // binding
  ExpectWithinLimits(law, s);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// Issue 12: a displacement of 3e305 m made LeastSpeedLimit double its bracket to infinity and
// loop forever. The library answers (no S'max fits) without the case loader's range check.
TEST(CamSynthesisTest, AbsurdHeightEndsWithAnInfeasibleAnswer) {
  SynthesisSpec s = Paper();
  s.height_m = 3e305;
  EXPECT_EQ(LeastSpeedLimit(s), INFINITY);
  try {
    SynthesizeRise(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the least S'max that fits with these acceleration "
                                         "limits is inf mm/rad"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// A rise whose decelerating side is capped by a spring reserve that falls with the lift faster
// than the jerk limit lets S'' follow: a gas load of 6 N against a 1000 N/m spring leaves
// k·(S − 6 mm) of spring force, so the cap (K m ω² = 1) drops from 2 m/rad² at the crest to 0
// at 6 mm, at k·S' ≈ 10 m/rad³ where S' ≈ 10 mm/rad, above the jerk limit of 8 m/rad³.
SynthesisSpec FallingCap() {
  SynthesisSpec s;
  s.rise_rad = 63.0 * kDeg;
  s.height_m = 8e-3;
  s.accel_limit = 0.25;
  s.decel_limit = 0.25;
  s.jerk_limit = 8.0;
  s.min_spring_reserve = 1.0;
  s.train.mass_kg = 1.0;
  s.train.preload_N = 0.0;
  s.train.rate_N_m = 1000.0;
  s.train.gas_force_N = 6.0;
  s.cam_omega = 1.0;
  return s;
}

TEST(CamSynthesisBackOffTest, EarlierStepsAreLoweredSoThatTheCapAndTheJerkBothHold) {
  const SynthesisSpec s = FallingCap();
  const SynthesizedLaw law = SynthesizeRise(s);
  EXPECT_GT(law.backed_off_steps, 0u);
  EXPECT_TRUE(law.spring_reserve_limited);
  ExpectWithinLimits(law, s);  // the jerk limit at every step
  double worst = INFINITY;     // the least reserve where S'' < 0 (beyond round-off)
  for (size_t i = 0; i < law.phi.size(); ++i)
    if (law.s2[i] < -1e-12) worst = std::min(worst, s.train.SpringForceN(law.s[i]) / -law.s2[i]);
  EXPECT_GE(worst, 1.0 - 1e-9);  // (K m ω² = 1)
}

}  // namespace
}  // namespace needle
