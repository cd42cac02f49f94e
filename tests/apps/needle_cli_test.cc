// The `needle` command end to end: exit status, one-line errors, no partial output.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "run_command.h"

namespace needle {
namespace {

using testing::Case;
using testing::RunNeedle;

int Lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

TEST(NeedleCliTest, HelpDocumentsEveryOption) {
  const auto r = RunNeedle("kinematics --help");
  EXPECT_EQ(r.status, 0);
  for (const char* opt : {"--rpm", "--step", "--spline", "--units", "--json", "--csv"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  }
}

TEST(NeedleCliTest, KinematicsJsonHasTheDocumentedKeys) {
  const auto r = RunNeedle("kinematics " + Case("basu-cam4.toml") + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key :
       {"speed_rpm", "spline", "injection_period_s", "max_lift_mm", "mean_lift_mm", "rho",
        "max_velocity_m_s", "max_velocity_deg", "min_velocity_m_s", "min_velocity_deg",
        "max_acceleration_m_s2", "max_acceleration_deg", "min_acceleration_m_s2",
        "min_acceleration_deg", "table"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_DOUBLE_EQ(j["speed_rpm"].get<double>(), 400.0);
  EXPECT_NEAR(j["injection_period_s"].get<double>(), 55.0 / 2400.0, 1e-12);
  const auto& row = j["table"][0];
  for (const char* key :
       {"crank_deg", "time_s", "lift_mm", "velocity_m_s", "acceleration_m_s2", "jerk_m_s3"}) {
    EXPECT_TRUE(row.contains(key)) << key;
  }
}

TEST(NeedleCliTest, ShapePreservingSplineReportsAccelerationAsNull) {
  const auto r = RunNeedle("kinematics " + Case("basu-cam4.toml") + " --json --spline pchip");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["max_acceleration_m_s2"].is_null());
  EXPECT_TRUE(j["table"][3]["acceleration_m_s2"].is_null());
  EXPECT_FALSE(j["table"][3]["velocity_m_s"].is_null());
  const auto text = RunNeedle("kinematics " + Case("basu-cam4.toml") + " --spline makima");
  EXPECT_NE(text.out.find("acceleration unavailable: makima is C1 only"), std::string::npos);
}

TEST(NeedleCliTest, RpmOverrideScalesVelocityLinearly) {
  const auto a =
      nlohmann::json::parse(RunNeedle("kinematics " + Case("basu-cam4.toml") + " --json").out);
  const auto b = nlohmann::json::parse(
      RunNeedle("kinematics " + Case("basu-cam4.toml") + " --json --rpm 800").out);
  EXPECT_NEAR(b["max_velocity_m_s"].get<double>(), 2 * a["max_velocity_m_s"].get<double>(), 1e-12);
  EXPECT_NEAR(b["max_acceleration_m_s2"].get<double>(),
              4 * a["max_acceleration_m_s2"].get<double>(), 1e-9);
}

TEST(NeedleCliTest, PaperColumnsAppearBesideTheTable) {
  const auto r = RunNeedle("kinematics " + Case("basu-cam4.toml") + " --units paper");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("paper |v|"), std::string::npos);
  EXPECT_NE(r.out.find("v dcm/s"), std::string::npos);
}

TEST(NeedleCliTest, CsvIsWrittenWhole) {
  const std::string csv = "/tmp/needle_cli_" + std::to_string(getpid()) + ".csv";
  const auto r = RunNeedle("kinematics " + Case("basu-example1.toml") + " --step 1 --csv " + csv);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = testing::Slurp(csv);
  EXPECT_EQ(text.rfind("crank_deg,time_s,lift_mm,velocity_m_s,acceleration_m_s2,jerk_m_s3\n", 0),
            0u);
  EXPECT_EQ(Lines(text), 1 + 56);  // header + −15…40 in 1° steps
  std::remove(csv.c_str());
}

TEST(NeedleCliTest, BadInputIsOneLineExitTwoAndNoOutputFile) {
  const std::string dir = "/tmp/needle_cli_bad_" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  const std::string bad = dir + "/bad.toml";
  {
    std::ofstream f(bad);
    f << "[engine]\nspeed_rpm = 400\n[lift]\ncrank_deg = [0, 5, 5, 10]\nlift_mm = [0, 1, 2, 0]\n";
  }
  const std::string csv = dir + "/out.csv";
  const auto r = RunNeedle("kinematics " + bad + " --csv " + csv);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "needle: " + bad +
                       ": [lift] crank_deg: angles must increase strictly, but entry 2 (5) follows "
                       "entry 1 (5)\n");
  EXPECT_FALSE(std::filesystem::exists(csv));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);  // only bad.toml
  std::filesystem::remove_all(dir);
}

TEST(NeedleCliTest, BadOptionsExitTwo) {
  const auto spline = RunNeedle("kinematics " + Case("basu-cam4.toml") + " --spline cubic");
  EXPECT_EQ(spline.status, 2);
  EXPECT_EQ(spline.err,
            "needle: --spline: unknown kind \"cubic\"; expected one of natural, not-a-knot, "
            "clamped, quintic, pchip, makima, smoothing\n");
  EXPECT_EQ(RunNeedle("kinematics " + Case("basu-cam4.toml") + " --rpm -3").status, 2);
  EXPECT_EQ(RunNeedle("kinematics").status, 2);
  EXPECT_EQ(RunNeedle("frobnicate").status, 2);
  const auto missing = RunNeedle("kinematics /no/such.toml");
  EXPECT_EQ(missing.status, 2);
  EXPECT_EQ(missing.err, "needle: /no/such.toml: cannot open the case file for reading\n");
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

using testing::Case;
using testing::RunNeedle;

TEST(NeedleCliSpringTest, SpringJsonHasTheDocumentedKeys) {
  const auto r = RunNeedle("spring " + Case("basu-example1.toml") + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key :
       {"injection_period_s", "basu_preload_kgf", "actual_preload_kgf", "deviation_percent",
        "inertia_force_kgf", "min_quasi_static_force_N", "min_quasi_static_force_deg",
        "liftoff_rpm_quasi_static", "required_preload_N", "preload_margin_percent", "helical"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_NEAR(j["actual_preload_kgf"].get<double>(), 790.0, 1e-9);
  EXPECT_NEAR(j["deviation_percent"].get<double>(), -2.7, 0.05);
  EXPECT_TRUE(j["helical"]["pass"].get<bool>());
}

TEST(NeedleCliSpringTest, AWeakSpringFailsWithExitOne) {
  // Example 2's spring at 3000 rpm: the needle would need far more preload.
  const auto r = RunNeedle("spring " + Case("basu-example2.toml") + " --rpm 3000");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.out.find("spring check: FAIL"), std::string::npos);
}

TEST(NeedleCliSpringTest, SpringNeedsNeedleAndSpringSections) {
  const auto r = RunNeedle("spring " + Case("basu-cam4.toml"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "needle: " + Case("basu-cam4.toml") +
                       ": [needle] mass_kg: section [needle] is missing; the spring check needs "
                       "the moving mass\n");
}

TEST(NeedleCliSpringTest, DesignJsonNamesUnitsInKeys) {
  const auto r = RunNeedle("design " + Case("basu-example2-engine.toml") + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"fuel_per_cycle_g",
                          "fuel_per_cycle_cm3",
                          "mixing_ratio",
                          "air_per_cycle_cm3",
                          "air_expanded_cm3",
                          "air_velocity_m_s",
                          "mean_cross_section_mm2",
                          "discharge_passage_mm",
                          "mean_lift_mm",
                          "max_lift_mm",
                          "lift_table",
                          "cam_disk_mm",
                          "roller_mm",
                          "passage_height_mm",
                          "needle_diameter_mm",
                          "cage_diameter_mm",
                          "spring_preload_kgf",
                          "max_lift_cross_section_mm2",
                          "nozzle_cross_section_mm2",
                          "nozzle_hole_mm"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["lift_table"].size(), 12u);
}

TEST(NeedleCliSpringTest, DesignBadInputExitsTwo) {
  const std::string path = "/tmp/needle_cli_engine_" + std::to_string(getpid()) + ".toml";
  {
    std::ofstream f(path);
    f << "[engine]\npower_hp = 100\nspeed_rpm = 300\n[design]\ndischarge_passage_mm = -6\n";
  }
  const auto r = RunNeedle("design " + path);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "needle: " + path + ": [design] discharge_passage_mm: must be positive, got -6\n");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace needle
