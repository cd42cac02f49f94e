#include "lib/cam_profile.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/units.h"

namespace needle {

void FollowerGeometry::Validate() const {
  if (!(base_radius_m > 0.0)) throw std::invalid_argument("base circle radius must be positive");
  if (!(roller_radius_m >= 0.0)) throw std::invalid_argument("roller radius must not be negative");
  if (!(std::abs(offset_m) < base_radius_m + roller_radius_m)) {
    throw std::invalid_argument(
        "follower offset must be smaller than base circle plus roller radius");
  }
  if (!(lever_ratio > 0.0)) throw std::invalid_argument("lever ratio must be positive");
}

double HertzLineStress(double force_N, double radius1_m, double radius2_m, double modulus_Pa,
                       double poisson, double length_m) {
  const double inv_r = 1.0 / radius1_m + 1.0 / radius2_m;  // 1/R*
  if (!(force_N > 0.0) || !(inv_r > 0.0)) return 0.0;
  const double e_star = modulus_Pa / (2.0 * (1.0 - poisson * poisson));  // E*
  return std::sqrt(force_N * e_star * inv_r / (kPi * length_m));
}

CamProfile MakeCamProfile(const Displacement& disp, const FollowerGeometry& g, int n) {
  g.Validate();
  if (n < 8) throw std::invalid_argument("a cam profile needs at least 8 points");
  const double r0 = g.base_radius_m + g.roller_radius_m;
  const double e = g.offset_m;
  const double d = std::sqrt(r0 * r0 - e * e);
  CamProfile p;
  p.min_profile_radius_m = INFINITY;
  for (int k = 0; k < n; ++k) {
    const double psi = 2.0 * kPi * k / n;
    std::array<double, 3> sv = disp(psi);
    for (double& v : sv) v *= g.lever_ratio;
    const double s = sv[0], s1 = sv[1], s2 = sv[2];
    const double c = std::cos(psi), sn = std::sin(psi);
    ProfilePoint q;
    q.cam_rad = psi;
    q.s_m = s;
    q.pitch_x_m = e * c + (d + s) * sn;  // P(ψ)
    q.pitch_y_m = -e * sn + (d + s) * c;
    const double xp = -e * sn + s1 * sn + (d + s) * c;  // P'
    const double yp = -e * c + s1 * c - (d + s) * sn;
    const double xpp = -e * c + s2 * sn + 2.0 * s1 * c - (d + s) * sn;  // P''
    const double ypp = e * sn + s2 * c - 2.0 * s1 * sn - (d + s) * c;
    const double speed = std::hypot(xp, yp);
    // Inward normal (towards the cam): the tangent turned by −90°, (y', −x')/|P'|.
    q.x_m = q.pitch_x_m + g.roller_radius_m * yp / speed;
    q.y_m = q.pitch_y_m - g.roller_radius_m * xp / speed;
    q.pressure_angle_rad = std::atan((s1 - e) / (d + s));  // tan φ = (s' − e)/(d + s)
    q.pitch_radius_m = speed * speed * speed / (yp * xpp - xp * ypp);
    q.profile_radius_m = q.pitch_radius_m - g.roller_radius_m;
    if (std::abs(q.pressure_angle_rad) > std::abs(p.max_pressure_angle_rad)) {
      p.max_pressure_angle_rad = q.pressure_angle_rad;
      p.max_pressure_angle_at_rad = psi;
    }
    if (q.pitch_radius_m > 0.0 && q.profile_radius_m < p.min_profile_radius_m) {
      p.min_profile_radius_m = q.profile_radius_m;
      p.min_profile_radius_at_rad = psi;
    }
    // A profile radius of zero is a cusp: undercut as much as a negative one.
    if (q.pitch_radius_m > 0.0 && q.pitch_radius_m <= g.roller_radius_m) p.undercut = true;
    p.points.push_back(q);
  }
  return p;
}

}  // namespace needle
