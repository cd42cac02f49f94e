#pragma once
/// @file
/// The synthesis specification `needle synth SPEC.toml` reads (synthesis_file.cc), in SI.

#include <optional>
#include <string>

#include "lib/cam_synthesis.h"
#include "lib/engine_cycle.h"
#include "lib/follower.h"

namespace needle {

/// A synthesis specification (`needle synth SPEC.toml`): [rise] angle_deg, lift_mm, step_deg;
/// [limits] speed_mm_rad, acceleration_mm_rad2, deceleration_mm_rad2, jerk_mm_rad3;
/// [checks] base_radius_mm, roller_radius_mm, offset_mm, max_pressure_angle_deg,
/// min_profile_radius_mm (the last two steer every step; offset must then be 0);
/// [output] fall = "mirror" | "none", crank_start_deg, speed_rpm, cycle (for --case).
struct SynthesisFile {
  std::string path, title;
  /// [rise] and [limits], read straight into the synthesis' own spec (lib/cam_synthesis.h: Φ,
  /// H, the step, S'max, a⁺, a⁻, j); its follower, caps, train and ω stay unset here (the
  /// synthesis scene sets them from [checks] and [output], SpecOf).
  SynthesisSpec rise;
  /// [checks] follower and its shape keys (roller_radius, face_radius, face_half_width: 0 where
  /// not given; a face's half-width caps S' (flat) or φ (curved)). Its own base_radius_m and
  /// offset_m stay 0: the file's are base_radius_m and offset_m below (FollowerOf joins them).
  FollowerGeometry follower;
  std::optional<double> base_radius_m;
  /// Lubrication: the least entrainment velocity at [output] speed_rpm, m/s (steers S'').
  std::optional<double> min_entrainment_m_s;
  double offset_m = 0.0;
  std::optional<double> max_pressure_angle_rad;
  std::optional<double> min_profile_radius_m;  ///< steer S'' so the profile keeps this radius
  /// Spring reserve (steers S'' on the decelerating side) and contact stress (checked):
  std::optional<double> spring_preload_N, spring_rate_N_m, moving_mass_kg, min_spring_reserve;
  std::optional<double> contact_length_m;  ///< roller width in contact, for Hertz stress
  double elastic_modulus_Pa = 210e9, poisson = 0.3;
  std::optional<double> max_contact_stress_Pa;

  bool mirror_fall = true;
  double crank_start_rad = 0.0;
  double speed_rpm = 1000.0;
  EngineCycle cycle = EngineCycle::kFourStroke;
};
SynthesisFile LoadSynthesisFile(const std::string& path);
/// The same from text; `path` names it in messages.
SynthesisFile ParseSynthesisFile(const std::string& text, const std::string& path);

}  // namespace needle
