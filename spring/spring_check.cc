#include "spring/spring_check.h"

#include <cmath>

#include "lib/units.h"
#include "spring/basu_formula.h"

namespace needle {

SpringCheckResult CheckSpring(const Case& c, const LiftLaw& law, double speed_rpm) {
  if (!c.needle) {
    throw CaseError(
        c.path +
        ": [needle] mass_kg: section [needle] is missing; the spring check needs the moving mass");
  }
  if (!c.spring) {
    throw CaseError(
        c.path +
        ": [spring] preload: section [spring] is missing; the spring check needs preload and rate");
  }
  if (!law.HasAcceleration()) {
    throw CaseError(
        c.path + ": [lift] spline: \"" + SplineKindName(law.kind()) +
        "\" has no acceleration; the spring check needs a C2 spline (not-a-knot, natural, "
        "clamped, quintic or smoothing)");
  }
  SpringCheckResult r;
  r.speed_rpm = speed_rpm;
  const Kinematics kin(law, speed_rpm);
  r.kinematics = kin.Summarize();
  const KinematicsSummary& sum = r.kinematics;
  const double omega = kin.omega();
  r.train.mass_kg = c.needle->mass_kg;
  r.train.preload_N = c.spring->preload_N;
  r.train.gas_force_N = c.needle->gas_force_N;
  if (c.spring->helical) {
    try {
      r.helical = CheckHelicalSpring(*c.spring->helical, c.spring->preload_N, sum.max_lift_m,
                                     speed_rpm, c.engine.cycle == "four-stroke");
    } catch (const std::invalid_argument& e) {
      throw CaseError(c.path + ": [spring]: " + e.what());
    }
  }
  r.train.rate_N_m = c.spring->rate_N_m ? *c.spring->rate_N_m : r.helical->rate_N_m;
  const bool max_wins =
      std::abs(*sum.max_acceleration_m_s2) >= std::abs(*sum.min_acceleration_m_s2);
  r.max_abs_acceleration_m_s2 = max_wins ? *sum.max_acceleration_m_s2 : -*sum.min_acceleration_m_s2;
  r.max_abs_acceleration_rad = max_wins ? *sum.max_acceleration_rad : *sum.min_acceleration_rad;
  r.inertia_force_N = r.train.mass_kg * r.max_abs_acceleration_m_s2;  // m·max|a|
  if (c.needle->diameter_m)
    r.basu_preload_N = BasuPreloadN(*c.needle->diameter_m, sum.injection_period_s);
  r.min_quasi_static = MinQuasiStaticForce(law, r.train, omega);
  r.liftoff_rpm_quasi_static = QuasiStaticLiftoffRpm(law, r.train);
  r.required_preload_N =
      RequiredPreloadN(law, r.train, omega, c.spring->safety_factor, c.spring->overspeed_factor);
  r.preload_margin_percent =
      r.required_preload_N > 0
          ? 100.0 * (r.train.preload_N - r.required_preload_N) / r.required_preload_N
          : INFINITY;
  r.preload_ok = r.train.preload_N >= r.required_preload_N;
  r.pass = r.preload_ok && (!r.helical || r.helical->pass());
  return r;
}

}  // namespace needle
