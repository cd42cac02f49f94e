// needle-bench: run time against error, and the performance targets (issue 5).
//
//   needle-bench dynamics   --out DIR   work-precision of every integrator on three scenes
//   needle-bench kinematics --out DIR   spline error against table spacing and build time
//   needle-bench targets                the four performance targets, met or missed by how much
//   needle-bench size                   needle size: each stage's time and springs kept
//   needle-bench fit                    needle fit: a calibration's cost on the bench traces
//   needle-bench all        --out DIR   all of them, and DIR/summary.md
//
// Times are medians over repeated runs on one core (the overspeed speed-up uses two).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "apps/bench/bench_common.h"
#include "lib/output.h"

int main(int argc, char** argv) {
  CLI::App app{"needle-bench: run time against error for needle's integrators and splines"};
  app.require_subcommand(1);
  std::string out = "bench";
  int repeats = 5;
  bool quick = false;
  auto* dyn = app.add_subcommand("dynamics", "work-precision of every integrator on three scenes");
  auto* kin =
      app.add_subcommand("kinematics", "spline error against spacing, build and table time");
  auto* tgt = app.add_subcommand("targets", "the performance targets");
  auto* ovs = app.add_subcommand(
      "overspeed", "the overspeed search, check and a tolerance sample: before and after");
  auto* siz = app.add_subcommand("size", "needle size: each stage's time and springs kept");
  auto* exa = app.add_subcommand("exact", "method exact against dopri5 at rtol 1e-8, per scene");
  auto* srv = app.add_subcommand("serve", "needle serve: a change to its reply, per bundled case");
  auto* fit = app.add_subcommand("fit", "needle fit: a calibration's cost on the bench traces");
  auto* all = app.add_subcommand("all", "everything, and OUT/summary.md");
  for (auto* c : {dyn, kin, tgt, ovs, siz, exa, srv, fit, all}) {
    c->add_option("--out", out, "output folder (default bench)");
    c->add_option("--repeats", repeats, "timed repeats per configuration (median)")
        ->check(CLI::PositiveNumber);
    c->add_flag("--quick", quick, "tolerances 1e-3, 1e-6, 1e-9, 1e-12 only");
  }
  CLI11_PARSE(app, argc, argv);
  try {
    std::filesystem::create_directories(out);
    std::string md;
    if (dyn->parsed() || all->parsed()) md += needle::bench::RunDynamics(out, repeats, quick);
    if (kin->parsed() || all->parsed()) md += needle::bench::RunKinematics(out, repeats);
    if (tgt->parsed() || all->parsed()) md += needle::bench::RunTargets(repeats);
    if (ovs->parsed() || all->parsed()) md += needle::bench::RunOverspeedComparison(repeats);
    if (siz->parsed() || all->parsed()) md += needle::bench::RunSizing(repeats);
    if (exa->parsed() || all->parsed()) md += needle::bench::RunExactComparison(repeats);
    if (srv->parsed() || all->parsed()) md += needle::bench::RunServe(repeats);
    if (fit->parsed() || all->parsed()) md += needle::bench::RunFit(repeats);
    needle::WriteFileAtomically(out + "/summary.md", md);
    std::cout << md;
  } catch (const std::exception& e) {
    std::cerr << "needle-bench: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
