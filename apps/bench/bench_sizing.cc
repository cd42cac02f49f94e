// needle-bench size: `needle size` on one core, each stage's time and the springs it kept.
#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/bench/bench_common.h"
#include "apps/case/case_file.h"
#include "apps/study/spring_sizing_scene.h"
#include "lib/input_file.h"

namespace needle::bench {

// `needle size` (issue 35) on one core: the whole sizing, each stage's time and the springs it
// kept, medians over the repeats; target ≤ 1 s including the dynamic verification.
std::string RunSizing(int repeats) {
  std::ostringstream md;
  md << "## needle size (one thread, medians)\n\n| case | candidates | evaluated | passed | kept "
        "| checked | closed form | check | whole | target ≤ 1 s |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  const std::string ex2 = ReadInputFile(CaseDir() + "basu-example2.toml", "case file");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"basu-example2, [sizing] max_outer_diameter_mm = 52",
       ex2 + "\n[sizing]\nmax_outer_diameter_mm = 52\n"},
      {"basu-example2 in its own space (no fit)", ex2},
      {"basu-example1", ReadInputFile(CaseDir() + "basu-example1.toml", "case file")}};
  for (const auto& [name, text] : cases) {
    const Case c = ParseCase(text, name);
    SizeOptions o;
    o.threads = 1;
    std::vector<double> whole, closed, check;
    SizeResult r;
    for (int i = 0; i < repeats; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const BoundCase b = Bind(c);  // the lift law built, as each `needle size` does
      r = SizeCase(b, *b.lift.law, o);
      whole.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      closed.push_back(r.stages[0].seconds * 1e3);
      check.push_back(r.stages.size() > 1 ? r.stages[1].seconds * 1e3 : 0.0);
    }
    const auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    const double w = median(whole);
    md << "| " << name << " | " << r.closed_form.candidates << " | " << r.closed_form.evaluated
       << " | " << r.closed_form.passed << " | " << r.closed_form.best.size() << " | "
       << r.verified.size() << (r.winner ? " (1 passed)" : "") << " | " << Num(median(closed))
       << " ms | " << Num(median(check)) << " ms | " << Num(w) << " ms | "
       << (w <= 1000.0 ? "met" : "missed by " + Num(w - 1000.0) + " ms") << " |\n";
  }
  md << '\n';
  return md.str();
}

}  // namespace needle::bench
