// The compare job's item rules on items built by hand: matching by key in A's order then B's
// extras, what is a verdict, and that only pass against fail flips.
#include "apps/study/compare_checks.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

namespace needle {
namespace {

CheckValue Num(double v) { return {CheckValue::Kind::kNumber, v, false, {}}; }
CheckValue Whole(long long v) {
  return {CheckValue::Kind::kCount, static_cast<double>(v), false, {}};
}
CheckValue Yes(bool v) { return {CheckValue::Kind::kFlag, 0.0, v, {}}; }
CheckValue Txt(const std::string& v) { return {CheckValue::Kind::kText, 0.0, false, v}; }

TEST(CompareChecksTest, ItemsMatchByKey) {
  const std::vector<CheckItem> a = {
      {"g.n", Whole(2)}, {"g.ok", Yes(true)}, {"overall", Txt("pass")}, {"x_mm", Num(1.0)}};
  const std::vector<CheckItem> b = {{"g.ok", Yes(false)},
                                    {"h.status", Txt("budget")},
                                    {"overall", Txt("pass")},
                                    {"x_mm", Num(3.5)}};
  const std::vector<ComparedItem> items = CompareChecks(a, b);
  ASSERT_EQ(items.size(), 5u);
  EXPECT_EQ(items[0].key, "g.n");
  EXPECT_EQ(items[0].b.kind, CheckValue::Kind::kNone);
  EXPECT_FALSE(items[0].verdict);
  EXPECT_EQ(items[1].key, "g.ok");
  EXPECT_TRUE(items[1].verdict && items[1].flips);
  EXPECT_EQ(items[2].key, "overall");
  EXPECT_TRUE(items[2].verdict && !items[2].flips && !items[2].differs);
  EXPECT_EQ(items[3].key, "x_mm");
  EXPECT_EQ(items[3].b.number - items[3].a.number, 2.5);
  EXPECT_EQ(items[4].key, "h.status");  // B's own item, after A's
  EXPECT_EQ(items[4].a.kind, CheckValue::Kind::kNone);
  EXPECT_TRUE(items[4].verdict && !items[4].flips && items[4].differs);  // a status: no flip
}

TEST(CompareChecksTest, OnlyPassAgainstFailFlips) {
  const std::vector<CheckItem> a = {
      {"kinematics.spline", Txt("natural")}, {"limits.x.verdict", Txt("pass")},
      {"limits.x.value", Num(1.0)},          {"limits.y.verdict", Txt("pass")},
      {"limits.z.verdict", Txt("fail")},     {"overall", Txt("pass")}};
  const std::vector<CheckItem> b = {{"kinematics.spline", Txt("pchip")},
                                    {"limits.x.verdict", Txt("fail")},
                                    {"limits.x.value", Whole(1)},
                                    {"limits.y.verdict", Txt("not judged")},
                                    {"overall", Txt("pass")}};
  std::map<std::string, ComparedItem> by_key;
  for (const ComparedItem& i : CompareChecks(a, b)) by_key[i.key] = i;
  EXPECT_TRUE(by_key.at("limits.x.verdict").flips);
  EXPECT_FALSE(by_key.at("limits.y.verdict").flips);  // pass → not judged: a difference
  EXPECT_TRUE(by_key.at("limits.y.verdict").differs);
  EXPECT_FALSE(by_key.at("limits.z.verdict").flips);  // fail → absent: a difference
  EXPECT_TRUE(by_key.at("limits.z.verdict").differs);
  EXPECT_FALSE(by_key.at("kinematics.spline").flips);
  EXPECT_TRUE(by_key.at("kinematics.spline").differs);
  EXPECT_FALSE(by_key.at("overall").flips || by_key.at("overall").differs);
  EXPECT_FALSE(by_key.at("limits.x.value").verdict);                            // a number
  EXPECT_TRUE(by_key.at("limits.x.value").a == by_key.at("limits.x.value").b);  // 1.0 == 1
}

}  // namespace
}  // namespace needle
