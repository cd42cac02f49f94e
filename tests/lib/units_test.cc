#include "lib/units.h"

#include <gtest/gtest.h>

namespace needle {
namespace {

TEST(UnitsTest, ConvertsToSiAndBack) {
  EXPECT_DOUBLE_EQ(ToSi(Dimension::kForce, "kgf", 1.0), 9.80665);
  EXPECT_DOUBLE_EQ(ToSi(Dimension::kLength, "mm", 2.5), 2.5e-3);
  EXPECT_DOUBLE_EQ(ToSi(Dimension::kVelocity, "dcm_s", 4.8), 0.48);
  EXPECT_DOUBLE_EQ(ToSi(Dimension::kAngle, "deg", 180.0), kPi);
  EXPECT_DOUBLE_EQ(ToSi(Dimension::kTemperature, "C", 20.0), 293.15);
  EXPECT_DOUBLE_EQ(FromSi(Dimension::kTemperature, "C", 293.15), 20.0);
  EXPECT_DOUBLE_EQ(ToSi(Dimension::kStiffness, "N_mm", 10.0), 1e4);
  EXPECT_NEAR(ToSi(Dimension::kSlope, "mm_deg", 1.0), 1e-3 * 180.0 / kPi, 1e-15);
  EXPECT_NEAR(FromSi(Dimension::kForce, "kgf", ToSi(Dimension::kForce, "kgf", 790.0)), 790.0,
              1e-12);
  EXPECT_DOUBLE_EQ(OmegaFromRpm(60.0), 2 * kPi);
}

TEST(UnitsTest, UnknownUnitIsRejectedWithTheKnownOnes) {
  try {
    ToSi(Dimension::kForce, "lbf", 1.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unit 'lbf' is not a unit of force (known: N, kN, kgf)");
  }
}

}  // namespace
}  // namespace needle
