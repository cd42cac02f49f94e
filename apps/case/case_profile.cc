#include "apps/case/case_profile.h"

#include <cmath>
#include <memory>
#include <stdexcept>

#include "dynamics/model/cam_input.h"
#include "lib/engine_cycle.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

FollowerGeometry CaseFollower(const BoundCase& c) {
  if (!c.profile)
    throw CaseError(c.path + ": [profile] base_radius_mm: section [profile] is missing");
  return c.profile->follower;
}

double CrankOfCam(const BoundCase& c, double cam_zero_crank_rad, double cam_rad) {
  const double k = CrankTurnsPerCycle(c.engine.cycle), cycle_rad = 2 * kPi * k;
  const double from_zero = k * cam_rad - cycle_rad * std::floor(k * cam_rad / cycle_rad);
  return cam_zero_crank_rad + from_zero - (from_zero >= cycle_rad / 2 ? cycle_rad : 0.0);
}

std::string CamAndCrank(const BoundCase& c, double cam_zero_crank_rad, double cam_rad, int decimals,
                        const std::string& degree) {
  return "cam " + Fixed(cam_rad / kDeg, decimals) + degree + " (crank " +
         Fixed(CrankOfCam(c, cam_zero_crank_rad, cam_rad) / kDeg, decimals) + degree + ")";
}

CamProfile MakeCaseProfile(const BoundCase& c, const LiftLaw& law, double* cam_zero_crank_rad) {
  const FollowerGeometry g = CaseFollower(c);
  const double play = c.train ? c.train->play_m : 0.0;
  std::unique_ptr<CamInput> cam;
  try {
    cam = std::make_unique<CamInput>(
        law, play, c.train && c.train->linear_ramp ? RampKind::kLinear : RampKind::kTangent,
        c.train ? c.train->ramp_rad : 0.0);
  } catch (const std::invalid_argument& e) {
    throw CaseError(c.path + ": [train] ramp: " + e.what());
  }
  // Cam angle ψ = 0 at the start of the rise; four-stroke: θ = θ_start + 2ψ.
  const double k = CrankTurnsPerCycle(c.engine.cycle);
  const double theta0 = cam->rise_start_rad();
  if (cam_zero_crank_rad) *cam_zero_crank_rad = theta0;
  const Displacement disp = [&](double psi) {
    const double th = theta0 + k * psi;
    return std::array<double, 3>{cam->U(th) + play, k * cam->Slope(th), k * k * cam->Curvature(th)};
  };
  return MakeCamProfile(disp, g, c.profile->points);
}

}  // namespace needle
