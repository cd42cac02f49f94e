#include "spring/helical_spring.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/name_table.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {
namespace {

// The one name table of the ends.
constexpr NameRow<SpringEnds> kEndsNames[] = {
    {SpringEnds::kClosedGround, "closed-ground"},
    {SpringEnds::kClosed, "closed"},
    {SpringEnds::kOpenGround, "open-ground"},
    {SpringEnds::kOpen, "open"},
};

// The one name table of the stress factors, with their equations and sources.
constexpr NameRow<StressFactor> kFactorNames[] = {
    {StressFactor::kBergstrasser, "bergstrasser"},
    {StressFactor::kWahl, "wahl"},
    {StressFactor::kDirectShear, "direct-shear"},
};
struct FactorText {
  StressFactor factor;
  const char* title;
  const char* equation;
  const char* source;
};
constexpr FactorText kFactorTexts[] = {
    {StressFactor::kBergstrasser, "Bergstrasser", "k = (w + 0.5)/(w - 0.75)",
     "EN 13906-1 (Bergstrasser)"},
    {StressFactor::kWahl, "Wahl", "k = (4w - 1)/(4w - 4) + 0.615/w",
     "A. M. Wahl, Mechanical Springs (1963); Shigley 9th ed. eq. 10-4; Bhandari ch. 10"},
    {StressFactor::kDirectShear, "direct-shear", "K_s = 1 + 1/(2w)",
     "direct shear only: Shigley 9th ed. eq. 10-2 (static loads); Khurmi & Gupta ch. 23; "
     "Bhandari's K_s"},
};
const FactorText& TextOf(StressFactor f) {
  for (const FactorText& t : kFactorTexts)
    if (t.factor == f) return t;
  return kFactorTexts[0];
}

}  // namespace

const char* StressFactorName(StressFactor f) { return NameOf(kFactorNames, f); }
std::optional<StressFactor> ParseStressFactor(const std::string& name) {
  return ValueOf(kFactorNames, name);
}
std::string StressFactorChoice() { return NameChoice(kFactorNames); }
const char* StressFactorTitle(StressFactor f) { return TextOf(f).title; }
const char* StressFactorEquation(StressFactor f) { return TextOf(f).equation; }
const char* StressFactorSource(StressFactor f) { return TextOf(f).source; }

const char* SpringEndsName(SpringEnds ends) { return NameOf(kEndsNames, ends); }

std::optional<SpringEnds> ParseSpringEnds(const std::string& name) {
  return ValueOf(kEndsNames, name);
}

std::string SpringEndsList() { return NameChoice(kEndsNames); }

double HelicalRate(const HelicalGeometry& g) {
  return g.shear_modulus_Pa * std::pow(g.wire_m, 4) /
         (8.0 * std::pow(g.coil_m, 3) * g.active_coils);  // G d⁴/(8D³n)
}

double StressCorrection(double w, StressFactor f) {
  switch (f) {
    case StressFactor::kWahl:
      return (4.0 * w - 1.0) / (4.0 * w - 4.0) + 0.615 / w;
    case StressFactor::kDirectShear:
      return 1.0 + 0.5 / w;  // K_s = 1 + 1/(2w)
    case StressFactor::kBergstrasser:
      break;
  }
  return (w + 0.5) / (w - 0.75);
}

double BucklingDeflection(const HelicalGeometry& g, double elastic_modulus_Pa,
                          double end_fixation) {
  const double q = g.shear_modulus_Pa / elastic_modulus_Pa;  // G/E
  const double slender = kPi * g.coil_m / (end_fixation * g.free_length_m);
  const double radicand = 1.0 - (1.0 - q) / (0.5 + q) * slender * slender;
  if (!(radicand >= 0.0)) return INFINITY;
  return g.free_length_m * 0.5 / (1.0 - q) * (1.0 - std::sqrt(radicand));
}

FatigueCheck SpringFatigue(const HelicalGeometry& g, double index, double force_min_N,
                           double force_max_N) {
  const bool bhandari = g.fatigue_criterion == FatigueCriterion::kBhandari;
  // τ = k·8FD/(πd³) at both ends of the stroke, with the mean's and the amplitude's k.
  const auto stress = [&](StressFactor f, double force_N) {
    const double d = g.wire_m;
    return StressCorrection(index, f) * 8.0 * g.coil_m / (kPi * d * d * d) * force_N;
  };
  const StressFactor k_mean = bhandari ? StressFactor::kDirectShear : g.stress_factor;
  const StressFactor k_amplitude = bhandari ? StressFactor::kWahl : g.stress_factor;
  const double mean = 0.5 * (stress(k_mean, force_max_N) + stress(k_mean, force_min_N));
  const double amplitude =
      0.5 * (stress(k_amplitude, force_max_N) - stress(k_amplitude, force_min_N));
  return CheckFatigue(g.fatigue_criterion, mean, amplitude, g.tensile_Pa, g.shot_peened, g.grade);
}

HelicalSpringCheck CheckHelicalSpring(const HelicalGeometry& g, double preload_N, double max_lift_m,
                                      double speed_rpm, EngineCycle cycle) {
  HelicalSpringCheck c;
  const double d = g.wire_m, D = g.coil_m, n = g.active_coils;
  c.rate_N_m = HelicalRate(g);
  c.index = D / d;
  c.stress_factor = g.stress_factor;
  c.correction_factor = StressCorrection(c.index, g.stress_factor);
  const double tau_per_N = c.correction_factor * 8.0 * D / (kPi * d * d * d);  // k·8D/(πd³)
  c.stress_preload_Pa = tau_per_N * preload_N;
  c.stress_full_lift_Pa = tau_per_N * (preload_N + c.rate_N_m * max_lift_m);
  c.allowable_stress_Pa = g.allowable_fraction * g.tensile_Pa;
  switch (g.ends) {
    case SpringEnds::kClosedGround:
      c.total_coils = n + 2.0;
      c.solid_length_m = c.total_coils * d;
      break;
    case SpringEnds::kClosed:
      c.total_coils = n + 2.0;
      c.solid_length_m = (c.total_coils + 1.5) * d;
      break;
    case SpringEnds::kOpenGround:
      c.total_coils = n + 1.0;
      c.solid_length_m = c.total_coils * d;
      break;
    case SpringEnds::kOpen:
      c.total_coils = n;
      c.solid_length_m = (n + 1.0) * d;
      break;
  }
  const double preload_deflection = preload_N / c.rate_N_m;
  if (preload_deflection >= g.free_length_m - c.solid_length_m) {
    throw std::invalid_argument(
        "the preload compresses the spring to solid or beyond: preload deflection " +
        std::to_string(preload_deflection * 1e3) + " mm, free length " +
        std::to_string(g.free_length_m * 1e3) + " mm, solid length " +
        std::to_string(c.solid_length_m * 1e3) + " mm; use a longer spring or fewer coils");
  }
  c.length_preload_m = g.free_length_m - preload_deflection;
  c.length_full_lift_m = c.length_preload_m - max_lift_m;
  c.clearance_full_lift_m = c.length_full_lift_m - c.solid_length_m;
  c.min_clearance_m = (0.0015 * D * D / d + 0.1 * d) * n;  // S_a = (0.0015 D²/d + 0.1 d) n
  c.surge_hz =
      d / (2.0 * kPi * n * D * D) * std::sqrt(g.shear_modulus_Pa / (2.0 * g.density_kg_m3));
  c.cam_hz = speed_rpm / (60.0 * CrankTurnsPerCycle(cycle));
  c.surge_ratio = c.surge_hz / c.cam_hz;
  c.stress_ok = c.stress_full_lift_Pa <= c.allowable_stress_Pa;
  c.clearance_ok = c.clearance_full_lift_m >= c.min_clearance_m;
  c.surge_ok = c.surge_ratio >= kMinSurgeRatio;
  c.fatigue = SpringFatigue(g, c.index, preload_N, preload_N + c.rate_N_m * max_lift_m);
  c.fatigue_judged = g.fatigue_criterion == FatigueCriterion::kBhandari || d < kZimmerliMaxWire_m;
  c.fatigue_ok = !c.fatigue_judged || c.fatigue.safety_factor >= 1.0;
  return c;
}

std::vector<Field> HelicalFields(const HelicalSpringCheck& h) {
  using namespace display;
  return {
      {"rate", kNPerMm, h.rate_N_m, 2},
      {"index", kNone, h.index, 2},
      TextField("stress_correction", StressFactorName(h.stress_factor)),
      {"correction_factor", kNone, h.correction_factor, 3},
      {"stress_preload", kMPa, h.stress_preload_Pa, 0},
      {"stress_full_lift", kMPa, h.stress_full_lift_Pa, 0},
      {"allowable_stress", kMPa, h.allowable_stress_Pa, 0},
      {"total_coils", kNone, h.total_coils, 1},
      {"solid_length", kMm, h.solid_length_m, 1},
      {"length_preload", kMm, h.length_preload_m, 1},
      {"length_full_lift", kMm, h.length_full_lift_m, 1},
      {"clearance_full_lift", kMm, h.clearance_full_lift_m, 2},
      {"min_clearance", kMm, h.min_clearance_m, 2},
      {"surge", kHz, h.surge_hz, 1},
      {"cam", kHz, h.cam_hz, 3},
      {"surge_ratio", kNone, h.surge_ratio, DecimalsApart(h.surge_ratio, kMinSurgeRatio, 1)},
      TextField("stress_correction_source", StressFactorSource(h.stress_factor)),
      TextField("fatigue_criterion", CriterionInfo(h.fatigue.criterion).name),
      TextField("fatigue_source", CriterionInfo(h.fatigue.criterion).source),
      {"fatigue_safety_factor", kNone,
       h.fatigue_judged ? FiniteOrNone(h.fatigue.safety_factor) : std::nullopt, 2},
      FlagField("stress_ok", h.stress_ok),
      FlagField("clearance_ok", h.clearance_ok),
      FlagField("surge_ok", h.surge_ok),
      FlagField("fatigue_judged", h.fatigue_judged),
      FlagField("fatigue_ok", h.fatigue_ok),
      FlagField("pass", h.pass()),
  };
}

std::string SpringConventionsMarkdown() {
  std::string md = "| key | value | equation | source |\n|---|---|---|---|\n";
  for (const FatigueCriterionInfo& c : AllFatigueCriteria()) {
    md += std::string("| `fatigue_criterion` | `\"") + c.name + "\"`" +
          (c.criterion == FatigueCriterion::kGoodmanZimmerli ? " (default)" : "") + " | " +
          c.equation + " | " + c.source + " |\n";
  }
  for (const NameRow<StressFactor>& row : kFactorNames) {
    md += std::string("| `stress_correction` | `\"") + row.name + "\"`" +
          (row.value == StressFactor::kBergstrasser ? " (default)" : "") + " | " +
          StressFactorEquation(row.value) + " | " + StressFactorSource(row.value) + " |\n";
  }
  return md;
}

}  // namespace needle
