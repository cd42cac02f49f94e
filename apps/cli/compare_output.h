#pragma once
/// @file
/// `needle compare` as a job and its writers: CompareCases checks both designs as `check` does
/// and sets their `check --json` objects side by side (CompareChecks); CompareJson, CompareText
/// and CompareReport write the comparison. Internal to the command line and the Python module.

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/cli/compare_command.h"
#include "apps/report/html_report.h"
#include "apps/study/check_scene.h"

namespace needle {

/// One design checked: the case, its lift law, the check and its `check --json` object.
struct CheckedDesign {
  Case c;
  std::shared_ptr<const LiftLaw> law;
  CheckResult result;
  nlohmann::json json;
};

/// Two designs checked and set side by side.
struct Comparison {
  CheckedDesign a, b;
  std::vector<ComparedItem> items;     ///< every number, verdict and text of both
  std::vector<std::string> flipped;    ///< the keys of the verdicts that flip
  std::vector<std::string> differing;  ///< the keys of the verdicts and texts that only differ
  std::vector<std::string> unlike;     ///< why the two are not like for like (empty: they are)
  int status() const { return flipped.empty() ? 0 : 1; }  ///< exit 1 when a verdict flips
};

/// Checks both cases as `check` does (at `speed_rpm` when given, else each case's own) and
/// compares them; `report_path` is written into each check's JSON object. `progress` gets the
/// runs done of both sweeps.
Comparison CompareCases(Case a, Case b, std::optional<double> speed_rpm,
                        const std::string& report_path,
                        const std::function<void(int, int)>& progress = {});

/// What `compare --json` prints.
nlohmann::json CompareJson(const Comparison& cmp, const std::string& report_path);
/// What `compare` prints.
std::string CompareText(const Comparison& cmp, const std::string& report_path);
/// The HTML report: verdicts, quantities, failing items, both designs' curves overlaid.
Report CompareReport(const Comparison& cmp);

}  // namespace needle
