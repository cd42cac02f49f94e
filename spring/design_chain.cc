#include "spring/design_chain.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/units.h"
#include "spring/basu_formula.h"

namespace needle {
namespace {

constexpr double kTwoR = 0.354;   // 2r/h = 0.924 · 0.3827
constexpr double kBeta = 0.3827;  // β/h = sin 22.5°
constexpr double kAtm = 101325.0;

std::string Mm(double m) { return std::to_string(m * 1e3); }

}  // namespace

double SeatCrossSection(double h, double d) {
  if (!(d > 0.0))
    throw std::invalid_argument("cross-section curve: the passage diameter must be positive, got " +
                                Mm(d) + " mm");
  if (!(h >= 0.0))
    throw std::invalid_argument("cross-section curve: the lift must not be negative, got " + Mm(h) +
                                " mm");
  const double crest = d / (2.0 * kTwoR);  // dq/dh = 0
  if (h > crest) {
    throw std::invalid_argument("cross-section curve: a lift of " + Mm(h) +
                                " mm is beyond the curve for d = " + Mm(d) +
                                " mm (it covers lifts up to " + Mm(crest) + " mm)");
  }
  return (d - kTwoR * h) * kPi * kBeta * h;  // q = (d − 0.354h)·π·0.3827h
}

double LiftForCrossSection(double q, double d) {
  if (!(d > 0.0))
    throw std::invalid_argument("cross-section curve: the passage diameter must be positive");
  if (!(q >= 0.0))
    throw std::invalid_argument("cross-section curve: the cross-section must not be negative");
  // 0.354·π·0.3827 h² − π·0.3827 d h + q = 0, rising root.
  const double a = kTwoR * kPi * kBeta, b = -kPi * kBeta * d;
  const double disc = b * b - 4.0 * a * q;
  if (disc < 0.0) {
    throw std::invalid_argument("cross-section curve: " + std::to_string(q * 1e6) +
                                " mm² exceeds the largest cross-section of d = " + Mm(d) + " mm (" +
                                std::to_string(b * b / (4.0 * a) * 1e6) + " mm²)");
  }
  return (-b - std::sqrt(disc)) / (2.0 * a);
}

double BasuMixingRatio(double n) {
  // Least squares through (125, 15), (300, 21.5), (400, 25).
  const double xs[3] = {125, 300, 400}, ys[3] = {15.0, 21.5, 25.0};
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < 3; ++i) {
    sx += xs[i];
    sy += ys[i];
    sxx += xs[i] * xs[i];
    sxy += xs[i] * ys[i];
  }
  const double slope = (3 * sxy - sx * sy) / (3 * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / 3.0;
  return intercept + slope * n;
}

double OutflowVelocity(double phi, double temperature_K, double r) {
  if (!(r > 0.0 && r < 1.0)) {
    throw std::invalid_argument(
        "outflow velocity: the pressure ratio p0/p1 must be in (0, 1), got " + std::to_string(r));
  }
  return 44.8 * phi * std::sqrt(temperature_K * (1.0 - std::pow(r, 0.286)));  // w₀
}

DesignResult RunDesignChain(const DesignInputs& in) {
  DesignResult r;
  const double n = in.speed_rpm;
  const double hp = in.power_W / 735.49875;
  const double cycles_per_rev = 1.0 / CrankTurnsPerCycle(in.cycle);
  r.fuel_per_cycle_g = hp * in.fuel_g_hp_h / (60.0 * n * cycles_per_rev);      // N_i b c/(60 n)
  r.fuel_per_cycle_cm3 = r.fuel_per_cycle_g / (in.fuel_density_kg_m3 * 1e-3);  // G/γ
  r.mixing_ratio_from_line = !in.mixing_ratio.has_value();
  r.mixing_ratio = in.mixing_ratio.value_or(BasuMixingRatio(n));
  r.air_per_cycle_cm3 = r.mixing_ratio * r.fuel_per_cycle_cm3;  // ν G/γ at p₁
  r.air_expanded_cm3 =
      r.air_per_cycle_cm3 * in.injection_air_pressure_Pa / in.cylinder_pressure_Pa;  // · p₁/p₀
  r.mixture_cm3 = r.air_expanded_cm3 + r.fuel_per_cycle_cm3;
  r.injection_period_s = (in.injection_crank_rad / kDeg) / (6.0 * n);  // Δθ/(6n)
  r.pressure_ratio = in.gauge_ratio
                         ? (in.cylinder_pressure_Pa - kAtm) / (in.injection_air_pressure_Pa - kAtm)
                         : in.cylinder_pressure_Pa / in.injection_air_pressure_Pa;
  r.air_velocity_m_s =
      OutflowVelocity(in.velocity_coefficient, in.air_temperature_K, r.pressure_ratio);
  r.mean_cross_section_m2 =
      r.mixture_cm3 * 1e-6 / (r.air_velocity_m_s * r.injection_period_s);  // V/(w₀ t)

  auto trial = [&](double d) {
    PassageTrial t;
    t.passage_m = d;
    t.mean_lift_m = LiftForCrossSection(r.mean_cross_section_m2, d);
    t.max_lift_m = in.rho * t.mean_lift_m;
    t.accepted = t.max_lift_m <= in.max_lift_limit_m;
    return t;
  };
  if (in.discharge_passage_m) {
    PassageTrial t = trial(*in.discharge_passage_m);
    t.accepted = true;  // the user's choice stands; the limit is reported, not enforced
    r.trials.push_back(t);
  } else {
    for (double d : in.passage_candidates_m) {
      try {
        r.trials.push_back(trial(d));
      } catch (const std::invalid_argument&) {
        r.trials.push_back({d, NAN, NAN, false});  // cannot pass the cross-section at all
        continue;
      }
      if (r.trials.back().accepted) break;
    }
    if (r.trials.empty() || !r.trials.back().accepted) {
      throw std::invalid_argument(
          "no candidate discharge-passage diameter keeps the maximum lift within " +
          Mm(in.max_lift_limit_m) + " mm; give discharge_passage_mm or larger candidates");
    }
  }
  const PassageTrial& chosen = r.trials.back();
  r.discharge_passage_m = chosen.passage_m;
  r.mean_lift_m = chosen.mean_lift_m;
  r.max_lift_m = chosen.max_lift_m;
  r.lift_table = BasuNormalCurve(r.max_lift_m);
  // Cam disk: peripheral velocity v at cam speed n/2 (four-stroke): D = v·60·2/(π n).
  r.cam_disk_computed_m = in.cam_peripheral_velocity_m_s * 60.0 / (kPi * n * cycles_per_rev);
  r.cam_disk_m = in.cam_disk_m.value_or(r.cam_disk_computed_m);
  r.roller_m = r.cam_disk_m / in.disk_to_roller;
  r.passage_height_m = 1.25 * r.discharge_passage_m;
  r.needle_diameter_suggested_m = 2.0 * r.discharge_passage_m;
  r.needle_diameter_m = in.needle_diameter_m.value_or(r.needle_diameter_suggested_m);
  r.cage_diameter_m = 2.25 * r.needle_diameter_m;
  r.spring_preload_N = BasuPreloadN(r.needle_diameter_m, r.injection_period_s);
  r.max_lift_cross_section_m2 = SeatCrossSection(r.max_lift_m, r.discharge_passage_m);
  r.nozzle_cross_section_m2 = in.nozzle_ratio * r.max_lift_cross_section_m2;
  r.nozzle_holes = in.nozzle_holes;
  r.nozzle_hole_m = std::sqrt(4.0 * r.nozzle_cross_section_m2 / (kPi * in.nozzle_holes));
  return r;
}

std::vector<Field> DesignFields(const DesignResult& r) {
  using namespace display;
  return {
      {"fuel_per_cycle", kGram, r.fuel_per_cycle_g, 3},
      {"fuel_per_cycle", kCm3, r.fuel_per_cycle_cm3, 3},
      {"mixing_ratio", kNone, r.mixing_ratio, 2},
      {"air_per_cycle", kCm3, r.air_per_cycle_cm3, 1},
      {"air_expanded", kCm3, r.air_expanded_cm3, 1},
      {"mixture", kCm3, r.mixture_cm3, 1},
      {"injection_period", kS, r.injection_period_s, 4},
      {"pressure_ratio", kNone, r.pressure_ratio, 4},
      {"air_velocity", kMPerS, r.air_velocity_m_s, 1},
      {"mean_cross_section", kMm2, r.mean_cross_section_m2, 2},
      {"discharge_passage", kMm, r.discharge_passage_m, 1},
      {"mean_lift", kMm, r.mean_lift_m, 3},
      {"max_lift", kMm, r.max_lift_m, 3},
      {"cam_disk_computed", kMm, r.cam_disk_computed_m, 1},
      {"cam_disk", kMm, r.cam_disk_m, 1},
      {"roller", kMm, r.roller_m, 1},
      {"passage_height", kMm, r.passage_height_m, 2},
      {"needle_diameter_suggested", kMm, r.needle_diameter_suggested_m, 1},
      {"needle_diameter", kMm, r.needle_diameter_m, 2},
      {"cage_diameter", kMm, r.cage_diameter_m, 1},
      {"spring_preload", kKgForce, r.spring_preload_N, 1},
      {"spring_preload", kN, r.spring_preload_N, 0},
      {"max_lift_cross_section", kMm2, r.max_lift_cross_section_m2, 2},
      {"nozzle_cross_section", kMm2, r.nozzle_cross_section_m2, 2},
      {"nozzle_holes", kNone, static_cast<double>(r.nozzle_holes), 0, "", true},
      {"nozzle_hole", kMm, r.nozzle_hole_m, 3},
  };
}

std::vector<Field> PassageTrialFields(const PassageTrial& t) {
  return {
      {"discharge_passage", display::kMm, t.passage_m, 1},
      {"mean_lift", display::kMm, FiniteOrNone(t.mean_lift_m), 3},
      {"max_lift", display::kMm, FiniteOrNone(t.max_lift_m), 3},
      FlagField("accepted", t.accepted),
  };
}

const std::vector<Column>& DesignLiftColumns() {
  static const std::vector<Column> columns = {{"crank", display::kDegree}, {"lift", display::kMm}};
  return columns;
}

}  // namespace needle
