#include "spring/spring_check.h"

#include <cmath>

#include "lib/lift_data.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/basu_formula.h"

namespace needle {

std::vector<std::string> SpringFailures(const SpringCheckResult& r, bool surge_screen) {
  std::vector<std::string> out;
  if (!r.combustion_ok) {
    out.push_back("combustion load: the preload " + Fixed(r.train.preload_N / kKgf, 1) +
                  " kgf does not withstand S x F_g = " + Fixed(r.safety_factor, 2) + " x " +
                  Fixed(r.gas_force_N / kKgf, 1) + " kgf (" + r.gas_source + "), margin " +
                  Fixed(r.combustion_margin_percent, 1) + " %");
  }
  if (!r.basu_ok) {
    out.push_back("Basu's formula: the preload " + Fixed(r.train.preload_N / kKgf, 1) + " kgf is " +
                  Fixed(-*r.basu_deviation_percent, 1) + " % below " +
                  Fixed(*r.basu_preload_N / kKgf, 1) + " kgf (tolerance " +
                  Fixed(r.basu_tolerance_percent, 1) + " %)");
  }
  if (!r.decelerates) {
    out.push_back(
        "inertia sizing: undecided: the lift table never decelerates (a lift that "
        "returns to its seat must), so it does not hold the lift's top; give the whole "
        "lift");
  } else if (!r.unresolved.empty() && r.train.preload_N >= r.required_preload_N) {
    out.push_back("inertia sizing: undecided: " + r.unresolved);
  } else if (UndecidedWithinAccuracy(r)) {
    out.push_back("inertia sizing: undecided within the table's accuracy: the preload " +
                  Fixed(r.train.preload_N, 1) + " N meets the required " +
                  Fixed(r.required_preload_N, 1) + " N of the fitted lift, not the " +
                  Fixed(r.required_preload_unsafe_N.value_or(0.0), 1) +
                  " N at its acceleration band's unsafe end");
  } else if (!r.preload_ok) {
    out.push_back("inertia sizing: the preload " + Fixed(r.train.preload_N, 1) +
                  " N is below the required " + Fixed(r.required_preload_N, 1) + " N, margin " +
                  Fixed(r.preload_margin_percent, 1) + " %");
  }
  const bool helical_fails =
      r.helical && (!r.helical->stress_ok || !r.helical->clearance_ok || !r.helical->fatigue_ok ||
                    (!r.helical->surge_ok && surge_screen));
  if (helical_fails) {  // each item with its figures, "; " between
    const HelicalSpringCheck& h = *r.helical;
    std::vector<std::string> items;
    if (!h.stress_ok)
      items.push_back("shear stress " + Fixed(h.stress_full_lift_Pa * 1e-6, 0) +
                      " MPa above the allowable " + Fixed(h.allowable_stress_Pa * 1e-6, 0) +
                      " MPa");
    if (!h.clearance_ok)
      items.push_back("coil gaps " + Fixed(h.clearance_full_lift_m * 1e3, 2) + " mm below S_a " +
                      Fixed(h.min_clearance_m * 1e3, 2) + " mm");
    if (!h.surge_ok && surge_screen)
      items.push_back("surge ratio " +
                      Fixed(h.surge_ratio, DecimalsApart(h.surge_ratio, kMinSurgeRatio, 1)) +
                      " below 13");
    if (!h.fatigue_ok)
      items.push_back(std::string("fatigue: the working stroke is outside the ") +
                      CriterionInfo(h.fatigue.criterion).title + " line (n_f " +
                      Fixed(h.fatigue.safety_factor, 2) + " < 1)");
    std::string line = "helical spring: ";
    for (size_t i = 0; i < items.size(); ++i) line += (i ? "; " : "") + items[i];
    out.push_back(line);
  }
  return out;
}

SpringCheckResult CheckSpring(const NeedleParameters& needle, const SpringParameters& spring,
                              const LiftLaw& law, double speed_rpm, EngineCycle cycle,
                              const std::string& where) {
  if (!law.HasAcceleration()) {
    throw CaseError(
        where + ": [lift] spline: \"" + SplineKindName(law.kind()) +
        "\" has no acceleration; the spring check needs a C2 spline (not-a-knot, natural, "
        "clamped, quintic or smoothing)");
  }
  SpringCheckResult r;
  r.speed_rpm = speed_rpm;
  const Kinematics kin(law, speed_rpm);
  r.kinematics = kin.Summarize();
  const KinematicsSummary& sum = r.kinematics;
  const double omega = kin.omega();
  r.train.mass_kg = needle.mass_kg;
  r.train.preload_N = spring.preload_N;
  r.train.gas_force_N = needle.gas_force_N;
  if (spring.helical) {
    try {
      r.helical =
          CheckHelicalSpring(*spring.helical, spring.preload_N, sum.max_lift_m, speed_rpm, cycle);
    } catch (const std::invalid_argument& e) {
      throw CaseError(where + ": [spring]: " + e.what());
    }
  }
  r.train.rate_N_m = spring.rate_N_m ? *spring.rate_N_m : r.helical->rate_N_m;
  const bool max_wins =
      std::abs(*sum.max_acceleration_m_s2) >= std::abs(*sum.min_acceleration_m_s2);
  r.max_abs_acceleration_m_s2 = max_wins ? *sum.max_acceleration_m_s2 : -*sum.min_acceleration_m_s2;
  r.max_abs_acceleration_rad = max_wins ? *sum.max_acceleration_rad : *sum.min_acceleration_rad;
  r.inertia_force_N = r.train.mass_kg * r.max_abs_acceleration_m_s2;  // m·max|a|
  if (needle.diameter_m)
    r.basu_preload_N = BasuPreloadN(*needle.diameter_m, sum.injection_period_s);
  r.min_quasi_static = MinQuasiStaticForce(law, r.train, omega);
  r.liftoff_rpm_quasi_static = QuasiStaticLiftoffRpm(law, r.train);
  r.required_preload_N =
      RequiredPreloadN(law, r.train, omega, spring.safety_factor, spring.overspeed_factor);
  r.preload_margin_percent =
      r.required_preload_N > 0
          ? 100.0 * (r.train.preload_N - r.required_preload_N) / r.required_preload_N
          : INFINITY;
  r.liftoff_rpm_quasi_static_band = QuasiStaticLiftoffBand(law, r.train);
  r.required_preload_unsafe_N =
      RequiredPreloadUnsafeN(law, r.train, omega, spring.safety_factor, spring.overspeed_factor);
  if (r.required_preload_unsafe_N && *r.required_preload_unsafe_N > 0.0) {
    r.preload_margin_unsafe_percent =
        100.0 * (r.train.preload_N - *r.required_preload_unsafe_N) / *r.required_preload_unsafe_N;
  }
  // Decelerating beyond round-off: a millionth of the scale ω² L/Θ² of a lift L over the open
  // duration Θ (a straight table's fitted s'' is a round-off's −1e-16 of it).
  const double span_rad = sum.close_rad - sum.open_rad;
  const double scale_m_s2 =
      span_rad > 0.0 ? omega * omega * sum.max_lift_m / (span_rad * span_rad) : 0.0;
  r.decelerates = *sum.min_acceleration_m_s2 < -1e-6 * scale_m_s2;
  r.unresolved = UnresolvedSides(law.table());
  r.preload_ok = r.decelerates && r.unresolved.empty() &&
                 r.train.preload_N >= r.required_preload_unsafe_N.value_or(r.required_preload_N);
  const double S = spring.safety_factor;
  r.safety_factor = S;
  r.gas_force_N = r.train.gas_force_N;
  r.gas_source = needle.gas_source;
  r.combustion_ok = r.train.preload_N >= S * r.gas_force_N;
  r.combustion_margin_percent =
      r.gas_force_N > 0 ? 100.0 * (r.train.preload_N - S * r.gas_force_N) / (S * r.gas_force_N)
                        : INFINITY;
  r.basu_tolerance_percent = spring.basu_tolerance_percent;
  if (r.basu_preload_N) {
    r.basu_deviation_percent = 100.0 * (r.train.preload_N - *r.basu_preload_N) / *r.basu_preload_N;
    r.basu_ok = *r.basu_deviation_percent >= -r.basu_tolerance_percent;
  }
  for (double v : {r.inertia_force_N, r.min_quasi_static.force_N, r.required_preload_N,
                   r.gas_force_N, r.train.preload_N}) {
    if (!std::isfinite(v)) {
      throw CaseError(where +
                      ": [needle]/[spring]: a spring-check quantity is not finite (inertia force "
                      "m·max|a|, contact force or required preload overflows); check mass_kg, "
                      "preload and rate for absurd values");
    }
  }
  r.failures = SpringFailures(r);
  r.pass = r.failures.empty();
  if (std::optional<std::string> slip = PreloadSlip(r)) r.warnings.push_back(*slip);
  return r;
}

bool UndecidedWithinAccuracy(const SpringCheckResult& r) {
  return r.decelerates && r.unresolved.empty() && !r.preload_ok &&
         r.train.preload_N >= r.required_preload_N;
}

std::string PreloadMarginNote(const SpringCheckResult& r) {
  if (!r.unresolved.empty()) return " of a lift the table does not resolve";
  if (UndecidedWithinAccuracy(r) && r.preload_margin_unsafe_percent) {
    return " of the fitted lift, " + Fixed(*r.preload_margin_unsafe_percent, 1) +
           " % at its acceleration band's unsafe end";
  }
  return "";
}

std::optional<std::string> PreloadSlip(const SpringCheckResult& r) {
  std::string rule;
  double largest = 0.0;
  const auto consider = [&](const char* name, double v) {
    if (v > largest) {
      largest = v;
      rule = name;
    }
  };
  consider("Basu's formula", r.basu_preload_N.value_or(0.0));
  consider("the combustion load S·F_g", r.safety_factor * r.gas_force_N);
  consider("the inertia sizing", r.required_preload_N);
  const double p0 = r.train.preload_N;
  // A rule under 1e-4 of the preload bounds nothing a slip could be read from (a lift whose
  // deceleration is round-off: "10771019217.3× the largest rule (the inertia sizing, 0 N)").
  if (!(largest >= 1e-4 * p0) || !(p0 > 3.0 * largest)) return std::nullopt;
  const std::string line = "the preload " + Fixed(p0, 0) + " N is " + Fixed(p0 / largest, 1) +
                           "× the largest rule (" + rule + ", " + Fixed(largest, 0) + " N)";
  std::string hint;
  struct Slip {
    double factor;
    const char* shown;
    const char* what;
  };
  double best = 3.0;  // the least ratio left after the slip, within 3×
  for (const Slip& s : {Slip{9.80665, "9.81", "kgf for N"}, Slip{1000.0, "1000", "kN for N"},
                        Slip{4.4482216, "4.45", "lbf for N"}}) {
    const double left = std::max(p0 / s.factor / largest, largest * s.factor / p0);
    if (left < best) {
      best = left;
      hint = std::string("; ") + s.shown + "×: " + s.what + "?";
    }
  }
  return line + hint;
}

std::vector<Field> SpringCheckFields(const SpringCheckResult& r) {
  using namespace display;
  std::vector<Field> fields = {
      {"basu_preload", kKgForce, r.basu_preload_N, 1},
      {"actual_preload", kKgForce, r.train.preload_N, 1},
      {"deviation", kPercent, r.basu_deviation_percent, 1},
      {"max_abs_acceleration", kMPerS2, r.max_abs_acceleration_m_s2, 2},
      {"max_abs_acceleration", kDegree, r.max_abs_acceleration_rad, 1},
      {"inertia_force", kKgForce, r.inertia_force_N, 2},
      {"spring_rate", kNPerMm, r.train.rate_N_m, 2},
      {"min_quasi_static_force", kN, r.min_quasi_static.force_N, 1},
      {"min_quasi_static_force", kDegree, r.min_quasi_static.crank_rad, 2},
      {"n_qs", kRpm, FiniteOrNone(r.liftoff_rpm_quasi_static), 1, "liftoff_rpm_quasi_static"},
      {"required_preload", kN, r.required_preload_N, 1},
      {"required_preload", kKgForce, r.required_preload_N, 2},
      {"preload_margin", kPercent, FiniteOrNone(r.preload_margin_percent), 1},
      {"preload_margin_unsafe", kPercent, r.preload_margin_unsafe_percent, 1},
      {"gas_force", kN, r.gas_force_N, 1},
      TextField("gas_source", r.gas_source),
      FlagField("combustion_ok", r.combustion_ok),
      {"combustion_margin", kPercent, FiniteOrNone(r.combustion_margin_percent), 1},
      {"basu_tolerance", kPercent, r.basu_tolerance_percent, 1},
      FlagField("basu_ok", r.basu_ok),
      FlagField("preload_ok", r.preload_ok),
      FlagField("pass", r.pass),
  };
  // The lift table's accuracy carried to n_qs (a local fit's band); its upper end null where
  // the band of every deceleration reaches zero (the accuracy leaves n_qs unbounded above).
  const auto& band = r.liftoff_rpm_quasi_static_band;
  if (band) {
    Field f = ListField("n_qs_band", kRpm, {band->low, band->high});
    f.key = "liftoff_rpm_quasi_static_band";
    f.decimals = 1;
    fields.insert(fields.begin() + 10, f);  // after n_qs
  }
  return fields;
}

}  // namespace needle
