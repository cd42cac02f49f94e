#include "apps/bench/bench_common.h"

#include <cmath>
#include <sstream>

#include "apps/case/case_file.h"

namespace needle::bench {

std::string CaseDir() { return std::string(NEEDLE_SOURCE_DIR) + "/cases/"; }

BoundCase BindBundled(const std::string& file) { return Bind(LoadCase(CaseDir() + file)); }

OverspeedOptions SearchOptions(const BoundCase& c, double from_rpm, double to_rpm, int threads) {
  OverspeedOptions o;
  o.from_rpm = from_rpm;
  o.to_rpm = to_rpm;
  o.threads = threads;
  o.simulation = c.run;
  return o;
}

const std::vector<BenchScene>& Scenes() {
  static const std::vector<BenchScene> scenes = {
      {"soft", "basu-cam4-light-spring.toml",
       "light train, no play, 52 contact oscillations per event", 400},
      {"stiff", "basu-cam4-stiff-train.toml", "stiff train, 942 contact oscillations per event",
       400},
      {"liftoff", "basu-example2.toml",
       "0.5 mm play on 10-degree ramps at 1500 rpm: lash impact and lift-off", 1500},
  };
  return scenes;
}

const std::vector<Method>& Methods() { return AllMethods(); }

Method Named(const std::string& name) {
  const std::optional<Method> m = ParseMethod(name);
  if (!m) throw std::logic_error("bench: no method \"" + name + "\" in the method table");
  return *m;
}

std::string Num(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

std::vector<std::pair<std::string, double>>& EventRatios() {
  static std::vector<std::pair<std::string, double>> ratios;
  return ratios;
}

}  // namespace needle::bench
