#pragma once
/// @file
/// Numerical synthesis of a rise law S(φ) under limits on its derivatives, with a section of
/// constant maximum speed when the limit on S' is active (MATEC Web Conf. 226, 01031, 2018).
/// φ is the cam angle (rad), S the follower displacement (m), S' = dS/dφ and so on.
///
/// Both sides of the rise are formed step by step from their ends at rest, A forward with
/// S'' ≥ 0 and C backward with S'' ≤ 0, each step taking the largest |S''| the limits allow:
///
///     |S''_i| ≤ a (a⁺ on side A, a⁻ on side C),   |S''_i − S''_{i−1}| / Δφ ≤ j   (S''' limit),
///     S'_i = S'_{i−1} + Δφ (S''_i + S''_{i−1})/2,   S_i = S_{i−1} + Δφ (S'_i + S'_{i−1})/2,
///
/// always advancing the side whose S' is lower, so that the two meet where S' agrees. With a
/// limit S'max, each side also keeps S'_i + S''_i²/(2j) ≤ S'max (so that S'' can come back to
/// zero exactly at S'max) and stops there; the displacement left over is covered at constant
/// speed over φ₀ = ΔS / S'max. With a jerk limit, two sides that would meet below S'max (S''
/// > 0 on A, < 0 on C: a step in S'') are made to meet at the largest speed V* ≤ S'max both
/// reach with S'' back at 0, so S''' stays within the limit where they join too. All limits are
/// scaled by one factor α ≤ 1 (found by bisection) so that the rise takes exactly the given angle;
/// the law is then stretched by at most one step to close the angle exactly, which only lowers
/// every derivative.
///
/// The follower's limits (lib/follower.h) and the spring's act as caps on S' and |S''| at each
/// step. When a cap falls faster than the jerk limit lets S'' follow (S''_i − cap > j·Δφ), the
/// step before is formed again with S'' ≤ cap + j·Δφ, and so on back as far as needed — the
/// paper's "back-off" — so that both the cap and the jerk limit hold.

#include <optional>
#include <string>
#include <vector>

#include "lib/follower.h"
#include "lib/rigid_train.h"

namespace needle {

/// The specification of a rise. Every field has a default where one makes sense.
struct SynthesisSpec {
  double rise_rad = 0.0;       ///< angular length of the rise Φ, cam rad, > 0
  double height_m = 0.0;       ///< displacement H, m, > 0
  double step_rad = 0.0;       ///< step Δφ; 0: Φ/4000
  double speed_limit = 1e300;  ///< S'max, m/rad (default: none)
  double accel_limit = 0.0;    ///< a⁺, largest positive S'', m/rad², > 0
  double decel_limit = 0.0;    ///< a⁻, largest |S''| where negative, m/rad², > 0
  double jerk_limit = 1e300;   ///< j, largest |S'''|, m/rad³ (default: none)
  /// The follower and the limits it steers by, applied at every step as caps on S' and S''
  /// (lib/follower.h, radial: offset 0). Active when follower.base_radius_m > 0. The face
  /// half-width of a flat face caps S' everywhere (the contact lies S' off the axis), so it
  /// acts as S'max and can make the constant-speed section.
  FollowerGeometry follower;
  FollowerLimits follower_limits;  ///< pressure angle, least profile radius, entrainment
  /// Spring reserve K > 0: on the decelerating side the spring force must stay K times the
  /// inertia force, F_spring(S) ≥ K·m·ω²·|S''| (lib/rigid_train.h), a cap
  /// |S''| ≤ F_spring(S)/(K·m·ω²). Needs the train (mass, preload, rate; its gas load is
  /// counted too) and the cam speed ω. 0: no such limit.
  double min_spring_reserve = 0.0;
  /// Contact stress σ_H ≤ this as a cap on |S''| (Hertz line contact of the cam's radius
  /// against the follower's, F = m·ω²·S'' + P₀ + k·S), Pa; 0: no such limit. Needs the
  /// follower, the train and ω.
  double max_contact_stress_Pa = 0.0;
  double contact_length_m = 0.0;      ///< L of the line contact, m, > 0 with the stress limit
  double elastic_modulus_Pa = 210e9;  ///< E of cam and follower (the same material)
  double poisson = 0.3;               ///< ν
  /// The moving mass and the spring, used with min_spring_reserve and max_contact_stress_Pa.
  RigidTrain train;
  double cam_omega = 0.0;  ///< cam angular speed ω, rad/s, > 0 with either
  /// Throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

struct SynthesizedLaw {
  std::vector<double> phi, s, s1, s2, s3;  ///< φ (rad), S (m), S', S'', S''' on the steps
  double scale = 1.0;                      ///< α, the fraction of the limits used
  bool speed_limit_active = false;
  bool pressure_angle_limited = false;  ///< the pressure-angle cap bound S' somewhere
  bool curvature_limited = false;       ///< the curvature cap bound S'' somewhere

  bool spring_reserve_limited = false;  ///< the spring-reserve cap bound S'' somewhere
  bool lubrication_limited = false;     ///< the entrainment cap bound S'' somewhere
  bool stress_limited = false;          ///< the contact-stress cap bound S'' somewhere
  bool face_width_limited = false;      ///< a flat face's half-width, not S'max, set S'
  /// Steps formed again with a lower S'' because a later step could not meet a cap within the
  /// jerk limit (MATEC 2018: "decreases the value of S'' at one of the previous steps").
  size_t backed_off_steps = 0;
  /// > 0: the sides would have met below S'max with S'' of opposite signs (a jerk step), so
  /// they were made to meet at this S', m/rad, with S'' = 0 on both (the jerk limit honoured
  /// everywhere); 0 otherwise.
  double meet_speed = 0.0;

  double constant_start_rad = 0.0, constant_end_rad = 0.0;  ///< the constant-speed section
  double constant_length_rad() const { return constant_end_rad - constant_start_rad; }
  /// Index where side A ends and side C begins (the junction), or the constant section starts.
  size_t junction = 0;
};

/// Forms the rise. Throws std::invalid_argument when the limits cannot raise H within Φ, with
/// the shortest rise they allow and the least S'max (or acceleration scale) that would fit.
SynthesizedLaw SynthesizeRise(const SynthesisSpec& spec);

/// The smallest S'max with which the rise fits (the other limits as given), m/rad.
double LeastSpeedLimit(const SynthesisSpec& spec);

/// The smallest base-circle radius with which the rise fits under the follower's limits (the
/// other limits as given), m; +∞ without a follower or beyond a millionfold of the given one.
double LeastBaseRadius(const SynthesisSpec& spec);

}  // namespace needle
