#include "apps/study/spring_job.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "apps/case/plausible_ranges.h"
#include "apps/study/check_scene.h"

namespace needle {

CaseSpringCheck CheckCaseSpring(const BoundCase& c, const std::optional<double>& speed_rpm) {
  RequireSpeed(speed_rpm);
  const double speed = speed_rpm.value_or(c.engine.speed_rpm);
  const LiftLaw& law = *c.lift.law;
  CaseSpringCheck r{c, speed, law.kind(), CheckSpring(c, law, speed)};
  // A table off the seat at an end is no valve's lift from its seat: undecided, and failed.
  for (std::string& line : TableEndFailures(law, law.Max(0).value)) {
    r.check.failures.push_back(std::move(line));
    r.check.pass = false;
  }
  return r;
}

DesignResult DesignFromEngine(const DesignInputs& in) {
  try {
    return RunDesignChain(in);
  } catch (const std::invalid_argument& e) {
    throw CaseError(in.path + ": [design]: " + e.what());
  }
}

}  // namespace needle
