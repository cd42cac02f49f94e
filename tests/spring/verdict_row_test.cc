// The one verdict row of check's limits and size's rules (issue 52): margin and verdict.
#include "spring/verdict_row.h"

#include <gtest/gtest.h>

#include <cmath>

namespace needle {
namespace {

TEST(VerdictRowTest, AtMostPassesUpToItsLimitAndFailsPastIt) {
  VerdictRow x =
      VerdictRow::Unjudged("seating_velocity", "seating velocity", "m/s", true, 1.5, "Blair");
  EXPECT_EQ(x.verdict, "not judged");
  EXPECT_TRUE(std::isnan(x.value));
  x.Judge(1.5, "at 20 deg");
  EXPECT_EQ(x.verdict, "pass");  // a margin of 0 passes
  EXPECT_EQ(x.margin, 0.0);
  EXPECT_EQ(x.note, "at 20 deg");
  x.Judge(1.8);
  EXPECT_EQ(x.verdict, "fail");
  EXPECT_DOUBLE_EQ(x.margin, -0.3);
  EXPECT_DOUBLE_EQ(x.Violation(), 0.3 / 1.5);
  EXPECT_EQ(x.UnitSuffix(), " m/s");
}

TEST(VerdictRowTest, AtLeastPassesFromItsLimitAndANanFails) {
  VerdictRow x = VerdictRow::Unjudged("fatigue", "fatigue safety factor", "", false, 1.5);
  x.Judge(2.0);
  EXPECT_TRUE(x.passes());
  EXPECT_DOUBLE_EQ(x.margin, 0.5);
  EXPECT_EQ(x.Violation(), 0.0);
  x.Judge(1.2);
  EXPECT_FALSE(x.passes());
  EXPECT_NEAR(x.Violation(), 0.2, 1e-15);
  x.Judge(NAN);  // a value that could not be had is no pass
  EXPECT_EQ(x.verdict, "fail");
  EXPECT_EQ(x.UnitSuffix(), "");
}

}  // namespace
}  // namespace needle
