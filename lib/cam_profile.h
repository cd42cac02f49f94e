#pragma once
/// @file
/// Cam profile for a translating roller follower (offset e, base circle r_b, roller r_r), the
/// cam turning through ψ. With R₀ = r_b + r_r and d = √(R₀² − e²), the roller centre in the
/// cam's frame (the pitch curve) is
///
///     P(ψ) = ( e cos ψ + (d + s) sin ψ ,  −e sin ψ + (d + s) cos ψ ),
///
/// the profile is P offset by r_r towards the cam along the normal, the pressure angle is
/// φ = atan((s' − e)/(d + s)), and the radius of curvature of the pitch curve is
/// ρ_p = |P'|³ / (P'_y P''_x − P'_x P''_y) (positive where convex); the profile's radius is
/// ρ_p − r_r, and a convex stretch with ρ_p < r_r undercuts (the profile would loop).
/// A roller on a rocker of lever ratio λ is taken as a translating follower moving λ·s
/// (small rocker angles).

#include <array>
#include <functional>
#include <vector>

namespace needle {

struct FollowerGeometry {
  double base_radius_m = 0.0;    ///< r_b, > 0
  double roller_radius_m = 0.0;  ///< r_r, ≥ 0
  double offset_m = 0.0;         ///< e, |e| < r_b + r_r
  double lever_ratio = 1.0;      ///< λ, roller travel per needle travel, > 0
  void Validate() const;
};

/// s(ψ), s'(ψ), s''(ψ) of the follower (m, per cam rad), measured from the base circle.
using Displacement = std::function<std::array<double, 3>(double cam_rad)>;

struct ProfilePoint {
  double cam_rad = 0.0;
  double s_m = 0.0;
  double pitch_x_m = 0.0, pitch_y_m = 0.0;
  double x_m = 0.0, y_m = 0.0;  ///< profile point
  double pressure_angle_rad = 0.0;
  double pitch_radius_m = 0.0;    ///< ρ_p (signed, + convex)
  double profile_radius_m = 0.0;  ///< ρ_p − r_r
};

struct CamProfile {
  std::vector<ProfilePoint> points;
  double max_pressure_angle_rad = 0.0, max_pressure_angle_at_rad = 0.0;
  double min_profile_radius_m = 0.0, min_profile_radius_at_rad = 0.0;  ///< over convex stretches
  bool undercut = false;
};

/// The profile on `n` equal steps of a full turn starting at ψ = 0.
CamProfile MakeCamProfile(const Displacement& s, const FollowerGeometry& g, int n);

/// Hertz line contact between two cylinders of the same material (Pa):
///     σ = √(F E* / (π L R*)),   1/R* = 1/ρ₁ + 1/ρ₂ (signed: concave negative),
///     E* = E / (2(1 − ν²)).
/// 0 when F ≤ 0 (no contact) or the surfaces conform (1/R* ≤ 0).
double HertzLineStress(double force_N, double radius1_m, double radius2_m, double modulus_Pa,
                       double poisson, double length_m);

}  // namespace needle
