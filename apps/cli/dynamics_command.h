#pragma once
/// @file
/// `needle simulate CASE [--rpm N] [--method KIND] [--rtol X] [--cycles N] [--dynamic] [--json]
/// [--csv FILE]`
/// and `needle overspeed CASE [--from RPM] [--to RPM] [--threads N] [--json]`.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "apps/case/case_file.h"
#include "apps/report/output_format.h"
#include "apps/study/dynamics_jobs.h"

namespace needle {

struct SimulateCommandOptions {
  std::string case_path;
  SimulateJobOptions run;  ///< --rpm, --method, --rtol, --cycles, --dynamic
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
  std::optional<std::string> csv;             ///< --csv: the time series, streamed
};

CLI::App* AddSimulateCommand(CLI::App& app, SimulateCommandOptions& options);
/// Exit 1 when the needle lifts off (a jump episode) at the speed simulated.
int RunSimulateCommand(const SimulateCommandOptions& options);

struct OverspeedCommandOptions {
  std::string case_path;
  OverspeedJobOptions search;  ///< --from, --to, --method, --rtol, --threads, --step-rpm
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
};

CLI::App* AddOverspeedCommand(CLI::App& app, OverspeedCommandOptions& options);
/// Exit 1 when the needle lifts off at or below the case's rated speed.
int RunOverspeedCommand(const OverspeedCommandOptions& options);

}  // namespace needle
