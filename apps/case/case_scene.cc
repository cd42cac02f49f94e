#include "apps/case/case_scene.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "lib/units.h"
#include "spring/helical_spring.h"
#include "spring/resonance.h"

namespace needle {

Scene MakeScene(const Case& c) {
  return MakeScene(c, std::make_shared<const LiftLaw>(MakeLiftLaw(c)));
}

Scene MakeScene(const Case& c, std::shared_ptr<const LiftLaw> law) {
  if (!c.needle)
    throw CaseError(
        c.path +
        ": [needle] mass_kg: section [needle] is missing; the dynamics needs the moving mass");
  if (!c.spring)
    throw CaseError(
        c.path +
        ": [spring] preload: section [spring] is missing; the dynamics needs preload and rate");
  if (!c.train)
    throw CaseError(c.path +
                    ": [train] contact_stiffness: section [train] is missing; the dynamics needs "
                    "the contact stiffness");
  Scene s;
  s.law = std::move(law);
  if (!s.law->HasAcceleration()) {
    throw CaseError(c.path + ": [lift] spline: \"" + SplineKindName(s.law->kind()) +
                    "\" is C1 only; the dynamics needs a C2 spline (not-a-knot, natural, clamped, "
                    "quintic, smoothing, local)");
  }
  try {
    s.cam = std::make_shared<const CamInput>(
        *s.law, c.train->play_m, c.train->linear_ramp ? RampKind::kLinear : RampKind::kTangent,
        c.train->ramp_rad);
  } catch (const std::invalid_argument& e) {
    throw CaseError(c.path + ": [train] ramp: " + e.what());
  }
  s.train.mass_kg = c.needle->mass_kg;
  s.train.gas_force_N = c.needle->gas_force_N;
  s.train.preload_N = c.spring->preload_N;
  if (c.spring->rate_N_m) {
    s.train.rate_N_m = *c.spring->rate_N_m;
  } else {
    s.train.rate_N_m = HelicalRate(*c.spring->helical);
  }
  s.train.coil_masses = c.spring->masses;
  if (c.spring->masses > 1) {
    s.train.spring_mass_kg = ActiveSpringMassKg(*c.spring->helical);
    s.train.surge_damping_ratio = c.spring->surge_damping_ratio;
    // The travel from installed to solid (the helical check's lengths).
    try {
      const HelicalSpringCheck lengths = CheckHelicalSpring(
          *c.spring->helical, c.spring->preload_N, 0.0, c.engine.speed_rpm, c.engine.cycle);
      s.train.coil_travel_m = lengths.length_preload_m - lengths.solid_length_m;
    } catch (const std::invalid_argument& e) {
      throw CaseError(c.path + ": [spring] preload: " + e.what());
    }
    s.train.coil_clash = c.spring->coil_clash;
    s.train.clash_stiffness_N_m =
        c.spring->clash_stiffness_N_m.value_or(c.train->contact_stiffness_N_m);
    s.train.clash_damping_ratio =
        c.spring->clash_damping_ratio.value_or(c.train->contact_damping_ratio);
  }
  s.train.contact_stiffness_N_m = c.train->contact_stiffness_N_m;
  s.train.contact_damping_ratio = c.train->contact_damping_ratio;
  s.train.seat_stiffness_N_m = c.train->seat_stiffness_N_m;
  s.train.seat_damping_ratio = c.train->seat_damping_ratio;
  if (c.train->rigid) {
    s.train.contact = ContactKind::kRigid;
    s.train.restitution = c.train->restitution;
    s.train.seat_restitution = c.train->seat_restitution;
  }
  s.revolution_rad = 2.0 * kPi * CrankTurnsPerCycle(c.engine.cycle);
  if (c.solver) {
    s.start_rad = c.solver->start_rad;
    s.end_rad = c.solver->end_rad;
    const auto refusal = c.solver->cycles > 1 ? CyclesRefusal(s) : std::nullopt;
    if (refusal) throw CaseError(c.path + ": [solver] cycles: " + *refusal);
  }
  return s;
}

SimulationOptions OptionsFromCase(const Case& c) {
  SimulationOptions o;
  if (c.solver) {
    o.method = c.solver->method;
    o.integrator.rtol = c.solver->rtol;
    o.integrator.atol_m = c.solver->atol_m.value_or(DefaultAtol(c.solver->rtol));
    o.integrator.max_steps = c.solver->max_steps;
    o.integrator.max_events = c.solver->max_events;
    o.integrator.max_seconds = c.solver->max_seconds;
    o.settle_limit_deg = c.solver->settle_limit_deg;
    o.cycles = c.solver->cycles;
    o.period_tolerance = c.solver->period_tolerance;
  } else {
    o.integrator.atol_m = DefaultAtol(o.integrator.rtol);
  }
  return o;
}

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
  return CheckSpring(*c.needle, *c.spring, law, speed_rpm, c.engine.cycle, c.path);
}

}  // namespace needle
