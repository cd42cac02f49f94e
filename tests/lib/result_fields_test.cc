// Result fields: one description (name, SI value, display unit) from which JSON keys, CSV
// headers and shown values follow.
#include "lib/result_fields.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "lib/units.h"

namespace needle {
namespace {

TEST(ResultFieldsTest, KeysAreTheNameAndTheUnit) {
  EXPECT_EQ((Field{"max_lift", display::kMm, 1e-3}.Key()), "max_lift_mm");
  EXPECT_EQ((Field{"max_S1", display::kMmPerRad, 1.0}.Key()), "max_S1_mm_rad");
  EXPECT_EQ((Field{"limits_used_fraction", display::kNone, 0.5}.Key()), "limits_used_fraction");
  EXPECT_EQ((Column{"S2", display::kMmPerRad2}.Key()), "S2_mm_rad2");
  // A published key kept as it was.
  EXPECT_EQ((Field{"n_qs", display::kRpm, 1.0, 1, "liftoff_rpm_quasi_static"}.Key()),
            "liftoff_rpm_quasi_static");
}

// Shown values are the SI values converted the one way each unit says: angles divided by
// π/180 (so 90° is exactly π/2's image), lengths multiplied by 1e3, stresses by 1e-6.
TEST(ResultFieldsTest, ShownValuesConvertFromSi) {
  EXPECT_EQ(*(Field{"a", display::kDegree, kPi / 2}.Shown()), (kPi / 2) / kDeg);
  EXPECT_NEAR(*(Field{"a", display::kDegree, kPi / 2}.Shown()), 90.0, 1e-13);
  EXPECT_EQ(*(Field{"s", display::kMm, 2.5e-3}.Shown()), 2.5e-3 * 1e3);
  EXPECT_EQ(*(Field{"p", display::kMPa, 1.5e9}.Shown()), 1500.0);
  EXPECT_EQ(*(Field{"f", display::kN, 12.25}.Shown()), 12.25);
  EXPECT_FALSE((Field{"none", display::kMm, std::nullopt}.Shown()).has_value());
}

TEST(ResultFieldsTest, CsvTableConvertsEachColumn) {
  const std::string csv =
      CsvTable({{"cam", display::kDegree}, {"S", display::kMm}}, {{kPi, 1e-3}, {0.0, 2e-3}}, 6);
  EXPECT_EQ(csv, "cam_deg,S_mm\n180,1\n0,2\n");
}

// The same table as SI columns: the values as they are, each under name_siunit.
TEST(ResultFieldsTest, SiColumnsKeepTheSiValues) {
  const auto columns =
      SiColumns({{"cam", display::kDegree}, {"S1", display::kMmPerRad}, {"n", display::kNone}},
                {{kPi, 1e-3, 2.0}, {0.0, 2e-3, 3.0}});
  ASSERT_EQ(columns.size(), 3u);
  EXPECT_EQ(columns.at("cam_rad"), (std::vector<double>{kPi, 0.0}));
  EXPECT_EQ(columns.at("S1_m_rad"), (std::vector<double>{1e-3, 2e-3}));
  EXPECT_EQ(columns.at("n"), (std::vector<double>{2.0, 3.0}));
}

TEST(ResultFieldsTest, CsvTableRefusesARaggedRow) {
  try {
    CsvTable({{"cam", display::kDegree}, {"S", display::kMm}}, {{1.0}}, 6);
    FAIL() << "no throw";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "CsvTable: a row has 1 values for 2 columns");
  }
}

}  // namespace
}  // namespace needle
