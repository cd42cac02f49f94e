// needle-bench serve: the design page's request → reply over loopback, per bundled case.
#include <cmath>
#include <filesystem>
#include <future>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "apps/bench/bench_common.h"
#include "apps/serve/design_api.h"
#include "apps/serve/design_server.h"
#include "lib/case_error.h"

// Last: its <resolv.h> defines _res, a name Eigen uses (bench_common.h includes Eigen).
#include <httplib.h>

namespace needle::bench {

std::string RunServe(int repeats) {
  std::ostringstream md;
  md << "## needle serve: a change to its reply (2 cores, loopback, medians)\n\n"
        "POST /api/design with one override (the preload, or the rated speed where the case has "
        "no spring), as the page sends on a slider's move: the check and the page's curves, "
        "over HTTP. The page's drawing (uPlot) comes on top; the page shows the whole, input "
        "to redraw, in its header.\n\n"
        "| case | median | slowest | target ≤ 100 ms |\n|---|---|---|---|\n";
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(CaseDir()))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  int met = 0, cases = 0;
  for (const auto& file : files) {
    std::optional<DesignSession> session;
    try {
      session.emplace(file.string());
    } catch (const CaseError&) {
      continue;  // an engine or synthesis file: not a scene
    }
    std::promise<int> bound;
    ServeOptions o;
    o.port = 0;
    o.on_listening = [&bound](int port) { bound.set_value(port); };
    std::thread server([&] { Serve(*session, o); });
    httplib::Client client("127.0.0.1", bound.get_future().get());
    client.set_read_timeout(300, 0);
    // The preload's key as the case writes it (preload_kgf, preload_N), else the rated speed.
    const nlohmann::json c = nlohmann::json::parse(session->CaseJson());
    std::string section = "engine", key = "speed_rpm";
    if (c.contains("spring"))
      for (const auto& [k, v] : c["spring"].items())
        if (k.rfind("preload_", 0) == 0) section = "spring", key = k;
    const double base = c[section][key].get<double>();
    std::vector<double> ms;
    for (int i = 0; i < repeats; ++i) {
      nlohmann::json change;
      change[section][key] = base * (1.0 + 0.002 * (i + 1));  // a slider's small move
      const std::string body = change.dump();
      const auto t0 = std::chrono::steady_clock::now();
      const auto r = client.Post("/api/design", body, "application/json");
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      if (!r || r->status != 200) {
        ms.back() = NAN;
        break;
      }
    }
    StopServing();
    server.join();
    ms.erase(std::remove_if(ms.begin(), ms.end(), [](double x) { return !std::isfinite(x); }),
             ms.end());
    if (ms.empty()) {
      md << "| " << file.filename().string() << " | refused | | missed |\n";
      ++cases;
      continue;
    }
    std::sort(ms.begin(), ms.end());
    const double median = ms[ms.size() / 2], slowest = ms.back();
    ++cases;
    met += median <= 100.0;
    md << "| " << file.filename().string() << " | " << Num(median) << " ms | " << Num(slowest)
       << " ms | " << (median <= 100.0 ? "met" : "missed by " + Num(median - 100.0) + " ms")
       << " |\n";
  }
  md << "\n" << met << " of " << cases << " cases within 100 ms.\n\n";
  return md.str();
}

}  // namespace needle::bench
