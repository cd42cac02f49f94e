#pragma once
/// @file
/// The writers of the tolerance study (apps/study/tolerance_study.h): its JSON object, its text
/// and its HTML report with the histograms.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "apps/case/bound_case.h"
#include "apps/report/html_report.h"
#include "apps/study/tolerance_study.h"

namespace needle {

/// What `tolerance --json` prints for a study of case `c` (without the report's path).
nlohmann::json ToleranceJson(const BoundCase& c, const ToleranceResult& result);
/// The study's HTML report: the scatter, the failure probability and its drivers, the
/// distributions and a histogram of each headline quantity.
Report ToleranceReport(const BoundCase& c, const ToleranceResult& result, std::uint64_t seed);
/// What `tolerance` prints without --json.
std::string ToleranceText(const BoundCase& c, const ToleranceResult& result, std::uint64_t seed,
                          const std::optional<std::string>& report_path);

}  // namespace needle
