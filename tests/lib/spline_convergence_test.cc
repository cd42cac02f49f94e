// Velocity and acceleration error of each spline kind against closed-form cam laws
// (cycloidal, harmonic, 3-4-5 polynomial) as the table spacing halves, with and without the
// paper's 0.01 mm rounding; the measured orders are asserted against theory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "lib/cam_laws.h"
#include "lib/lift_law.h"
#include "lib/units.h"

namespace needle {
namespace {

constexpr double kHeight = 2.5e-3;     // m
constexpr double kBeta = 60.0 * kDeg;  // rise angle

struct Errors {
  double velocity;      // max |s' − s'_exact| / max |s'_exact|
  double acceleration;  // max |s'' − s''_exact| / max |s''_exact|
};

Errors Measure(const CamLaw& law, SplineKind kind, double step_deg, double rounding_m = 0.0) {
  LiftTable t;
  const int n = static_cast<int>(std::lround(60.0 / step_deg));
  for (int i = 0; i <= n; ++i) {
    const double th = kBeta * i / n;
    double s = law.Lift(th);
    if (rounding_m > 0) s = std::round(s / rounding_m) * rounding_m;
    t.crank_rad.push_back(th);
    t.lift_m.push_back(s);
  }
  SplineOptions o;
  o.kind = kind;
  if (rounding_m > 0) o.sigma = rounding_m / std::sqrt(12.0);
  const LiftLaw lift(t, o);
  double ev = 0, ea = 0, sv = 0, sa = 0;
  for (int k = 0; k <= 6000; ++k) {
    const double th = kBeta * k / 6000.0;
    ev = std::max(ev, std::abs(lift.Derivative(th, 1) - law.Derivative(th, 1)));
    sv = std::max(sv, std::abs(law.Derivative(th, 1)));
    if (lift.HasAcceleration()) {
      ea = std::max(ea, std::abs(lift.Derivative(th, 2) - law.Derivative(th, 2)));
      sa = std::max(sa, std::abs(law.Derivative(th, 2)));
    }
  }
  return {ev / sv, sa > 0 ? ea / sa : NAN};
}

struct Orders {
  double velocity, acceleration;
};

// Observed order log2(e(h)/e(h/2)) between `coarse_deg` and half of it.
Orders Order(const CamLaw& law, SplineKind kind, double coarse_deg = 2.5) {
  const Errors coarse = Measure(law, kind, coarse_deg), fine = Measure(law, kind, coarse_deg / 2);
  return {std::log2(coarse.velocity / fine.velocity),
          std::log2(coarse.acceleration / fine.acceleration)};
}

const CamLaw kCycloidal(CamLawKind::kCycloidal, kHeight, kBeta);
const CamLaw kHarmonic(CamLawKind::kHarmonic, kHeight, kBeta);
const CamLaw kPoly345(CamLawKind::kPoly345, kHeight, kBeta);

TEST(SplineConvergenceTest, PrintsTheErrorTable) {
  // Not an assertion: the table this suite checks, for the log and docs/lift-data.md.
  std::printf("%-18s %-11s %11s %11s %11s %11s %11s\n", "law", "spline", "v err 5deg", "v err 1deg",
              "a err 5deg", "a err 1deg", "a 1deg rnd");
  for (const CamLaw* law : {&kCycloidal, &kHarmonic, &kPoly345}) {
    for (SplineKind kind : AllSplineKinds()) {
      const Errors e5 = Measure(*law, kind, 5.0), e1 = Measure(*law, kind, 1.0);
      const Errors r1 = Measure(*law, kind, 1.0, 1e-5);
      std::printf("%-18s %-11s %11.2e %11.2e %11.2e %11.2e %11.2e\n", law->name().c_str(),
                  SplineKindName(kind).c_str(), e5.velocity, e1.velocity, e5.acceleration,
                  e1.acceleration, r1.acceleration);
      // Interpolating kinds converge; the smoothing spline's and the local fit's error floor is
      // set by σ (they may move each value by about σ whatever the spacing), an exact fit has
      // none.
      if (kind != SplineKind::kSmoothing && kind != SplineKind::kLocal && e5.velocity > 1e-10) {
        EXPECT_LT(e1.velocity, e5.velocity) << law->name() << " " << SplineKindName(kind);
      }
    }
  }
}

TEST(SplineConvergenceTest, NotAKnotIsThirdOrderInVelocitySecondInAcceleration) {
  for (const CamLaw* law : {&kCycloidal, &kHarmonic, &kPoly345}) {
    const Orders o = Order(*law, SplineKind::kNotAKnot);
    EXPECT_GT(o.velocity, 2.8) << law->name();
    EXPECT_GT(o.acceleration, 1.8) << law->name();
  }
}

TEST(SplineConvergenceTest, ClampedAtRestIsThirdOrderOnLawsThatStartAtRest) {
  for (const CamLaw* law : {&kCycloidal, &kHarmonic, &kPoly345}) {
    const Orders o = Order(*law, SplineKind::kClamped);  // s'(0) = s'(β) = 0: the true slopes
    EXPECT_GT(o.velocity, 2.8) << law->name();
    EXPECT_GT(o.acceleration, 1.8) << law->name();
  }
}

TEST(SplineConvergenceTest, NaturalIsThirdOrderOnlyWhereTheEndCurvatureIsZero) {
  // Cycloidal and 3-4-5 have s''(0) = s''(β) = 0: natural is right there.
  for (const CamLaw* law : {&kCycloidal, &kPoly345}) {
    const Orders o = Order(*law, SplineKind::kNatural);
    EXPECT_GT(o.velocity, 2.8) << law->name();
    EXPECT_GT(o.acceleration, 1.8) << law->name();
  }
  // Harmonic has s''(0) = Hπ²/(2β²) ≠ 0: the natural end forces a wrong curvature, and the
  // acceleration error at the ends does not shrink with h at all.
  const Orders harmonic = Order(kHarmonic, SplineKind::kNatural);
  EXPECT_LT(harmonic.acceleration, 0.2);
  EXPECT_GT(Measure(kHarmonic, SplineKind::kNatural, 1.0).acceleration, 0.5);
}

TEST(SplineConvergenceTest, QuinticIsHigherOrderAndExactOnThe345Law) {
  const Orders o = Order(kCycloidal, SplineKind::kQuintic);
  EXPECT_GT(o.velocity, 4.5);
  EXPECT_GT(o.acceleration, 3.5);
  EXPECT_LT(Measure(kPoly345, SplineKind::kQuintic, 5.0).acceleration, 1e-9);  // s is a quintic
}

TEST(SplineConvergenceTest, ShapePreservingKindsConvergeInVelocity) {
  for (SplineKind kind : {SplineKind::kPchip, SplineKind::kMakima}) {
    // Secant-based slopes are O(h²) accurate: velocity order 2 (pchip is there by 2.5°,
    // makima approaches it more slowly: 1.7 between 2.5° and 1.25°).
    const Orders o = Order(kCycloidal, kind, 1.25);
    EXPECT_GT(o.velocity, 1.8) << SplineKindName(kind);
    EXPECT_TRUE(std::isnan(Measure(kCycloidal, kind, 5.0).acceleration));  // unavailable
  }
}

TEST(SplineConvergenceTest, RoundingTo10umMakesInterpolatedAccelerationWorseAtFineSpacing) {
  // Rounding error e ≈ 5 µm divided by h² grows as h shrinks: at 1° the interpolating
  // cubic's acceleration is worse than at 5°, and the smoothing spline is better than it.
  const Errors r5 = Measure(kCycloidal, SplineKind::kNotAKnot, 5.0, 1e-5);
  const Errors r1 = Measure(kCycloidal, SplineKind::kNotAKnot, 1.0, 1e-5);
  const Errors s1 = Measure(kCycloidal, SplineKind::kSmoothing, 1.0, 1e-5);
  EXPECT_GT(r1.acceleration, r5.acceleration);
  EXPECT_LT(s1.acceleration, 0.5 * r1.acceleration);
}

}  // namespace
}  // namespace needle
