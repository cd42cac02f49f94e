// Spring surge modes of the lumped chain and the cam's harmonics, against closed forms.
#include "spring/resonance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lib/units.h"

namespace needle {
namespace {

constexpr double kRate = 40e3, kMass = 0.05;  // 40 N/mm, 50 g of active coils

TEST(ResonanceTest, TwentyMassesGiveTheWaveEquationsFirstThreeModesWithinOnePercent) {
  const std::vector<double> f = ChainNaturalFrequenciesHz(kRate, kMass, 20, 3);
  for (int i = 1; i <= 3; ++i) {
    const double wave = SurgeFrequencyHz(kRate, kMass, i);
    EXPECT_NEAR(f[i - 1] / wave, 1.0, 0.01) << "mode " << i;
    // And exactly the discrete chain's (N/π)√(k/m_s)·sin(iπ/2N).
    EXPECT_NEAR(f[i - 1], 20.0 / kPi * std::sqrt(kRate / kMass) * std::sin(i * kPi / 40.0),
                1e-9 * wave);
  }
}

TEST(ResonanceTest, ChainErrorFallsWithTheSquareOfTheSegments) {
  const double wave = SurgeFrequencyHz(kRate, kMass, 2);
  const double e20 = std::abs(ChainNaturalFrequenciesHz(kRate, kMass, 20, 2)[1] / wave - 1);
  const double e40 = std::abs(ChainNaturalFrequenciesHz(kRate, kMass, 40, 2)[1] / wave - 1);
  EXPECT_NEAR(std::log2(e20 / e40), 2.0, 0.02);
}

TEST(ResonanceTest, SurgeOfTheHelicalFormula) {
  HelicalGeometry g;
  g.wire_m = 4e-3;
  g.coil_m = 30e-3;
  g.active_coils = 6;
  g.shear_modulus_Pa = 79.5e9;
  g.density_kg_m3 = 7850;
  const double k = g.shear_modulus_Pa * std::pow(g.wire_m, 4) / (8 * std::pow(g.coil_m, 3) * 6);
  // f_e = d/(2π n D²)·√(G/(2ρ)) (EN 13906-1) is the first mode of ½√(k/m_s).
  EXPECT_NEAR(SurgeFrequencyHz(k, ActiveSpringMassKg(g), 1),
              g.wire_m / (2 * kPi * 6 * g.coil_m * g.coil_m) * std::sqrt(79.5e9 / (2 * 7850)),
              1e-9);
}

TEST(ResonanceTest, HarmonicsOfATwoCosineLift) {
  // u = (H/2)(1 − cos ψ) + (H/20)(1 − cos 3ψ) over the whole cam revolution (ψ = θ/2,
  // four-stroke): c₁ = H/2, c₃ = H/20, every other order ~0 (spline error); the acceleration's
  // harmonics are i²c_i: H/2 and 9H/20, so order 3 is significant at 5 %.
  const double h = 2e-3;
  LiftTable t;
  for (int i = 0; i <= 720; ++i) {
    const double th = 4 * kPi * i / 720.0;
    t.crank_rad.push_back(th);
    t.lift_m.push_back(0.5 * h * (1 - std::cos(th / 2)) + 0.05 * h * (1 - std::cos(1.5 * th)));
  }
  SplineOptions o;
  o.kind = SplineKind::kQuintic;
  const LiftLaw law(t, o);
  const CamHarmonics c = LiftHarmonics(law, 4 * kPi, 12, 0.05);
  EXPECT_NEAR(c.lift_m[0], 0.55 * h, 1e-9);
  EXPECT_NEAR(c.lift_m[1], h / 2, 1e-9);
  EXPECT_NEAR(c.lift_m[3], h / 20, 1e-9);
  for (int i : {2, 4, 5, 6, 7, 8, 9, 10, 11, 12}) EXPECT_LT(c.lift_m[i], 1e-9) << "order " << i;
  EXPECT_NEAR(c.acceleration_m_rad2[1], h / 2, 1e-9);
  EXPECT_NEAR(c.acceleration_m_rad2[3], 9 * h / 20, 1e-9);
  EXPECT_EQ(c.highest_significant_order, 3);
  EXPECT_EQ(LiftHarmonics(law, 4 * kPi, 12, 0.95).highest_significant_order, 1);
}

TEST(ResonanceTest, RefusesImpossibleArguments) {
  EXPECT_THROW(ChainNaturalFrequenciesHz(kRate, kMass, 20, 20), std::invalid_argument);
  EXPECT_THROW(ChainNaturalFrequenciesHz(-1, kMass, 20, 3), std::invalid_argument);
}

}  // namespace
}  // namespace needle
