// The three follower kinds against closed forms: a flat face on an eccentric circle, a curved
// face against a roller of the same radius, a curved face of growing radius against the flat
// one, a cusp at exactly the predicted lift, and the synthesis caps against their formulas.
#include "lib/follower.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lib/cam_profile.h"
#include "lib/units.h"

namespace needle {
namespace {

// A disk of radius R whose centre is ε from the cam's: under a radial flat face the lift is
// harmonic, s = ε(1 − cos ψ) over the base circle R − ε.
Displacement EccentricFlat(double eps) {
  return [eps](double psi) {
    return std::array<double, 3>{eps * (1 - std::cos(psi)), eps * std::sin(psi),
                                 eps * std::cos(psi)};
  };
}

FollowerGeometry Flat(double base_radius_m) {
  FollowerGeometry g;
  g.kind = FollowerKind::kFlat;
  g.base_radius_m = base_radius_m;
  return g;
}

TEST(FollowerTest, FlatFaceOnAnEccentricCircle) {
  // ρ = r_b + s + s'' = R at every angle; the contact lies s' = ε sin ψ off the axis; the
  // profile is the disk, centred (0, −ε) in the cam's frame; entrainment −(R + ε cos ψ)/2 and
  // sliding −(R − ε cos ψ) per cam rad.
  const double R = 0.03, eps = 0.004;
  const CamProfile p = MakeCamProfile(EccentricFlat(eps), Flat(R - eps), 360);
  for (const ProfilePoint& q : p.points) {
    const double psi = q.cam_rad;
    EXPECT_NEAR(q.profile_radius_m, R, 1e-15) << psi;
    EXPECT_NEAR(q.contact_offset_m, eps * std::sin(psi), 1e-16);
    EXPECT_EQ(q.pressure_angle_rad, 0.0);
    EXPECT_NEAR(std::hypot(q.x_m, q.y_m + eps), R, 1e-15) << psi;
    EXPECT_NEAR(q.entrainment_m_rad, -(R + eps * std::cos(psi)) / 2, 1e-16);
    EXPECT_NEAR(q.sliding_m_rad, -(R - eps * std::cos(psi)), 1e-16);
  }
  EXPECT_FALSE(p.undercut);
  EXPECT_NEAR(p.max_contact_offset_m, eps, 1e-9);  // at ψ = 90°, a sample point
  EXPECT_NEAR(p.min_profile_radius_m, R, 1e-15);
}

TEST(FollowerTest, FlatFaceCuspsExactlyWhereTheLiftExceedsTheBaseRadius) {
  // s = H sin²ψ: ρ = r_b + H/2 + (3H/2) cos 2ψ, least r_b − H at ψ = 90°: a cusp iff H ≥ r_b.
  const double rb = 0.01;
  auto law = [](double h) -> Displacement {
    return [h](double psi) {
      return std::array<double, 3>{h * std::sin(psi) * std::sin(psi), h * std::sin(2 * psi),
                                   2 * h * std::cos(2 * psi)};
    };
  };
  const CamProfile ok = MakeCamProfile(law(0.99 * rb), Flat(rb), 360);
  EXPECT_FALSE(ok.undercut);
  EXPECT_NEAR(ok.min_profile_radius_m, 0.01 * rb, 1e-15);
  EXPECT_NEAR(ok.min_profile_radius_at_rad, kPi / 2, 1e-12);
  const CamProfile bad = MakeCamProfile(law(1.01 * rb), Flat(rb), 360);
  EXPECT_TRUE(bad.undercut);
  EXPECT_NEAR(bad.min_profile_radius_m, -0.01 * rb, 1e-15);
}

TEST(FollowerTest, CurvedFaceHasTheRollersPitchCurveButSlides) {
  // The same law under a roller and a curved face of the same radius: the same pitch curve,
  // profile, pressure angle and radius, to the last bit; the roller does not slide, the face
  // does, and its contact lies r·sin φ off the axis.
  const double H = 0.008, beta = kPi / 2;
  const Displacement s = [&](double psi) {
    if (psi > beta) return std::array<double, 3>{H, 0.0, 0.0};
    const double k = kPi / beta;
    return std::array<double, 3>{0.5 * H * (1 - std::cos(k * psi)), 0.5 * H * k * std::sin(k * psi),
                                 0.5 * H * k * k * std::cos(k * psi)};
  };
  FollowerGeometry roller;
  roller.base_radius_m = 0.02;
  roller.roller_radius_m = 0.00825;
  FollowerGeometry curved = roller;
  curved.kind = FollowerKind::kCurved;
  curved.roller_radius_m = 0.0;
  curved.face_radius_m = 0.00825;
  const CamProfile a = MakeCamProfile(s, roller, 720), b = MakeCamProfile(s, curved, 720);
  double most_sliding = 0.0;
  for (size_t i = 0; i < a.points.size(); ++i) {
    const ProfilePoint &p = a.points[i], &q = b.points[i];
    EXPECT_EQ(p.pitch_x_m, q.pitch_x_m);
    EXPECT_EQ(p.pitch_y_m, q.pitch_y_m);
    EXPECT_EQ(p.x_m, q.x_m);
    EXPECT_EQ(p.y_m, q.y_m);
    EXPECT_EQ(p.pressure_angle_rad, q.pressure_angle_rad);
    EXPECT_EQ(p.profile_radius_m, q.profile_radius_m);
    EXPECT_EQ(p.sliding_m_rad, 0.0);
    EXPECT_EQ(p.contact_offset_m, 0.0);
    EXPECT_NEAR(q.contact_offset_m, 0.00825 * std::sin(q.pressure_angle_rad), 1e-18);
    most_sliding = std::max(most_sliding, std::abs(q.sliding_m_rad));
  }
  EXPECT_GT(most_sliding, 0.01);  // of the order of r_b
  EXPECT_EQ(a.undercut, b.undercut);
}

TEST(FollowerTest, CurvedFaceVelocitiesAtRestAndInTheFlatLimit) {
  // On the base circle the cam slides under a still face at r_b per rad and the face does not
  // move: u_c = −r_b, u_f = 0.
  FollowerGeometry g;
  g.kind = FollowerKind::kCurved;
  g.base_radius_m = 0.02;
  g.face_radius_m = 0.005;
  const ProfilePoint rest = FollowerContact(g, 0.3, {0.0, 0.0, 0.0});
  EXPECT_NEAR(rest.entrainment_m_rad, -0.01, 1e-17);
  EXPECT_NEAR(rest.sliding_m_rad, -0.02, 1e-17);
  // A face of growing radius tends to the flat face: on the eccentric circle the entrainment
  // and sliding approach −(R + ε cos ψ)/2 and −(R − ε cos ψ), the error falling like 1/r.
  const double R = 0.03, eps = 0.004;
  double last_error = INFINITY;
  for (double r : {1.0, 10.0, 100.0}) {
    g.base_radius_m = R - eps;
    g.face_radius_m = r;
    // The lift of a radial curved face of radius r on the disk (as for a roller of radius r).
    const double q = R + r;
    double error = 0.0;
    for (double psi = 0.1; psi < 6.2; psi += 0.5) {
      const double sn = std::sin(psi), c = std::cos(psi);
      const double w = std::sqrt(q * q - eps * eps * sn * sn), dw = -eps * eps * sn * c / w;
      const double s0 = -eps * c + w - (R - eps + r);
      const double s1 = eps * sn + dw;
      const double s2 = eps * c - eps * eps * ((c * c - sn * sn) * w - sn * c * dw) / (w * w);
      const ProfilePoint p = FollowerContact(g, psi, {s0, s1, s2});
      error = std::max({error, std::abs(p.entrainment_m_rad + (R + eps * c) / 2),
                        std::abs(p.sliding_m_rad + (R - eps * c))});
    }
    EXPECT_LT(error, 0.2 * last_error + 1e-12) << r;
    last_error = error;
  }
  EXPECT_LT(last_error, 2e-6);
}

TEST(FollowerTest, CapsMatchTheirFormulas) {
  FollowerLimits lim;
  lim.min_profile_radius_m = 0.002;
  lim.min_entrainment_m_rad = 0.003;
  const double s = 0.004, s1 = 0.006;
  // Flat: ρ = r_b + s + s'' ≥ ρmin and (r_b + s + 2s'')/2 ≥ u: |S''| ≤ min(r_b + s − ρmin,
  // (r_b + s − 2u)/2) on the convex side; the face caps S' at its half-width.
  FollowerGeometry flat = Flat(0.01);
  flat.face_half_width_m = 0.007;
  AccelerationCap c = AccelerationCapAt(flat, lim, s, s1, true);
  EXPECT_NEAR(c.value, (0.014 - 0.006) / 2, 1e-15);
  EXPECT_EQ(c.source, CapSource::kLubrication);
  lim.min_entrainment_m_rad = 0.0;
  c = AccelerationCapAt(flat, lim, s, s1, true);
  EXPECT_NEAR(c.value, 0.014 - 0.002, 1e-15);
  EXPECT_EQ(c.source, CapSource::kCurvature);
  EXPECT_EQ(AccelerationCapAt(flat, lim, s, s1, false).value, 1e300);  // S'' > 0 only helps
  EXPECT_EQ(SpeedCap(flat, lim, s), 0.007);
  // Roller: the pitch radius (R² + S'²)^{3/2}/(R² + 2S'² − R S'') ≥ r + ρmin.
  FollowerGeometry roller;
  roller.base_radius_m = 0.01;
  roller.roller_radius_m = 0.005;
  const double big_r = 0.01 + 0.005 + s;
  const double expected =
      (std::pow(big_r * big_r + s1 * s1, 1.5) / 0.007 - big_r * big_r - 2 * s1 * s1) / big_r;
  EXPECT_NEAR(AccelerationCapAt(roller, lim, s, s1, true).value, expected, 1e-15);
  lim.max_pressure_angle_rad = 30 * kDeg;
  EXPECT_NEAR(SpeedCap(roller, lim, s), big_r * std::tan(30 * kDeg), 1e-17);
  // Curved with a face half-width w < r: r sin φ ≤ w, tan φ ≤ w/√(r² − w²).
  FollowerGeometry curved = roller;
  curved.kind = FollowerKind::kCurved;
  curved.face_radius_m = 0.005;
  curved.face_half_width_m = 0.002;
  EXPECT_NEAR(SpeedCap(curved, lim, s), big_r * 0.002 / std::sqrt(0.005 * 0.005 - 0.002 * 0.002),
              1e-17);
  // A limit that fails at S'' = 0 already leaves no room.
  lim.min_profile_radius_m = 0.05;
  EXPECT_EQ(AccelerationCapAt(flat, lim, s, s1, true).value, 0.0);
}

TEST(FollowerTest, NamesAndValidation) {
  for (FollowerKind k : {FollowerKind::kRoller, FollowerKind::kFlat, FollowerKind::kCurved})
    EXPECT_EQ(ParseFollowerKind(FollowerKindName(k)), k);
  EXPECT_FALSE(ParseFollowerKind("knife"));
  FollowerGeometry g;
  g.kind = FollowerKind::kCurved;
  g.base_radius_m = 0.01;
  try {
    g.Validate();
    ADD_FAILURE() << "a curved face without a radius was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "FollowerGeometry.face_radius_m = 0: must be positive for a curved face");
  }
  g.face_radius_m = 0.005;
  g.offset_m = 0.015;  // at the edge: base radius plus face radius
  try {
    g.Validate();
    ADD_FAILURE() << "an offset past the base circle and face was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "FollowerGeometry.offset_m = 0.015: must be smaller than base radius plus face "
                 "radius");
  }
  g = Flat(0.01);
  g.offset_m = 0.5;  // a flat face may sit far off centre: only its contact offset moves
  EXPECT_NO_THROW(g.Validate());
}

}  // namespace
}  // namespace needle
