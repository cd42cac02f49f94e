// Cam profile of a translating roller follower against closed forms.
#include "lib/cam_profile.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace needle
