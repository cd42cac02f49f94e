#pragma once
/// @file
/// The writers of the compare job (apps/study/compare_checks.h): the JSON object (both checks'
/// `check --json` objects, the items with B − A, the flips), the text, and the HTML report with
/// both designs' curves overlaid.

#include <nlohmann/json.hpp>
#include <string>

#include "apps/report/html_report.h"
#include "apps/study/compare_checks.h"

namespace needle {

/// What `compare --json` prints; `report_path` is the report written (in each check's object
/// too).
nlohmann::json CompareJson(const Comparison& cmp, const std::string& report_path);
/// What `compare` prints.
std::string CompareText(const Comparison& cmp, const std::string& report_path);
/// The HTML report: verdicts, quantities, failing items, both designs' curves overlaid.
Report CompareReport(const Comparison& cmp);

}  // namespace needle
