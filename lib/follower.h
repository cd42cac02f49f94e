#pragma once
/// @file
/// The follower that touches the cam, one kind per row of one table: what a kind makes of the
/// displacement law at one cam angle, and the limits it puts on S' and S'' when a law is
/// synthesized (lib/cam_synthesis.h). docs/model.md §10 states it in words.
///
/// Every kind translates along an axis at offset e from the cam centre. The cam turns through
/// ψ; its frame is the follower's turned by −ψ, R(−ψ). s, s', s'' are the follower's
/// displacement from the base circle and its derivatives per cam radian.
///
///   roller  a roller of radius r on a pin; its centre runs on the pitch curve
///           P(ψ) = R(−ψ)·(e, d + s),  d = √((r_b + r)² − e²),
///           the contact C = P + r·N (N the inward normal); it rolls without slip.
///   curved  a face of radius r fixed to the follower (MATEC 2018's "cylindrical surface"):
///           the same pitch curve and profile as a roller of that radius, but the face slides.
///   flat    a flat face square to the axis: C(ψ) = R(−ψ)·(s', r_b + s), so the contact lies
///           s' − e off the follower's axis; pressure angle 0; radius ρ = r_b + s + s''.
///
/// For roller and curved: tan φ = (s' − e)/(d + s), the pitch radius
/// ρ_p = |P'|³/(P'_y P''_x − P'_x P''_y) (+ convex), the profile radius ρ = ρ_p − r, and the
/// contact r·sin φ off the axis on a curved face. A convex stretch with ρ_p ≤ r undercuts; a flat
/// face cusps where ρ ≤ 0 (it cannot follow a concave or pointed cam).
///
/// Surface velocities at the contact per unit cam speed (m/rad; × ω for m/s), along the
/// contact's tangent T (J turns by +90°, V = R(−ψ)(0, s') the follower's own speed):
///   cam surface relative to the contact point   u_c = −T·C',
///   follower face relative to the contact point u_f = T·(V − J·C − C')  (a face that slides),
///                                               u_f = u_c                 (a roller that rolls),
///   entrainment ū = (u_c + u_f)/2,  sliding u_c − u_f.
/// For the flat face these are ū = −(r_b + s + 2s'')/2 and sliding −(r_b + s): the entrainment
/// vanishes where ρ = −s'', the classic loss of the lubricant film of flat tappets (Dyson,
/// Tribology International 13 (1980) 121–132).

#include <array>
#include <optional>
#include <string>

namespace needle {

/// The kinds of follower; names in FollowerKindName.
enum class FollowerKind { kRoller, kFlat, kCurved };

/// "roller", "flat", "curved".
const char* FollowerKindName(FollowerKind kind);
/// The kind named `name`, or nullopt.
std::optional<FollowerKind> ParseFollowerKind(const std::string& name);

struct FollowerGeometry {
  FollowerKind kind = FollowerKind::kRoller;  ///< the follower's kind
  double base_radius_m = 0.0;                 ///< r_b, > 0
  double roller_radius_m = 0.0;               ///< roller: r, ≥ 0 (0: a knife edge)
  double face_radius_m = 0.0;                 ///< curved: the face's radius r, > 0
  double face_half_width_m = 0.0;  ///< flat and curved: the face's half-width, > 0; 0: not given
  double offset_m = 0.0;           ///< e; roller and curved: |e| < r_b + r
  double lever_ratio = 1.0;        ///< λ, roller travel per needle travel, > 0
  /// The radius of the follower's contact surface: r for roller and curved, +∞ for flat.
  double ContactRadius() const;
  /// Throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

/// The follower on the cam at one angle.
struct ProfilePoint {
  double cam_rad = 0.0;
  double s_m = 0.0;
  double pitch_x_m = 0.0, pitch_y_m = 0.0;  ///< roller centre (flat: the contact point)
  double x_m = 0.0, y_m = 0.0;              ///< profile point: the contact, in the cam's frame
  double pressure_angle_rad = 0.0;          ///< φ (flat: 0)
  double pitch_radius_m = 0.0;     ///< ρ_p (signed, + convex; flat: equals profile_radius_m)
  double profile_radius_m = 0.0;   ///< ρ, the cam's radius at the contact (+ convex)
  double contact_offset_m = 0.0;   ///< the contact's distance from the axis along the face
                                   ///< (flat: s' − e, curved: r·sin φ, roller: 0)
  double entrainment_m_rad = 0.0;  ///< ū/ω, signed, m per cam rad
  double sliding_m_rad = 0.0;      ///< (u_c − u_f)/ω, signed, m per cam rad (roller: 0)
  bool undercut = false;           ///< roller, curved: 0 < ρ_p ≤ r; flat: ρ ≤ 0
};

/// The contact at cam angle ψ for displacement s (m) and its derivatives s', s'' per cam rad
/// (already multiplied by the lever ratio).
ProfilePoint FollowerContact(const FollowerGeometry& g, double cam_rad,
                             const std::array<double, 3>& s);

/// Limits that steer a synthesis step by step (lib/cam_synthesis.h). Radial followers only
/// (offset 0): then every quantity depends on (s, s', s'') alone, not on ψ.
struct FollowerLimits {
  double max_pressure_angle_rad = 0.0;  ///< φmax in (0, π/2) for roller and curved; 0: none
  double min_profile_radius_m = -1.0;   ///< ρmin ≥ 0 wherever the cam is convex; < 0: none
  double min_entrainment_m_rad = 0.0;   ///< |ū|/ω ≥ this (lubrication), m/rad; 0: none
};

/// The largest S' (m/rad) a radial follower allows at displacement s: the pressure angle
/// (S' ≤ (r_b + r + s)·tan φmax) and the face (flat: S' ≤ half-width; curved: r·sin φ ≤
/// half-width). +∞ when nothing binds.
double SpeedCap(const FollowerGeometry& g, const FollowerLimits& lim, double s_m);

/// Which limit set an acceleration cap.
enum class CapSource { kNone, kCurvature, kLubrication };

/// The largest |S''| (m/rad²) a radial follower allows at (s, s') on the convex side
/// (S'' < 0, `convex`) or the other: the profile radius (ρ ≥ ρmin) and the entrainment
/// (|ū|/ω ≥ its limit). Both are affine in S'' (ū, 1/ρ_p and the flat face's ρ are), so the
/// cap is exact. 0 when a limit fails even at S'' = 0; +∞ when nothing binds.
struct AccelerationCap {
  double value = 1e300;
  CapSource source = CapSource::kNone;
};
AccelerationCap AccelerationCapAt(const FollowerGeometry& g, const FollowerLimits& lim, double s_m,
                                  double s1, bool convex);

/// Hertz line contact between two cylinders of the same material (Pa):
///     σ = √(F E* / (π L R*)),   1/R* = 1/ρ₁ + 1/ρ₂ (signed: concave negative; a flat face ∞),
///     E* = E / (2(1 − ν²)).
/// 0 when F ≤ 0 (no contact) or the surfaces conform (1/R* ≤ 0).
double HertzLineStress(double force_N, double radius1_m, double radius2_m, double modulus_Pa,
                       double poisson, double length_m);

/// The Hertz line stress at contact `q` of follower `g` under `force_N` (HertzLineStress): the
/// cam's radius ρ against the follower's, a flat face's (or a roller of radius 0, none given)
/// counted as ∞.
double ContactStress(const FollowerGeometry& g, const ProfilePoint& q, double force_N,
                     double modulus_Pa, double poisson, double length_m);

}  // namespace needle
