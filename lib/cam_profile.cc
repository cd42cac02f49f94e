#include "lib/cam_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lib/units.h"

namespace needle {

CamProfile MakeCamProfile(const Displacement& disp, const FollowerGeometry& g, int n) {
  g.Validate();
  if (n < 8) throw std::invalid_argument("a cam profile needs at least 8 points");
  const bool flat = g.kind == FollowerKind::kFlat;
  CamProfile p;
  p.min_profile_radius_m = INFINITY;
  p.min_entrainment_m_rad = INFINITY;
  for (int k = 0; k < n; ++k) {
    const double psi = 2.0 * kPi * k / n;
    std::array<double, 3> sv = disp(psi);
    for (double& v : sv) v *= g.lever_ratio;
    const ProfilePoint q = FollowerContact(g, psi, sv);
    if (std::abs(q.pressure_angle_rad) > std::abs(p.max_pressure_angle_rad)) {
      p.max_pressure_angle_rad = q.pressure_angle_rad;
      p.max_pressure_angle_at_rad = psi;
    }
    if ((flat || q.pitch_radius_m > 0.0) && q.profile_radius_m < p.min_profile_radius_m) {
      p.min_profile_radius_m = q.profile_radius_m;
      p.min_profile_radius_at_rad = psi;
    }
    if (std::abs(q.contact_offset_m) > p.max_contact_offset_m) {
      p.max_contact_offset_m = std::abs(q.contact_offset_m);
      p.max_contact_offset_at_rad = psi;
    }
    if (std::abs(q.entrainment_m_rad) < p.min_entrainment_m_rad) {
      p.min_entrainment_m_rad = std::abs(q.entrainment_m_rad);
      p.min_entrainment_at_rad = psi;
    }
    // Between two points whose entrainment has opposite signs it passes through zero.
    if (!p.points.empty() && p.min_entrainment_m_rad > 0.0) {
      const ProfilePoint& prev = p.points.back();
      if ((prev.entrainment_m_rad < 0.0) != (q.entrainment_m_rad < 0.0)) {
        const double w = prev.entrainment_m_rad / (prev.entrainment_m_rad - q.entrainment_m_rad);
        p.min_entrainment_m_rad = 0.0;
        p.min_entrainment_at_rad = prev.cam_rad + w * (psi - prev.cam_rad);
      }
    }
    p.max_sliding_m_rad = std::max(p.max_sliding_m_rad, std::abs(q.sliding_m_rad));
    p.undercut = p.undercut || q.undercut;
    p.points.push_back(q);
  }
  p.off_face = g.kind != FollowerKind::kRoller && g.face_half_width_m > 0.0 &&
               p.max_contact_offset_m > g.face_half_width_m;
  return p;
}

}  // namespace needle
