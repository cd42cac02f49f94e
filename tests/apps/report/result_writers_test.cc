// The writers of a field table: a string, a yes/no and a list reach JSON as themselves, the
// text as words; a number without a value is null and "none".
#include "apps/report/result_writers.h"

#include <gtest/gtest.h>

#include "lib/units.h"

namespace needle {
namespace {

TEST(ResultWritersTest, EveryKindOfFieldReachesJsonAndText) {
  const std::vector<Field> fields = {
      TextField("spline", "quintic"),
      FlagField("measured", false),
      ListField("breaks", display::kDegree, {kPi / 2, kPi}),
      {"max_lift", display::kMm, 2.5e-3, 3},
      {"undershoot", display::kDegree, std::nullopt, 2},
  };
  nlohmann::json j;
  PutFields(j, fields);
  EXPECT_EQ(j.dump(),
            "{\"breaks_deg\":[90.0,180.0],\"max_lift_mm\":2.5,\"measured\":false,"
            "\"spline\":\"quintic\",\"undershoot_deg\":null}");
  EXPECT_EQ(FieldText(FieldAt(fields, "spline")), "quintic");
  EXPECT_EQ(FieldText(FieldAt(fields, "measured")), "no");
  EXPECT_EQ(ValueText(FieldAt(fields, "breaks_deg")), "90.000 180.000");
  EXPECT_EQ(FieldText(FieldAt(fields, "max_lift_mm")), "2.500 mm");
  EXPECT_EQ(FieldText(FieldAt(fields, "undershoot_deg")), "none");
}

}  // namespace
}  // namespace needle
