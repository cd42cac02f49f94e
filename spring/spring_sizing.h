#pragma once
/// @file
/// Sizing a helical compression spring (issue 35): the best spring of a discrete space of
/// wires, mean coil diameters and active coil counts that passes every closed-form rule of the
/// spring check, each evaluated by the check's own code (spring/helical_spring.h's
/// CheckHelicalSpring for the rate, stresses, lengths, gaps, surge and fatigue; the caller's
/// preload rule, for a valve spring spring/quasi_static.h's RequiredPreloadN with the combustion
/// load and Basu's formula). For each candidate (wire, D, n):
///
///     rate       k = G d⁴/(8 D³ n);  active mass m_s = ρ π² d² D n/4;  total coils n_t (ends)
///     preload    P₀ = the least the duty accepts for (k, m_s), rounded up to 0.1 N
///     installed  L₁ = max(L₁,min, L_c + h + gap) (the shortest that keeps the gap at full lift
///                h); L₀ = L₁ + P₀/k rounded up to the free-length step, L₁ = L₀ − P₀/k ≤ L₁,max
///     rules      gap at full lift ≥ S_a (or the stated gap), f_e/f_cam ≥ the surge ratio, τ at
///                full lift ≤ the allowable, the criterion's n_f ≥ the fatigue factor (where
///                judged), no buckling at full lift (EN 13906-1, end-fixation factor ν)
///     objective  least mass ρ π² d² D n_t/4 (default), least installed length, least shear
///                stress at full lift, or least outer diameter D + d; ties broken by mass, then
///                wire, D, n.
///     stated rate  (SizingDuty::rate_N_m, a textbook's load pair over its stroke) n is not
///                searched: each (wire, D) takes the fewest coils whose rate is at most it.
///
/// The search: the (wire, D) groups in the order of a lower bound of the objective (its value at
/// the fewest coils), stopping when the bound exceeds the `keep`-th best group found; inside a
/// group, coil counts upward, stopping where the surge ratio or the length needed already fails
/// (both only worsen with more coils) and, for the mass, at the first spring that passes (mass
/// grows with n). Its answer is the exhaustive search's (SizingOptions::exhaustive).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lib/engine_cycle.h"
#include "spring/helical_spring.h"
#include "spring/spring_parameters.h"
#include "spring/verdict_row.h"
#include "spring/wire_material.h"

namespace needle {

/// ISO 3's R40 series of preferred numbers, one decade: 1.00, 1.06, …, 9.50.
const std::vector<double>& R40PreferredNumbers();
/// The R40 preferred sizes in [lo_m, hi_m] (decades scaled), m, ascending.
std::vector<double> PreferredWireDiameters(double lo_m, double hi_m);

/// One wire the spring may be wound from.
struct SizingWire {
  std::string label;                  ///< "VDSiCr", "case wire", …
  std::optional<WireGrade> grade;     ///< when a grade of the table
  double wire_m = 0.0;                ///< d
  double tensile_Pa = 0.0;            ///< R_m at this diameter
  double shear_modulus_Pa = 0.0;      ///< G
  double elastic_modulus_Pa = 206e9;  ///< E (buckling), EN 13906-1's 206 GPa for spring steel
  double density_kg_m3 = 7850.0;
};

/// What may be chosen and what must fit. SI.
struct SizingSpace {
  std::vector<SizingWire> wires;
  double min_index = 4.0, max_index = 20.0;  ///< D/d (EN 13906-1: 4…20)
  double coil_step_m = 0.5e-3;               ///< D on the multiples of this step
  double min_active_coils = 2.0, max_active_coils = 30.0, active_coil_step = 0.5;
  std::optional<double> max_outer_m;  ///< D + d at most
  std::optional<double> min_inner_m;  ///< D − d at least (over the needle guide)
  double min_installed_m = 0.0;       ///< L₁, the length at the seated preload, at least
  double max_installed_m = 1e9;       ///< … and at most
  double free_length_step_m = 1e-4;   ///< L₀ rounded up to this (0: not rounded)
  SpringEnds ends = SpringEnds::kClosedGround;
  StressFactor stress_factor = StressFactor::kBergstrasser;
  FatigueCriterion fatigue_criterion = FatigueCriterion::kGoodmanZimmerli;
  bool shot_peened = false;
  double allowable_fraction = 0.5;  ///< allowable shear stress / R_m
  double end_fixation = 0.5;        ///< ν of EN 13906-1's buckling (0.5: both ends fixed)
};

/// The least preload a spring of rate k and active coil mass m_s may have, and the rule that
/// sets it (for the output: "inertia sizing", "Basu's formula", "combustion load").
struct PreloadNeed {
  double preload_N = 0.0;
  std::string rule;
  /// When the preload is stated (a textbook's P₁): the least the duty's own rules ask, and that
  /// rule; the sizing judges the stated preload against it.
  std::optional<double> required_N;
  std::string required_rule;
};

/// What the spring must do.
struct SizingDuty {
  double stroke_m = 0.0;   ///< h, the deflection from seated to full lift
  double speed_rpm = 0.0;  ///< rated speed for the surge ratio; 0: no surge rule
  EngineCycle cycle = EngineCycle::kFourStroke;  ///< the crank-to-cam rule
  /// The least preload for (rate N/m, active coil mass kg).
  std::function<PreloadNeed(double, double)> preload;
  /// A preload below every `preload` answer (known without the rate: S·F_g, Basu's formula less
  /// its tolerance), N. A spring that fails the stress or fatigue rule at it fails them at its
  /// own preload too (both only worsen as P₀ grows with τ_a fixed), so the search screens with
  /// it before asking `preload`.
  double preload_floor_N = 0.0;
  double min_fatigue_factor = 1.0;  ///< the criterion's n_f at least (where judged)
  /// A stated rate, N/m: each (wire, D) takes the fewest coils on the space's steps whose rate
  /// is at most this (a textbook design's P₁ → P₂ over the stroke); absent: every count.
  std::optional<double> rate_N_m;
  /// A textbook's load pair (both or neither): the spring is judged deflected to P₂, by
  /// max(stroke, (P₂ − P₁)/k), where its rounded rate reaches less over the stroke; P₁ is the
  /// preload `preload` returns.
  std::optional<double> closed_load_N, open_load_N;
  std::optional<double> min_gap_m;          ///< gap at full lift at least; absent: S_a
  double min_surge_ratio = kMinSurgeRatio;  ///< f_e/f_cam at least
  bool buckling = true;                     ///< judge buckling
};

enum class SizingObjective { kMass, kHeight, kStress, kDiameter };
/// "mass", "height", "stress", "diameter" (least outer diameter D + d, in mm).
std::string SizingObjectiveName(SizingObjective o);

/// One rule judged on a candidate, in display units: the check's verdict row
/// (spring/verdict_row.h), judged pass or fail.
using SizingRule = VerdictRow;

/// A candidate spring and what the rules said.
struct SizedSpring {
  int wire_index = 0;        ///< into SizingSpace::wires
  HelicalGeometry geometry;  ///< d, D, n, L₀, G, ρ, R_m, ends, correction, peening
  double preload_N = 0.0;    ///< P₀
  std::string preload_rule;  ///< the rule that set it
  double installed_m = 0.0;  ///< L₁ = L₀ − P₀/k
  double rate_N_m = 0.0;
  double total_coils = 0.0;
  double mass_kg = 0.0;         ///< all coils, ρ π² d² D n_t/4
  double active_mass_kg = 0.0;  ///< m_s
  double buckling_m = 0.0;      ///< EN 13906-1's buckling deflection s_K; +∞ when none
  std::optional<HelicalSpringCheck> check;  ///< the check's helical verdict (when evaluated)
  std::vector<SizingRule> rules;            ///< the rules judged, in order
  bool pass = false;
  double objective = 0.0;
};

/// A spring as fields (lib/result_fields.h): its wire's label, d, D (mm), active and total
/// coils, free and installed length (mm), preload (N) and the rule that set it, rate (N/mm),
/// mass (kg), whether it passes, and its fatigue factor n_f when checked (none if infinite).
std::vector<Field> SizedSpringFields(const SizedSpring& s, const SizingSpace& space);

/// A rule of a spring as fields: its key and unit, value, limit, direction, margin (none when
/// not finite) and verdict.
std::vector<Field> SizingRuleFields(const SizingRule& rule);

/// Orders by objective, then mass, wire, D, n: true when a is better than b.
bool BetterSpring(const SizedSpring& a, const SizedSpring& b);

struct SizingOptions {
  SizingObjective objective = SizingObjective::kMass;
  int keep = 5;             ///< the best springs kept, one per (wire, D) group
  bool exhaustive = false;  ///< evaluate every candidate fully (the reference answer)
  /// Also scan the whole space for the front between mass and fatigue safety factor (every
  /// passing spring, not only the kept ones).
  bool front = false;
};

struct SizingResult {
  std::vector<SizedSpring> best;  ///< passing, best first, one per (wire, D); at most keep
  long candidates = 0;            ///< springs in the space (wire × D × n)
  long groups = 0;                ///< (wire, D) groups
  /// (wire, D) groups left out because no coil count of the space gives the stated rate.
  long rate_misses = 0;
  long evaluated = 0;  ///< springs the rules were evaluated on
  long passed = 0;     ///< of those, springs that passed every rule
  /// When nothing passes: the candidate whose worst rule fails least (evaluated fully), and
  /// that rule; absent when the space is empty.
  std::optional<SizedSpring> closest;
  std::optional<SizingRule> binding;
  /// With SizingOptions::front: the front between mass and fatigue factor over every passing
  /// spring of the space (MassFatigueFront), and the springs that scan evaluated.
  std::vector<SizedSpring> front;
  long front_evaluated = 0;
};

/// Evaluates one candidate: (wire, D, n); all rules when `full`, else up to the first that
/// fails. Throws std::invalid_argument on an index out of range.
SizedSpring EvaluateSpring(const SizingSpace& space, const SizingDuty& duty, int wire_index,
                           double coil_m, double active_coils, SizingObjective objective,
                           bool full);

/// The search (file comment). Throws std::invalid_argument when the space has no wire or the
/// duty no preload rule.
SizingResult SizeSpring(const SizingSpace& space, const SizingDuty& duty,
                        const SizingOptions& options = {});

/// The mass of `coils` coils of `g`'s wire, ρ π² d² D n / 4, kg.
double CoilMassKg(const HelicalGeometry& g, double coils);

/// Springs of `springs` on the front between mass and fatigue safety factor: none lighter has
/// a factor as high. Lightest first; springs whose fatigue is not judged (Zimmerli's data:
/// wire of 10 mm or more) have no factor and are left out.
std::vector<SizedSpring> MassFatigueFront(const std::vector<SizedSpring>& springs);

}  // namespace needle
