#pragma once
/// @file
/// The writers of a fit (apps/study/fit_job.h, `needle fit`): its JSON object (Markdown is that
/// object's, output_format.h), its text, and its HTML report with measured against fitted lift
/// and the residual of each trace.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "apps/case/bound_case.h"
#include "apps/report/html_report.h"
#include "apps/study/fit_job.h"

namespace needle {

/// What `fit --json` prints: `parameters: {KEY: {value, low, high, start, identified, …}}`,
/// `correlations`, `unseparated`, `traces`, `model`, `liftoff_rpm_dynamic: {value, low, high}`.
nlohmann::json FitJson(const BoundCase& c, const FitResult& result);
/// The fit's HTML report: the table of values, the correlations, and per trace a figure of
/// measured against fitted lift and one of the residual against the noise.
Report FitReport(const BoundCase& c, const FitResult& result);
/// What `fit` prints without --json.
std::string FitText(const BoundCase& c, const FitResult& result,
                    const std::optional<std::string>& report_path,
                    const std::optional<std::string>& case_path);

}  // namespace needle
