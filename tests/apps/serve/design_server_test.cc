// `needle serve`: the overrides merged as a case file, the API over loopback against `needle
// check --json`, a thousand malformed requests, superseded work dropped, SIGINT, and the page in
// the system's Chromium.
#include "apps/serve/design_server.h"

#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <future>
#include <random>
#include <regex>
#include <thread>

#include "apps/serve/design_api.h"
#include "lib/case_error.h"
#include "run_command.h"

namespace needle {
namespace {

using testing::Case;
using testing::RunNeedle;

// A server on a free loopback port for the test's lifetime.
class Running {
 public:
  explicit Running(const std::string& case_file) : session_(Case(case_file)) {
    std::promise<int> bound;
    ServeOptions o;
    o.port = 0;
    o.on_listening = [&bound](int port) { bound.set_value(port); };
    thread_ = std::thread([this, o] { status_ = Serve(session_, o); });
    port_ = bound.get_future().get();
  }
  ~Running() {
    StopServing();
    thread_.join();
  }
  httplib::Client Client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(60, 0);
    return c;
  }
  int port() const { return port_; }

 private:
  DesignSession session_;
  std::thread thread_;
  int port_ = 0;
  int status_ = -1;
};

// The check's JSON without what differs between two runs of the same case (where it is, the
// report written, wall times).
nlohmann::json Comparable(nlohmann::json j) {
  j.erase("case");
  j.erase("report");
  return nlohmann::json::parse(std::regex_replace(
      j.dump(), std::regex(R"("[a-z_]*seconds[a-z_]*":[-0-9.e+]+)"), R"("seconds":0)"));
}

TEST(DesignApiTest, OverridesReplaceTheSameQuantityInAnotherUnit) {
  const std::string text = "title = \"t\"\n[spring]\npreload_kgf = 790\nwire_mm = 16\n";
  const std::string merged = CaseWithOverrides(
      text, nlohmann::json::parse(R"({"spring": {"preload_N": 1700}, "train": {"play_mm": 0.3}})"),
      "t.toml");
  EXPECT_EQ(merged.find("preload_kgf"), std::string::npos) << merged;
  EXPECT_NE(merged.find("preload_N = 1700"), std::string::npos) << merged;
  EXPECT_NE(merged.find("wire_mm = 16"), std::string::npos) << merged;
  EXPECT_NE(merged.find("\n[train]\nplay_mm = 0.3\n"), std::string::npos) << merged;
  // The file's own lines stay, a multi-line array replaced whole.
  const std::string lift = "[lift]\n# measured\nlift_mm = [0,\n  1,\n  0]\ncrank_deg = [0, 1, 2]\n";
  const std::string relift =
      CaseWithOverrides(lift, nlohmann::json::parse(R"({"lift": {"lift_um": 5}})"), "t.toml");
  EXPECT_EQ(relift, "[lift]\nlift_um = 5\n# measured\ncrank_deg = [0, 1, 2]\n");
  // A section written as dotted keys at the root is refused, naming the fix.
  try {
    CaseWithOverrides("spring.preload_kgf = 790\n",
                      nlohmann::json::parse(R"({"spring": {"preload_N": 1}})"), "t.toml");
    ADD_FAILURE() << "dotted keys accepted";
  } catch (const CaseError& e) {
    EXPECT_STREQ(e.what(),
                 "t.toml: overrides: [spring]: the case writes this section inline or as dotted "
                 "keys; write it as a [spring] block to tune it here");
  }
  EXPECT_EQ(CaseWithOverrides("[train]\nramp = \"tangent\"#c1\n",
                              nlohmann::json::parse(R"({"train": {"ramp": "linear"}})"), "t.toml"),
            "[train]\nramp = 'linear'  #c1\n");
  // A replaced line's own comment stays on the new line.
  EXPECT_EQ(CaseWithOverrides("[needle]\nmass_kg = 1.2  # Basu: \"about 1.2 kg\"\n",
                              nlohmann::json::parse(R"({"needle": {"mass_g": 900}})"), "t.toml"),
            "[needle]\nmass_g = 900  # Basu: \"about 1.2 kg\"\n");
  const auto refused = [&](const std::string& overrides) {
    try {
      CaseWithOverrides(text, nlohmann::json::parse(overrides), "t.toml");
    } catch (const CaseError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused(R"({"spring": 5})"),
            "t.toml: overrides: spring: expected an object of keys, such as {\"preload_N\": 1700}");
  EXPECT_EQ(refused(R"({"spring": {"preload_N": [1, 2]}})"),
            "t.toml: overrides: [spring] preload_N: expected a number, a string or true/false");
  EXPECT_EQ(refused(R"({"spring": {"preload_N = 1\n[x]\ny": 2}})"),
            "t.toml: overrides: \"spring\" \"preload_N = 1\\n[x]\\ny\": expected section and key "
            "names of letters, digits and _");
  EXPECT_EQ(refused(R"([1])"),
            "t.toml: overrides: expected a JSON object of sections, such as "
            "{\"spring\": {\"preload_N\": 1700}}");
}

TEST(DesignServerTest, ApiCheckIsTheCommandLinesCheck) {
  Running server("basu-example1.toml");
  httplib::Client client = server.Client();
  const std::string overrides = R"({"spring": {"preload_N": 6000}})";
  const auto api = client.Post("/api/check", overrides, "application/json");
  ASSERT_TRUE(api);
  ASSERT_EQ(api->status, 200) << api->body;
  // The same case written with the override and checked by the command line.
  const auto saved = client.Post("/api/case-text", overrides, "application/json");
  ASSERT_TRUE(saved && saved->status == 200);
  const std::string path = testing::TempPath("serve-preload.toml");
  std::ofstream(path) << nlohmann::json::parse(saved->body)["toml"].get<std::string>();
  const auto cli = RunNeedle("check " + path + " --json --out " + testing::TempPath("serve-out"));
  ASSERT_EQ(cli.status, 1) << cli.err;  // 6000 N lifts off below f·n: the check fails
  const nlohmann::json a = nlohmann::json::parse(api->body), b = nlohmann::json::parse(cli.out);
  EXPECT_EQ(Comparable(a), Comparable(b));
  EXPECT_EQ(a["overall"], "fail");
  // A bad override: the command line's one line, with 400.
  const auto bad =
      client.Post("/api/check", R"({"spring": {"preload_N": -5}})", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(nlohmann::json::parse(bad->body)["error"],
            Case("basu-example1.toml") + ": [spring] preload_N: must not be negative, got -5 N");
}

TEST(DesignServerTest, SupersededWorkIsDroppedAndASlowCheckBlocksNothing) {
  Running server("basu-example1.toml");
  httplib::Client client = server.Client();
  httplib::Headers newer = {{"X-Needle-Seq", "5"}}, older = {{"X-Needle-Seq", "3"}};
  const auto first = client.Post("/api/design", newer, "{}", "application/json");
  ASSERT_TRUE(first);
  EXPECT_EQ(first->status, 200);
  const nlohmann::json design = nlohmann::json::parse(first->body);
  EXPECT_TRUE(design["series"].contains("kinematics"));
  EXPECT_TRUE(design["series"].contains("run"));
  EXPECT_TRUE(design["series"].contains("overspeed"));
  // Example 1's run has its lash and its seating: both marked, at the run's own angles.
  const auto& impacts = design["series"]["impacts"];
  ASSERT_GE(impacts["crank_deg"].size(), 2u);
  EXPECT_EQ(impacts["kind"].size(), impacts["crank_deg"].size());
  // The force at f·n = 1.2 × 125 rpm beside the rated one.
  EXPECT_EQ(design["series"]["run_overspeed"]["speed_rpm"], 150.0);
  EXPECT_GT(design["series"]["run_overspeed"]["contact_force_N"]["value"].size(), 100u);
  const auto stale = client.Post("/api/design", older, "{}", "application/json");
  ASSERT_TRUE(stale);
  EXPECT_EQ(stale->status, 409);
  // Another page (a reload, a second tab) counts its own changes: its first is not stale.
  const auto other_page = client.Post(
      "/api/design", {{"X-Needle-Seq", "1"}, {"X-Needle-Client", "b"}}, "{}", "application/json");
  ASSERT_TRUE(other_page);
  EXPECT_EQ(other_page->status, 200);
}

// On the 20-coil-mass chain (a design of about a second): the case is served while a design
// computes, and a change that waits behind the running one is dropped as soon as a newer one
// of its page arrives — before the running one ends, never computed.
TEST(DesignServerTest, AWaitingChangeIsDroppedWhenANewerComesAndNothingElseWaits) {
  Running server("basu-example1-clash.toml");
  std::atomic<bool> first_done{false};
  std::thread first([&] {
    httplib::Client c = server.Client();
    c.Post("/api/design", {{"X-Needle-Client", "p"}, {"X-Needle-Seq", "1"}}, "{}",
           "application/json");
    first_done = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::atomic<int> second_status{0};
  std::atomic<bool> second_before_first{false};
  std::thread second([&] {
    httplib::Client c = server.Client();
    const auto r = c.Post("/api/design", {{"X-Needle-Client", "p"}, {"X-Needle-Seq", "2"}}, "{}",
                          "application/json");
    second_before_first = !first_done.load();
    second_status = r ? r->status : -1;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  httplib::Client other = server.Client();
  const auto page = other.Get("/api/case");
  const bool served_while_computing = !first_done.load();
  const auto third = other.Post("/api/design", {{"X-Needle-Client", "p"}, {"X-Needle-Seq", "3"}},
                                R"({"engine": {"speed_rpm": 126}})", "application/json");
  second.join();
  first.join();
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_TRUE(served_while_computing) << "the design ended before the case was served";
  EXPECT_EQ(second_status.load(), 409);
  EXPECT_TRUE(second_before_first.load()) << "the waiting change was computed or kept waiting";
  ASSERT_TRUE(third);
  EXPECT_EQ(third->status, 200);
}

TEST(DesignServerTest, AThousandMalformedRequestsNeverStopTheServer) {
  Running server("basu-example1.toml");
  httplib::Client client = server.Client();
  std::mt19937 random(7);
  int refused = 0;
  for (int i = 0; i < 1000; ++i) {
    std::string body;
    switch (i % 8) {
      case 0:  // random bytes (not all blank: a blank body is no overrides, a valid request)
        body = "\x01";
        for (int k = 0; k < 1 + static_cast<int>(random() % 300); ++k)
          body += static_cast<char>(random() % 256);
        break;
      case 1:
        body = "{\"spring\": {\"preload_N\": " + std::to_string(i) + "}";  // cut short
        break;
      case 2:
        body = R"({"spring": [1, 2, 3]})";
        break;
      case 3:
        body = R"({"nosuchsection": {"x": 1}})";
        break;
      case 4:
        body = R"({"spring": {"preload_N": "many"}})";
        break;
      case 5:
        body = std::string(1 << 20, '[') + "]";  // over the 1 MiB limit
        break;
      case 6:
        body = R"({"spring": {"preload_kgf": 1e400}})";
        break;
      case 7:
        body = R"({"train": {"play_mm": null}})";
        break;
    }
    const char* path = i % 3 == 0 ? "/api/check" : (i % 3 == 1 ? "/api/design" : "/api/case-text");
    const auto r = client.Post(path, body, "application/json");
    ASSERT_TRUE(r) << "request " << i << " got no reply";
    EXPECT_TRUE(r->status == 400 || r->status == 413) << i << ": " << r->status << " " << r->body;
    refused += r->status >= 400;
  }
  EXPECT_EQ(refused, 1000);
  // Raw garbage on the socket, a wrong method, an unknown path.
  for (int i = 0; i < 20; ++i) {
    httplib::Client raw = server.Client();
    EXPECT_TRUE(raw.Get("/no/such/page"));
  }
  EXPECT_EQ(client.Get("/api/check")->status, 404);
  const auto ok = client.Post("/api/check", "{}", "application/json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
}

TEST(DesignServerTest, APortInUseIsRefusedAndFilesAreNotOpened) {
  Running server("basu-example1.toml");
  const DesignSession second(Case("basu-cam4.toml"));
  ServeOptions o;
  o.port = server.port();
  try {
    Serve(second, o);
    FAIL() << "a second server shared the port";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--host/--port: cannot listen on 127.0.0.1:" + std::to_string(server.port()) +
                  " (the port in use, or the host not an address of this machine)");
  }
  httplib::Client client = server.Client();
  const auto r =
      client.Post("/api/check", R"({"lift": {"csv": "/etc/passwd"}})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(nlohmann::json::parse(r->body)["error"],
            Case("basu-example1.toml") +
                ": overrides: [lift] csv: names a file; the design page does not open files (edit "
                "the case)");
  // A chunked body has no length to hold to the limit; a foreign Host is not served.
  httplib::Headers chunked = {{"Transfer-Encoding", "chunked"}};
  const auto c = client.Post("/api/check", chunked, "{}", "application/json");
  ASSERT_TRUE(c);
  EXPECT_EQ(c->status, 411);
  const auto rebound = client.Get("/api/case", {{"Host", "attacker.example:80"}});
  ASSERT_TRUE(rebound);
  EXPECT_EQ(rebound->status, 403);
  // An error without a body of its own still says what, in one JSON line.
  const auto missing = client.Get("/no/such/page");
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(nlohmann::json::parse(missing->body)["error"], "no such page or API: /no/such/page");
}

TEST(DesignServerTest, AMeasuredTableHasItsAccelerationBand) {
  Running server("measured-cycloidal.toml");
  httplib::Client client = server.Client();
  const auto local =
      client.Post("/api/design", R"({"lift": {"spline": "local"}})", "application/json");
  ASSERT_TRUE(local && local->status == 200) << (local ? local->body : "");
  const auto band = nlohmann::json::parse(local->body)["series"]["acceleration_band"];
  ASSERT_GE(band["crank_deg"].size(), 2u);
  for (size_t i = 0; i < band["crank_deg"].size(); ++i)
    EXPECT_LT(band["low_m_s2"][i].get<double>(), band["high_m_s2"][i].get<double>());
  // A smoothing spline carries its band at the knots of its two extremes (lib/spline_band.h).
  const auto smooth = client.Post("/api/design", "{}", "application/json");
  const auto at_extremes = nlohmann::json::parse(smooth->body)["series"]["acceleration_band"];
  ASSERT_EQ(at_extremes["crank_deg"].size(), 2u);
  for (size_t i = 0; i < 2; ++i)
    EXPECT_LT(at_extremes["low_m_s2"][i].get<double>(), at_extremes["high_m_s2"][i].get<double>());
}

// The page's force curve keeps the run's peak (the report's LineEnvelope, not every n-th point):
// Example 2 at 1100 rpm, its lash impact, against `needle simulate`'s largest contact force.
TEST(DesignServerTest, ThePagesForceCurveKeepsTheRunsPeak) {
  Running server("basu-example2.toml");
  httplib::Client client = server.Client();
  const auto r =
      client.Post("/api/design", R"({"engine": {"speed_rpm": 1100}})", "application/json");
  ASSERT_TRUE(r && r->status == 200);
  const auto curve = nlohmann::json::parse(r->body)["series"]["run"]["contact_force_N"];
  double peak = 0.0;
  for (const auto& v : curve["value"]) peak = std::max(peak, v.get<double>());
  const auto cli = RunNeedle("simulate " + Case("basu-example2.toml") + " --rpm 1100 --json");
  ASSERT_EQ(cli.status, 0) << cli.err;
  EXPECT_DOUBLE_EQ(peak, nlohmann::json::parse(cli.out)["max_contact_force_N"].get<double>());
  EXPECT_LE(curve["value"].size(), 4u * 2 * 860);  // at most four rows a column
}

TEST(DesignServerTest, SigintEndsTheCommandCleanly) {
  const std::string out = testing::TempPath("serve-stdout");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    freopen(out.c_str(), "w", stdout);
    execl(NEEDLE_BINARY, NEEDLE_BINARY, "serve", Case("basu-example2.toml").c_str(), "--port", "0",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  std::string line;
  for (int i = 0; i < 200 && line.find("http://") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
    line = testing::Slurp(out);
  }
  ASSERT_NE(line.find("http://127.0.0.1:"), std::string::npos) << line;
  kill(pid, SIGINT);
  int status = 0;
  pid_t ended = 0;
  for (int i = 0; i < 400 && (ended = waitpid(pid, &status, WNOHANG)) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  if (ended != pid) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    FAIL() << "needle serve did not end within 10 s of SIGINT";
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  // A bad case is refused before anything is bound: one line, exit 2.
  const auto bad = RunNeedle("serve /no/such.toml --port 0");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.err.rfind("needle: /no/such.toml: ", 0), 0u) << bad.err;
}

// The page in the system's Chromium: the preload slider moved (its input event, by the page's
// ?spring.preload_kgf= link), the n_dyn it shows equals `needle check --json`'s for that preload;
// a screenshot is kept in the test's folder (serve-page.png).
TEST(DesignServerTest, ThePageInChromiumShowsTheCommandLinesNdyn) {
  if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
    if (std::getenv("CI")) FAIL() << "chromium is not installed on CI (setup.sh --tests)";
    GTEST_SKIP() << "chromium is not installed (bash scripts/setup.sh --tests)";
  }
  Running server("basu-example1.toml");
  const std::string url =
      "http://127.0.0.1:" + std::to_string(server.port()) + "/?spring.preload_kgf=700";
  const std::string flags =
      "--headless --no-sandbox --disable-gpu --virtual-time-budget=20000 "
      "--user-data-dir=" +
      testing::TempPath("chromium-profile") + " ";
  const std::string dom = testing::TempPath("serve-dom.html");
  ASSERT_EQ(std::system(("timeout 120 chromium " + flags + "--dump-dom '" + url + "' > " + dom +
                         " 2>/dev/null")
                            .c_str()),
            0);
  const std::string page = testing::Slurp(dom);
  const std::smatch m = [&] {
    std::smatch s;
    std::regex_search(page, s, std::regex(R"(id="n_dyn">([0-9.]+)<)"));
    return s;
  }();
  ASSERT_EQ(m.size(), 2u) << page.substr(0, 2000);
  // The command line on the same design.
  httplib::Client client = server.Client();
  const auto saved =
      client.Post("/api/case-text", R"({"spring": {"preload_kgf": 700}})", "application/json");
  const std::string path = testing::TempPath("serve-700.toml");
  std::ofstream(path) << nlohmann::json::parse(saved->body)["toml"].get<std::string>();
  const auto cli = RunNeedle("check " + path + " --json --out " + testing::TempPath("serve-out"));
  const double n_dyn =
      nlohmann::json::parse(cli.out)["overspeed"]["liftoff_rpm_dynamic"].get<double>();
  char expected[32];
  std::snprintf(expected, sizeof expected, "%.1f", n_dyn);
  EXPECT_EQ(m[1].str(), expected);
  EXPECT_NE(m[1].str(), "650.4");  // not the case's own n_dyn (790 kgf): the slider moved it
  // The screenshot, the test's artefact.
  const std::string png = "serve-page.png";
  EXPECT_EQ(std::system(("timeout 120 chromium " + flags + "--window-size=1400,1000 --screenshot=" +
                         png + " '" + url + "' >/dev/null 2>&1")
                            .c_str()),
            0);
  EXPECT_GT(testing::Slurp(png).size(), 10000u);
}

}  // namespace
}  // namespace needle
