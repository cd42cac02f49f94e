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
#include "lib/result_fields.h"

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

/// The follower as fields (lib/result_fields.h): its kind, the base radius, the roller's or
/// the face's radius and the face's half-width where the kind has them, offset and lever.
std::vector<Field> FollowerFields(const FollowerGeometry& g);

/// The profile's extremes as fields: the contact's offset on the face, the entrainment and
/// sliding speeds at the cam speed `cam_omega` (rad/s), the pressure angle and the least
/// radius of curvature, each with the cam angle where it is, and the two verdicts.
std::vector<Field> CamProfileFields(const CamProfile& p, double cam_omega);

/// Every point's columns: cam angle (deg), x and y (mm), pressure angle (deg), radius of
/// curvature (mm), contact offset (mm); the first three are the CAD coordinates.
const std::vector<Column>& ProfileColumns();

/// One point's SI values in ProfileColumns()' order.
std::vector<double> ProfileRowSi(const ProfilePoint& q);

}  // namespace needle
