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

#include <optional>
#include <string>
#include <vector>

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
  /// Limits that depend on the cam and follower, applied at every step as caps on S' and
  /// S'' (radial roller follower: offset 0). Active when base_radius_m > 0.
  double base_radius_m = 0.0;           ///< r_b
  double roller_radius_m = 0.0;         ///< r_r
  double max_pressure_angle_rad = 0.0;  ///< φmax > 0: S' ≤ (r_b + r_r + S)·tan φmax
  /// ρmin ≥ 0: on convex stretches (S'' < 0) the pitch radius (R² + S'²)^{3/2}/(R² + 2S'² − R S'')
  /// with R = r_b + r_r + S stays ≥ r_r + ρmin, so the profile keeps a radius of at least ρmin
  /// (no undercut). Negative: no curvature limit.
  double min_profile_radius_m = -1.0;
  /// Spring reserve K > 0: on the decelerating side the spring force must stay K times the
  /// inertia force, F_spring(S) ≥ K·m·ω²·|S''| (lib/rigid_train.h), a cap
  /// |S''| ≤ F_spring(S)/(K·m·ω²). Needs the train (mass, preload, rate; its gas load is
  /// counted too) and the cam speed ω. 0: no such limit.
  double min_spring_reserve = 0.0;
  RigidTrain train;        ///< the moving mass and the spring, used with min_spring_reserve
  double cam_omega = 0.0;  ///< cam angular speed ω, rad/s, > 0 with min_spring_reserve
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

}  // namespace needle
