#include "apps/cli/fit_command.h"

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/case/measured_trace.h"
#include "apps/case/plausible_ranges.h"
#include "apps/cli/cli_checks.h"
#include "apps/report/command_output.h"
#include "apps/report/fit_writer.h"
#include "apps/report/html_report.h"
#include "apps/report/output_paths.h"
#include "apps/serve/design_api.h"
#include "apps/study/fit_job.h"
#include "lib/case_error.h"
#include "lib/input_file.h"

namespace needle {

CLI::App* AddFitCommand(CLI::App& app, FitCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("fit", kFitCommandSummary);
  cmd->add_option("CASE", o.case_path, "case file (TOML)")->required();
  cmd->add_option("--trace", o.traces,
                  "measured trace, CSV of crank_deg and lift_mm (or lift_um), optional time_s; "
                  "once per trace")
      ->required();
  cmd->add_option("--rpm", o.speeds_rpm, "the speed of each --trace, rpm, in the same order")
      ->required();
  cmd->add_option("--free", o.free, "the keys to fit, comma-separated: " + FitKeyList())
      ->required()
      ->delimiter(',');
  cmd->add_option("--bounds", o.bounds,
                  "KEY=LOW:HIGH in the key's unit (default: the plausible ranges)");
  cmd->add_option("--starts", o.starts, "starts of the local search (default 12)")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--seed", o.seed, "seed of the starts and of n_dyn's draws (default 1)")
      ->transform(Seed());
  cmd->add_flag("--no-liftoff", o.no_liftoff, "skip n_dyn's prediction");
  cmd->add_option("--case", o.case_out, "write the calibrated case (TOML) here");
  cmd->add_option("--out", o.out_dir, "write the report (measured against fitted) to this folder");
  cmd->add_flag("--json", o.json, "print one JSON object");
  return cmd;
}

int RunFitCommand(const FitCommandOptions& o) {
  if (o.traces.size() != o.speeds_rpm.size()) {
    throw CaseError("--rpm: " + std::to_string(o.speeds_rpm.size()) + " speed(s) for " +
                    std::to_string(o.traces.size()) + " --trace(s); give one --rpm per --trace");
  }
  for (double n : o.speeds_rpm) RequireSpeed(n, "--rpm");
  const Case loaded = LoadCase(o.case_path);
  FitOptions options;
  for (const std::string& k : o.free) options.free.push_back(ParseFitKey(k));
  for (const std::string& b : o.bounds) options.bounds.push_back(ParseFitBound(b));
  options.starts = o.starts;
  options.seed = o.seed;
  options.predict_liftoff = !o.no_liftoff;
  std::vector<OutputPath> outputs;
  std::optional<std::string> report_path;
  if (o.out_dir) {
    report_path = ReportPath(*o.out_dir,
                             "fit-" + std::filesystem::path(loaded.path).stem().string() + ".html");
    outputs.push_back({"--out", *report_path});
  }
  if (o.case_out) outputs.push_back({"--case", *o.case_out});
  std::vector<std::string> inputs = CaseInputs(loaded);
  inputs.insert(inputs.end(), o.traces.begin(), o.traces.end());
  CheckOutputPaths(outputs, inputs);
  const BoundCase c = Bind(loaded);
  std::vector<MeasuredTrace> traces;
  for (size_t i = 0; i < o.traces.size(); ++i) {
    traces.push_back(ReadMeasuredTrace(o.traces[i], o.speeds_rpm[i], c));
  }
  const FitResult r = FitCase(c, traces, options);
  if (o.case_out) {
    nlohmann::json overrides = nlohmann::json::object();
    for (const auto& [section, kv] : FittedOverrides(r)) overrides[section][kv.first] = kv.second;
    // A lift table read from a CSV beside the case: named from where the calibrated case goes.
    if (!c.lift.csv_path.empty()) {
      namespace fs = std::filesystem;
      const fs::path csv = fs::absolute(c.lift.csv_path);
      const fs::path folder = fs::absolute(*o.case_out).parent_path();
      if (folder != fs::absolute(o.case_path).parent_path()) {
        overrides["lift"]["csv"] = csv.lexically_relative(folder).string();
      }
    }
    WriteOutput({"--case", *o.case_out}, CaseWithOverrides(ReadInputFile(o.case_path, "case"),
                                                           overrides, o.case_path, true));
  }
  if (report_path) WriteOutput({"--out", *report_path}, FitReport(c, r).Html());
  if (o.json) {
    nlohmann::json j = FitJson(c, r);
    if (report_path) j["report"] = *report_path;
    if (o.case_out) j["calibrated_case"] = *o.case_out;
    std::cout << FormatObject(j, o.format);
    return 0;
  }
  PrintText(FitText(c, r, report_path, o.case_out));
  return 0;
}

}  // namespace needle
