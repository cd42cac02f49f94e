// Lift laws: Basu's normal curve, mean lift and ρ, extremes, the closed needle outside the
// table, and the smoothing spline's robustness to the paper's rounding.
#include "lib/lift_law.h"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cmath>
#include <random>

#include "apps/case/case_file.h"
#include "lib/cam_laws.h"
#include "lib/kinematics.h"
#include "lib/units.h"

namespace needle {
namespace {

const std::string kPaper = std::string(NEEDLE_SHARED_DIR) + "/basu-tm477.toml";
const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

TEST(LiftLawTest, NormalCurveMatchesThePaperTable) {
  const toml::table paper = toml::parse_file(kPaper);
  const auto* percent = paper["normal_curve"]["percent"].as_array();
  const auto* crank = paper["normal_curve"]["crank_deg"].as_array();
  ASSERT_TRUE(percent && crank);
  const LiftTable t = BasuNormalCurve(2.5e-3);
  ASSERT_EQ(t.lift_m.size(), percent->size());
  for (size_t i = 0; i < t.lift_m.size(); ++i) {
    EXPECT_DOUBLE_EQ(t.lift_m[i], 2.5e-3 * percent->get(i)->value<double>().value() / 100.0);
    EXPECT_NEAR(t.crank_rad[i], crank->get(i)->value<double>().value() * kDeg, 1e-15);
  }
}

TEST(LiftLawTest, NormalCurveMeanLiftAndRhoBesideBasusPlanimetry) {
  // Basu measured 1.18 mm by planimetry for 2.5 mm (ρ = 2.12). The spline's exact integral
  // agrees with Simpson's rule on the table to 0.5 %, and with Basu to 3 %.
  const LiftTable t = BasuNormalCurve(2.5e-3);
  double simpson = 0;
  for (size_t i = 0; i + 2 < t.lift_m.size(); i += 2) {
    simpson += (t.lift_m[i] + 4 * t.lift_m[i + 1] + t.lift_m[i + 2]) / 3.0;
  }
  simpson += 0.5 * (t.lift_m[10] + t.lift_m[11]);  // last odd interval: trapezoid
  simpson /= 11.0;
  for (SplineKind kind : {SplineKind::kNotAKnot, SplineKind::kNatural, SplineKind::kClamped,
                          SplineKind::kQuintic, SplineKind::kPchip}) {
    SplineOptions o;
    o.kind = kind;
    const LiftLaw law(t, o);
    EXPECT_NEAR(law.MeanLift(), simpson, 0.005 * simpson) << SplineKindName(kind);
    const double rho = 2.5e-3 / law.MeanLift();
    EXPECT_NEAR(rho, 2.12, 0.03 * 2.12) << SplineKindName(kind);
  }
}

TEST(LiftLawTest, ClosedOutsideTheTable) {
  SplineOptions o;
  const LiftLaw law(BasuNormalCurve(2.5e-3), o);
  EXPECT_EQ(law.Lift(-16 * kDeg), 0.0);
  EXPECT_EQ(law.Derivative(41 * kDeg, 1), 0.0);
  EXPECT_NEAR(law.Lift(20 * kDeg), 2.5e-3, 1e-15);
}

TEST(LiftLawTest, ExtremesOfAClosedFormLawAreFoundWithTheirAngles) {
  // Cycloidal rise sampled finely: max velocity 2H/β at β/2, max acceleration 2πH/β² at β/4.
  const double h = 3e-3, beta = 50 * kDeg;
  const CamLaw law(CamLawKind::kCycloidal, h, beta);
  LiftTable t;
  for (int i = 0; i <= 200; ++i) {
    t.crank_rad.push_back(beta * i / 200.0);
    t.lift_m.push_back(law.Lift(beta * i / 200.0));
  }
  SplineOptions o;
  o.kind = SplineKind::kQuintic;
  const LiftLaw lift(t, o);
  EXPECT_NEAR(lift.Max(1).value, 2 * h / beta, 1e-9);
  EXPECT_NEAR(lift.Max(1).crank_rad, beta / 2, 1e-6);
  EXPECT_NEAR(lift.Max(2).value, 2 * kPi * h / (beta * beta), 1e-6);
  EXPECT_NEAR(lift.Max(2).crank_rad, beta / 4, 1e-4);
  EXPECT_NEAR(lift.Min(2).crank_rad, 3 * beta / 4, 1e-4);
  EXPECT_NEAR(lift.Max(0).value, h, 1e-12);
}

TEST(LiftLawTest, InjectionPeriodIsLiftDurationOverSixN) {
  // Basu: 55° at 125 rpm is 55·60/(125·360) = 0.0733 s; at 400 rpm 0.0229 s.
  const Case c = LoadCase(kCases + "basu-example1.toml");
  const LiftLaw law = MakeLiftLaw(c);
  EXPECT_NEAR(Kinematics(law, 125).Summarize().injection_period_s, 55.0 / (6 * 125), 1e-15);
  EXPECT_NEAR(Kinematics(law, 400).Summarize().injection_period_s, 55.0 / (6 * 400), 1e-15);
}

// Spread (standard deviation) of the largest deceleration of a table when every lift is
// perturbed uniformly within ±0.005 mm (half the paper's resolution).
double DecelerationSpread(const LiftTable& table, SplineKind kind) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-0.005e-3, 0.005e-3);
  double sum = 0, sum2 = 0;
  const int trials = 60;
  for (int k = 0; k < trials; ++k) {
    LiftTable t = table;
    for (size_t i = 1; i + 1 < t.lift_m.size(); ++i)
      t.lift_m[i] = std::max(0.0, t.lift_m[i] + u(rng));
    SplineOptions o;
    o.kind = kind;
    const double a = LiftLaw(t, o).Min(2).value;
    sum += a;
    sum2 += a * a;
  }
  const double mean = sum / trials;
  return std::sqrt(std::max(0.0, sum2 / trials - mean * mean));
}

TEST(LiftLawTest, SmoothingSplineNarrowsTheAccelerationSpreadUnderRounding) {
  for (const char* name : {"basu-cam4.toml", "basu-example1.toml"}) {
    const Case c = LoadCase(kCases + name);
    const double cubic = DecelerationSpread(c.lift.table, SplineKind::kNotAKnot);
    const double smooth = DecelerationSpread(c.lift.table, SplineKind::kSmoothing);
    std::printf("%s: spread of min s'' under ±0.005 mm: not-a-knot %.4g, smoothing %.4g m/rad²\n",
                name, cubic, smooth);
    EXPECT_LT(smooth, cubic) << name;
  }
}

// A cam of two parabolas joined with equal slope (s'' = 2 then −2 at θ = 1): built apart on each
// piece (breaks), the not-a-knot cubic reproduces each parabola, so s'' keeps its jump to
// round-off; one spline across the join smears it.
TEST(LiftLawTest, BreaksKeepAJumpInTheAccelerationThatOneSplineSmears) {
  LiftTable t;
  for (int i = 0; i <= 20; ++i) {
    const double x = 0.1 * i;
    t.crank_rad.push_back(x);
    t.lift_m.push_back(x <= 1.0 ? x * x : 1.0 + 2.0 * (x - 1.0) - (x - 1.0) * (x - 1.0));
  }
  LiftLawOptions o;
  o.breaks_rad = {1.0};
  const LiftLaw broken(t, o);
  EXPECT_TRUE(broken.HasAcceleration());
  for (double x : {0.05, 0.55, 0.95, 0.999999})
    EXPECT_NEAR(broken.Derivative(x, 2), 2.0, 1e-9) << x;
  for (double x : {1.0, 1.05, 1.55, 1.95}) EXPECT_NEAR(broken.Derivative(x, 2), -2.0, 1e-9) << x;
  EXPECT_NEAR(broken.Derivative(1.0 - 1e-12, 1), 2.0, 1e-9);  // slopes still meet
  EXPECT_NEAR(broken.Derivative(1.0, 1), 2.0, 1e-9);
  const LiftLaw smeared(t, LiftLawOptions{});
  EXPECT_GT(std::abs(smeared.Derivative(0.95, 2) - 2.0), 0.1);
}

TEST(LiftLawTest, BreaksMustBeTableAnglesInsideTheOpenLiftOfAnExactTable) {
  LiftTable t{{0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8}, {0, 1, 2, 3, 4, 5, 6, 7, 8}};
  const auto message = [&](std::vector<double> breaks, double closed_level = 0.0) {
    LiftLawOptions o;
    o.breaks_rad = std::move(breaks);
    o.closed_level_m = closed_level;
    try {
      LiftLaw law(t, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  for (double& y : t.lift_m) y *= 1e-3;
  EXPECT_EQ(message({0.25}),
            "break 0 (14.3239°) must be an angle of the table strictly inside the open lift (0° "
            "to 45.8366°)");
  EXPECT_EQ(message({0.8}),
            "break 0 (45.8366°) must be an angle of the table strictly inside the open lift (0° "
            "to 45.8366°)");
  EXPECT_EQ(message({0.5, 0.4}), "break 1 (22.9183°) must come after the one before it");
  EXPECT_EQ(message({0.1}),
            "the piece 0° to 5.72958° between breaks has 2 points; \"not-a-knot\" needs at "
            "least 4");
  // Measured data is built apart at its breaks too (issue 50: the seat and the junctions found
  // in a measured table).
  EXPECT_EQ(message({0.4}, 1e-5), "no error");
  EXPECT_EQ(message({0.4}), "no error");
}

}  // namespace
}  // namespace needle
