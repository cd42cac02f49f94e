#pragma once
/// @file
/// The cam profile over a full turn for any follower kind of lib/follower.h (roller, flat
/// face, curved face), the cam turning through ψ: at each of n equal steps the contact point,
/// the pressure angle, the cam's radius of curvature, the contact's place on the face and the
/// surface velocities (lib/follower.h's equations), and over the turn their extremes and the
/// verdicts: undercut (roller, curved: a convex stretch with ρ_p ≤ r; flat: ρ ≤ 0, a cusp) and
/// the contact running off the face. A follower on a rocker of lever ratio λ is taken as a
/// translating follower moving λ·s (small rocker angles).

#include <array>
#include <functional>
#include <vector>

#include "lib/follower.h"

namespace needle {

/// s(ψ), s'(ψ), s''(ψ) of the follower (m, per cam rad), measured from the base circle.
using Displacement = std::function<std::array<double, 3>(double cam_rad)>;

struct CamProfile {
  std::vector<ProfilePoint> points;
  double max_pressure_angle_rad = 0.0, max_pressure_angle_at_rad = 0.0;
  double min_profile_radius_m = 0.0, min_profile_radius_at_rad = 0.0;  ///< over convex stretches
  bool undercut = false;  ///< some point undercuts (flat: a cusp, ρ ≤ 0)
  /// The largest |offset of the contact along the face| (flat, curved; roller: 0) and where.
  double max_contact_offset_m = 0.0, max_contact_offset_at_rad = 0.0;
  bool off_face = false;  ///< that offset exceeds the face's half-width, when one is given
  /// The least |entrainment velocity| per cam rad (lubrication) and where, m/rad.
  double min_entrainment_m_rad = 0.0, min_entrainment_at_rad = 0.0;
  double max_sliding_m_rad = 0.0;  ///< the largest |sliding velocity| per cam rad, m/rad
};

/// The profile on `n` equal steps of a full turn starting at ψ = 0 (lib/follower.h for each
/// point). The least profile radius is taken over convex stretches (flat: everywhere).
CamProfile MakeCamProfile(const Displacement& s, const FollowerGeometry& g, int n);

}  // namespace needle
