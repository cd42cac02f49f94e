// The check's JSON object (check_writers.h).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/bound_case.h"
#include "apps/case/case_profile.h"
#include "apps/report/check_writers.h"
#include "apps/report/html_report.h"
#include "apps/report/output_paths.h"
#include "apps/report/result_writers.h"
#include "apps/study/check_scene.h"
#include "dynamics/overspeed.h"
#include "dynamics/simulation.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/spring_check.h"

namespace needle {

nlohmann::json CheckJson(const BoundCase& c, const LiftLaw& law, const CheckResult& result,
                         const std::string& report_path) {
  nlohmann::json j;
  j["case"] = c.path;
  j["speed_rpm"] = result.speed_rpm;
  j["overall"] = result.pass ? "pass" : "fail";
  j["failing"] = result.failing;
  j["warnings"] = result.warnings;
  j["skipped"] = result.skipped;
  j["not_judged"] = result.not_judged;
  j["report"] = report_path;
  for (const FieldGroup& group : CheckFields(result)) PutFields(j[group.name], group.fields);
  j["kinematics"]["spline"] = SplineKindName(law.kind());
  if (result.spring) j["spring"]["failures"] = result.spring->failures;
  j["limits"] = RecordList(result.limits, LimitRowFields);
  if (result.harmonics) {
    j["resonance"]["surge_modes_Hz"] = result.surge_modes_hz;
    j["resonance"]["highest_significant_order"] = result.harmonics->highest_significant_order;
  }
  return j;
}

}  // namespace needle
