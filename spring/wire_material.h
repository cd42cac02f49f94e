#pragma once
/// @file
/// Spring wire by grade, and the fatigue strength of a helical spring made of it
/// (docs/model.md §7):
///
///     tensile strength   R_m(d) = A / d^m        (d in mm, R_m in MPa; A, m per grade)
///     torsional ultimate S_su = 0.67 R_m
///     Zimmerli's infinite-life strengths (any steel, wire below 10 mm, 10⁷ cycles and beyond):
///                        unpeened     S_sa = 35 kpsi (241 MPa) at S_sm = 55 kpsi (379 MPa)
///                        shot-peened  S_sa = 57.5 kpsi (396 MPa) at S_sm = 77.5 kpsi (534 MPa)
///     Goodman            S_se = S_sa / (1 − S_sm/S_su),   S_a = r S_se S_su / (r S_su + S_se)
///     Gerber             S_se = S_sa / (1 − (S_sm/S_su)²),
///                        S_a = r² S_su²/(2 S_se) · (−1 + √(1 + (2 S_se/(r S_su))²))
///     ASME-elliptic      S_se = S_sa / √(1 − (S_sm/S_sy)²),
///                        S_a = r S_se S_sy / √(S_se² + r² S_sy²),  S_sy = 0.45 S_ut
///     Sines              S_a = S_sa (the mean stress has no effect)
///     safety factor      n_f = S_a / τ_a  on the load line r = τ_a/τ_m through the origin
///     Bhandari           τ_m with K_s = 1 + 1/(2C), τ_a with Wahl's K; the line from
///                        A (S'se/2, S'se/2) to B (S_sy, 0), S'se = 0.22 S_ut, S_sy = 0.45 S_ut:
///                        1/n_f = (τ_a (S_sy − S'se/2)/(S'se/2) + τ_m) / S_sy
///
/// The A, m pairs are those of the ASTM wire each EN 10270 grade corresponds to (Budynas &
/// Nisbett, Shigley's Mechanical Engineering Design, 9th ed., Table 10-4): SH and DH (EN
/// 10270-1, patented cold-drawn) as music wire A228; VDC (EN 10270-2) as oil-tempered A229
/// (valve quality A230 has its strength); VDCrV as chrome-vanadium A232; VDSiCr as
/// chrome-silicon A401. S_su = 0.67 R_m and Zimmerli's strengths are that book's §10-8/10-9
/// (F. P. Zimmerli, "Human Failures in Spring Applications", The Mainspring 17, Associated
/// Spring Corp., 1957). The shear modulus is EN 13906-1's: 81.5 GPa for EN 10270-1 wire,
/// 79.5 GPa for EN 10270-2.

#include <optional>
#include <string>
#include <vector>

namespace needle {

/// Spring wire grades by EN name.
enum class WireGrade { kSH, kDH, kVDC, kVDCrV, kVDSiCr };

/// Every grade, in the name table's order.
const std::vector<WireGrade>& AllWireGrades();
/// "SH", "DH", "VDC", "VDCrV", "VDSiCr".
std::string WireGradeName(WireGrade g);
/// The grade of an EN name (exact spelling), or nullopt.
std::optional<WireGrade> ParseWireGrade(const std::string& name);
/// "SH, DH, VDC, VDCrV, VDSiCr" for messages.
std::string WireGradeList();

/// What the library knows of one grade.
struct WireGradeData {
  std::string standard;     ///< "EN 10270-1" or "EN 10270-2"
  std::string astm;         ///< the ASTM wire whose R_m(d) it uses
  double a_MPa_mm = 0.0;    ///< A of R_m = A / d^m, MPa·mm^m
  double m = 0.0;           ///< exponent m
  double min_wire_m = 0.0;  ///< the fit's diameter range, m
  double max_wire_m = 0.0;
  double shear_modulus_Pa = 0.0;  ///< G, Pa
};
const WireGradeData& GradeData(WireGrade g);

/// R_m(d) of grade `g` for wire diameter d (m), Pa. Throws std::invalid_argument naming the
/// grade, the diameter and the range when d is outside the fit's range.
double TensileStrengthPa(WireGrade g, double wire_m);

/// Zimmerli's infinite-life strength pair, Pa.
struct FatigueStrength {
  double amplitude_Pa = 0.0;  ///< S_sa
  double mean_Pa = 0.0;       ///< S_sm
};
/// Unpeened or shot-peened (Zimmerli).
FatigueStrength ZimmerliStrength(bool shot_peened);
/// Zimmerli's data cover wire below this diameter, m.
constexpr double kZimmerliMaxWire_m = 10e-3;

/// How a helical spring's fatigue is judged: the school's line through the spring's strengths
/// (the file comment's equations; docs/springs.md holds them in one table with their sources).
enum class FatigueCriterion { kGoodmanZimmerli, kGerber, kAsmeElliptic, kSines, kBhandari };

/// A criterion's name in a case file and outputs, its line and its source, for outputs and
/// docs/springs.md.
struct FatigueCriterionInfo {
  FatigueCriterion criterion;
  const char* name;      ///< "goodman-zimmerli", …
  const char* title;     ///< "Goodman", "Gerber", … (in rule names and text)
  const char* equation;  ///< the line and the factor, in the file comment's symbols
  const char* source;    ///< the book and section it is reproduced from
};
/// Every criterion, in the name table's order.
const std::vector<FatigueCriterionInfo>& AllFatigueCriteria();
const FatigueCriterionInfo& CriterionInfo(FatigueCriterion c);
/// The criterion of a case-file name (exact spelling), or nullopt.
std::optional<FatigueCriterion> ParseFatigueCriterion(const std::string& name);
/// "\"goodman-zimmerli\", … or \"bhandari\"" for messages.
std::string FatigueCriterionChoice();

/// Bhandari's pulsating endurance S'se and yield S_sy as fractions of S_ut: 0.22 and 0.45 for
/// oil-hardened and tempered wire (his Ex. 10.13 and 10.14), 0.21 and 0.42 for patented
/// cold-drawn wire (EN 10270-1 grades).
struct BhandariFractions {
  double endurance = 0.22;  ///< S'se / S_ut
  double yield = 0.45;      ///< S_sy / S_ut
};
BhandariFractions BhandariFractionsFor(std::optional<WireGrade> grade);

/// Shigley's torsional yield for the ASME-elliptic line, S_sy = 0.45 S_ut (Table 10-6: music
/// wire and cold-drawn carbon steel, set not removed; its hardened and tempered steels, the VD
/// grades' kind, have 50 %, so 0.45 is on the safe side for them; stainless 35 % is not covered).
constexpr double kAsmeYieldFraction = 0.45;

/// The fatigue check of a stress cycle: its mean τ_m and amplitude τ_a (corrected shear
/// stresses, Pa), by one criterion.
struct FatigueCheck {
  FatigueCriterion criterion = FatigueCriterion::kGoodmanZimmerli;
  double stress_amplitude_Pa = 0.0;    ///< τ_a
  double stress_mean_Pa = 0.0;         ///< τ_m
  double torsional_ultimate_Pa = 0.0;  ///< S_su = 0.67 R_m
  double yield_Pa = 0.0;               ///< S_sy (ASME-elliptic, Bhandari); 0 where unused
  /// Zimmerli's pair used (the Zimmerli criteria); Bhandari: his point A, (S'se/2, S'se/2).
  FatigueStrength strength;
  double endurance_Pa = 0.0;   ///< S_se at zero mean stress (Bhandari: S'se, pulsating)
  double limit_Pa = 0.0;       ///< S_a where the load line meets the criterion (Bhandari: n τ_a)
  double safety_factor = 0.0;  ///< n_f: the verdict's number
};

/// The check of a cycle of mean τ_m ≥ 0 and amplitude τ_a ≥ 0 (τ_m ≥ τ_a on one stress factor;
/// Bhandari's K_s/Wahl split may break that near zero preload) for a wire of tensile strength
/// `tensile_Pa` by `criterion`; `grade` picks Bhandari's fractions. On a Zimmerli line: +∞ when τ_a
/// = 0 (no alternating stress), 0 when the wire is weaker than Zimmerli's mean strength (no
/// endurance at all). Bhandari's line holds at τ_a = 0 too (S_sy/τ_m).
FatigueCheck CheckFatigue(FatigueCriterion criterion, double stress_mean_Pa,
                          double stress_amplitude_Pa, double tensile_Pa, bool shot_peened,
                          std::optional<WireGrade> grade = std::nullopt);

}  // namespace needle
