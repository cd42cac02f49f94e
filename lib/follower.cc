#include "lib/follower.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "lib/field_error.h"
#include "lib/name_table.h"
#include "lib/units.h"

namespace needle {
namespace {

// The one name table.
constexpr NameRow<FollowerKind> kKindNames[] = {
    {FollowerKind::kRoller, "roller"},
    {FollowerKind::kFlat, "flat"},
    {FollowerKind::kCurved, "curved"},
};

std::string Num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// The cap |S''| ≤ value at which fn(contact(S'')) ≥ 0 stops holding, fn affine in S''.
// `dir` is the sign of S'' on this side; `probe` a step of S'' of the problem's size.
template <class At, class Fn>
double AffineCap(const At& at, Fn fn, double dir, double probe) {
  const double g0 = fn(at(0.0));
  if (!(g0 >= 0.0)) return 0.0;
  const double slope = (fn(at(dir * probe)) - g0) / probe;  // per unit of |S''|
  if (!(slope < 0.0)) return 1e300;
  return g0 / -slope;
}

}  // namespace

const char* FollowerKindName(FollowerKind kind) { return NameOf(kKindNames, kind); }

std::optional<FollowerKind> ParseFollowerKind(const std::string& name) {
  return ValueOf(kKindNames, name);
}

double FollowerGeometry::ContactRadius() const {
  switch (kind) {
    case FollowerKind::kRoller:
      return roller_radius_m;
    case FollowerKind::kCurved:
      return face_radius_m;
    case FollowerKind::kFlat:
      break;
  }
  return INFINITY;
}

void FollowerGeometry::Validate() const {
  auto req = [](bool ok, const char* field, double v, const std::string& rule) {
    if (!ok) throw FieldError("FollowerGeometry", field, Num(v), v, rule);
  };
  req(base_radius_m > 0.0 && std::isfinite(base_radius_m), "base_radius_m", base_radius_m,
      "must be positive");
  req(lever_ratio > 0.0 && std::isfinite(lever_ratio), "lever_ratio", lever_ratio,
      "must be positive");
  req(face_half_width_m >= 0.0 && std::isfinite(face_half_width_m), "face_half_width_m",
      face_half_width_m, "must not be negative (0: not given)");
  req(std::isfinite(offset_m), "offset_m", offset_m, "must be finite");
  if (kind == FollowerKind::kRoller) {
    req(roller_radius_m >= 0.0 && std::isfinite(roller_radius_m), "roller_radius_m",
        roller_radius_m, "must not be negative");
  }
  if (kind == FollowerKind::kCurved) {
    req(face_radius_m > 0.0 && std::isfinite(face_radius_m), "face_radius_m", face_radius_m,
        "must be positive for a curved face");
  }
  if (kind != FollowerKind::kFlat) {
    req(std::abs(offset_m) < base_radius_m + ContactRadius(), "offset_m", offset_m,
        std::string("must be smaller than base radius plus ") +
            (kind == FollowerKind::kCurved ? "face" : "roller") + " radius");
  }
}

ProfilePoint FollowerContact(const FollowerGeometry& g, double psi,
                             const std::array<double, 3>& sv) {
  const double s = sv[0], s1 = sv[1], s2 = sv[2];
  const double c = std::cos(psi), sn = std::sin(psi);
  const double e = g.offset_m;
  ProfilePoint q;
  q.cam_rad = psi;
  q.s_m = s;
  double u_c = 0.0, u_f = 0.0;  // surface velocities relative to the contact, per cam rad
  if (g.kind == FollowerKind::kFlat) {
    const double h = g.base_radius_m + s;   // the face's distance from the cam centre
    q.x_m = q.pitch_x_m = s1 * c + h * sn;  // C = R(−ψ)(s', r_b + s)
    q.y_m = q.pitch_y_m = -s1 * sn + h * c;
    q.pressure_angle_rad = 0.0;
    q.profile_radius_m = q.pitch_radius_m = h + s2;  // ρ = r_b + s + s''
    q.contact_offset_m = s1 - e;
    u_c = -q.profile_radius_m;  // −T·C' with C' = ρ·R(−ψ)(1, 0)
    u_f = -s2;                  // T·(V − J C − C') = −s''
    q.undercut = !(q.profile_radius_m > 0.0);
  } else {
    const double r = g.ContactRadius();
    const double r0 = g.base_radius_m + r;
    const double d = std::sqrt(r0 * r0 - e * e);
    q.pitch_x_m = e * c + (d + s) * sn;  // P(ψ)
    q.pitch_y_m = -e * sn + (d + s) * c;
    const double xp = -e * sn + s1 * sn + (d + s) * c;  // P'
    const double yp = -e * c + s1 * c - (d + s) * sn;
    const double xpp = -e * c + s2 * sn + 2.0 * s1 * c - (d + s) * sn;  // P''
    const double ypp = e * sn + s2 * c - 2.0 * s1 * sn - (d + s) * c;
    const double speed = std::hypot(xp, yp);
    const double tx = xp / speed, ty = yp / speed;  // T
    // Inward normal (towards the cam): the tangent turned by −90°, (y', −x')/|P'|.
    q.x_m = q.pitch_x_m + r * ty;
    q.y_m = q.pitch_y_m - r * tx;
    q.pressure_angle_rad = std::atan((s1 - e) / (d + s));  // tan φ = (s' − e)/(d + s)
    const double kappa = (yp * xpp - xp * ypp) / (speed * speed * speed);  // 1/ρ_p
    q.pitch_radius_m = 1.0 / kappa;
    q.profile_radius_m = q.pitch_radius_m - r;
    // C' = P'(1 − r/ρ_p): the contact runs along the profile slower than the centre.
    const double stretch = 1.0 - r * kappa;
    u_c = -speed * stretch;
    if (g.kind == FollowerKind::kRoller) {
      u_f = u_c;  // rolling without slip
    } else {
      q.contact_offset_m = r * std::sin(q.pressure_angle_rad);
      const double vx = s1 * sn, vy = s1 * c;               // V = R(−ψ)(0, s')
      const double jcx = -q.y_m, jcy = q.x_m;               // J·C
      const double cpx = xp * stretch, cpy = yp * stretch;  // C'
      u_f = tx * (vx - jcx - cpx) + ty * (vy - jcy - cpy);
    }
    // A profile radius of zero is a cusp: undercut as much as a negative one.
    q.undercut = kappa > 0.0 && r * kappa >= 1.0;
  }
  q.entrainment_m_rad = 0.5 * (u_c + u_f);
  q.sliding_m_rad = u_c - u_f;
  return q;
}

double SpeedCap(const FollowerGeometry& g, const FollowerLimits& lim, double s_m) {
  double cap = 1e300;
  if (g.kind == FollowerKind::kFlat) {
    if (g.face_half_width_m > 0.0) cap = g.face_half_width_m;  // s' ≤ w (radial)
    return cap;
  }
  const double r = g.ContactRadius();
  const double big_r = g.base_radius_m + r + s_m;  // tan φ = S'/R on a radial follower
  if (lim.max_pressure_angle_rad > 0.0) cap = big_r * std::tan(lim.max_pressure_angle_rad);
  if (g.kind == FollowerKind::kCurved && g.face_half_width_m > 0.0 && g.face_half_width_m < r) {
    // r·sin φ ≤ w  ⇔  tan φ ≤ w/√(r² − w²)
    const double w = g.face_half_width_m;
    cap = std::min(cap, big_r * w / std::sqrt(r * r - w * w));
  }
  return cap;
}

AccelerationCap AccelerationCapAt(const FollowerGeometry& g, const FollowerLimits& lim, double s_m,
                                  double s1, bool convex) {
  AccelerationCap cap;
  const auto at = [&](double s2) { return FollowerContact(g, 0.0, {s_m, s1, s2}); };
  const double dir = convex ? -1.0 : 1.0;
  const double r = g.kind == FollowerKind::kFlat ? 0.0 : g.ContactRadius();
  const double probe = g.base_radius_m + r + s_m;  // S'' of the size of R
  if (convex && lim.min_profile_radius_m >= 0.0) {
    double v = 1e300;
    if (g.kind == FollowerKind::kFlat) {
      v = AffineCap(
          at, [&](const ProfilePoint& q) { return q.profile_radius_m - lim.min_profile_radius_m; },
          dir, probe);
    } else if (r + lim.min_profile_radius_m > 0.0) {
      // ρ_p ≥ r + ρmin on a convex stretch  ⇔  1/ρ_p ≤ 1/(r + ρmin); 1/ρ_p is affine in S''.
      const double k_max = 1.0 / (r + lim.min_profile_radius_m);
      v = AffineCap(
          at, [&](const ProfilePoint& q) { return k_max - 1.0 / q.pitch_radius_m; }, dir, probe);
    }
    if (v < cap.value) cap = {v, CapSource::kCurvature};
  }
  if (lim.min_entrainment_m_rad > 0.0) {
    const double sign = at(0.0).entrainment_m_rad < 0.0 ? -1.0 : 1.0;
    const double v = AffineCap(
        at,
        [&](const ProfilePoint& q) {
          return sign * q.entrainment_m_rad - lim.min_entrainment_m_rad;
        },
        dir, probe);
    if (v < cap.value) cap = {v, CapSource::kLubrication};
  }
  return cap;
}

double HertzLineStress(double force_N, double radius1_m, double radius2_m, double modulus_Pa,
                       double poisson, double length_m) {
  const double inv_r = 1.0 / radius1_m + 1.0 / radius2_m;  // 1/R*
  if (!(force_N > 0.0) || !(inv_r > 0.0)) return 0.0;
  const double e_star = modulus_Pa / (2.0 * (1.0 - poisson * poisson));  // E*
  return std::sqrt(force_N * e_star * inv_r / (kPi * length_m));
}

double ContactStress(const FollowerGeometry& g, const ProfilePoint& q, double force_N,
                     double modulus_Pa, double poisson, double length_m) {
  const double partner = g.ContactRadius();
  return HertzLineStress(force_N, q.profile_radius_m, partner > 0.0 ? partner : INFINITY,
                         modulus_Pa, poisson, length_m);
}

}  // namespace needle
