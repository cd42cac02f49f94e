// `needle check`: what it runs and skips, exit statuses, the report file; and the report in a
// real browser (headless Chromium; skipped with a message where it is not installed, failed on
// CI).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "run_command.h"

namespace needle {
namespace {

using testing::Case;
using testing::RunNeedle;

std::string TempDir(const std::string& tag) {
  const std::string dir = "/tmp/needle_check_" + tag + "_" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(CheckReportTest, KinematicsOnlyCaseSaysWhatItSkipped) {
  const std::string dir = TempDir("cam4");
  const auto r = RunNeedle("check " + Case("basu-cam4.toml") + " --out " + dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("skipped: spring check: the case has no [needle] and [spring] sections"),
            std::string::npos);
  EXPECT_NE(r.out.find("skipped: dynamics and overspeed: the case has no [needle], [spring] and "
                       "[train] sections"),
            std::string::npos);
  const std::string html = testing::Slurp(dir + "/basu-cam4.html");
  EXPECT_EQ(Count(html, "<svg"), 1);
  EXPECT_NE(html.find("crank angle (deg)"), std::string::npos);  // axes with units
  std::filesystem::remove_all(dir);
}

TEST(CheckReportTest, FullSceneHasEveryFigureAndPasses) {
  const std::string dir = TempDir("ex1");
  const auto r = RunNeedle("check " + Case("basu-example1.toml") + " --out " + dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("report: " + dir + "/basu-example1.html (6 figures)"), std::string::npos)
      << r.out;
  const std::string html = testing::Slurp(dir + "/basu-example1.html");
  // With its helical spring: the surge figure and the resonance map.
  EXPECT_EQ(Count(html, "<svg"), 6);
  for (const char* label : {"lift (mm)", "velocity (m/s)", "contact force (N)", "speed (rpm)",
                            "jump (deg)", "frequency (Hz)", "Resonance map", "<h2>Limits</h2>",
                            "against the massless spring", "massless spring"}) {
    EXPECT_NE(html.find(label), std::string::npos) << label;
  }
  EXPECT_NE(html.find("energy residual"), std::string::npos);
  EXPECT_NE(html.find("exact"), std::string::npos);  // the method auto chose
  std::filesystem::remove_all(dir);
}

// Job 3 of the report: the velocity and acceleration table like the paper's, the table's points
// over the spline; a C¹ spline leaves out the acceleration panel and says so.
TEST(CheckReportTest, KinematicsTableAndPointsAndC1Splines) {
  const std::string dir = TempDir("kin");
  const auto r = RunNeedle("check " + Case("basu-example1.toml") + " --out " + dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = testing::Slurp(dir + "/basu-example1.html");
  EXPECT_NE(html.find("<h2>Kinematics table at 125 rpm</h2>"), std::string::npos);
  EXPECT_NE(html.find("<th>velocity (dcm/s)</th><th>acceleration (m/s²)</th>"), std::string::npos);
  // The crest row of Example 1: 3.670 mm at 20°, the table's own value.
  EXPECT_NE(html.find("<tr><td>20.0</td><td>3.670</td>"), std::string::npos);
  EXPECT_NE(html.find("points: the lift table"), std::string::npos);
  const std::string pchip = dir + "/pchip.toml";
  {
    std::ifstream in(Case("basu-cam4.toml"));
    std::stringstream s;
    s << in.rdbuf();
    std::string text = s.str();
    text.replace(text.find("spline = \"not-a-knot\""), 21, "spline = \"pchip\"");
    std::ofstream(pchip) << text;
  }
  const auto p = RunNeedle("check " + pchip + " --out " + dir);
  EXPECT_EQ(p.status, 0) << p.err;
  EXPECT_NE(p.out.find("skipped: acceleration panel and table column: the pchip spline is C¹ "
                       "only (its second derivative jumps at the knots)"),
            std::string::npos)
      << p.out;
  const std::string phtml = testing::Slurp(dir + "/pchip.html");
  EXPECT_EQ(Count(phtml, "<svg"), 1);
  EXPECT_EQ(phtml.find("acceleration (m/s²)'"), std::string::npos);
  EXPECT_NE(phtml.find("<td>n/a</td>"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// A case whose lift comes from a CSV of measured readings: checked end to end.
TEST(CheckReportTest, MeasuredCsvCase) {
  const std::string dir = TempDir("measured");
  const auto r = RunNeedle("check " + Case("measured-cycloidal.toml") + " --out " + dir);
  EXPECT_EQ(r.status, 0) << r.err;
  const std::string html = testing::Slurp(dir + "/measured-cycloidal.html");
  EXPECT_NE(html.find("dense table (191 points): measured data, noise 0.0048 mm (estimated); "
                      "smoothing spline"),
            std::string::npos);
  EXPECT_NE(html.find("points: the lift readings"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// `check` checks the cam profile when the case has [profile]: an undercut fails the check.
TEST(CheckReportTest, UndercutCamFailsTheCheck) {
  const std::string dir = TempDir("undercut");
  const std::string path = dir + "/undercut.toml";
  {
    std::ifstream in(Case("basu-cam4.toml"));
    std::stringstream s;
    s << in.rdbuf();
    std::ofstream(path) << s.str() << "[profile]\nbase_radius_mm = 8\nroller_radius_mm = 12\n";
  }
  const auto p = RunNeedle("profile " + path);
  EXPECT_EQ(p.status, 1);
  EXPECT_NE(p.out.find("UNDERCUT"), std::string::npos);
  const auto r = RunNeedle("check " + path + " --out " + dir);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("cam profile: UNDERCUT"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fails: cam profile: the profile undercuts: least radius -10.48 mm"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("overall: FAIL"), std::string::npos);
  const std::string html = testing::Slurp(dir + "/undercut.html");
  EXPECT_NE(html.find("<h2>Failing</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2>Cam profile</h2>"), std::string::npos);
  // Without [profile] the check says it skipped the profile.
  const auto k = RunNeedle("check " + Case("basu-cam4.toml") + " --out " + dir);
  EXPECT_NE(k.out.find("skipped: cam profile: the case has no [profile] section"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(CheckReportTest, LiftOffAtTheRatedSpeedFailsWithExitOne) {
  const std::string dir = TempDir("ex2");
  const auto r = RunNeedle("check " + Case("basu-example2.toml") + " --out " + dir + " --rpm 1400");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.out.find("lift-off at 1400 rpm: YES"), std::string::npos);
  EXPECT_NE(r.out.find("overall: FAIL"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(CheckReportTest, BadInputLeavesNoReport) {
  const std::string dir = TempDir("bad");
  const std::string bad = dir + "/broken.toml";
  {
    std::ofstream f(bad);
    f << "[engine]\nspeed_rpm = 400\n[lift]\ncrank_deg = [0, 1]\nlift_mm = [0, nan]\n";
  }
  const auto r = RunNeedle("check " + bad + " --out " + dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "needle: " + bad + ": [lift] lift_mm[1]: is NaN; expected a finite number\n");
  EXPECT_FALSE(std::filesystem::exists(dir + "/broken.html"));
  // A folder inside a file cannot be made: one line naming the option.
  const auto nodir = RunNeedle("check " + Case("basu-cam4.toml") + " --out " + bad + "/sub");
  EXPECT_EQ(nodir.status, 2);
  EXPECT_EQ(nodir.err, "needle: --out: " + bad +
                           "/sub is not a folder and cannot be made one (Not a directory)\n");
  // A missing folder is made.
  const auto made = RunNeedle("check " + Case("basu-cam4.toml") + " --out " + dir + "/a/b");
  EXPECT_EQ(made.status, 0) << made.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/a/b/basu-cam4.html"));
  std::filesystem::remove_all(dir);
}

TEST(CheckReportTest, AnOutFolderThatCannotBeReachedIsBadInput) {
  // A symbolic link to itself: filesystem::is_directory threw, exit 3 with the raw message.
  const std::string dir = TempDir("loop"), loop = dir + "/loop";
  std::filesystem::create_symlink(loop, loop);
  for (const std::string& command :
       {"check " + Case("basu-cam4.toml"),
        "tolerance " + Case("basu-example2.toml") + " --samples 2",
        "compare " + Case("basu-cam4.toml") + " " + Case("basu-cam4.toml")}) {
    for (const std::string& out : {loop, loop + "/sub"}) {
      const auto r = RunNeedle(command + " --out " + out);
      EXPECT_EQ(r.status, 2) << command;
      EXPECT_EQ(r.err, "needle: --out: " + out +
                           " is not a folder and cannot be made one (Too many levels of symbolic "
                           "links)\n")
          << command;
      EXPECT_TRUE(r.out.empty());
    }
  }
  std::filesystem::remove_all(dir);
}

// Where stderr is no terminal (here a file), the overspeed sweep and the tolerance study say
// how far they are in a line now and then; under --json they are quiet, and stdout is the same.
TEST(CheckReportTest, ProgressIsALineNowAndThenOutsideATerminal) {
  const std::string dir = TempDir("progress");
  const std::regex line("overspeed: [0-9]+ of about [0-9]+ speeds");
  const auto text = RunNeedle("check " + Case("basu-example1.toml") + " --out " + dir);
  ASSERT_EQ(text.status, 0) << text.err;
  std::istringstream lines(text.err);
  int n = 0;
  for (std::string l; std::getline(lines, l); ++n) EXPECT_TRUE(std::regex_match(l, line)) << l;
  EXPECT_GE(n, 5);                                             // about one per tenth of the sweep
  EXPECT_LE(n, 30);                                            // not one per speed
  EXPECT_EQ(text.out.find("overspeed: "), std::string::npos);  // stdout untouched
  const auto json = RunNeedle("check " + Case("basu-example1.toml") + " --out " + dir + " --json");
  EXPECT_EQ(json.status, 0);
  EXPECT_EQ(json.err, "");
  EXPECT_TRUE(nlohmann::json::accept(json.out)) << json.out;
  const auto study = RunNeedle("tolerance " + Case("basu-example2.toml") + " --samples 20");
  ASSERT_EQ(study.status, 0) << study.err;
  EXPECT_NE(study.err.find("tolerance: 20/20 samples\n"), std::string::npos) << study.err;
  const auto quiet = RunNeedle("tolerance " + Case("basu-example2.toml") + " --samples 20 --json");
  EXPECT_EQ(quiet.err, "");
  std::filesystem::remove_all(dir);
}

// Reproducer 1 of issue 11 through `check --json`: every failing item named, one verdict.
TEST(CheckReportTest, JsonNamesEveryFailingItem) {
  const std::string dir = TempDir("json");
  const auto r =
      RunNeedle("check " + Case("new-engine-weak-spring.toml") + " --out " + dir + " --json");
  EXPECT_EQ(r.status, 1) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["overall"], "fail");
  EXPECT_FALSE(j["spring"]["basu_ok"].get<bool>());
  EXPECT_FALSE(j["spring"]["combustion_ok"].get<bool>());
  ASSERT_EQ(j["failing"].size(), 3u) << r.out;
  EXPECT_EQ(j["failing"][1],
            "spring check: Basu's formula: the preload 40.0 kgf is 80.6 % below 206.2 kgf "
            "(tolerance 10.0 %)");
  EXPECT_EQ(j["skipped"][0], "dynamics and overspeed: the case has no [train] section");
  EXPECT_TRUE(std::filesystem::exists(j["report"].get<std::string>()));
  std::filesystem::remove_all(dir);
}

TEST(CheckReportTest, HelpDocumentsEveryCommandAndOption) {
  const auto top = RunNeedle("--help");
  EXPECT_EQ(top.status, 0);
  for (const char* cmd : {"check", "compare", "kinematics", "spring", "design", "simulate",
                          "overspeed", "synth", "profile", "tolerance"}) {
    EXPECT_NE(top.out.find(cmd), std::string::npos) << cmd;
    EXPECT_EQ(RunNeedle(std::string(cmd) + " --help").status, 0) << cmd;
  }
  const auto check = RunNeedle("check --help");
  for (const char* opt : {"--out", "--rpm"})
    EXPECT_NE(check.out.find(opt), std::string::npos) << opt;
}

// The report in a real browser. README's test set-up installs Chromium, so CI runs this; on
// CI (CI set) a missing Chromium fails instead of skipping. A copy of the report with a probe
// script appended reports the laid-out size of every figure and table; the screenshot is kept
// in the build folder (build/test-output/) and its path printed.
TEST(CheckReportTest, ReportRendersInHeadlessChromium) {
  if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
    if (std::getenv("CI") != nullptr)
      FAIL() << "chromium is not installed on CI; README's test set-up (setup.sh --tests) "
                "installs it";
    GTEST_SKIP() << "chromium is not installed (bash scripts/setup.sh --tests): browser rendering "
                    "not tested";
  }
  const std::string dir = TempDir("browser");
  ASSERT_EQ(RunNeedle("check " + Case("basu-example1.toml") + " --out " + dir).status, 0);
  const std::string html = testing::Slurp(dir + "/basu-example1.html");
  const int figures = Count(html, "<svg"), tables = Count(html, "<table");
  EXPECT_EQ(figures, 6);
  EXPECT_GE(tables, 7);
  const std::string probe =
      "<script>const out = [];"
      "document.querySelectorAll('svg, table').forEach(e => {"
      "  const r = e.getBoundingClientRect();"
      "  out.push(e.tagName.toLowerCase() + ' ' + Math.round(r.width) + ' ' + Math.round(r.height)"
      "           + ' ' + (e.tagName === 'TABLE' ? e.rows.length : "
      "e.querySelectorAll('path').length));"
      "});"
      "const pre = document.createElement('pre'); pre.id = 'probe';"
      "pre.textContent = '[' + out.join(';') + ']'; document.body.appendChild(pre);</script>";
  {
    std::ofstream copy(dir + "/probe.html");
    copy << html.substr(0, html.rfind("</body>")) << probe << "</body></html>";
  }
  const std::string flags =
      "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking "
      "--disable-component-update --disable-sync --window-size=1000,3400 --user-data-dir=" +
      dir + "/profile ";
  // The DOM Chromium built and laid out, with the probe's line in it.
  const std::string dom = dir + "/dom.html";
  ASSERT_EQ(std::system(("timeout 120 chromium " + flags + "--dump-dom file://" + dir +
                         "/probe.html >" + dom + " 2>/dev/null")
                            .c_str()),
            0);
  const std::string text = testing::Slurp(dom);
  EXPECT_NE(text.find("Overall: <span class=\"pass\">pass</span>"), std::string::npos);
  const std::smatch m = [&] {
    std::smatch found;
    std::regex_search(text, found, std::regex(R"(<pre id="probe">\[([^\]]*)\])"));
    return found;
  }();
  ASSERT_FALSE(m.empty()) << "the probe did not run";
  std::istringstream items(m[1].str());
  std::string item;
  int svgs = 0, drawn_tables = 0;
  while (std::getline(items, item, ';')) {
    std::istringstream f(item);
    std::string tag;
    int width = 0, height = 0, parts = 0;
    f >> tag >> width >> height >> parts;
    if (tag == "svg") {
      ++svgs;
      EXPECT_GE(width, 300) << item;  // a figure laid out at its size, with drawn curves
      EXPECT_GE(height, 200) << item;
      EXPECT_GE(parts, 5) << item;
    } else {
      ++drawn_tables;
      EXPECT_GT(width, 100) << item;  // a table with rows, laid out
      EXPECT_GT(height, 10) << item;
      EXPECT_GE(parts, 1) << item;
    }
  }
  EXPECT_EQ(svgs, figures);
  EXPECT_EQ(drawn_tables, tables);
  // A screenshot of the whole page, kept: a PNG of the asked size with real content in it.
  const std::string kept =
      (std::filesystem::path(NEEDLE_BINARY).parent_path() / "test-output").string();
  std::filesystem::create_directories(kept);
  const std::string png = kept + "/report-basu-example1.png";
  std::filesystem::remove(png);
  ASSERT_EQ(std::system(("timeout 120 chromium " + flags + "--screenshot=" + png + " file://" +
                         dir + "/basu-example1.html >/dev/null 2>&1")
                            .c_str()),
            0);
  const std::string bytes = testing::Slurp(png);
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  auto be32 = [&](size_t at) {
    return (static_cast<unsigned char>(bytes[at]) << 24) |
           (static_cast<unsigned char>(bytes[at + 1]) << 16) |
           (static_cast<unsigned char>(bytes[at + 2]) << 8) |
           static_cast<unsigned char>(bytes[at + 3]);
  };
  EXPECT_EQ(be32(16), 1000u);        // IHDR width
  EXPECT_EQ(be32(20), 3400u);        // IHDR height
  EXPECT_GT(bytes.size(), 100000u);  // four plots and tables compress to well over 100 kB
  std::cout << "[browser] Chromium laid out " << svgs << " figures and " << drawn_tables
            << " tables; screenshot kept at " << png << '\n';
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// Issue 51: beside "pass", the check says which rows it could not judge and why (Example 1:
// no roller width for the Hertz row, a 16 mm wire beyond Zimmerli's data for fatigue).
TEST(CheckReportTest, BesideItsVerdictTheCheckNamesTheRowsItCouldNotJudge) {
  const std::string dir = TempDir("ex1-judged");
  const auto r = RunNeedle("check " + Case("basu-example1.toml") + " --out " + dir);
  EXPECT_EQ(r.status, 0) << r.err;
  const std::string why =
      "Hertz stress cam-roller (no [limits] contact_length_mm (the roller's width)); spring "
      "fatigue safety factor (Goodman) (wire 16.0 mm: Zimmerli's data cover wire below 10 mm)";
  EXPECT_NE(r.out.find("overall: pass; not judged: " + why + "\n"), std::string::npos) << r.out;
  const std::string html = testing::Slurp(dir + "/basu-example1.html");
  EXPECT_NE(html.find("; not judged: Hertz stress cam-roller"), std::string::npos);
  const auto j = RunNeedle("check " + Case("basu-example1.toml") + " --out " + dir + " --json");
  EXPECT_EQ(nlohmann::json::parse(j.out)["not_judged"], why);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace needle
