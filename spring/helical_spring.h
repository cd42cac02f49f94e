#pragma once
/// @file
/// Check of a helical compression valve spring (EN 13906-1 where it speaks):
///
///     rate            R = G d⁴ / (8 D³ n)
///     index           w = D/d, 4 ≤ w ≤ 20
///     shear stress    τ = k · 8 F D / (π d³),
///                     k = (w + 0.5)/(w − 0.75) (Bergsträsser), (4w − 1)/(4w − 4) + 0.615/w
///                     (Wahl) or 1 + 1/(2w) (direct shear only)
///     solid length    L_c = n_t d (closed, ground), (n_t + 1.5) d (closed), (n + 1) d (open),
///                     (n + 1) d with n_t = n + 1 (open, ground); n_t = n + 2 for closed ends
///     minimum gaps    S_a = (0.0015 D²/d + 0.1 d) n at the largest deflection
///     surge           f_e = d/(2π n D²) · √(G/(2ρ))   (fixed at both ends, first mode)
///     cam frequency   f_cam = n_rpm/120 (four-stroke), n_rpm/60 (two-stroke)
///
///     fatigue         τ_min = τ(P₀), τ_max = τ(P₀ + R h_max), judged by the spring's
///                     criterion (spring/wire_material.h; Goodman with Zimmerli's strengths by
///                     default), n_f = S_a/τ_a
///
/// Passes when τ at full lift ≤ allowable fraction · R_m, the gaps at full lift ≥ S_a,
/// f_e/f_cam ≥ 13, and n_f ≥ 1 (the working stroke inside the criterion's line) where its data
/// apply (Zimmerli's: wire below 10 mm, beyond which fatigue is not judged and says so;
/// Bhandari's line: any wire).

#include "lib/engine_cycle.h"
#include "lib/result_fields.h"
#include "spring/spring_parameters.h"
#include "spring/wire_material.h"

namespace needle {

/// The surge ratio a valve spring must reach (f_e / f_cam).
constexpr double kMinSurgeRatio = 13.0;

struct HelicalSpringCheck {
  double rate_N_m = 0.0;
  double index = 0.0;              ///< w = D/d
  double correction_factor = 0.0;  ///< k (Bergsträsser, Wahl or direct shear)
  StressFactor stress_factor = StressFactor::kBergstrasser;
  double stress_preload_Pa = 0.0;
  double stress_full_lift_Pa = 0.0;
  double allowable_stress_Pa = 0.0;
  double total_coils = 0.0;
  double solid_length_m = 0.0;
  double length_preload_m = 0.0;       ///< L0 − P0/R
  double length_full_lift_m = 0.0;     ///< L0 − P0/R − h_max
  double clearance_full_lift_m = 0.0;  ///< length at full lift − L_c
  double min_clearance_m = 0.0;        ///< S_a
  double surge_hz = 0.0;
  double cam_hz = 0.0;
  double surge_ratio = 0.0;
  /// The working stroke's fatigue check by the spring's criterion.
  FatigueCheck fatigue;
  bool fatigue_judged = false;  ///< Bhandari's line, or wire below kZimmerliMaxWire_m
  bool stress_ok = false, clearance_ok = false, surge_ok = false;
  bool fatigue_ok = true;  ///< n_f ≥ 1 (true when not judged)
  bool pass() const { return stress_ok && clearance_ok && surge_ok && fatigue_ok; }
};

/// The check as fields (lib/result_fields.h): rate (N/mm), index, correction and its factor,
/// the stresses (MPa), coils, lengths and clearances (mm), surge and cam (Hz) and their ratio,
/// the fatigue criterion and factor n_f (none where not judged, or unbounded), each sub-verdict
/// and the whole.
std::vector<Field> HelicalFields(const HelicalSpringCheck& h);

/// The rate R = G d⁴ / (8 D³ n) of `g`, N/m.
double HelicalRate(const HelicalGeometry& g);

/// Stress-correction factor k for index w (> 0.75) by `factor`.
double StressCorrection(double index, StressFactor factor);

/// The fatigue check of `g` cycled between force_min_N and force_max_N by its criterion: the
/// mean and amplitude stresses with its stress factor (Bhandari: K_s on the mean, Wahl's on
/// the amplitude, whatever the case's factor).
FatigueCheck SpringFatigue(const HelicalGeometry& g, double index, double force_min_N,
                           double force_max_N);

/// EN 13906-1's buckling deflection of `g` (free length L₀, mean diameter D) of elastic modulus E
/// with end-fixation factor ν (0.5 both ends fixed and guided parallel, 1 both hinged, 2 one end
/// free), m:
///
///     s_K = L₀ · 0.5/(1 − G/E) · [1 − √(1 − (1 − G/E)/(0.5 + G/E) · (π D/(ν L₀))²)];
///
/// +∞ when the root is imaginary: the spring does not buckle at any deflection.
double BucklingDeflection(const HelicalGeometry& g, double elastic_modulus_Pa, double end_fixation);

/// docs/springs.md's table of the conventions a case may choose, generated here so that it
/// cannot drift: each fatigue criterion ([spring] fatigue_criterion) and stress factor
/// (stress_correction) with its equation and source. A test holds the docs equal to it.
std::string SpringConventionsMarkdown();

/// Checks `g` carrying `preload_N` at the seat and preload + R·max_lift at full lift.
/// speed_rpm and `cycle` set the cam frequency. Throws std::invalid_argument when the
/// preload already compresses the spring beyond its free length.
HelicalSpringCheck CheckHelicalSpring(const HelicalGeometry& g, double preload_N, double max_lift_m,
                                      double speed_rpm, EngineCycle cycle);

}  // namespace needle
