// Basu's spring formula against his two worked examples and the actual springs.
#include "spring/basu_formula.h"

#include <gtest/gtest.h>

#include "lib/units.h"

namespace needle {
namespace {

TEST(BasuFormulaTest, Example1AgainstTheBuiltSpring) {
  // d = 31 mm, t = 0.0734 s: (π·3.1²/4)·35·1.6·(1/0.0734)^¼ = 812.0 kgf. Basu prints the
  // formula but not its value; the spring "had a tension of 790 kg": −2.7 %, inside his
  // "deviations never more than 3 %".
  const double p = BasuPreloadN(31e-3, 0.0734) / kKgf;
  EXPECT_NEAR(p, 812.04, 0.005);
  EXPECT_NEAR(100.0 * (790.0 - p) / p, -2.71, 0.005);
}

TEST(BasuFormulaTest, Example2BesideBasus184) {
  // d = 1.28 cm, t = 0.023 s: the formula gives 185.05 kgf; Basu prints 184 (0.6 % lower —
  // his arithmetic, not ours: 1.2868 cm² · 56 · 2.5679 = 185.05). The built spring, 176 kg,
  // is 4.9 % below the formula (4.3 % below Basu's 184): above his "never more than 3 %".
  const double p = BasuPreloadN(12.8e-3, 0.023) / kKgf;
  EXPECT_NEAR(p, 185.05, 0.01);
  EXPECT_NEAR(p, 184.0, 0.006 * 184.0);
  EXPECT_NEAR(100.0 * (176.0 - p) / p, -4.89, 0.01);
}

TEST(BasuFormulaTest, ScalesAsDiameterSquaredAndPeriodToTheMinusQuarter) {
  const double base = BasuPreloadN(20e-3, 0.05);
  EXPECT_NEAR(BasuPreloadN(40e-3, 0.05) / base, 4.0, 1e-12);
  EXPECT_NEAR(BasuPreloadN(20e-3, 0.05 / 16.0) / base, 2.0, 1e-12);
}

TEST(BasuFormulaTest, RejectsNonPositiveInput) {
  try {
    BasuPreloadN(0.0, 0.05);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "Basu's formula: the needle diameter must be positive, got 0.000000 mm");
  }
  try {
    BasuPreloadN(0.02, -1.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "Basu's formula: the injection period must be positive, got -1.000000 s");
  }
}

}  // namespace
}  // namespace needle
