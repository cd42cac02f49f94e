#pragma once
/// @file
/// The cam profile of a case with [profile] (lib/cam_profile.h): the needle's cam input u(θ),
/// roller play on Basu's tangent (or linear) ramps included, turned into the follower's
/// displacement over one cam revolution (four-stroke: cam at half crank speed), ψ = 0 at the
/// start of the rise. Shared by `needle profile` and `needle check`.

#include <string>

#include "apps/case/bound_case.h"
#include "lib/cam_profile.h"

namespace needle {

/// The profile of `c` (which must have [profile]; throws CaseError naming what is missing or
/// invalid) on `c.profile->points` steps of a cam revolution. `cam_zero_crank_rad`, when given,
/// receives the crank angle of ψ = 0.
CamProfile MakeCaseProfile(const BoundCase& c, const LiftLaw& law,
                           double* cam_zero_crank_rad = nullptr);

/// The crank angle of cam angle `cam_rad` of that profile, rad: θ = θ₀ + kψ (k crank turns a
/// cam turn), taken within half an engine cycle of θ₀ (ψ near 360° lies just before the rise).
double CrankOfCam(const BoundCase& c, double cam_zero_crank_rad, double cam_rad);

/// "cam 9.0° (crank 2.5°)": a profile's cam angle, counted from the rise's foot, and the crank
/// angle of the case's lift table there; `decimals` after the point, `degree` "°" or " deg".
std::string CamAndCrank(const BoundCase& c, double cam_zero_crank_rad, double cam_rad, int decimals,
                        const std::string& degree);

/// The follower geometry of a case's [profile].
FollowerGeometry CaseFollower(const BoundCase& c);

}  // namespace needle
