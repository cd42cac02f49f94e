// Every integrator of the method table on the same closed forms: a free oscillation of the
// needle on its seat and on the cam (x(t) = y_eq + a cos ωt, ω = √((k_contact + k)/m)), the
// global error's convergence as the tolerance tightens, per-state absolute tolerances, and
// the options' validation. A new method in the table is tested here without a new line.
#include "dynamics/solver/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "dynamics/solver/stepper.h"
#include "tests/dynamics/test_laws.h"

namespace needle {
namespace {

struct Outcome {
  double error = 0.0;  // |y(t_end) − closed form| / amplitude
  IntegrationStats stats;
};

// Seat only (play keeps the cam at −δ away) or cam only (no play, u = 1 mm before the table):
//   seat: m ÿ = −k_s y − P₀ − k y;   cam: m ÿ = k_c (u − y) − P₀ − k y.
Outcome Oscillate(Method method, double rtol, bool seat_mode, IntegratorOptions o = {}) {
  const double m = 1.0, k = 1e4, preload = 100.0, stiffness = 1e6;
  const LiftLaw law = FarLaw(seat_mode ? 0.0 : 1e-3);
  const CamInput cam(law, seat_mode ? 0.5e-3 : 0.0, RampKind::kLinear, 0.1);
  TrainParameters p;
  p.mass_kg = m;
  p.preload_N = preload;
  p.rate_N_m = k;
  p.contact_stiffness_N_m = p.seat_stiffness_N_m = stiffness;
  p.contact_damping_ratio = p.seat_damping_ratio = 0.0;
  const NeedleTrain train(cam, p, 10.0, 0.0);
  const double y_eq =
      seat_mode ? -preload / (stiffness + k) : (stiffness * 1e-3 - preload) / (stiffness + k);
  const double w = std::sqrt((stiffness + k) / m);
  const double a = 0.05e-3;
  const TrainState x0 = {y_eq + a, 0.0, 0.0, 0.0};
  Recorder recorder(train, false);
  o.rtol = rtol;
  o.atol_m = DefaultAtol(rtol);
  const double t_end = 0.07;  // 11 periods, θ stays below 0.8 rad
  Outcome r;
  r.stats = Integrate(method, train, x0, t_end, recorder, o);
  EXPECT_NEAR(r.stats.final_time, t_end, 1e-12) << MethodName(method);
  if (method != Method::kBaselineDopri5) {  // the baseline has no modes: it gates forces
    EXPECT_EQ(r.stats.final_phase.mode.seat, seat_mode) << MethodName(method);
    EXPECT_EQ(r.stats.final_phase.mode.cam, !seat_mode) << MethodName(method);
  }
  EXPECT_TRUE(recorder.impacts().empty()) << MethodName(method);
  r.error = std::abs(r.stats.final_state[0] - (y_eq + a * std::cos(w * t_end))) / a;
  return r;
}

TEST(IntegratorTest, EveryMethodIsInTheTableAndNamedOnce) {
  EXPECT_EQ(AllMethods().size(), 7u);
  for (Method m : AllMethods()) EXPECT_EQ(ParseMethod(MethodName(m)), m);
  EXPECT_EQ(MethodList(),
            "auto, dopri5, rkf78, rosenbrock4, cvode-bdf, cvode-adams, exact or "
            "baseline-dopri5");
  EXPECT_FALSE(ParseMethod("euler").has_value());
}

TEST(IntegratorTest, EveryMethodFollowsTheSeatOscillationsClosedForm) {
  for (Method m : AllMethods()) {
    EXPECT_LT(Oscillate(m, 1e-10, true).error, 1e-6) << MethodName(m);
  }
}

TEST(IntegratorTest, EveryMethodFollowsTheCamOscillationsClosedForm) {
  for (Method m : AllMethods()) {
    EXPECT_LT(Oscillate(m, 1e-10, false).error, 1e-6) << MethodName(m);
  }
}

TEST(IntegratorTest, EveryMethodsErrorShrinksWithTheTolerance) {
  // Tolerance proportionality: over 11 periods the global error falls at least tenfold per
  // hundredfold tighter rtol, for every method, from 1e-6 to 1e-10 (the measured slopes of
  // log error against log rtol are printed).
  for (Method m : AllMethods()) {
    if (MethodIsClosedForm(m)) continue;  // no tolerance: its error is round-off (next test)
    const double e6 = Oscillate(m, 1e-6, true).error;
    const double e8 = Oscillate(m, 1e-8, true).error;
    const double e10 = Oscillate(m, 1e-10, true).error;
    std::printf("%-16s error %.2e %.2e %.2e  slope %.2f %.2f\n", MethodName(m).c_str(), e6, e8, e10,
                std::log10(e6 / e8) / 2.0, std::log10(e8 / e10) / 2.0);
    EXPECT_LT(e8, e6 / 10.0) << MethodName(m);
    EXPECT_LT(e10, e8 / 10.0) << MethodName(m);
  }
}

TEST(IntegratorTest, TheClosedFormIsExactToRoundOffWhateverTheTolerance) {
  // The same 11 periods by each method the table calls closed form ("exact"): the error is
  // round-off, not a tolerance's (a time stepper marked so fails here at rtol 1e-4).
  int closed = 0;
  for (Method m : AllMethods()) {
    if (!MethodIsClosedForm(m)) continue;
    ++closed;
    for (double rtol : {1e-4, 1e-8, 1e-12}) {
      EXPECT_LT(Oscillate(m, rtol, true).error, 1e-13) << MethodName(m) << " " << rtol;
      EXPECT_LT(Oscillate(m, rtol, false).error, 1e-13) << MethodName(m) << " " << rtol;
    }
  }
  EXPECT_EQ(closed, 1);
}

// The table's capabilities (issue 52): auto's pick for each kind of train is a method that can
// take it; the baseline is the one method outside the event driver.
TEST(IntegratorTest, TheMethodTableCarriesAutosPicksAndTheDriversMethods) {
  EXPECT_FALSE(MethodRigidRefusal(AutoMethodFor(AutoCase::kRigid)).has_value());
  EXPECT_TRUE(MethodIsClosedForm(AutoMethodFor(AutoCase::kLinear)));
  for (AutoCase c : {AutoCase::kRigid, AutoCase::kNonStiff, AutoCase::kStiff}) {
    EXPECT_FALSE(MethodIsClosedForm(AutoMethodFor(c))) << static_cast<int>(c);
    EXPECT_TRUE(MethodIsEventDriven(AutoMethodFor(c))) << static_cast<int>(c);
  }
  EXPECT_EQ(MethodName(AutoMethodFor(AutoCase::kStiff)), "cvode-bdf");
  EXPECT_EQ(MethodName(AutoMethodFor(AutoCase::kNonStiff)), "dopri5");
  int outside = 0;
  for (Method m : AllMethods()) outside += !MethodIsEventDriven(m);
  EXPECT_EQ(outside, 1);
  EXPECT_FALSE(MethodIsEventDriven(*ParseMethod("baseline-dopri5")));
}

TEST(IntegratorTest, PerStateToleranceEqualToTheLiftsIsTheDefaultBitForBit) {
  // atol_m_s and atol_J default to the number atol_m: setting them to it changes nothing; a
  // different one scales the states the backends see and still meets the closed form.
  for (Method m : AllMethods()) {
    if (m == Method::kExact) continue;  // takes no tolerances
    IntegratorOptions same;
    same.atol_m_s = same.atol_J = DefaultAtol(1e-9);
    const Outcome a = Oscillate(m, 1e-9, true), b = Oscillate(m, 1e-9, true, same);
    EXPECT_EQ(a.stats.final_state, b.stats.final_state) << MethodName(m);
    EXPECT_EQ(a.stats.steps, b.stats.steps) << MethodName(m);
    IntegratorOptions scaled;
    scaled.atol_m_s = 1e-9;  // m/s: velocities of 0.05 mm × 1000 rad/s = 0.05 m/s
    scaled.atol_J = 1e-9;
    const Outcome c = Oscillate(m, 1e-9, true, scaled);
    EXPECT_NE(a.stats.final_state, c.stats.final_state) << MethodName(m);
    EXPECT_LT(c.error, 1e-5) << MethodName(m);
  }
}

TEST(IntegratorTest, OptionsAreValidatedByName) {
  IntegratorOptions o;
  o.rtol = 1e-1;
  try {
    o.Validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "IntegratorOptions.rtol = 0.100000: must be in [1e-14, 1e-2]");
  }
  o.rtol = 1e-8;
  o.atol_m_s = -1.0;
  EXPECT_THROW(o.Validate(), std::invalid_argument);
  o.atol_m_s = 0.0;
  EXPECT_EQ(o.AbsoluteTolerances()[1], o.atol_m);
  o.atol_J = 1e-6;
  EXPECT_EQ(o.AbsoluteTolerances()[3], 1e-6);
}

// The right-hand side keeps the contacts it computed, for the driver to reuse at the step's end
// (an FSAL method's last stage): only for the same state, time and phase to the bit, and equal
// to what Evaluate gives there. A chain of 5 coil masses, its states scaled (per-state atol).
TEST(TrainSystemTest, TheLastContactsServeOnlyTheirOwnStateTimeAndPhase) {
  const LiftLaw law = FarLaw(1e-3);
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  TrainParameters p;
  p.mass_kg = 0.8;
  p.preload_N = 900.0;
  p.rate_N_m = 5e4;
  p.coil_masses = 5;
  p.spring_mass_kg = 0.6;
  p.surge_damping_ratio = 0.05;
  const NeedleTrain train(cam, p, 60.0, 0.0);
  IntegratorOptions o;
  o.atol_m_s = 1e-5;  // scaled states: z ≠ x
  TrainSystem system(train, o);
  system.phase.mode.cam = true;
  TrainState x(train.StateSize(), 0.0);
  x[0] = 0.99e-3;
  x[1] = 0.02;
  for (int i = 0; i < train.Coils(); ++i) {
    x[4 + i] = 0.99e-3 * (train.Coils() - i) / (train.Coils() + 1.0);
    x[4 + train.Coils() + i] = 0.01 * i;
  }
  const TrainState z = system.ToScaled(x);
  x = system.FromScaled(z);  // the state as the right-hand side sees it
  const double t = 0.004;
  EXPECT_EQ(system.LastContacts(x, t), nullptr);  // nothing evaluated yet
  TrainState dzdt;
  system(z, dzdt, t);
  const Contacts* kept = system.LastContacts(x, t);
  ASSERT_NE(kept, nullptr);
  const Contacts c = train.Evaluate(x, t, system.phase);
  EXPECT_EQ(std::memcmp(kept, &c, sizeof(Contacts)), 0);
  EXPECT_GT(c.f_c_raw, 0.0);
  EXPECT_EQ(system.LastContacts(x, std::nextafter(t, 1.0)), nullptr);
  TrainState moved = x;
  moved[4 + train.Coils()] = std::nextafter(moved[4 + train.Coils()], 1.0);  // a coil's speed
  EXPECT_EQ(system.LastContacts(moved, t), nullptr);
  system.phase.mode.seat = true;
  EXPECT_EQ(system.LastContacts(x, t), nullptr);
  system.phase.mode.seat = false;
  system.phase.segment_end_rad = 1.0;
  EXPECT_EQ(system.LastContacts(x, t), nullptr);
  system.phase.segment_end_rad = std::numeric_limits<double>::infinity();
  system.phase.gated = true;
  EXPECT_EQ(system.LastContacts(x, t), nullptr);
  system.phase.gated = false;
  EXPECT_NE(system.LastContacts(x, t), nullptr);
}

}  // namespace
}  // namespace needle
