#pragma once
/// @file
/// The writers of `needle check`'s result: the JSON object (CheckJson, also compare's and the
/// Python module's), and the HTML report with its gnuplot figures (CheckReport). Writers only:
/// everything they show was computed by CheckScene (apps/study/check_scene.h).

#include <nlohmann/json.hpp>
#include <string>

#include "apps/case/case_file.h"
#include "apps/report/html_report.h"
#include "apps/study/check_scene.h"

namespace needle {

/// What `check --json` prints for case `c` (lift law `law`) and its result; `report_path` is the
/// report the run wrote.
nlohmann::json CheckJson(const Case& c, const LiftLaw& law, const CheckResult& result,
                         const std::string& report_path);

/// What `check` prints without --json: the verdicts, n_qs and n_dyn, the limits table, what
/// warns and fails, the report written (`report_path`, with its `figures`) and the overall
/// verdict.
std::string CheckText(const Case& c, const CheckResult& result, const std::string& report_path,
                      int figures);

/// The check's HTML report: the scene, the kinematics, the spring, the dynamics, the sweep, the
/// limits table and the figures (given to `gnuplot`, when given, as they are made). Throws
/// std::runtime_error naming gnuplot's failure.
Report CheckReport(const Case& c, const LiftLaw& law, const CheckResult& result,
                   Gnuplot* gnuplot = nullptr);

}  // namespace needle
