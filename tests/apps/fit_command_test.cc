// `needle fit` end to end (apps/cli/fit_command.h) on docs/fit.md's bench traces: the fitted
// values, the calibrated case `needle spring` reads back, and every bad input one line, exit 2,
// nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "run_command.h"

namespace needle {
namespace {

using testing::Case;
using testing::RunNeedle;
using testing::TempPath;

std::string Trace(int rpm) {
  return std::string(NEEDLE_SOURCE_DIR) + "/docs/fit/trace-" + std::to_string(rpm) + "rpm.csv";
}

std::string Traces() {
  return " --trace " + Trace(400) + " --rpm 400 --trace " + Trace(700) + " --rpm 700";
}

TEST(FitCommandTest, FitsWritesTheCalibratedCaseAndItsReport) {
  const std::string out = TempPath("fit-out"), cal = TempPath("fit-calibrated.toml");
  const auto r = RunNeedle("fit " + Case("basu-example1.toml") + Traces() +
                           " --free spring.preload_kgf,needle.mass_kg,train.contact_stiffness_N_m"
                           " --no-liftoff --json --case " +
                           cal + " --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // The bench's engine: a spring relaxed to 711 kgf, 13 kg, a 3e8 N/m roller contact.
  const auto& p = j["parameters"];
  for (const auto& [key, truth] : {std::pair<std::string, double>{"spring.preload_kgf", 711.0},
                                   {"needle.mass_kg", 13.0},
                                   {"train.contact_stiffness_N_m", 3e8}}) {
    EXPECT_LE(p[key]["low"].get<double>(), truth) << key;
    EXPECT_GE(p[key]["high"].get<double>(), truth) << key;
  }
  EXPECT_FALSE(j["model"]["misses_something"].get<bool>());
  EXPECT_EQ(j["traces"].size(), 2u);
  EXPECT_EQ(j["calibrated_case"], cal);
  EXPECT_TRUE(std::filesystem::exists(out + "/fit-basu-example1.html"));
  // The calibrated case is the case with the fitted keys: needle spring reads its preload.
  const auto spring = RunNeedle("spring " + cal + " --json");
  ASSERT_EQ(spring.status == 0 || spring.status == 1, true) << spring.err;
  const std::string text = testing::Slurp(cal);
  EXPECT_NE(text.find("preload_kgf = "), std::string::npos);
  EXPECT_NE(text.find("# Basu: \"the combined weight"), std::string::npos);  // its lines kept
  const auto again = RunNeedle("fit " + cal + Traces() +
                               " --free spring.preload_kgf --no-liftoff"
                               " --json");
  ASSERT_EQ(again.status, 0) << again.err;
  const auto k = nlohmann::json::parse(again.out)["parameters"]["spring.preload_kgf"];
  EXPECT_NEAR(k["value"].get<double>(), p["spring.preload_kgf"]["value"].get<double>(), 0.5);
  EXPECT_NEAR(k["start"].get<double>(), p["spring.preload_kgf"]["value"].get<double>(), 1e-9);
}

TEST(FitCommandTest, BadInputIsOneLineExitTwoAndNothingWritten) {
  const std::string cal = TempPath("fit-never.toml");
  std::filesystem::remove(cal);
  const std::string base = "fit " + Case("basu-example1.toml") + " --case " + cal;
  auto r = RunNeedle(base + " --trace " + Trace(400) + " --free spring.preload_kgf");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "needle: --rpm is required (see needle --help)\n");
  r = RunNeedle(base + Traces() + " --rpm 500 --free spring.preload_kgf");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "needle: --rpm: 3 speed(s) for 2 --trace(s); give one --rpm per --trace\n");
  r = RunNeedle(base + Traces() + " --free spring.stiffness_N_m");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("needle: --free: 'spring.stiffness_N_m' is not a key needle fit can "
                        "free; expected one of needle.mass_kg, ",
                        0),
            0u)
      << r.err;
  r = RunNeedle(base + Traces() + " --free train.play_mm --bounds train.play_mm=2:1");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "needle: --bounds: 'train.play_mm=2:1': the low bound must be below the high "
            "one\n");
  r = RunNeedle(base + " --trace /nonexistent/trace.csv --rpm 400 --free spring.preload_kgf");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("/nonexistent/trace.csv"), std::string::npos) << r.err;
  // A trace with its angles out of order.
  const std::string bad = TempPath("fit-bad-trace.csv");
  std::ofstream(bad) << "crank_deg,lift_mm\n0,0\n1,0.1\n0.5,0.2\n";
  r = RunNeedle(base + " --trace " + bad + " --rpm 400 --free spring.preload_kgf");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "needle: " + bad +
                       ":4:1: crank_deg 0.5 does not increase after 1 (line 3); angles must "
                       "increase strictly\n");
  // An output that cannot be written: refused before the fit.
  r = RunNeedle("fit " + Case("basu-example1.toml") + Traces() +
                " --free spring.preload_kgf --case /nonexistent/dir/cal.toml");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("--case"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(cal));
}

}  // namespace
}  // namespace needle
