#pragma once
/// @file
/// `needle compare A.toml B.toml [--out DIR] [--rpm N] [--json]`: two designs side by side.
/// Both are checked as `needle check` checks them (apps/study/check_scene.h); every quantity and
/// verdict `check --json` reports is shown for both, with the difference B − A, every verdict
/// that flips named, and one report DIR/compare-A-B.html with the lift, velocity and
/// acceleration of both overlaid, and their quasi-static and dynamic contact forces. Exit 1
/// when a verdict flips, 0 when none does, 2 on bad input.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "apps/report/output_format.h"

namespace needle {

struct CompareCommandOptions {
  std::string a_path, b_path;                 ///< the design and the one it is set against
  std::string out_dir = ".";                  ///< where the report goes (made when missing)
  std::optional<double> speed_rpm;            ///< rated speed for both; default each case's own
  bool json = false;                          ///< one JSON object instead of the text
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
};

CLI::App* AddCompareCommand(CLI::App& app, CompareCommandOptions& options);
int RunCompareCommand(const CompareCommandOptions& options);

}  // namespace needle
