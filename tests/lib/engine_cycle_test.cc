// The engine cycle's one crank-to-cam rule and its name table (lib/engine_cycle.h).
#include "lib/engine_cycle.h"

#include <gtest/gtest.h>

#include "lib/name_table.h"

namespace needle {
namespace {

TEST(EngineCycleTest, CrankTurnsPerCycle) {
  EXPECT_EQ(CrankTurnsPerCycle(EngineCycle::kFourStroke), 2.0);  // the cam at half crank speed
  EXPECT_EQ(CrankTurnsPerCycle(EngineCycle::kTwoStroke), 1.0);
}

TEST(EngineCycleTest, NamesRoundTrip) {
  for (EngineCycle c : {EngineCycle::kFourStroke, EngineCycle::kTwoStroke}) {
    EXPECT_EQ(ParseEngineCycle(EngineCycleName(c)), c);
  }
  EXPECT_STREQ(EngineCycleName(EngineCycle::kFourStroke), "four-stroke");
  EXPECT_FALSE(ParseEngineCycle("Four-Stroke"));
  EXPECT_EQ(EngineCycleList(), "\"four-stroke\" or \"two-stroke\"");
}

enum class Fruit { kApple, kPear, kPlum };
constexpr NameRow<Fruit> kFruitNames[] = {{Fruit::kApple, "apple"}, {Fruit::kPear, "pear"}};

TEST(NameTableTest, LooksUpBothWaysAndListsTheNames) {
  EXPECT_STREQ(NameOf(kFruitNames, Fruit::kPear), "pear");
  EXPECT_STREQ(NameOf(kFruitNames, Fruit::kPlum), "?");  // a value without a row
  EXPECT_EQ(ValueOf(kFruitNames, "apple"), Fruit::kApple);
  EXPECT_FALSE(ValueOf(kFruitNames, "plum"));
  EXPECT_EQ(NameList(kFruitNames), "apple, pear");
  EXPECT_EQ(NameList(kFruitNames, " or ", true), "\"apple\" or \"pear\"");
  constexpr NameRow<Fruit> kThree[] = {
      {Fruit::kApple, "apple"}, {Fruit::kPear, "pear"}, {Fruit::kPlum, "plum"}};
  EXPECT_EQ(NameChoice(kThree), "\"apple\", \"pear\" or \"plum\"");
}

}  // namespace
}  // namespace needle
