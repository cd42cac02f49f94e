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
///     safety factor      n_f = S_a / τ_a  on the load line r = τ_a/τ_m through the origin
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

/// The fatigue check of a stress cycle τ_min → τ_max (corrected shear stresses, Pa).
struct FatigueCheck {
  double stress_amplitude_Pa = 0.0;    ///< τ_a = (τ_max − τ_min)/2
  double stress_mean_Pa = 0.0;         ///< τ_m = (τ_max + τ_min)/2
  double torsional_ultimate_Pa = 0.0;  ///< S_su = 0.67 R_m
  FatigueStrength strength;            ///< Zimmerli's pair used
  double goodman_endurance_Pa = 0.0;   ///< S_se (Goodman)
  double goodman_limit_Pa = 0.0;       ///< S_a on the load line (Goodman)
  double goodman_safety_factor = 0.0;  ///< n_f = S_a/τ_a (Goodman): the verdict's number
  double gerber_safety_factor = 0.0;   ///< n_f (Gerber), for comparison
};

/// The check of τ_min → τ_max (0 ≤ τ_min < τ_max) for a wire of tensile strength `tensile_Pa`;
/// +∞ safety factors when τ_max = τ_min (no alternating stress).
FatigueCheck CheckFatigue(double stress_min_Pa, double stress_max_Pa, double tensile_Pa,
                          bool shot_peened);

}  // namespace needle
