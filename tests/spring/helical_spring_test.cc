// Helical compression spring check: closed forms and a published worked example.
#include "spring/helical_spring.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "lib/units.h"

namespace needle {
namespace {

HelicalGeometry Bhandari101() {
  // V. B. Bhandari, "Design of Machine Elements", Example 10.1, as computed by its public
  // Scilab textbook companion (FOSSEE, book 764, EX10.1): P = 1250 N, C = 6, d = 7 mm,
  // D = 42 mm, N = 8 active coils, squared and ground ends (Nt = 10), G = 81 370 N/mm²,
  // S_ut = 1090 N/mm², permissible shear 50 % of S_ut, 1 mm gap between coils. Printed:
  // d = 6.625083 mm (before rounding to 7), free length 109.337611 mm.
  HelicalGeometry g;
  g.wire_m = 7e-3;
  g.coil_m = 42e-3;
  g.active_coils = 8;
  g.free_length_m = 109.337611e-3;
  g.shear_modulus_Pa = 81370e6;
  g.tensile_Pa = 1090e6;
  g.ends = SpringEnds::kClosedGround;
  g.stress_factor = StressFactor::kWahl;
  g.allowable_fraction = 0.5;
  return g;
}

TEST(HelicalSpringTest, ReproducesBhandariExample10_1) {
  const HelicalGeometry g = Bhandari101();
  // Wire diameter from the permissible stress: d = √(8 K P C/(π τ)), K Wahl at C = 6.
  const double k = StressCorrection(6.0, StressFactor::kWahl);
  EXPECT_NEAR(std::sqrt(8 * k * 1250 * 6 / (kPi * 545.0)), 6.625083, 5e-7);
  // Free length = solid (Nt·d = 70) + gaps ((Nt − 1)·1 = 9) + deflection under 1250 N:
  // with no preload the spring is solid-plus-gaps at 1250 N, so the check at "preload"
  // 1250 N must leave exactly the 9 mm of gaps.
  const HelicalSpringCheck c = CheckHelicalSpring(g, 1250.0, 0.0, 600, EngineCycle::kFourStroke);
  EXPECT_NEAR(c.solid_length_m, 70e-3, 1e-12);
  EXPECT_NEAR(c.total_coils, 10.0, 0);
  EXPECT_NEAR(c.clearance_full_lift_m, 9e-3, 1e-9);
  // Rate G d⁴/(8 D³ N) = 81370·2401/(8·74088·8) N/mm.
  EXPECT_NEAR(c.rate_N_m * 1e-3, 81370.0 * 2401.0 / (8.0 * 74088.0 * 8.0), 1e-9);
  // Stress at 1250 N: K·8PD/(πd³) below the permissible 545 N/mm².
  EXPECT_NEAR(c.stress_preload_Pa * 1e-6, k * 8 * 1250 * 42 / (kPi * 343), 1e-9);
  EXPECT_LT(c.stress_preload_Pa, c.allowable_stress_Pa);
}

TEST(HelicalSpringTest, CorrectionFactors) {
  // Bergsträsser (w + 0.5)/(w − 0.75) and Wahl (4w − 1)/(4w − 4) + 0.615/w at w = 6.
  EXPECT_NEAR(StressCorrection(6.0, StressFactor::kBergstrasser), 6.5 / 5.25, 1e-15);
  EXPECT_NEAR(StressCorrection(6.0, StressFactor::kWahl), 23.0 / 20.0 + 0.615 / 6.0, 1e-15);
  // They agree to within 2 % over the usual range 4…20 and both tend to 1.
  for (double w = 4; w <= 20; w += 0.5) {
    EXPECT_NEAR(StressCorrection(w, StressFactor::kBergstrasser),
                StressCorrection(w, StressFactor::kWahl),
                0.02 * StressCorrection(w, StressFactor::kWahl));
  }
  EXPECT_NEAR(StressCorrection(1e6, StressFactor::kBergstrasser), 1.0, 1e-5);
}

TEST(HelicalSpringTest, SurgeFrequencyIsHalfTheSquareRootOfRateOverSpringMass) {
  // A spring fixed at both ends: f₁ = ½√(R/m_s), m_s = ρ (πd²/4)(π D n).
  HelicalGeometry g = Bhandari101();
  g.density_kg_m3 = 7850;
  const HelicalSpringCheck c = CheckHelicalSpring(g, 100.0, 1e-3, 1200, EngineCycle::kFourStroke);
  const double mass =
      g.density_kg_m3 * kPi * g.wire_m * g.wire_m / 4 * kPi * g.coil_m * g.active_coils;
  EXPECT_NEAR(c.surge_hz, 0.5 * std::sqrt(c.rate_N_m / mass), 1e-9 * c.surge_hz);
  EXPECT_NEAR(c.cam_hz, 10.0, 1e-12);  // four-stroke: 1200 rpm / 120
  EXPECT_EQ(c.surge_ok, c.surge_ratio >= 13.0);
}

TEST(HelicalSpringTest, SolidLengthByEndType) {
  HelicalGeometry g = Bhandari101();
  const std::pair<SpringEnds, double> cases[] = {{SpringEnds::kClosedGround, 10 * 7e-3},
                                                 {SpringEnds::kClosed, 11.5 * 7e-3},
                                                 {SpringEnds::kOpenGround, 9 * 7e-3},
                                                 {SpringEnds::kOpen, 9 * 7e-3}};
  for (const auto& [ends, solid] : cases) {
    g.ends = ends;
    EXPECT_NEAR(CheckHelicalSpring(g, 10.0, 0.0, 600, EngineCycle::kFourStroke).solid_length_m,
                solid, 1e-12);
  }
}

TEST(HelicalSpringTest, MinimumGapsAndFailures) {
  HelicalGeometry g = Bhandari101();
  const HelicalSpringCheck c = CheckHelicalSpring(g, 1000.0, 2e-3, 600, EngineCycle::kFourStroke);
  EXPECT_NEAR(c.min_clearance_m, (0.0015 * 42 * 42 / 7 + 0.7) * 8 * 1e-3, 1e-12);  // S_a
  // Too much preload: the spring would be solid.
  try {
    CheckHelicalSpring(g, 5000.0, 0.0, 600, EngineCycle::kFourStroke);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("the preload compresses the spring to solid or beyond", 0), 0u);
  }
  // Over-stressed: the stress check fails and so does the whole check.
  g.tensile_Pa = 600e6;
  const HelicalSpringCheck weak = CheckHelicalSpring(g, 1200.0, 0.0, 600, EngineCycle::kFourStroke);
  EXPECT_FALSE(weak.stress_ok);
  EXPECT_FALSE(weak.pass());
}

// The check as fields: Bhandari's spring in the units a designer reads (N/mm, MPa, mm), the
// correction by name and every sub-verdict.
TEST(HelicalSpringTest, FieldsShowTheCheckInItsUnits) {
  const HelicalSpringCheck c =
      CheckHelicalSpring(Bhandari101(), 1250.0, 0.0, 600, EngineCycle::kFourStroke);
  const std::vector<Field> f = HelicalFields(c);
  EXPECT_NEAR(*FieldAt(f, "rate_N_mm").Shown(), 81370.0 * 2401.0 / (8.0 * 74088.0 * 8.0), 1e-9);
  EXPECT_NEAR(*FieldAt(f, "solid_length_mm").Shown(), 70.0, 1e-9);
  EXPECT_NEAR(*FieldAt(f, "clearance_full_lift_mm").Shown(), 9.0, 1e-6);
  EXPECT_EQ(*FieldAt(f, "stress_preload_MPa").Shown(), c.stress_preload_Pa * 1e-6);
  EXPECT_EQ(FieldAt(f, "stress_correction").text, StressFactorName(c.stress_factor));
  EXPECT_EQ(FieldAt(f, "stress_ok").flag, c.stress_ok);
  EXPECT_EQ(FieldAt(f, "pass").flag, c.pass());
  EXPECT_EQ(*FieldAt(f, "surge_hz").Shown(), c.surge_hz);
}

// docs/springs.md carries the code's table of criteria and factors: it cannot drift. On a
// mismatch the code's table is written to springs-table.md in the test's directory.
TEST(HelicalSpringTest, TheDocsConventionsTableIsTheCodes) {
  std::ifstream in(std::string(NEEDLE_SOURCE_DIR) + "/docs/springs.md");
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string begin = "<!-- conventions: begin -->\n", end = "<!-- conventions: end -->";
  const size_t b = doc.str().find(begin), e = doc.str().find(end);
  ASSERT_TRUE(b != std::string::npos && e != std::string::npos);
  const std::string table = SpringConventionsMarkdown();
  const bool same = doc.str().substr(b + begin.size(), e - b - begin.size()) == table;
  if (!same) std::ofstream("springs-table.md") << table;
  EXPECT_TRUE(same) << "regenerate docs/springs.md's table from SpringConventionsMarkdown() "
                       "(written to springs-table.md)";
  // Five criteria and three factors, each with a source.
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 2 + 5 + 3);
}

}  // namespace
}  // namespace needle
