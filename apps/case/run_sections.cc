// [engine], [train], [solver], [overspeed], [tolerance], [profile] and [paper]
// (section_reader.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "apps/case/plausible_ranges.h"
#include "apps/case/section_reader.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle::case_internal {

TrainSection ReadTrain(SectionReader r) {
  TrainSection t;
  if (auto contact = r.OptionalString("contact")) {
    if (*contact != "compliant" && *contact != "rigid")
      r.Fail("contact", "expected \"compliant\" or \"rigid\", got \"" + *contact + "\"");
    if (*contact == "rigid") t.contact = ContactKind::kRigid;
  }
  // Each law's keys, read straight into the contact parameters; the other law's are refused.
  const auto number = [&r](const char* key, double& into) {
    if (auto v = r.OptionalNumber(key)) into = *v;
  };
  const auto stiffness = [&r](const char* key) {
    return r.OptionalQuantity(key, Dimension::kStiffness);
  };
  if (t.rigid()) {
    t.contact_stiffness_N_m = t.seat_stiffness_N_m = 0.0;  // a rigid law has none
    number("restitution", t.restitution);                  // Newton's restitution
    number("seat_restitution", t.seat_restitution);
    for (const char* key : {"contact_stiffness", "seat_stiffness"}) {
      if (stiffness(key))
        r.Fail(r.last_key(), "applies to contact = \"compliant\"; a rigid contact has none");
    }
    for (const char* key : {"contact_damping_ratio", "seat_damping_ratio"}) {
      if (r.OptionalNumber(key))
        r.Fail(key, "applies to contact = \"compliant\"; a rigid contact has restitution");
    }
  } else {
    for (const char* key : {"restitution", "seat_restitution"}) {
      if (r.OptionalNumber(key))
        r.Fail(key, "applies to contact = \"rigid\"; a compliant contact has a damping ratio");
    }
    t.contact_stiffness_N_m = r.Quantity("contact_stiffness", Dimension::kStiffness);
    t.seat_stiffness_N_m = stiffness("seat_stiffness").value_or(t.contact_stiffness_N_m);
    number("contact_damping_ratio", t.contact_damping_ratio);
    number("seat_damping_ratio", t.seat_damping_ratio);
  }
  r.Validated([&t] { t.ContactParameters::Validate(); });  // the laws' one rule
  if (auto play = r.OptionalQuantity("play", Dimension::kLength)) {
    if (!(*play >= 0.0))
      r.Fail(r.last_key(), "must not be negative, got " + Number(*play * 1e3) + " mm");
    t.play_m = *play;
  }
  r.Known("ramp");
  const auto ramp = r.OptionalString("ramp");
  const auto ramp_angle = r.OptionalQuantity("ramp", Dimension::kAngle);
  if (ramp && *ramp != "tangent")
    r.Fail("ramp", "expected \"tangent\" or ramp_deg = <angle>, got \"" + *ramp + "\"");
  if (ramp && ramp_angle) r.Fail("ramp", "give ramp = \"tangent\" or ramp_deg, not both");
  if (ramp_angle) {
    if (!(*ramp_angle > 0.0))
      r.Fail(r.last_key(), "must be positive, got " + Number(*ramp_angle / kDeg) + " deg");
    t.linear_ramp = true;
    t.ramp_rad = *ramp_angle;
  }
  r.Finish();
  return t;
}

SolverSection ReadSolver(SectionReader r) {
  SolverSection s;
  SimulationOptions& o = s.run;
  IntegratorOptions& i = o.integrator;
  if (auto m = r.OptionalString("method")) {
    if (!MethodNameFault(*m).empty())
      r.Fail("method", "expected one of " + MethodList() + "; got \"" + *m + "\"");
    o.method = *m;
  }
  if (auto rtol = r.OptionalNumber("rtol")) i.rtol = *rtol;
  const auto atol = r.OptionalQuantity("atol", Dimension::kLength);
  i.atol_m = atol.value_or(DefaultAtol(i.rtol));
  s.atol_given = atol.has_value();
  // Budgets: whole numbers in a range a long holds.
  for (auto [key, into] :
       {std::pair<const char*, long*>{"max_steps", &i.max_steps}, {"max_events", &i.max_events}}) {
    if (auto v = OptionalCount(r, key, 1e12, "1e12")) *into = *v;
  }
  if (auto v = r.OptionalNumber("max_seconds")) {
    if (!(*v >= 0.0 && *v <= 86400.0))
      r.Fail("max_seconds", "must be in [0, 86400] s (0: no wall-time budget), got " + Number(*v));
    i.max_seconds = *v;
  }
  if (auto settle = r.OptionalQuantity("settle", Dimension::kAngle))
    o.settle_limit_deg = *settle / kDeg;
  if (auto v = OptionalCount(r, "cycles", kMaxCycles, std::to_string(kMaxCycles)))
    o.cycles = static_cast<int>(*v);
  if (auto v = r.OptionalNumber("period_tolerance")) o.period_tolerance = *v;
  r.Validated([&o] { o.Validate(); });  // the run options' one rule
  s.start_rad = r.OptionalQuantity("start", Dimension::kAngle);
  s.end_rad = r.OptionalQuantity("end", Dimension::kAngle);
  if (s.start_rad && s.end_rad && !(*s.end_rad > *s.start_rad)) {
    r.Fail("end_deg", "must be after start_deg");
  }
  r.Finish();
  return s;
}

OverspeedSection ReadOverspeed(SectionReader r) {
  OverspeedSection o;
  o.from_rpm = r.OptionalQuantity("from", Dimension::kRotationSpeed);
  o.to_rpm = r.OptionalQuantity("to", Dimension::kRotationSpeed);
  if (o.from_rpm && !(*o.from_rpm > 0.0))
    r.Fail("from_rpm", "must be positive, got " + Number(*o.from_rpm));
  if (o.from_rpm && o.to_rpm && !(*o.to_rpm > *o.from_rpm)) {
    r.Fail("to_rpm", "the sweep range is empty: to_rpm (" + Number(*o.to_rpm) +
                         ") must exceed from_rpm (" + Number(*o.from_rpm) + ")");
  }
  o.steady_state = r.OptionalBool("steady_state").value_or(false);
  r.Finish();
  return o;
}

ToleranceSection ReadTolerance(SectionReader r) {
  ToleranceSection t;
  // Each σ in its plausible range (apps/case/plausible_ranges.h), checked by Finish.
  const auto sigma = [&r](const std::string& name, Dimension d, double& into) {
    if (auto v = r.OptionalQuantity(name, d)) into = *v;
  };
  r.Declare("lift_correlation");  // not a unit of `lift`
  sigma("lift", Dimension::kLength, t.lift_sigma_m);
  if (auto v = r.OptionalQuantity("lift_correlation", Dimension::kAngle)) {
    t.lift_correlation_rad = *v;
    t.lift_correlation_given = true;
  }
  t.given = true;
  sigma("mass", Dimension::kPercent, t.mass_fraction);
  sigma("preload", Dimension::kPercent, t.preload_fraction);
  sigma("rate", Dimension::kPercent, t.rate_fraction);
  sigma("stiffness", Dimension::kPercent, t.stiffness_fraction);
  sigma("play", Dimension::kLength, t.play_sigma_m);
  sigma("speed", Dimension::kPercent, t.speed_fraction);
  r.Finish();
  return t;
}

ProfileSection ReadProfile(SectionReader r) {
  ProfileSection p;
  FollowerGeometry& g = p.follower;
  g = ReadFollowerKeys(r);
  g.base_radius_m = *SignedLength(r, "base_radius", true, true);
  g.offset_m = r.OptionalQuantity("offset", Dimension::kLength).value_or(0.0);
  if (auto l = r.OptionalNumber("lever_ratio")) g.lever_ratio = *l;
  r.Validated([&g] { g.Validate(); });  // the follower's one rule (lib/follower.h)
  if (auto n = r.OptionalNumber("points")) {
    if (!(*n >= 8 && *n <= 1e6) || *n != std::floor(*n))
      r.Fail("points", "must be a whole number in 8…1e6");
    p.points = static_cast<int>(*n);
  }
  r.Finish();
  return p;
}

EngineSection ReadEngine(SectionReader r) {
  if (!r.present()) r.Fail("speed_rpm", "section [engine] is missing; it needs speed_rpm");
  EngineSection e;
  e.speed_rpm = r.Quantity("speed", Dimension::kRotationSpeed);
  if (!(e.speed_rpm > 0.0)) r.Fail("speed_rpm", "must be positive, got " + Number(e.speed_rpm));
  if (auto cycle = OptionalCycle(r)) e.cycle = *cycle;
  r.Finish();
  return e;
}

PaperSection ReadPaper(SectionReader r) {
  PaperSection p;
  const auto crank = r.OptionalQuantityArray("crank", Dimension::kAngle);
  const auto velocity = r.OptionalQuantityArray("velocity", Dimension::kVelocity);
  if (crank.has_value() != velocity.has_value()) {
    r.Fail(crank ? "crank_deg" : "velocity",
           "published velocities need both crank_deg and velocity_<unit>");
  }
  if (crank) {
    if (crank->size() != velocity->size()) {
      r.Fail("velocity", "has " + std::to_string(velocity->size()) + " values but crank_deg has " +
                             std::to_string(crank->size()));
    }
    p.crank_rad = *crank;
    p.velocity_m_s = *velocity;
  }
  p.max_acceleration_m_s2 = r.OptionalQuantity("max_acceleration", Dimension::kAcceleration);
  p.inertia_force_N = r.OptionalQuantity("inertia_force", Dimension::kForce);
  p.mean_lift_m = r.OptionalQuantity("mean_lift", Dimension::kLength);
  p.spring_preload_N = r.OptionalQuantity("spring_preload", Dimension::kForce);
  r.Finish();
  return p;
}

}  // namespace needle::case_internal
