// Result fields: one description (name, SI value, display unit) from which JSON keys, CSV
// headers and shown values follow.
#include "lib/result_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "lib/kinematics.h"
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

// A missing value (NaN: a C¹ spline's acceleration) is an empty CSV cell, not "nan".
TEST(ResultFieldsTest, CsvTableLeavesAMissingValueEmpty) {
  const std::string csv = CsvTable({{"lift", display::kMm}, {"acceleration", display::kMPerS2}},
                                   {{1e-3, std::nan("")}, {2e-3, 4.5}}, 6);
  EXPECT_EQ(csv, "lift_mm,acceleration_m_s2\n1,\n2,4.5\n");
}

// A string, a yes/no and a list are keyed by their name (a list by name_unit) and keep their
// values; a list is held in SI.
TEST(ResultFieldsTest, TextFlagAndListFieldsKeepTheirValues) {
  const Field text = TextField("spline", "quintic");
  EXPECT_EQ(text.Key(), "spline");
  EXPECT_EQ(text.kind, Field::Kind::kText);
  EXPECT_EQ(text.text, "quintic");
  const Field flag = FlagField("measured", true);
  EXPECT_EQ(flag.Key(), "measured");
  EXPECT_TRUE(flag.flag);
  const Field list = ListField("breaks", display::kDegree, {kPi / 2, kPi});
  EXPECT_EQ(list.Key(), "breaks_deg");
  EXPECT_EQ(list.list_si, (std::vector<double>{kPi / 2, kPi}));
}

// The kinematics table's columns and their SI keys (the Python module's arrays).
TEST(ResultFieldsTest, KinematicsColumnsAreKeyedByTheirUnits) {
  std::vector<std::string> keys, si_keys;
  for (const Column& c : KinematicsColumns()) {
    keys.push_back(c.Key());
    si_keys.push_back(c.SiKey());
  }
  EXPECT_EQ(keys, (std::vector<std::string>{"crank_deg", "time_s", "lift_mm", "velocity_m_s",
                                            "acceleration_m_s2", "jerk_m_s3"}));
  EXPECT_EQ(si_keys, (std::vector<std::string>{"crank_rad", "time_s", "lift_m", "velocity_m_s",
                                               "acceleration_m_s2", "jerk_m_s3"}));
  KinematicsPoint p;
  p.crank_rad = kPi;
  p.lift_m = 1e-3;
  const std::vector<double> row = KinematicsRowSi(p);
  EXPECT_EQ(row[0], kPi);
  EXPECT_TRUE(std::isnan(row[4]));  // no acceleration: a C¹ spline
  EXPECT_TRUE(std::isnan(row[5]));
}

// A table's field by key, and a non-finite value as none: the lookup names the key it misses.
TEST(ResultFieldsTest, FieldAtFindsByKeyAndFiniteOrNoneDropsTheUnbounded) {
  const std::vector<Field> fields = {{"max_lift", display::kMm, 1e-3}, CountField("steps", 7)};
  EXPECT_EQ(*FieldAt(fields, "max_lift_mm").Shown(), 1.0);
  EXPECT_TRUE(FieldAt(fields, "steps").count);
  try {
    FieldAt(fields, "max_lift_m");
    FAIL() << "no throw";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "no result field max_lift_m");
  }
  EXPECT_EQ(*FiniteOrNone(2.5), 2.5);
  EXPECT_FALSE(FiniteOrNone(INFINITY).has_value());
  EXPECT_FALSE(FiniteOrNone(std::nan("")).has_value());
}

}  // namespace
}  // namespace needle
