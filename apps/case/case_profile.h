#pragma once
/// @file
/// The cam profile of a case with [profile] (lib/cam_profile.h): the needle's cam input u(θ),
/// roller play on Basu's tangent (or linear) ramps included, turned into the follower's
/// displacement over one cam revolution (four-stroke: cam at half crank speed), ψ = 0 at the
/// start of the rise. Shared by `needle profile` and `needle check`.

#include "apps/case/case_file.h"
#include "lib/cam_profile.h"

namespace needle {

/// The profile of `c` (which must have [profile]; throws CaseError naming what is missing or
/// invalid) on `c.profile->points` steps of a cam revolution. `cam_zero_crank_rad`, when given,
/// receives the crank angle of ψ = 0.
CamProfile MakeCaseProfile(const Case& c, const LiftLaw& law, double* cam_zero_crank_rad = nullptr);

/// The follower geometry of a case's [profile].
FollowerGeometry CaseFollower(const Case& c);

}  // namespace needle
