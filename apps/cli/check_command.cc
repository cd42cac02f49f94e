#include "apps/cli/check_command.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/progress_bar.h"
#include "apps/report/check_writers.h"
#include "apps/report/command_output.h"
#include "apps/report/html_report.h"
#include "apps/report/output_paths.h"
#include "apps/study/check_scene.h"
#include "dynamics/overspeed.h"
#include "lib/output.h"

namespace needle {
CLI::App* AddCheckCommand(CLI::App& app, CheckCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "check", "The main job: check a scene end to end and write an HTML report");
  cmd->add_option("CASE", o.case_path, "case file (TOML)")->required();
  cmd->add_option("--out", o.out_dir, "folder for the report (default: the current folder)");
  AddSpeedOption(cmd, o.speed_rpm, "rated speed in rpm (default: [engine] speed_rpm)");
  cmd->add_flag("--json", o.json,
                "print one JSON object (the verdict, every failing item, what was skipped and the "
                "numbers behind them) instead of the text summary");
  return cmd;
}

int RunCheckCommand(const CheckCommandOptions& o) {
  const Case loaded = LoadCase(o.case_path);
  Gnuplot gnuplot;  // started now: its start-up runs beside the check
  const std::string path =
      ReportPath(o.out_dir, std::filesystem::path(loaded.path).stem().string() + ".html");
  CheckOutputPaths({{"--out", path}}, CaseInputs(loaded));
  const BoundCase c = Bind(loaded);
  CheckOptions options;
  options.speed_rpm = o.speed_rpm;
  const LiftLaw& law = *c.lift.law;
  // The report is made as the check runs: gnuplot draws each figure beside the rest of it.
  CheckReportWriter writer(c, law, c.lift.choice, o.speed_rpm.value_or(c.engine.speed_rpm),
                           &gnuplot);
  options.rated_run_done = [&writer](const SpringCheckResult& spring, const SimulationResult& run,
                                     const SimulationOptions& sim) {
    writer.RatedRun(spring, run, sim);
  };
  CheckResult result;
  {
    ProgressBar bar("overspeed", "speeds", o.json, true);
    options.progress = [&](int done, int total) { bar.Update(done, total); };
    result = CheckScene(c, options);
  }
  const Report report = writer.Finish(result);
  WriteOutput({"--out", path}, report.Html(gnuplot));
  if (o.json) {
    std::cout << FormatObject(CheckJson(c, law, result, path), o.format);
    return result.pass ? 0 : 1;
  }
  PrintText(CheckText(c, result, path, report.figures()));
  return result.pass ? 0 : 1;
}

}  // namespace needle
