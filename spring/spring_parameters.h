#pragma once
/// @file
/// The spring module's own parameters: the moving parts reduced to the needle, the valve
/// spring with its sizing rule, and a helical spring's geometry and material. Every field has
/// a default; SI throughout. The case-file layer (apps/case/case_file.h) fills them from a
/// case's [needle] and [spring].

#include <optional>
#include <string>

#include "spring/wire_material.h"

namespace needle {

/// The moving parts reduced to the needle (a case's [needle]), SI.
struct NeedleParameters {
  double mass_kg = 0.0;  ///< moving mass m (needle, disks, lever, a third of the spring), > 0
  std::optional<double> diameter_m;  ///< needle diameter d (Basu's formula), > 0
  double gas_force_N = 0.0;          ///< constant gas force F_g, opening positive
  /// Where F_g comes from: "stated", "combustion pressure … on d", "Basu's 35 kg/cm² on d",
  /// or "none (no needle diameter)".
  std::string gas_source;

  /// The needle's rules, in one place: m > 0, d > 0 when given, F_g finite. Throws FieldError
  /// (lib/field_error.h) naming the field, its value and the rule.
  void Validate() const;
};

/// End type of a helical compression spring (EN 13906-1).
enum class SpringEnds { kClosedGround, kClosed, kOpenGround, kOpen };
/// The ends' name in a case file ("closed-ground", "closed", "open-ground", "open").
const char* SpringEndsName(SpringEnds ends);
/// The ends of a name, or nullopt.
std::optional<SpringEnds> ParseSpringEnds(const std::string& name);
/// The names, quoted, for messages.
std::string SpringEndsList();

/// The stress-correction factor k of τ = k · 8 F D/(π d³) (spring/helical_spring.h):
/// Bergsträsser, Wahl, or the direct-shear factor K_s = 1 + 1/(2w) alone.
enum class StressFactor { kBergstrasser, kWahl, kDirectShear };
/// The factor's name in a case file ("bergstrasser", "wahl", "direct-shear").
const char* StressFactorName(StressFactor f);
/// The factor of a name, or nullopt.
std::optional<StressFactor> ParseStressFactor(const std::string& name);
/// The names, quoted, for messages.
std::string StressFactorChoice();
/// The factor's title ("Bergstrasser", "Wahl", "direct-shear"), equation and source, for
/// outputs and docs/springs.md.
const char* StressFactorTitle(StressFactor f);
const char* StressFactorEquation(StressFactor f);
const char* StressFactorSource(StressFactor f);

/// Helical compression spring geometry and material, all SI.
struct HelicalGeometry {
  double wire_m = 0.0;             ///< wire diameter d
  double coil_m = 0.0;             ///< mean coil diameter D
  double active_coils = 0.0;       ///< n
  double free_length_m = 0.0;      ///< L0
  double shear_modulus_Pa = 0.0;   ///< G
  double density_kg_m3 = 7850.0;   ///< ρ
  double tensile_Pa = 0.0;         ///< tensile strength R_m (from `grade` when not stated)
  std::optional<WireGrade> grade;  ///< the wire's EN grade, when named
  bool shot_peened = false;        ///< Zimmerli's peened strengths instead of unpeened
  SpringEnds ends = SpringEnds::kClosedGround;
  StressFactor stress_factor = StressFactor::kBergstrasser;  ///< k of the shear stress
  /// How fatigue is judged (spring/wire_material.h).
  FatigueCriterion fatigue_criterion = FatigueCriterion::kGoodmanZimmerli;
  double allowable_fraction = 0.5;  ///< allowable shear stress as a fraction of R_m
};

/// The valve spring and the sizing rule (a case's [spring]), SI.
struct SpringParameters {
  double preload_N = 0.0;          ///< P0 at the seated position, ≥ 0
  std::optional<double> rate_N_m;  ///< k; from the geometry when absent
  double safety_factor = 1.5;      ///< S of the preload sizing, ≥ 1
  double overspeed_factor = 1.2;   ///< f: sizing speed f·n, ≥ 1
  /// How far the preload may fall below Basu's formula and pass, percent (spring_check.h).
  double basu_tolerance_percent = 10.0;
  std::optional<HelicalGeometry> helical;  ///< present when wire_mm etc. are given
  /// N of the spring in the dynamics, 1…40: 1 the massless rate k beside the moving mass (which
  /// includes a third of the spring); N > 1 a chain of N segments and coil masses (needs
  /// `helical`: the active coils' mass).
  int masses = 1;
  double surge_damping_ratio = 0.0;  ///< ζ of the first surge mode when masses > 1, in [0, 1]
  /// Coil clash in the dynamics (masses > 1): a segment past its travel to solid meets the
  /// next coils through a compliant contact of this stiffness (N/m, > 0; absent: the [train]
  /// contact's) and damping ratio (≥ 0; absent: the [train] contact's).
  bool coil_clash = false;
  std::optional<double> clash_stiffness_N_m;
  std::optional<double> clash_damping_ratio;

  /// The spring's rules, in one place: P₀ ≥ 0, k ≥ 0, S and f at least 1, the Basu tolerance in
  /// [0, 100] %, the surge and clash damping ratios in [0, 1], the clash stiffness > 0. Throws
  /// FieldError (lib/field_error.h) naming the field, its value and the rule. The helical
  /// geometry's own rules (the spring index, the coils) are checked where it is read.
  void Validate() const;
};

}  // namespace needle
