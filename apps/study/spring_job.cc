#include "apps/study/spring_job.h"

#include <stdexcept>

#include "apps/case/plausible_ranges.h"

namespace needle {

CaseSpringCheck CheckCaseSpring(const BoundCase& c, const std::optional<double>& speed_rpm) {
  RequireSpeed(speed_rpm);
  const double speed = speed_rpm.value_or(c.engine.speed_rpm);
  const LiftLaw& law = *c.lift.law;
  return CaseSpringCheck{c, speed, law.kind(), CheckSpring(c, law, speed)};
}

DesignResult DesignFromEngine(const DesignInputs& in) {
  try {
    return RunDesignChain(in);
  } catch (const std::invalid_argument& e) {
    throw CaseError(in.path + ": [design]: " + e.what());
  }
}

}  // namespace needle
