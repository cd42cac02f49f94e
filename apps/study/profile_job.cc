#include "apps/study/profile_job.h"

#include "apps/case/case_profile.h"
#include "lib/engine_cycle.h"
#include "lib/units.h"

namespace needle {

CaseCamProfile ProfileOfCase(const BoundCase& c) {
  if (!c.profile)
    throw CaseError(c.path + ": [profile] base_radius_mm: section [profile] is missing");
  const LiftLaw& law = *c.lift.law;
  double theta0 = 0.0;
  CamProfile p = MakeCaseProfile(c, law, &theta0);
  // The cam's speed at the rated engine speed (four-stroke: half the crank's).
  const double cam_omega = OmegaFromRpm(c.engine.speed_rpm) / CrankTurnsPerCycle(c.engine.cycle);
  return CaseCamProfile{c,      CaseFollower(c), c.train ? c.train->play_m : 0.0,
                        theta0, cam_omega,       std::move(p)};
}

}  // namespace needle
