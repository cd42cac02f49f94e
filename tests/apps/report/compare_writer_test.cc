// Compare reads a check's items from its result (CheckItems, apps/study); `check --json`
// writes the same check from its field tables (CheckJson, apps/report). The two must agree:
// every leaf of the JSON object that compare sets side by side — numbers, yes/no values,
// counts, the overall verdict, statuses, the spline, each limits row's verdict, value and
// margin — is an item, in the JSON's order, with the JSON's value and kind. The leaves are read
// here as compare read them before it read the result.
#include "apps/report/compare_writer.h"

#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/report/check_writers.h"

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

void Leaves(const nlohmann::json& j, const std::string& prefix,
            std::vector<std::pair<std::string, nlohmann::json>>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    const nlohmann::json& v = it.value();
    if (v.is_object()) {
      Leaves(v, key, out);
    } else if (prefix.empty() && it.key() == "limits" && v.is_array()) {
      for (const nlohmann::json& row : v) {
        const std::string name = "limits." + row["name"].get<std::string>();
        for (const char* field : {"verdict", "value", "margin"})
          out.emplace_back(name + "." + field, row.value(field, nlohmann::json(nullptr)));
      }
    } else if (v.is_number() || v.is_boolean() || v.is_null() ||
               (v.is_string() &&
                (it.key() == "overall" || it.key() == "status" || it.key() == "spline"))) {
      out.emplace_back(key, v);
    }
  }
}

class CheckItemsTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CheckItemsTest, AreTheLeavesOfCheckJson) {
  const Case c = LoadCase(kCases + GetParam());
  const auto law = std::make_shared<const LiftLaw>(MakeLiftLaw(c));
  const CheckResult r = CheckScene(Bind(c), law);
  std::vector<std::pair<std::string, nlohmann::json>> leaves;
  Leaves(CheckJson(Bind(c), *law, r, "report.html"), "", leaves);
  const std::vector<CheckItem> items = CheckItems(r, law->kind());
  ASSERT_EQ(items.size(), leaves.size());
  for (size_t i = 0; i < items.size(); ++i) {
    SCOPED_TRACE(leaves[i].first);
    EXPECT_EQ(items[i].key, leaves[i].first);
    const nlohmann::json& v = leaves[i].second;
    const CheckValue& x = items[i].value;
    switch (x.kind) {
      case CheckValue::Kind::kNone:
        EXPECT_TRUE(v.is_null());
        break;
      case CheckValue::Kind::kFlag:
        EXPECT_EQ(v, nlohmann::json(x.flag));
        break;
      case CheckValue::Kind::kText:
        EXPECT_EQ(v, nlohmann::json(x.text));
        break;
      case CheckValue::Kind::kCount:
        EXPECT_TRUE(v.is_number_integer());
        EXPECT_EQ(v.get<long long>(), static_cast<long long>(x.number));
        break;
      case CheckValue::Kind::kNumber:
        EXPECT_TRUE(v.is_number_float());
        EXPECT_EQ(v.get<double>(), x.number);
        break;
    }
  }
}

// A pass, a fail with limits rows failing, a surge resonance, rigid contacts, a profile.
INSTANTIATE_TEST_SUITE_P(BundledCases, CheckItemsTest,
                         ::testing::Values("basu-example1.toml", "basu-example2.toml",
                                           "new-engine-weak-spring.toml",
                                           "basu-example1-surge.toml", "basu-example1-rigid.toml",
                                           "matec-2018-cam.toml"));

}  // namespace
}  // namespace needle
