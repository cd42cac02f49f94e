#pragma once
/// @file
/// The profile job: the cam profile of a case's lift law for its follower (lib/cam_profile.h:
/// the contact point's path r(θ) = r_b + S(θ) mapped through the follower's geometry, its
/// pressure angle, radius of curvature and undercut, the contact's entrainment and sliding
/// speeds at the rated speed). `needle profile` and the Python module call it; the writer is
/// apps/report/cam_writer.h.

#include "apps/case/bound_case.h"
#include "lib/cam_profile.h"
#include "lib/follower.h"

namespace needle {

struct CaseCamProfile {
  BoundCase c;                      ///< the case
  FollowerGeometry follower;        ///< its follower ([profile])
  double play_m = 0.0;              ///< the roller's play ([train] play_mm), m
  double cam_zero_crank_rad = 0.0;  ///< the crank angle where the cam angle is 0, rad
  double cam_omega_rad_s = 0.0;     ///< the cam's speed at the rated engine speed, rad/s
  CamProfile profile;               ///< the profile and its extremes
};

/// The profile of a bound case. Throws CaseError when it has no [profile].
CaseCamProfile ProfileOfCase(const BoundCase& c);

}  // namespace needle
