#pragma once
/// @file
/// `needle simulate CASE [--rpm N] [--method KIND] [--rtol X] [--cycles N] [--dynamic] [--json]
/// [--csv FILE]`
/// and `needle overspeed CASE [--from RPM] [--to RPM] [--threads N] [--json]`.

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>

#include "apps/case/case_file.h"
#include "apps/report/command_output.h"
#include "apps/report/output_format.h"
#include "dynamics/solver/contact_events.h"

namespace needle {

struct SimulateCommandOptions {
  std::string case_path;
  std::optional<double> speed_rpm;
  std::optional<std::string> method;
  std::optional<double> rtol;
  bool dynamic = false;  ///< run the dynamics even where the rigid answer would stand
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
  std::optional<std::string> csv;
  bool series = false;        ///< record the time series as columns without a CSV (Python)
  std::optional<int> cycles;  ///< cam revolutions back to back (default: [solver] cycles)
};

CLI::App* AddSimulateCommand(CLI::App& app, SimulateCommandOptions& options);
/// The run of a loaded case: its time series as columns when `series`, and each point to
/// `series_sink` (when given) as the run makes it (streamed: the --csv rows, SeriesColumns()).
/// With `csv` set, a run whose dynamics is skipped is refused. Throws CaseError on bad input.
CommandOutput ComputeSimulate(const Case& c, const SimulateCommandOptions& options,
                              const std::function<void(const SeriesPoint&)>& series_sink = {});
/// Exit 1 when the needle lifts off (a jump episode) at the speed simulated.
int RunSimulateCommand(const SimulateCommandOptions& options);

struct OverspeedCommandOptions {
  std::string case_path;
  std::optional<double> from_rpm, to_rpm;
  std::optional<std::string> method;
  std::optional<double> rtol;
  int threads = 0;
  std::optional<double> step_rpm;  ///< scan step Δn (default 2.5 % of --from, at least 1 rpm)
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
};

CLI::App* AddOverspeedCommand(CLI::App& app, OverspeedCommandOptions& options);
/// The sweep of a loaded case; `progress` (may be empty) hears of every run done.
CommandOutput ComputeOverspeed(const Case& c, const OverspeedCommandOptions& options,
                               const std::function<void(int, int)>& progress = {});
/// Exit 1 when the needle lifts off at or below the case's rated speed.
int RunOverspeedCommand(const OverspeedCommandOptions& options);

}  // namespace needle
