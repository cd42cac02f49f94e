#pragma once
/// @file
/// `needle compare A.toml B.toml [--out DIR] [--rpm N] [--json]`: two designs side by side.
/// Both are checked as `needle check` checks them (apps/study/check_scene.h); every quantity and
/// verdict `check --json` reports is shown for both, with the difference B − A, every verdict
/// that flips named, and one report DIR/compare-A-B.html with the lift, velocity and
/// acceleration of both overlaid, and their quasi-static and dynamic contact forces. Exit 1
/// when a verdict flips, 0 when none does, 2 on bad input.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

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

/// One reported item of both designs: a number (`a`, `b` and B − A), a pass/fail verdict (a
/// bool, the overall verdict, a limits row's verdict) or a text (a status, the spline kind).
/// Keys are the `check --json` paths ("spring.preload_margin"); a limits row's are
/// "limits.KEY.verdict", "limits.KEY.value" and "limits.KEY.margin".
struct ComparedItem {
  std::string key;
  nlohmann::json a, b;   ///< null where a design does not report the item (or does not judge it)
  bool verdict = false;  ///< not a number: a verdict or a text, shown in the verdict table
  /// Both sides are pass/fail (a bool, "pass" or "fail") and they differ: counts for exit 1.
  bool flips = false;
  /// A verdict or text that differs without flipping (a spline kind, a status, "pass" against
  /// "not judged" or absent): listed, not counted.
  bool differs = false;
};

/// Every number, bool, verdict and status of two `check --json` objects, in A's order then B's
/// extras.
std::vector<ComparedItem> CompareChecks(const nlohmann::json& a, const nlohmann::json& b);

}  // namespace needle
