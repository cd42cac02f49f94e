#pragma once
/// @file
/// `needle compare A.toml B.toml [--out DIR] [--rpm N] [--json]`: two designs side by side.
/// Both are checked as `needle check` checks them (apps/scene/check_scene.h); every quantity and
/// verdict `check --json` reports is shown for both, with the difference B − A, every verdict
/// that flips named, and one report DIR/compare-A-B.html with the lift, velocity and
/// acceleration of both overlaid, and their quasi-static and dynamic contact forces. Exit 1
/// when a verdict flips, 0 when none does, 2 on bad input.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace needle {

struct CompareCommandOptions {
  std::string a_path, b_path;       ///< the design and the one it is set against
  std::string out_dir = ".";        ///< where the report goes (made when missing)
  std::optional<double> speed_rpm;  ///< rated speed for both; default each case's own
  bool json = false;                ///< one JSON object instead of the text
};

CLI::App* AddCompareCommand(CLI::App& app, CompareCommandOptions& options);
int RunCompareCommand(const CompareCommandOptions& options);

/// One reported item of both designs: a number (`a`, `b` and B − A) or a verdict (a bool, a
/// status or the overall verdict). Keys are the `check --json` paths ("spring.preload_margin").
struct ComparedItem {
  std::string key;
  nlohmann::json a, b;  ///< null where a design does not report the item
  bool verdict = false;
  /// Verdicts: the two differ. Numbers: unused.
  bool flips = false;
};

/// Every number, bool and status of two `check --json` objects, in A's order then B's extras.
std::vector<ComparedItem> CompareChecks(const nlohmann::json& a, const nlohmann::json& b);

}  // namespace needle
