// The cam as the needle sees it (docs/model.md §3).
#include "dynamics/model/cam_input.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/units.h"

namespace needle {
namespace {

LiftLaw Law(SplineKind kind = SplineKind::kNotAKnot) {
  LiftTable t;
  for (int i = 0; i <= 4; ++i) {  // s = 2 mm · sin(πθ/0.4): end slopes ±π/0.4 · 2 mm
    t.crank_rad.push_back(0.1 * i);
    t.lift_m.push_back(2e-3 * std::sin(kPi * 0.1 * i / 0.4));
  }
  SplineOptions o;
  o.kind = kind;
  return LiftLaw(t, o);
}

TEST(CamInputTest, WithoutPlayTheEndsHoldTheTableValues) {
  const LiftLaw law = Law();
  const CamInput cam(law, 0.0, RampKind::kTangent, 0.0);
  EXPECT_EQ(cam.U(-0.5), 0.0);
  EXPECT_EQ(cam.Slope(-0.5), 0.0);
  EXPECT_NEAR(cam.U(0.2), 2e-3, 1e-15);
  EXPECT_EQ(cam.U(0.5), cam.U(0.4));
  EXPECT_EQ(cam.rise_start_rad(), 0.0);
  EXPECT_EQ(cam.fall_end_rad(), 0.4);
}

TEST(CamInputTest, TangentRampsReachTheBaseCircle) {
  const LiftLaw law = Law();
  const double play = 0.5e-3;
  const CamInput cam(law, play, RampKind::kTangent, 0.0);
  const double s0 = law.spline().Evaluate(0.0, 1), sn = law.spline().Evaluate(0.4, 1);
  EXPECT_NEAR(cam.rise_start_rad(), -play / s0, 1e-15);  // 0 + s0'(θ − 0) = −δ
  EXPECT_NEAR(cam.fall_end_rad(), 0.4 + play / -sn, 1e-15);
  EXPECT_NEAR(cam.U(cam.rise_start_rad() - 0.1), -play, 1e-18);
  EXPECT_NEAR(cam.U(0.5 * cam.rise_start_rad()), -0.5 * play, 1e-15);
  EXPECT_NEAR(cam.Slope(0.5 * cam.rise_start_rad()), s0, 1e-15);  // C¹ at θ0
  EXPECT_EQ(cam.Breaks().front(), cam.rise_start_rad());
  EXPECT_EQ(cam.Breaks().back(), cam.fall_end_rad());
}

// USlope (one search for the piece, NeedleTrain::Evaluate's) is U and Slope bit for bit, on every
// spline kind, the ramps, the base circle and at the breaks.
TEST(CamInputTest, USlopeIsUAndSlopeBitForBit) {
  for (const SplineKind kind : {SplineKind::kNotAKnot, SplineKind::kPchip, SplineKind::kMakima}) {
    const LiftLaw law = Law(kind);
    for (const double play : {0.0, 0.4e-3}) {
      const CamInput cam(law, play, RampKind::kLinear, 0.2);
      std::vector<double> angles = cam.Breaks();
      for (int i = 0; i <= 1000; ++i) angles.push_back(-0.5 + 1.4 * i / 1000.0);
      for (const double th : angles) {
        const auto [u, slope] = cam.USlope(th);
        EXPECT_EQ(u, cam.U(th)) << th;
        EXPECT_EQ(slope, cam.Slope(th)) << th;
      }
    }
  }
}

TEST(CamInputTest, LinearRamps) {
  const LiftLaw law = Law();
  const CamInput cam(law, 0.4e-3, RampKind::kLinear, 0.2);
  EXPECT_NEAR(cam.U(-0.1), -0.2e-3, 1e-15);  // halfway up from −δ to s(θ0) = 0
  EXPECT_NEAR(cam.Slope(-0.1), 0.4e-3 / 0.2, 1e-15);
  EXPECT_NEAR(cam.U(0.5), (law.spline().Evaluate(0.4) - 0.4e-3) / 2, 1e-15);
  EXPECT_NEAR(cam.U(0.7), -0.4e-3, 1e-15);
  // Pieces are half-open: at a break the value after it.
  EXPECT_EQ(cam.Slope(-0.2), 0.4e-3 / 0.2);
  EXPECT_EQ(cam.Slope(cam.fall_end_rad()), 0.0);
}

TEST(CamInputTest, ZeroEndSlopeCannotReachTheBaseCircle) {
  const LiftLaw law = Law(SplineKind::kClamped);  // at rest: zero end slopes
  try {
    CamInput(law, 0.5e-3, RampKind::kTangent, 0.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("tangent ramps need a rising start and a falling end, but the lift law's "
                      "end slopes are ",
                      0),
              0u)
        << m;
    EXPECT_NE(m.find("(the start is flat and the end is flat): no tangent there reaches the base "
                     "circle; give ramp_deg"),
              std::string::npos)
        << m;
  }
  EXPECT_THROW(CamInput(law, -1e-3, RampKind::kLinear, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// Tangent ramps refused say why, end by end: a law at rest at its ends (a clamped spline's, or
// any whose tangent would take more than a crank revolution to reach −δ) is "flat" there; a
// table that ends still rising has an end that "rises"; the way out is ramp_deg, and another
// spline kind only where the clamped one put the ends at rest. (A new user's 3-4-5 law exported
// to 9 decimals was told "a zero end slope" of slopes 7.9e-5 and +2.1e-5 mm/deg, and to use
// not-a-knot, which it used.)
TEST(CamInputTest, RefusedTangentRampsSayWhichEndAndWhy) {
  const auto refusal = [](const LiftLaw& law) {
    try {
      CamInput cam(law, 0.1e-3, RampKind::kTangent, 0.0);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string flat = refusal(Law(SplineKind::kClamped));
  EXPECT_NE(flat.find(" mm/deg (the start is flat and the end is flat): no tangent there reaches "
                      "the base circle; give ramp_deg (a linear ramp over that many degrees takes "
                      "up the play), or a spline whose ends follow the readings (not-a-knot) in "
                      "place of the clamped one, at rest by construction"),
            std::string::npos)
      << flat;
  LiftTable t;  // a quarter sine: rising from the seat, still rising at its last reading
  for (int i = 0; i <= 4; ++i) {
    t.crank_rad.push_back(0.1 * i);
    t.lift_m.push_back(2e-3 * std::sin(kPi * 0.1 * i / 1.0));
  }
  SplineOptions o;
  o.kind = SplineKind::kNotAKnot;
  const std::string rises = refusal(LiftLaw(t, o));
  EXPECT_NE(rises.find(" mm/deg (the end rises): no tangent there reaches the base circle; give "
                       "ramp_deg (a linear ramp over that many degrees takes up the play)"),
            std::string::npos)
      << rises;
  EXPECT_EQ(rises.find("not-a-knot"), std::string::npos) << rises;
}

// Issue 12: an end slope flat up to noise made the tangent ramp 42.5 million degrees long
// (and the run window with it). A ramp longer than a crank revolution is refused, with the way
// out; the play of the law above, 2 mm at slope 5π mm/rad, needs a ramp of 0.127 rad: fine.
TEST(CamInputTest, ARampLongerThanARevolutionIsRefused) {
  const LiftLaw law = Law();
  EXPECT_NO_THROW(CamInput(law, 2e-3, RampKind::kTangent, 0.0));
  // The end slope is about 2 mm·π/0.4 = 15.7 mm/rad: a play of 0.2 m takes ≈ 12.7 rad > 2π.
  const double slope = law.spline().Evaluate(0.0, 1);
  try {
    CamInput cam(law, 0.2, RampKind::kTangent, 0.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("the tangent ramp at the lift's start would take " +
                                              std::to_string(0.2 / slope / kDeg) + " deg",
                                          0),
              0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("more than a crank revolution"), std::string::npos);
  }
}

}  // namespace
}  // namespace needle
