// Cam profile of a translating roller follower against closed forms.
#include "lib/cam_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/units.h"

namespace needle {
namespace {

TEST(CamProfileTest, EccentricCircularCamIsACircle) {
  // A disk of radius R about a centre ε from the axis, radial roller follower of radius r:
  // the roller centre stays R + r from the disk centre, so
  //   s(ψ) = ε cos ψ + √((R + r)² − ε² sin² ψ) − (R − ε + r),   base circle R − ε,
  // and every profile point must lie on the disk: |P − C| = R, C = (0, ε) in the cam frame.
  const double R = 0.04, eps = 0.006, r = 0.01;
  const double q = R + r;
  const Displacement s = [&](double psi) {
    const double sn = std::sin(psi), c = std::cos(psi);
    const double w = std::sqrt(q * q - eps * eps * sn * sn);
    const double s0 = eps * c + w - (R - eps + r);
    const double s1 = -eps * sn - eps * eps * sn * c / w;
    const double dw = -eps * eps * sn * c / w;  // w'
    const double s2 = -eps * c - eps * eps * ((c * c - sn * sn) * w - sn * c * dw) / (w * w);
    return std::array<double, 3>{s0, s1, s2};
  };
  FollowerGeometry g;
  g.base_radius_m = R - eps;
  g.roller_radius_m = r;
  const CamProfile p = MakeCamProfile(s, g, 720);
  for (const ProfilePoint& pt : p.points) {
    EXPECT_NEAR(std::hypot(pt.x_m, pt.y_m - eps), R, 1e-12) << pt.cam_rad;
    EXPECT_NEAR(pt.pitch_radius_m, R + r, 1e-9) << pt.cam_rad;  // the pitch curve is a circle
    EXPECT_NEAR(pt.profile_radius_m, R, 1e-9);
  }
  EXPECT_FALSE(p.undercut);
}

TEST(CamProfileTest, PressureAngleByHand) {
  // Radial follower, harmonic rise of 8 mm over 90° of cam, r_b = 20 mm, r_r = 5 mm. At
  // ψ = 45°: s = 4 mm, s' = (H/2)(π/β) = 4·2 = 8 mm/rad, tan φ = 8/(25 + 4) → φ = 15.42°.
  const double H = 8e-3, beta = kPi / 2;
  const Displacement s = [&](double psi) {
    if (psi > beta) return std::array<double, 3>{H, 0.0, 0.0};
    return std::array<double, 3>{0.5 * H * (1 - std::cos(kPi * psi / beta)),
                                 0.5 * H * kPi / beta * std::sin(kPi * psi / beta),
                                 0.5 * H * kPi * kPi / (beta * beta) * std::cos(kPi * psi / beta)};
  };
  FollowerGeometry g;
  g.base_radius_m = 0.02;
  g.roller_radius_m = 0.005;
  const CamProfile p = MakeCamProfile(s, g, 8);  // ψ = 0, 45°, 90°, …
  EXPECT_NEAR(p.points[1].cam_rad, kPi / 4, 1e-15);
  EXPECT_NEAR(p.points[1].pressure_angle_rad / kDeg, std::atan(8.0 / 29.0) / kDeg, 1e-12);
  EXPECT_NEAR(std::atan(8.0 / 29.0) / kDeg, 15.42, 0.005);
}

TEST(CamProfileTest, SmallBaseCircleWithLargeRollerUndercuts) {
  // A steep rise near the crest is sharply convex; a roller larger than the pitch radius there
  // would cut the profile: detected.
  const double H = 10e-3, beta = 30 * kDeg;
  const Displacement s = [&](double psi) {
    const double x = std::fmod(psi, 2 * kPi);
    if (x > 2 * beta) return std::array<double, 3>{0.0, 0.0, 0.0};
    const double w = kPi / beta;  // rise and fall over 2β
    return std::array<double, 3>{0.5 * H * (1 - std::cos(w * x)), 0.5 * H * w * std::sin(w * x),
                                 0.5 * H * w * w * std::cos(w * x)};
  };
  FollowerGeometry g;
  g.base_radius_m = 0.008;
  g.roller_radius_m = 0.012;
  const CamProfile bad = MakeCamProfile(s, g, 3600);
  EXPECT_TRUE(bad.undercut);
  EXPECT_LT(bad.min_profile_radius_m, 0.0);
  g.base_radius_m = 0.08;
  g.roller_radius_m = 0.005;
  EXPECT_FALSE(MakeCamProfile(s, g, 3600).undercut);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

TEST(CamProfileTest, HertzLineStressByHand) {
  // 1000 N between a 10 mm cam radius and an 8.25 mm roller, 10 mm long, steel (210 GPa, 0.3):
  // E* = 210e9/(2·0.91) = 115.4 GPa, 1/R* = 100 + 121.2 = 221.2 /m,
  // σ = √(1000 · 115.4e9 · 221.2 / (π · 0.01)) = 901 MPa.
  EXPECT_NEAR(HertzLineStress(1000, 0.010, 0.00825, 210e9, 0.3, 0.010) * 1e-6, 901.4, 0.5);
  // Doubling the force raises it by √2; a concave cam radius lowers it; no force, no stress.
  EXPECT_NEAR(HertzLineStress(2000, 0.010, 0.00825, 210e9, 0.3, 0.010) /
                  HertzLineStress(1000, 0.010, 0.00825, 210e9, 0.3, 0.010),
              std::sqrt(2.0), 1e-12);
  EXPECT_LT(HertzLineStress(1000, -0.05, 0.00825, 210e9, 0.3, 0.010),
            HertzLineStress(1000, 0.05, 0.00825, 210e9, 0.3, 0.010));
  EXPECT_EQ(HertzLineStress(-1, 0.01, 0.01, 210e9, 0.3, 0.01), 0.0);
}

// The profile's fields: a follower shows only the radii its kind has; the eccentric disk's
// least radius of curvature is R in mm; the speeds are per-radian values times the cam's ω.
TEST(CamProfileTest, FieldsShowWhatTheFollowerAndProfileHave) {
  const double R = 0.04, eps = 0.006, r = 0.01, q = R + r;
  const Displacement s = [&](double psi) {
    const double sn = std::sin(psi), c = std::cos(psi);
    const double w = std::sqrt(q * q - eps * eps * sn * sn);
    const double dw = -eps * eps * sn * c / w;
    return std::array<double, 3>{
        eps * c + w - (R - eps + r), -eps * sn + dw,
        -eps * c - eps * eps * ((c * c - sn * sn) * w - sn * c * dw) / (w * w)};
  };
  FollowerGeometry g;
  g.base_radius_m = R - eps;
  g.roller_radius_m = r;
  const auto keys = [](const std::vector<Field>& fields) {
    std::vector<std::string> k;
    for (const Field& f : fields) k.push_back(f.Key());
    return k;
  };
  EXPECT_EQ(keys(FollowerFields(g)),
            (std::vector<std::string>{"follower", "base_radius_mm", "roller_radius_mm", "offset_mm",
                                      "lever_ratio"}));
  FollowerGeometry flat = g;
  flat.kind = FollowerKind::kFlat;
  flat.face_half_width_m = 0.02;
  EXPECT_EQ(keys(FollowerFields(flat)),
            (std::vector<std::string>{"follower", "base_radius_mm", "face_half_width_mm",
                                      "offset_mm", "lever_ratio"}));
  EXPECT_EQ(FollowerFields(flat)[0].text, "flat");

  const CamProfile p = MakeCamProfile(s, g, 720);
  const double omega = 50.0;
  const std::vector<Field> f = CamProfileFields(p, omega);
  EXPECT_NEAR(*FieldAt(f, "min_profile_radius_mm").Shown(), R * 1e3, 1e-6);
  EXPECT_EQ(*FieldAt(f, "max_sliding_speed_m_s").Shown(), p.max_sliding_m_rad * omega);
  EXPECT_EQ(*FieldAt(f, "min_entrainment_speed_m_s").Shown(), p.min_entrainment_m_rad * omega);
  EXPECT_FALSE(FieldAt(f, "undercut").flag);
  std::vector<std::string> si_keys;
  for (const Column& c : ProfileColumns()) si_keys.push_back(c.SiKey());
  EXPECT_EQ(si_keys, (std::vector<std::string>{"cam_rad", "x_m", "y_m", "pressure_angle_rad",
                                               "profile_radius_m", "contact_offset_m"}));
}

}  // namespace
}  // namespace needle
