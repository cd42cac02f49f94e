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

std::vector<Field> FollowerFields(const FollowerGeometry& g) {
  using namespace display;
  std::vector<Field> f = {TextField("follower", FollowerKindName(g.kind)),
                          {"base_radius", kMm, g.base_radius_m, 2}};
  if (g.kind == FollowerKind::kRoller) f.push_back({"roller_radius", kMm, g.roller_radius_m, 2});
  if (g.kind == FollowerKind::kCurved) f.push_back({"face_radius", kMm, g.face_radius_m, 2});
  if (g.face_half_width_m > 0.0) f.push_back({"face_half_width", kMm, g.face_half_width_m, 2});
  f.push_back({"offset", kMm, g.offset_m, 2});
  f.push_back({"lever_ratio", kNone, g.lever_ratio, 3});
  return f;
}

std::vector<Field> CamProfileFields(const CamProfile& p, double cam_omega) {
  using namespace display;
  return {
      {"max_contact_offset", kMm, p.max_contact_offset_m, 3},
      {"max_contact_offset_at_cam", kDegree, p.max_contact_offset_at_rad, 2},
      FlagField("off_face", p.off_face),
      {"min_entrainment_speed", kMPerS, p.min_entrainment_m_rad * cam_omega, 3},  // ω·|ū|
      {"min_entrainment_speed_at_cam", kDegree, p.min_entrainment_at_rad, 2},
      {"max_sliding_speed", kMPerS, p.max_sliding_m_rad * cam_omega, 3},
      {"max_pressure_angle", kDegree, p.max_pressure_angle_rad, 3},
      {"max_pressure_angle_at_cam", kDegree, p.max_pressure_angle_at_rad, 2},
      {"min_profile_radius", kMm, p.min_profile_radius_m, 3},
      {"min_profile_radius_at_cam", kDegree, p.min_profile_radius_at_rad, 2},
      FlagField("undercut", p.undercut),
  };
}

const std::vector<Column>& ProfileColumns() {
  using namespace display;
  static const std::vector<Column> columns = {{"cam", kDegree},
                                              {"x", kMm},
                                              {"y", kMm},
                                              {"pressure_angle", kDegree},
                                              {"profile_radius", kMm},
                                              {"contact_offset", kMm}};
  return columns;
}

std::vector<double> ProfileRowSi(const ProfilePoint& q) {
  return {q.cam_rad, q.x_m, q.y_m, q.pressure_angle_rad, q.profile_radius_m, q.contact_offset_m};
}

}  // namespace needle
