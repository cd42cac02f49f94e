#pragma once
/// @file
/// "Synthesize and verify a cam" as a library function: a synthesis file's rise law under its
/// derivative and geometry limits (lib/cam_synthesis.h, MATEC 2018), the fall mirrored when
/// asked, and the checks of its [checks] section evaluated on the result:
///
///     spring reserve   K(φ) = (P₀ + k·S)/(m·ω²·|S''|) ≥ K_min     where S'' < 0,
///     contact stress   σ_H(φ) = √(F·E*/(π·L·R*)) ≤ σ_max,   F = m·ω²·S'' + P₀ + k·S,
///     pressure angle   |φ_p| ≤ φ_max,   no undercut,
///
/// ω the cam's angular speed (half the crank's in a four-stroke engine), R* from the profile's
/// radius ρ and the roller's. The force balance is lib/rigid_train.h's. The command
/// (`needle synth`) only formats what this returns.

#include <optional>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "apps/case/case_writer.h"
#include "lib/cam_profile.h"
#include "lib/cam_synthesis.h"
#include "lib/result_fields.h"

namespace needle {

/// A largest (or least) value of a law and the cam angle where it falls.
struct LawExtreme {
  double value = 0.0;   ///< SI
  double at_rad = 0.0;  ///< cam angle, rad
};

/// What `needle synth` computes and checks. All SI; cam angles in rad.
struct SynthesisResult {
  SynthesisSpec spec;      ///< the limits the synthesis used
  SynthesizedLaw rise;     ///< the rise alone
  SynthesizedLaw law;      ///< the rise and, when [output] mirror_fall, its mirrored fall
  double cam_omega = 0.0;  ///< ω, cam rad/s, at [checks] speed_rpm
  LawExtreme max_s1, max_s2, min_s2, max_abs_s3;    ///< over the rise (S''' over every step)
  std::optional<CamProfile> profile;                ///< with [checks] base_radius
  std::optional<LawExtreme> min_spring_reserve;     ///< with a spring and a mass; +∞ if S'' ≥ 0
  std::optional<LawExtreme> max_contact_stress_Pa;  ///< with a contact length too
  bool pass = true;                                 ///< every check below holds
  std::vector<std::string> failing;                 ///< one line per failing check
};

/// Synthesizes and checks `f`. Throws CaseError naming the file and section when the limits
/// cannot be met (e.g. S'max·Φ < H).
SynthesisResult SynthesizeCam(const SynthesisFile& f);

/// The result's scalars, described once for the JSON and text writers.
std::vector<Field> SynthesisFields(const SynthesisResult& r);

/// The law as a table: cam_deg, S_mm, S1_mm_rad, S2_mm_rad2, S3_mm_rad3 (columns and SI rows).
std::vector<Column> SynthesisColumns();
std::vector<std::vector<double>> SynthesisRows(const SynthesizedLaw& law);

}  // namespace needle
