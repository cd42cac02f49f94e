#pragma once
/// @file
/// `needle check CASE [--out DIR] [--rpm N] [--json]`: the main job. Runs what the scene needs
/// (kinematics always; the spring check with [needle] and [spring]; the dynamics and the
/// overspeed sweep with [train]), says what it skipped and why, and writes DIR/<case>.html:
/// a self-contained report with figures drawn by gnuplot (DIR is made when missing). Exit 1
/// when a check fails (the spring, lift-off at the rated speed or at or below the overspeed
/// f·n, an undercut profile, a run that ended undecided), 2 on bad input.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "apps/report/check_writers.h"  // CheckJson, for the callers of the command
#include "apps/report/output_format.h"
#include "apps/study/check_scene.h"

namespace needle {

struct CheckCommandOptions {
  std::string case_path;
  std::string out_dir = ".";
  std::optional<double> speed_rpm;
  bool json = false;  ///< one JSON object on stdout instead of the text summary
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
};

CLI::App* AddCheckCommand(CLI::App& app, CheckCommandOptions& options);
int RunCheckCommand(const CheckCommandOptions& options);

}  // namespace needle
