#pragma once
/// @file
/// `needle kinematics CASE [--rpm N] [--step DEG] [--spline KIND] [--units paper|si]
/// [--json] [--csv FILE] [--cycle C] [--noise-mm X]`: the velocity and acceleration table of a lift
/// law, like NACA TM 477's, with the paper's published values beside it where the case has them.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "apps/case/case_file.h"
#include "apps/report/output_format.h"
#include "apps/study/kinematics_table.h"

namespace needle {

struct KinematicsCommandOptions {
  std::string case_path;              ///< the case file
  KinematicsTableOptions table;       ///< --rpm, --step
  std::optional<std::string> spline;  ///< --spline: the spline kind (default: [lift] spline)
  std::string units = "paper";        ///< "paper" (mm, dcm/s, m/s²) or "si" (m, m/s, m/s², m/s³)
  bool json = false;                  ///< print one JSON object instead of the table
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
  std::optional<std::string> csv;             ///< also write the table as CSV, atomically
  /// A bare CSV lift table as CASE: its cycle (for cam_deg columns; four-stroke when not given)
  /// and its noise σ, mm. A case file states both itself: either given with one is refused.
  std::optional<std::string> cycle;
  std::optional<double> noise_mm;
};

/// Registers the subcommand on `app`; `options` must outlive the parse.
CLI::App* AddKinematicsCommand(CLI::App& app, KinematicsCommandOptions& options);

/// Runs it, printing to stdout. Returns the exit status; throws CaseError on bad input.
int RunKinematicsCommand(const KinematicsCommandOptions& options);

}  // namespace needle
