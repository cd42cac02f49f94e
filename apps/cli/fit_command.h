#pragma once
/// @file
/// `needle fit CASE --trace FILE --rpm N [--trace FILE --rpm N]… --free KEY[,KEY…]
/// [--bounds KEY=LOW:HIGH]… [--starts K] [--seed S] [--no-liftoff] [--json] [--case OUT]
/// [--out DIR]`: the case's unknowns fitted to measured lift traces (apps/study/fit_job.h,
/// docs/fit.md): each value with its 95 % interval, the correlations and what the traces do not
/// separate, the residual against the traces' noise, n_dyn with its interval; --case writes the
/// calibrated case (`needle check` reads it), --out the report with measured against fitted lift.
/// Exit 0; 2 on bad input (a trace refused: one line naming the file and what was expected).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "apps/report/output_format.h"

namespace needle {

struct FitCommandOptions {
  std::string case_path;
  std::vector<std::string> traces;      ///< --trace, in order
  std::vector<double> speeds_rpm;       ///< --rpm, one per trace, in the same order
  std::vector<std::string> free;        ///< --free, comma-separated keys
  std::vector<std::string> bounds;      ///< --bounds KEY=LOW:HIGH
  int starts = 12;                      ///< --starts
  uint64_t seed = 1;                    ///< --seed
  bool no_liftoff = false;              ///< --no-liftoff: skip n_dyn's prediction
  std::optional<std::string> case_out;  ///< --case: the calibrated case
  std::optional<std::string> out_dir;   ///< --out: the report's folder
  bool json = false;
  OutputFormat format = OutputFormat::kText;
};

/// The command's one-line description (`needle --help`).
inline constexpr char kFitCommandSummary[] =
    "Fit the case's unknowns to measured lift traces: values with 95 % intervals, n_dyn";

CLI::App* AddFitCommand(CLI::App& app, FitCommandOptions& options);
int RunFitCommand(const FitCommandOptions& options);

}  // namespace needle
