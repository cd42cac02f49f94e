#pragma once
/// @file
/// What needle-bench's parts share (internal to apps/bench): the bundled cases' folder, the
/// three bench scenes, the methods measured, a median timer, number formatting, and the parts.
#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "apps/case/bound_case.h"
#include "dynamics/overspeed.h"
#include "dynamics/solver/integrator.h"

namespace needle::bench {

/// The bundled cases' folder, with its final '/'.
std::string CaseDir();

/// Bundled case `file` ("basu-example2.toml"), loaded and bound.
BoundCase BindBundled(const std::string& file);

/// The overspeed search of bound case `c` from `from_rpm` to `to_rpm` on `threads` threads,
/// its runs as the case asks (c.run).
OverspeedOptions SearchOptions(const BoundCase& c, double from_rpm, double to_rpm, int threads = 1);

/// A bench scene: its name, case file and speed.
struct BenchScene {
  std::string name, file, note;
  double rpm;
};

/// The three bench scenes (soft, stiff, liftoff).
const std::vector<BenchScene>& Scenes();
/// Every method of the work-precision study.
const std::vector<Method>& Methods();
/// The method of the method table named `name` (the bench's reference and peer runs).
Method Named(const std::string& name);

/// The median run time of `f` over `repeats` runs, s.
template <typename F>
double MedianSeconds(F&& f, int repeats) {
  std::vector<double> s;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(s.begin(), s.end());
  return s[s.size() / 2];
}

/// A number to `digits` significant digits ("–" when not finite).
std::string Num(double v, int digits = 3);

/// Baseline/event RHS ratios at a lift error of 0.1 µm, per scene, for the targets table (set
/// by RunDynamics).
std::vector<std::pair<std::string, double>>& EventRatios();

// The parts: each returns its Markdown section.
std::string RunDynamics(const std::string& out_dir, int repeats, bool quick);
std::string RunExactComparison(int repeats);
std::string RunKinematics(const std::string& out_dir, int repeats);
std::string RunTargets(int repeats);
std::string RunOverspeedComparison(int repeats);
std::string RunSizing(int repeats);
/// needle serve: a change to its reply over loopback, per bundled case.
std::string RunServe(int repeats);
/// needle fit: a calibration's cost on docs/fit.md's bench traces.
std::string RunFit(int repeats);

}  // namespace needle::bench
