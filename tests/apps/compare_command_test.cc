// `needle compare`: Basu's Example 1 against the same engine with a weaker spring (the spring
// verdict flips, and the preload's difference is the closed form), a design against itself (no
// flips, every difference zero), bad input, and the item matching on hand-made objects.
#include "apps/cli/compare_command.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lib/units.h"
#include "run_command.h"

namespace needle {
namespace {

using testing::Case;
using testing::RunNeedle;

std::string Dir(const std::string& tag) {
  const std::string dir = "/tmp/needle_compare_" + tag + "_" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  return dir;
}

const nlohmann::json& Item(const nlohmann::json& j, const std::string& key) {
  for (const auto& i : j["items"])
    if (i["key"] == key) return i;
  throw std::runtime_error("no item " + key);
}

TEST(CompareCommandTest, AWeakerSpringFlipsTheSpringVerdict) {
  const std::string dir = Dir("weak");
  const auto r = RunNeedle("compare " + Case("basu-example1.toml") + " " +
                           Case("basu-example1-weak-spring.toml") + " --out " + dir + " --json");
  ASSERT_EQ(r.status, 1) << r.err;  // a verdict flips
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["a"]["overall"], "pass");
  EXPECT_EQ(j["b"]["overall"], "fail");
  EXPECT_EQ(j["flipped"], nlohmann::json({"overall", "spring.basu_ok", "spring.pass"}));
  EXPECT_TRUE(Item(j, "spring.pass")["flips"].get<bool>());
  EXPECT_FALSE(Item(j, "spring.preload_ok")["flips"].get<bool>());
  // 600 against 790 kgf: (600 − 790)·9.80665 N.
  EXPECT_NEAR(Item(j, "spring.preload_N")["difference"].get<double>(), -190 * kKgf, 1e-9);
  // n_qs ∝ √P₀ nearly (the rate's share is small): both fall by about 1 − √(600/790) = 13 %.
  const double nqs = Item(j, "overspeed.liftoff_rpm_quasi_static")["a"].get<double>();
  EXPECT_LT(Item(j, "overspeed.liftoff_rpm_quasi_static")["b"].get<double>(), 0.9 * nqs);
  const std::string report =
      testing::Slurp(dir + "/compare-basu-example1-basu-example1-weak-spring.html");
  EXPECT_EQ(j["report"], dir + "/compare-basu-example1-basu-example1-weak-spring.html");
  EXPECT_EQ(std::count(report.begin(), report.end(), '\n') > 0, true);
  size_t svgs = 0;
  for (size_t at = report.find("<svg"); at != std::string::npos; at = report.find("<svg", at + 1))
    ++svgs;
  EXPECT_EQ(svgs, 2u);  // the overlaid SVAJ and the forces
  EXPECT_NE(report.find("<span class=\"fail\">flips</span>"), std::string::npos);
  // The text names the flips.
  const auto text = RunNeedle("compare " + Case("basu-example1.toml") + " " +
                              Case("basu-example1-weak-spring.toml") + " --out " + dir);
  EXPECT_EQ(text.status, 1);
  EXPECT_NE(text.out.find("spring.pass"), std::string::npos);
  EXPECT_NE(text.out.find("FLIPS"), std::string::npos);
  EXPECT_NE(text.out.find("3 verdict(s) flip"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(CompareCommandTest, ADesignAgainstItselfHasNoDifference) {
  const std::string dir = Dir("self");
  const auto r = RunNeedle("compare " + Case("basu-example2.toml") + " " +
                           Case("basu-example2.toml") + " --out " + dir + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["flipped"].empty());
  int numbers = 0;
  for (const auto& i : j["items"]) {
    if (i["verdict"].get<bool>()) {
      EXPECT_FALSE(i["flips"].get<bool>()) << i["key"];
    } else if (!i["difference"].is_null()) {
      EXPECT_EQ(i["difference"].get<double>(), 0.0) << i["key"];
      ++numbers;
    }
  }
  EXPECT_GE(numbers, 10);
  std::filesystem::remove_all(dir);
}

TEST(CompareCommandTest, BadInputIsOneLineAndWritesNothing) {
  const std::string dir = Dir("bad");
  const auto r = RunNeedle("compare " + Case("basu-example1.toml") + " " + dir + "/none.toml" +
                           " --out " + dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "needle: " + dir + "/none.toml: cannot open the case file for reading\n");
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(std::filesystem::exists(dir + "/compare-basu-example1-none.html"));
  // --out names a file, not a folder.
  const auto file = RunNeedle("compare " + Case("basu-example1.toml") + " " +
                              Case("basu-example2.toml") + " --out " + Case("basu-example1.toml"));
  EXPECT_EQ(file.status, 2);
  EXPECT_EQ(file.err, "needle: --out: " + Case("basu-example1.toml") +
                          " is not a folder and cannot be made one (Not a directory)\n");
  std::filesystem::remove_all(dir);
}

TEST(CompareCommandTest, ItemsMatchByPath) {
  const nlohmann::json a = {
      {"overall", "pass"}, {"x_mm", 1.0}, {"g", {{"ok", true}, {"n", 2}}}, {"failing", {"text"}}};
  const nlohmann::json b = {
      {"overall", "pass"}, {"x_mm", 3.5}, {"g", {{"ok", false}}}, {"h", {{"status", "budget"}}}};
  const std::vector<ComparedItem> items = CompareChecks(a, b);
  ASSERT_EQ(items.size(), 5u);  // failing (a list) is no item
  EXPECT_EQ(items[0].key, "g.n");
  EXPECT_EQ(items[0].b, nullptr);
  EXPECT_FALSE(items[0].verdict);
  EXPECT_EQ(items[1].key, "g.ok");
  EXPECT_TRUE(items[1].verdict && items[1].flips);
  EXPECT_EQ(items[2].key, "overall");
  EXPECT_TRUE(items[2].verdict && !items[2].flips);
  EXPECT_EQ(items[3].key, "x_mm");
  EXPECT_EQ(items[3].b.get<double>() - items[3].a.get<double>(), 2.5);
  EXPECT_EQ(items[4].key, "h.status");  // B's own item, after A's
  EXPECT_EQ(items[4].a, nullptr);
  EXPECT_TRUE(items[4].verdict && items[4].flips);
}

}  // namespace
}  // namespace needle
