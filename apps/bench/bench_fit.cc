// needle-bench fit: `needle fit`'s cost on docs/fit.md's bench traces (two 2,001-point traces),
// on one core: 4 unknowns with and without n_dyn's interval, and 2 unknowns on one trace.
#include <algorithm>
#include <chrono>
#include <sstream>

#include "apps/bench/bench_common.h"
#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/case/measured_trace.h"
#include "apps/study/fit_job.h"
#include "lib/output.h"

namespace needle::bench {

namespace {

struct FitTiming {
  double median_s = 0.0;
  int runs = 0;  // model runs of one fit
  double chi2 = 0.0;
};

FitTiming TimeFit(const BoundCase& b, const std::vector<MeasuredTrace>& traces, const FitOptions& o,
                  int repeats) {
  std::vector<double> seconds;
  FitTiming t;
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const FitResult r = FitCase(b, traces, o);
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    t.runs = r.model_runs;
    t.chi2 = r.chi2_reduced;
  }
  std::sort(seconds.begin(), seconds.end());
  t.median_s = seconds[seconds.size() / 2];
  return t;
}

}  // namespace

std::string RunFit(int repeats) {
  const std::string root = std::string(NEEDLE_SOURCE_DIR);
  const BoundCase b = Bind(LoadCase(root + "/cases/basu-example1.toml"));
  std::vector<MeasuredTrace> both;
  for (int rpm : {400, 700}) {
    both.push_back(
        ReadMeasuredTrace(root + "/docs/fit/trace-" + std::to_string(rpm) + "rpm.csv", rpm, b));
  }
  auto options = [](std::initializer_list<const char*> keys, bool liftoff) {
    FitOptions o;
    for (const char* k : keys) o.free.push_back(ParseFitKey(k));
    o.predict_liftoff = liftoff;
    return o;
  };
  const auto four = {"spring.preload_kgf", "needle.mass_kg", "train.contact_stiffness_N_m",
                     "train.contact_damping_ratio"};
  struct Row {
    std::string what;
    FitTiming t;
  };
  const int n = std::max(3, repeats);
  const std::vector<Row> rows = {
      {"4 unknowns, two traces (400 and 700 rpm)", TimeFit(b, both, options(four, false), n)},
      {"the same with n_dyn's interval (60 overspeed searches)",
       TimeFit(b, both, options(four, true), n)},
      {"2 unknowns (preload, contact damping), the 700 rpm trace",
       TimeFit(b, {both[1]}, options({"spring.preload_kgf", "train.contact_damping_ratio"}, false),
               n)}};
  std::ostringstream md;
  md << "## needle fit: a calibration's cost (one core, medians of " << n << ")\n\n"
     << "docs/fit.md's worked example: Basu's Example 1 fitted to its bench traces (2,001 "
        "readings each, 1,601 inside the run window), 12 starts.\n\n"
        "| fit | median | model runs | reduced χ² | target ≤ 2 s |\n|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    md << "| " << r.what << " | " << Fixed(r.t.median_s, 2) << " s | " << r.t.runs << " | "
       << Fixed(r.t.chi2, 3) << " | "
       << (r.what.rfind("4 unknowns", 0) == 0 ? (r.t.median_s <= 2.0 ? "met" : "missed") : "")
       << " |\n";
  }
  md << "\n";
  return md.str();
}

}  // namespace needle::bench
