// The Markdown writer over a command's JSON object (apps/report/markdown_writer.h), and
// `--format` as every command takes it.
#include "apps/report/markdown_writer.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "apps/report/output_format.h"
#include "run_command.h"

namespace needle {
namespace {

using testing::RunNeedle;

std::string Case(const std::string& name) {
  return std::string(NEEDLE_SOURCE_DIR) + "/cases/" + name;
}

TEST(MarkdownWriterTest, ScalarsRecordsAndNestedObjects) {
  const nlohmann::json j = nlohmann::json::parse(R"({
    "pass": true, "preload_N": 7747.25, "name": "a|b", "none": null, "empty": [],
    "angles_deg": [1, 2.5],
    "impacts": [{"crank_deg": -15.5, "kind": "lash"}, {"crank_deg": 40, "kind": "seat",
                 "speed_m_s": 0.12}],
    "helical": {"wire_mm": 16, "ok": false}
  })");
  // nlohmann orders an object's keys alphabetically; records keep their first-seen columns.
  EXPECT_EQ(MarkdownFromJson(j),
            "| key | value |\n|---|---|\n"
            "| angles_deg | 1, 2.5 |\n"
            "| empty | — |\n"
            "| name | a\\|b |\n"
            "| none | — |\n"
            "| pass | true |\n"
            "| preload_N | 7747.25 |\n"
            "\n## helical\n\n| key | value |\n|---|---|\n| ok | false |\n| wire_mm | 16 |\n"
            "\n## impacts\n\n| crank_deg | kind | speed_m_s |\n|---|---|---|\n"
            "| -15.5 | lash |  |\n| 40 | seat | 0.12 |\n");
}

TEST(MarkdownWriterTest, NumbersAreWrittenAsJsonWritesThem) {
  // The shortest text that reads back the same double: nothing rounded.
  const nlohmann::json j = {{"x", 0.1 + 0.2}};
  EXPECT_EQ(MarkdownFromJson(j), "| key | value |\n|---|---|\n| x | 0.30000000000000004 |\n");
}

TEST(MarkdownWriterTest, FormatNamesRoundTrip) {
  for (OutputFormat f : {OutputFormat::kText, OutputFormat::kJson, OutputFormat::kMarkdown}) {
    EXPECT_EQ(ParseOutputFormat(OutputFormatName(f)), f);
  }
  EXPECT_FALSE(ParseOutputFormat("xml"));
}

// Every command takes --format; markdown is the JSON object's values, json is --json.
TEST(OutputFormatTest, EveryCommandTakesFormat) {
  const std::string ex1 = Case("basu-example1.toml");
  for (const std::string& cmd :
       {"spring " + ex1, "simulate " + ex1, "kinematics " + ex1, "profile " + ex1,
        "overspeed " + ex1 + " --to 700", "design " + Case("basu-example1-engine.toml"),
        "synth " + Case("matec-2018-synth.toml")}) {
    const auto json = RunNeedle(cmd + " --json");
    const auto format_json = RunNeedle(cmd + " --format json");
    const auto md = RunNeedle(cmd + " --format markdown");
    EXPECT_EQ(json.out, format_json.out) << cmd;
    EXPECT_EQ(json.status, md.status) << cmd;
    ASSERT_FALSE(json.out.empty()) << cmd;
    EXPECT_EQ(md.out, MarkdownFromJson(nlohmann::json::parse(json.out))) << cmd;
  }
}

TEST(OutputFormatTest, MarkdownOfCheckCompareAndTolerance) {
  const std::string ex1 = Case("basu-example1.toml");
  const auto md = RunNeedle("check " + ex1 + " --out /tmp --format markdown");
  EXPECT_EQ(md.status, 0);
  EXPECT_NE(md.out.find("| overall | pass |"), std::string::npos) << md.out.substr(0, 400);
  const auto cmp = RunNeedle("compare " + ex1 + " " + Case("basu-example1-weak-spring.toml") +
                             " --out /tmp --format markdown");
  EXPECT_EQ(cmp.status, 1);
  EXPECT_NE(cmp.out.find("| flipped | overall, spring.basu_ok, spring.pass |"), std::string::npos)
      << cmp.out.substr(0, 400);
  const auto tol = RunNeedle("tolerance " + Case("basu-example2.toml") +
                             " --samples 2 --seed 1 --format markdown");
  EXPECT_EQ(tol.status, 0);
  EXPECT_NE(tol.out.find("| samples | 2 |"), std::string::npos) << tol.out.substr(0, 400);
}

TEST(OutputFormatTest, AnUnknownFormatIsBadInput) {
  const auto r = RunNeedle("spring " + Case("basu-example1.toml") + " --format xml");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--format: expected text, json or markdown, got 'xml'"), std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty());
}

}  // namespace
}  // namespace needle
