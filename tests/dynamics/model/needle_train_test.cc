// The train's equations: the energy audit, the analytic Jacobian against finite differences
// in every mode, the reset map of a restitution law and the parameters' validation. (The
// closed-form oscillation of every integrator: tests/dynamics/solver/integrator_test.cc.)
#include "dynamics/model/needle_train.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/solver/integrator.h"
#include "lib/units.h"
#include "tests/dynamics/test_laws.h"

namespace needle {
namespace {

TEST(NeedleTrainTest, EnergyAuditIsExactForAConservativeOscillation) {
  const LiftLaw law = FarLaw(0.0);
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

// A cam event inside the window: a (1 − cos) lift of 2 mm over [0.2, 1.2] rad.
LiftLaw Bump() {
  LiftTable t;
  for (int i = 0; i <= 20; ++i) {
    t.crank_rad.push_back(0.2 + i * 0.05);
    t.lift_m.push_back(1e-3 * (1.0 - std::cos(2.0 * kPi * i / 20.0)));
  }
  return LiftLaw(t, SplineOptions{});
}

TEST(NeedleTrainTest, JacobianMatchesCentralDifferencesInEveryMode) {
  // ∂f/∂x and ∂f/∂t of the right-hand side against central differences, on the rise and the
  // fall, the needle pressed into the cam, into its seat, or clear of both, in all four modes.
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  TrainParameters p;
  p.mass_kg = 0.8;
  p.preload_N = 900;
  p.rate_N_m = 5e4;
  p.gas_force_N = 120;
  p.contact_stiffness_N_m = 2e8;
  p.contact_damping_ratio = 0.07;
  p.seat_stiffness_N_m = 3e8;
  p.seat_damping_ratio = 0.04;
  const NeedleTrain train(cam, p, 60.0, 0.0);
  int checked = 0;
  for (double t : {0.0071, 0.0123, 0.0168}) {  // θ = 0.43, 0.74, 1.01 rad
    const double u = cam.U(train.Angle(t));
    for (double y : {u - 2e-6, u + 3e-6, -4e-6}) {  // into the cam, clear, into the seat
      for (int mode = 0; mode < 4; ++mode) {
        Phase phase;
        phase.mode = {(mode & 1) != 0, (mode & 2) != 0};
        const TrainState x = {y, 0.05, 0.3, 0.1};
        TrainJacobian J;
        TrainState ft;
        train.Jacobian(x, t, phase, J, ft);
        const std::array<double, 4> h = {1e-9, 1e-5, 1e-3, 1e-3};
        for (int c = 0; c < 4; ++c) {
          TrainState xp = x, xm = x, fp, fm;
          xp[c] += h[c];
          xm[c] -= h[c];
          train.Derivative(xp, t, phase, fp);
          train.Derivative(xm, t, phase, fm);
          for (int r = 0; r < 4; ++r) {
            const double fd = (fp[r] - fm[r]) / (2.0 * h[c]);
            EXPECT_NEAR(J[r * 4 + c], fd, 1e-6 * std::abs(fd) + 1e-6)
                << "row " << r << " col " << c << " t " << t << " y " << y << " mode " << mode;
            ++checked;
          }
        }
        const double ht = 1e-8;
        TrainState fp, fm;
        train.Derivative(x, t + ht, phase, fp);
        train.Derivative(x, t - ht, phase, fm);
        for (int r = 0; r < 4; ++r) {
          const double fd = (fp[r] - fm[r]) / (2.0 * ht);
          EXPECT_NEAR(ft[r], fd, 1e-5 * std::abs(fd) + 1e-4)
              << "df/dt row " << r << " t " << t << " y " << y << " mode " << mode;
        }
      }
    }
  }
  EXPECT_EQ(checked, 3 * 3 * 4 * 16);
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
