#pragma once
/// @file
/// `needle check CASE [--out DIR] [--rpm N]`: the main job. Runs what the scene needs
/// (kinematics always; the spring check with [needle] and [spring]; the dynamics and the
/// overspeed sweep with [train]), says what it skipped and why, and writes DIR/<case>.html:
/// a self-contained report with figures drawn by gnuplot. Exit 1 when a check fails (the
/// spring, or lift-off at or below the overspeed f·n), 2 on bad input.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace needle {

struct CheckCommandOptions {
  std::string case_path;
  std::string out_dir = ".";
  std::optional<double> speed_rpm;
};

CLI::App* AddCheckCommand(CLI::App& app, CheckCommandOptions& options);
int RunCheckCommand(const CheckCommandOptions& options);

}  // namespace needle
