// The check's JSON object (check_writers.h).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli/check_writers.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/output_paths.h"
#include "apps/cli/progress_bar.h"
#include "apps/cli/report.h"
#include "apps/cli/result_writers.h"
#include "apps/scene/case_file.h"
#include "apps/scene/case_profile.h"
#include "apps/scene/case_scene.h"
#include "apps/scene/check_scene.h"
#include "dynamics/overspeed.h"
#include "dynamics/simulation.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/spring_check.h"

namespace needle {

nlohmann::json CheckJson(const Case& c, const LiftLaw& law, const CheckResult& result,
                         const std::string& report_path) {
  const std::optional<SpringCheckResult>& spring = result.spring;
  const std::optional<SimulationResult>& run = result.run;
  const std::optional<OverspeedResult>& sweep = result.sweep;
  const std::optional<CamProfile>& profile = result.profile;
  const LiftLawChoice& choice = result.choice;
  nlohmann::json j;
  j["case"] = c.path;
  j["speed_rpm"] = result.speed_rpm;
  j["overall"] = result.pass ? "pass" : "fail";
  j["failing"] = result.failing;
  j["warnings"] = result.warnings;
  j["skipped"] = result.skipped;
  j["report"] = report_path;
  for (const FieldGroup& group : CheckFields(result)) PutFields(j[group.name], group.fields);
  j["kinematics"]["spline"] = SplineKindName(law.kind());
  j["kinematics"]["spline_reason"] = choice.reason;
  if (spring) {
    nlohmann::json& s = j["spring"];
    s["pass"] = spring->pass;
    s["preload_ok"] = spring->preload_ok;
    s["combustion_ok"] = spring->combustion_ok;
    s["basu_ok"] = spring->basu_ok;
    s["failures"] = spring->failures;
  }
  if (run) {
    nlohmann::json& d = j["dynamics"];
    d["liftoff"] = run->liftoff();
    d["status"] = RunStatusName(run->status);
    d["status_reason"] = run->status_reason;
    d["episodes"] = run->episodes.size();
    d["impacts"] = run->impacts.size();
  }
  if (sweep) j["overspeed"]["status"] = sweep->status;
  j["limits"] = nlohmann::json::array();
  for (const LimitRow& x : result.limits) {
    nlohmann::json row = {{"name", x.key},        {"unit", x.unit}, {"at_most", x.at_most},
                          {"verdict", x.verdict}, {"note", x.note}, {"source", x.source}};
    // NaN (not judged) is null in JSON.
    for (auto [k, v] : {std::pair<const char*, double>{"value", x.value},
                        {"limit", x.limit},
                        {"margin", x.margin}}) {
      row[k] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    }
    j["limits"].push_back(row);
  }
  if (result.harmonics) {
    j["resonance"]["surge_modes_Hz"] = result.surge_modes_hz;
    j["resonance"]["highest_significant_order"] = result.harmonics->highest_significant_order;
  }
  if (profile) j["profile"]["undercut"] = profile->undercut;
  return j;
}

}  // namespace needle
