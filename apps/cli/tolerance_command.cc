#include "apps/cli/tolerance_command.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/progress_bar.h"
#include "apps/report/command_output.h"
#include "apps/report/html_report.h"
#include "apps/report/output_paths.h"
#include "apps/report/result_writers.h"
#include "apps/report/tolerance_writer.h"
#include "apps/study/tolerance_study.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

CLI::App* AddToleranceCommand(CLI::App& app, ToleranceCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "tolerance", "Monte-Carlo tolerance study: distributions, failure probability, drivers");
  cmd->add_option("CASE", o.case_path, "case file; its [tolerance] section gives the scatter")
      ->required();
  cmd->add_option("--samples", o.samples, "number of samples (default 1000)")
      ->transform(WholeIn(kSamplesRange, "a number of samples"));
  cmd->add_option("--seed", o.seed, "the study's seed (default 1): the same seed, the same study")
      ->transform(Seed());
  cmd->add_option("--first-sample", o.first_sample,
                  "index of the first sample (default 0): a shard of a larger study")
      ->transform(WholeIn(kFirstSampleRange, "a sample number"));
  cmd->add_option("--threads", o.threads,
                  "threads (default and 0: all cores, which is also the most)")
      ->transform(WholeIn(kThreadsRange, "a number of threads"));
  cmd->add_option("--out", o.out_dir, "write the report with the histograms to this folder");
  cmd->add_flag("--json", o.json, "print one JSON object (every sample's inputs and outputs too)");
  return cmd;
}

int RunToleranceCommand(const ToleranceCommandOptions& o) {
  const Case loaded = LoadCase(o.case_path);
  std::optional<std::string> report_path;
  std::optional<Gnuplot> gnuplot;
  if (o.out_dir) {
    gnuplot.emplace();  // started now: its start-up runs beside the study
    report_path = ReportPath(
        *o.out_dir, "tolerance-" + std::filesystem::path(loaded.path).stem().string() + ".html");
    CheckOutputPaths({{"--out", *report_path}}, CaseInputs(loaded));
  }
  const BoundCase c = Bind(loaded);
  ToleranceOptions options;
  options.samples = o.samples;
  options.seed = o.seed;
  options.first_sample = o.first_sample;
  options.threads = o.threads;
  ToleranceResult r;
  {
    ProgressBar bar("tolerance", "samples", o.json);
    if (bar.active()) options.progress = [&](int done, int total) { bar.Update(done, total); };
    r = RunToleranceStudy(c, options);
  }
  if (report_path) {
    WriteOutput({"--out", *report_path}, ToleranceReport(c, r, o.seed).Html(*gnuplot));
  }
  if (o.json) {
    nlohmann::json j = ToleranceJson(c, r);
    if (report_path) j["report"] = *report_path;
    std::cout << FormatObject(j, o.format);
    return 0;
  }
  PrintText(ToleranceText(c, r, o.seed, report_path));
  return 0;
}

}  // namespace needle
