// Free oscillation in each contact mode against its closed form, for every integrator, and
// the error's convergence as the tolerance tightens.
#include "dynamics/model/needle_train.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/solver/integrator.h"

namespace needle {
namespace {

// A lift law far from the window: the cam input is constant over [0, 0.8] rad.
LiftLaw Law(double base_m) {
  LiftTable t;
  t.crank_rad = {1.0, 1.1, 1.2, 1.3, 1.4};
  t.lift_m = {base_m, base_m + 0.5e-3, base_m + 1e-3, base_m + 0.5e-3, base_m};
  return LiftLaw(t, SplineOptions{});
}

struct Case {
  double y_eq, omega, amplitude;
};

double Error(Method method, double rtol, bool seat_mode, double* frequency = nullptr) {
  const double m = 1.0, k = 1e4, preload = 100.0;
  const double stiffness = 1e6;
  const LiftLaw law = Law(seat_mode ? 0.0 : 1e-3);
  // Seat only: play keeps the cam (at −δ) away. Cam only: no play, u = 1 mm before the table.
  const CamInput cam(law, seat_mode ? 0.5e-3 : 0.0, RampKind::kLinear, 0.1);
  TrainParameters p;
  p.mass_kg = m;
  p.preload_N = preload;
  p.rate_N_m = k;
  p.contact_stiffness_N_m = stiffness;
  p.seat_stiffness_N_m = stiffness;
  p.contact_damping_ratio = 0.0;
  p.seat_damping_ratio = 0.0;
  const double omega = 10.0;
  NeedleTrain train(cam, p, omega, 0.0);
  // seat: m ÿ = −k_s y − P₀ − k y;  cam: m ÿ = k_c (u − y) − P₀ − k y.
  const double y_eq =
      seat_mode ? -preload / (stiffness + k) : (stiffness * 1e-3 - preload) / (stiffness + k);
  const double w = std::sqrt((stiffness + k) / m);
  if (frequency) *frequency = w;
  const double a = 0.05e-3;
  const TrainState x0 = {y_eq + a, 0.0, 0.0, 0.0};
  Recorder recorder(train, false);
  IntegratorOptions o;
  o.rtol = rtol;
  o.atol_m = rtol * 1e-3;
  const double t_end = 0.07;  // 11 periods, θ stays below 0.8 rad
  const IntegrationStats s = Integrate(method, train, x0, t_end, recorder, o);
  EXPECT_NEAR(s.final_time, t_end, 1e-12);
  EXPECT_EQ(s.final_phase.mode.seat, seat_mode);
  EXPECT_EQ(s.final_phase.mode.cam, !seat_mode);
  EXPECT_TRUE(recorder.impacts().empty());
  const double exact = y_eq + a * std::cos(w * t_end);
  return std::abs(s.final_state[0] - exact) / a;
}

TEST(NeedleTrainTest, SeatOnlyOscillatesAtSqrtOfSeatPlusSpringOverMass) {
  for (Method m : {Method::kDopri5, Method::kCvodeBdf, Method::kCvodeAdams}) {
    EXPECT_LT(Error(m, 1e-10, true), 1e-6) << MethodName(m);
  }
}

TEST(NeedleTrainTest, CamOnlyOscillatesAtSqrtOfContactPlusSpringOverMass) {
  for (Method m : {Method::kDopri5, Method::kCvodeBdf, Method::kCvodeAdams}) {
    EXPECT_LT(Error(m, 1e-10, false), 1e-6) << MethodName(m);
  }
}

TEST(NeedleTrainTest, Dopri5ErrorShrinksWithTheTolerance) {
  // Global error tracks the tolerance: a hundredfold tighter rtol gives at least a 30-fold
  // smaller error over 11 periods, down to 1e-9 of the amplitude.
  const double e6 = Error(Method::kDopri5, 1e-6, true);
  const double e8 = Error(Method::kDopri5, 1e-8, true);
  const double e10 = Error(Method::kDopri5, 1e-10, true);
  EXPECT_LT(e8, e6 / 30.0);
  EXPECT_LT(e10, e8 / 30.0);
  EXPECT_LT(e10, 1e-7);
}

TEST(NeedleTrainTest, EnergyAuditIsExactForAConservativeOscillation) {
  const LiftLaw law = Law(0.0);
  const CamInput cam(law, 0.5e-3, RampKind::kLinear, 0.1);
  TrainParameters p;
  p.preload_N = 100;
  p.rate_N_m = 1e4;
  p.contact_stiffness_N_m = p.seat_stiffness_N_m = 1e6;
  p.contact_damping_ratio = p.seat_damping_ratio = 0.0;
  NeedleTrain train(cam, p, 10.0, 0.0);
  const TrainState x0 = {-1e-4 + 3e-5, 0.0, 0.0, 0.0};
  Recorder recorder(train, false);
  IntegratorOptions o;
  o.rtol = 1e-11;
  o.atol_m = 1e-14;
  const IntegrationStats s = Integrate(Method::kDopri5, train, x0, 0.05, recorder, o);
  EXPECT_NEAR(train.Energy(s.final_state, s.final_time), train.Energy(x0, 0.0),
              1e-9 * std::abs(train.Energy(x0, 0.0)));
  EXPECT_EQ(s.final_state[2], 0.0);  // no cam work without cam contact
  EXPECT_NEAR(s.final_state[3], 0.0, 1e-18);
}

TEST(NeedleTrainTest, ParametersAreValidatedByName) {
  TrainParameters p;
  p.mass_kg = 0.0;
  try {
    p.Validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "TrainParameters.mass_kg = 0.000000: must be positive");
  }
  p.mass_kg = 1.0;
  p.contact_damping_ratio = -0.1;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.contact_damping_ratio = 0.1;
  p.contact_stiffness_N_m = -1.0;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace needle
