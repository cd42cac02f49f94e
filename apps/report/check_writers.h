#pragma once
/// @file
/// The writers of `needle check`'s result: the JSON object (CheckJson, also compare's and the
/// Python module's), and the HTML report with its gnuplot figures (CheckReport). Writers only:
/// everything they show was computed by CheckScene (apps/study/check_scene.h).

#include <nlohmann/json.hpp>
#include <string>

#include "apps/case/bound_case.h"
#include "apps/report/html_report.h"
#include "apps/study/check_scene.h"
#include "lib/kinematics.h"

namespace needle {

/// What `check --json` prints for case `c` (lift law `law`) and its result; `report_path` is the
/// report the run wrote.
nlohmann::json CheckJson(const BoundCase& c, const LiftLaw& law, const CheckResult& result,
                         const std::string& report_path);

/// What `check` prints without --json: the verdicts, n_qs and n_dyn, the limits table, what
/// warns and fails, the report written (`report_path`, with its `figures`) and the overall
/// verdict.
std::string CheckText(const BoundCase& c, const CheckResult& result, const std::string& report_path,
                      int figures);

/// The check's HTML report: the scene, the kinematics, the spring, the dynamics, the sweep, the
/// limits table and the figures (given to `gnuplot`, when given, as they are made). Throws
/// std::runtime_error naming gnuplot's failure.
Report CheckReport(const BoundCase& c, const LiftLaw& law, const CheckResult& result,
                   Gnuplot* gnuplot = nullptr);

/// The same report made as the check runs, so that its gnuplot draws each figure beside the rest
/// of the check as soon as what it shows is known: the kinematics when made, the rated-speed
/// run's force and motion when that run ends (RatedRun, from CheckOptions::rated_run_done), the
/// rest with the result (Finish). The document is CheckReport's to the byte.
class CheckReportWriter {
 public:
  /// `c` and `law` outlive this writer; `choice` and `rpm` are the check's (its result's).
  CheckReportWriter(const BoundCase& c, const LiftLaw& law, const LiftLawChoice& choice, double rpm,
                    Gnuplot* gnuplot = nullptr);
  /// The rated-speed run and the spring check it ran on (at most once; Finish gives them from
  /// the result when this was not called).
  void RatedRun(const SpringCheckResult& spring, const SimulationResult& run,
                const SimulationOptions& options);
  /// The whole report of `result`, the check whose rated run was given (once).
  Report Finish(const CheckResult& result);

 private:
  static constexpr size_t kNone = static_cast<size_t>(-1);
  const BoundCase& c_;
  const LiftLaw& law_;
  LiftLawChoice choice_;
  double rpm_;
  Kinematics kin_;
  Report report_;
  size_t top_ = kNone, spring_ = kNone, surge_ = kNone;  // places filled by Finish
  bool rated_ = false;
};

}  // namespace needle
