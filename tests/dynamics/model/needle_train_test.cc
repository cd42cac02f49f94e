// The train's equations: the energy audit, the analytic Jacobian against finite differences
// in every mode, the reset map of a restitution law and the parameters' validation; the spring
// as a chain of coil masses (its modes, its Jacobian, its audit). (The
// closed-form oscillation of every integrator: tests/dynamics/solver/integrator_test.cc.)
#include "dynamics/model/needle_train.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "dynamics/solver/integrator.h"
#include "lib/units.h"
#include "spring/resonance.h"
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

// The train of the Jacobian tests: both contacts compliant and damped, a gas load.
TrainParameters BumpTrain() {
  TrainParameters p;
  p.mass_kg = 0.8;
  p.preload_N = 900;
  p.rate_N_m = 5e4;
  p.gas_force_N = 120;
  p.contact_stiffness_N_m = 2e8;
  p.contact_damping_ratio = 0.07;
  p.seat_stiffness_N_m = 3e8;
  p.seat_damping_ratio = 0.04;
  return p;
}

// The one-mass train's ∂f/∂x (lift stepped by 1e-9 m, the rest by 1e-5 and 1e-3) and ∂f/∂t at
// (x, t) in `phase` against central differences, each failure tagged with `where`; returns the
// ∂f/∂x entries checked.
int ExpectJacobianMatches(const NeedleTrain& train, const TrainState& x, double t,
                          const Phase& phase, const std::string& where) {
  TrainJacobian J;
  TrainState ft;
  train.Jacobian(x, t, phase, J, ft);
  const std::array<double, 4> h = {1e-9, 1e-5, 1e-3, 1e-3};
  int checked = 0;
  for (int c = 0; c < 4; ++c) {
    TrainState xp = x, xm = x, fp, fm;
    xp[c] += h[c];
    xm[c] -= h[c];
    train.Derivative(xp, t, phase, fp);
    train.Derivative(xm, t, phase, fm);
    for (int r = 0; r < 4; ++r) {
      const double fd = (fp[r] - fm[r]) / (2.0 * h[c]);
      EXPECT_NEAR(J[r * 4 + c], fd, 1e-6 * std::abs(fd) + 1e-6)
          << "row " << r << " col " << c << where;
      ++checked;
    }
  }
  const double ht = 1e-8;
  TrainState fp, fm;
  train.Derivative(x, t + ht, phase, fp);
  train.Derivative(x, t - ht, phase, fm);
  for (int r = 0; r < 4; ++r) {
    const double fd = (fp[r] - fm[r]) / (2.0 * ht);
    EXPECT_NEAR(ft[r], fd, 1e-5 * std::abs(fd) + 1e-4) << "df/dt row " << r << where;
  }
  return checked;
}

TEST(NeedleTrainTest, JacobianMatchesCentralDifferencesInEveryMode) {
  // ∂f/∂x and ∂f/∂t of the right-hand side against central differences, on the rise and the
  // fall, the needle pressed into the cam, into its seat, or clear of both, in all four modes.
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  const NeedleTrain train(cam, BumpTrain(), 60.0, 0.0);
  int checked = 0;
  for (double t : {0.0071, 0.0123, 0.0168}) {  // θ = 0.43, 0.74, 1.01 rad
    const double u = cam.U(train.Angle(t));
    for (double y : {u - 2e-6, u + 3e-6, -4e-6}) {  // into the cam, clear, into the seat
      for (int mode = 0; mode < 4; ++mode) {
        Phase phase;
        phase.mode = {(mode & 1) != 0, (mode & 2) != 0};
        checked += ExpectJacobianMatches(train, {y, 0.05, 0.3, 0.1}, t, phase,
                                         " t " + std::to_string(t) + " y " + std::to_string(y) +
                                             " mode " + std::to_string(mode));
      }
    }
  }
  EXPECT_EQ(checked, 3 * 3 * 4 * 16);
}

// The same for a rigid train while a contact sticks: ẏ and ÿ are the surface's (ω u', ω² u''
// on the cam), functions of t alone, and the audit's Ḋ is zero. The Jacobian took ÿ's ∂/∂t as 0
// and kept the free needle's Ḋ row: rosenbrock4, which steps with it, took 43,517 steps on
// Example 1's rigid scene (dopri5: 49) and ran out of its budget at rtol 1e-12 (issue 51).
TEST(NeedleTrainTest, JacobianMatchesCentralDifferencesWhileARigidContactSticks) {
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  TrainParameters p = BumpTrain();
  p.contact = ContactKind::kRigid;
  p.contact_stiffness_N_m = p.seat_stiffness_N_m = 0.0;
  p.restitution = p.seat_restitution = 0.5;
  const NeedleTrain train(cam, p, 60.0, 0.0);
  int checked = 0;
  for (double t : {0.0071, 0.0123, 0.0168}) {
    for (const ContactMode mode : {ContactMode{true, false}, ContactMode{false, true}}) {
      Phase phase;
      phase.mode = mode;
      const TrainState x = {mode.cam ? cam.U(train.Angle(t)) : 0.0, 0.05, 0.3, 0.1};
      checked += ExpectJacobianMatches(
          train, x, t, phase, " t " + std::to_string(t) + " cam " + std::to_string(mode.cam));
    }
  }
  EXPECT_EQ(checked, 3 * 2 * 16);
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

// BumpTrain with its spring as `masses` coil masses: m_s = 0.6 kg, 5 % damping in the first mode.
TrainParameters ChainTrain(int masses) {
  TrainParameters p = BumpTrain();
  p.coil_masses = masses;
  p.spring_mass_kg = 0.6;
  p.surge_damping_ratio = 0.05;
  return p;
}

// The chain's ∂f/∂x (every column: lifts stepped by 1e-9 m, the rest by 1e-5) and ∂f/∂t of
// `train` at (x, t) in `phase` against central differences; returns the entries checked.
int ExpectChainJacobianMatches(const NeedleTrain& train, const TrainState& x, double t,
                               const Phase& phase, const std::string& where) {
  const int n = train.StateSize(), coils = train.Coils();
  TrainJacobian J;
  TrainState ft;
  train.Jacobian(x, t, phase, J, ft);
  EXPECT_EQ(static_cast<int>(J.size()), n * n);
  int checked = 0;
  for (int c = 0; c < n; ++c) {
    const double h = (c == 0 || (c >= 4 && c < 4 + coils)) ? 1e-9 : 1e-5;
    TrainState xp = x, xm = x, fp, fm;
    xp[c] += h;
    xm[c] -= h;
    train.Derivative(xp, t, phase, fp);
    train.Derivative(xm, t, phase, fm);
    for (int r = 0; r < n; ++r) {
      const double fd = (fp[r] - fm[r]) / (2.0 * h);
      EXPECT_NEAR(J[r * n + c], fd, 1e-6 * std::abs(fd) + 1e-5)
          << "row " << r << " col " << c << " " << where;
      ++checked;
    }
  }
  const double ht = 1e-8;
  TrainState fp, fm;
  train.Derivative(x, t + ht, phase, fp);
  train.Derivative(x, t - ht, phase, fm);
  for (int r = 0; r < n; ++r) {
    const double fd = (fp[r] - fm[r]) / (2.0 * ht);
    EXPECT_NEAR(ft[r], fd, 1e-5 * std::abs(fd) + 1e-4) << "df/dt row " << r << " " << where;
  }
  return checked;
}

TEST(NeedleTrainTest, TheCoilChainsJacobianMatchesCentralDifferences) {
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  const NeedleTrain train(cam, ChainTrain(4), 60.0, 0.0);
  ASSERT_EQ(train.StateSize(), 10);
  EXPECT_NEAR(train.NeedleMassKg(), 0.8 - 0.2 + 0.6 / 8.0, 1e-15);  // m − m_s/3 + m_s/(2N)
  int checked = 0;
  for (double t : {0.0071, 0.0168}) {
    const double u = cam.U(train.Angle(t));
    for (int mode = 0; mode < 4; ++mode) {
      Phase phase;
      phase.mode = {(mode & 1) != 0, (mode & 2) != 0};
      // The coils off their even compression, moving: x_i, then v_i.
      const TrainState x = {u - 2e-6, 0.05, 0.3, 0.1, 0.8 * u, 0.4 * u, 0.3 * u, -0.02, 0.03, 0.01};
      checked += ExpectChainJacobianMatches(
          train, x, t, phase, "t " + std::to_string(t) + " mode " + std::to_string(mode));
    }
  }
  EXPECT_EQ(checked, 2 * 4 * 100);
}

TEST(NeedleTrainTest, AChainOfTwentyRingsAtTheWaveEquationsFirstThreeModes) {
  // The needle held on a rigid seat: the coils are a spring fixed at both ends, whose modes are
  // f_i = i·½√(k/m_s) (the wave equation). The chain's ω² are the eigenvalues of −∂v̇/∂x from
  // the train's own Jacobian; N = 20 must be within 1 % for the first three.
  const LiftLaw law = FarLaw(0.0);
  const CamInput cam(law, 0.5e-3, RampKind::kLinear, 0.1);
  TrainParameters p = ChainTrain(20);
  p.contact = ContactKind::kRigid;
  p.surge_damping_ratio = 0.0;
  const NeedleTrain train(cam, p, 10.0, 0.0);
  TrainState x = train.EquilibriumStart();
  ASSERT_EQ(static_cast<int>(x.size()), 4 + 2 * 19);
  Phase held;
  held.mode.seat = true;
  TrainJacobian J;
  TrainState ft;
  train.Jacobian(x, 0.0, held, J, ft);
  const int n = train.StateSize(), c = train.Coils();
  Eigen::MatrixXd k(c, c);
  for (int i = 0; i < c; ++i) {
    for (int j = 0; j < c; ++j) k(i, j) = -J[(4 + c + i) * n + (4 + j)];  // −∂v̇_i/∂x_j
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes(k);
  const double f_1 = SurgeFrequencyHz(p.rate_N_m, p.spring_mass_kg, 1);
  // The lumped chain of the resonance map (spring/resonance.h), the same N segments.
  const std::vector<double> lumped = ChainNaturalFrequenciesHz(p.rate_N_m, p.spring_mass_kg, 20, 3);
  for (int i = 1; i <= 3; ++i) {
    const double f = std::sqrt(modes.eigenvalues()(i - 1)) / (2.0 * kPi);
    EXPECT_NEAR(f / lumped[i - 1], 1.0, 1e-12) << "mode " << i;
    EXPECT_NEAR(f / (i * f_1), 1.0, 0.01) << "mode " << i;
    EXPECT_LT(f, i * f_1) << "a lumped chain rings below the continuum";
  }
}

TEST(NeedleTrainTest, TheEnergyAuditClosesWithACoilChainThroughACamEvent) {
  // The chain of six coil masses, damped, through the bump and back on the seat, at rtol 1e-10:
  // W, D and E close about as well as they do for the massless spring with every time stepper
  // (measured: dopri5 7.7e-11, one mass 1.4e-12; rkf78 1.1e-8, 2.6e-8; rosenbrock4 1.9e-11,
  // 1.1e-11; cvode-bdf 2.3e-10, 3.0e-10), below 1e-8 but for rkf78 (whose one-mass residual is
  // above it already), and the coils ring (they take part).
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  const NeedleTrain chain(cam, ChainTrain(6), 60.0, 0.0), one(cam, ChainTrain(1), 60.0, 0.0);
  IntegratorOptions o;
  o.rtol = 1e-10;
  o.atol_m = 1e-13;
  const auto residual = [&](const NeedleTrain& train, Method m, TrainState* end) {
    const TrainState x0 = train.EquilibriumStart();
    Recorder recorder(train, false);
    const IntegrationStats s = Integrate(m, train, x0, 0.03, recorder, o);
    *end = s.final_state;
    return train.EnergyResidual(x0, s.final_state, s.final_time);
  };
  for (Method m : {Method::kDopri5, Method::kRkf78, Method::kRosenbrock4, Method::kCvodeBdf}) {
    TrainState end_chain, end_one;
    const double r_chain = residual(chain, m, &end_chain), r_one = residual(one, m, &end_one);
    EXPECT_LT(r_chain, 3.0 * r_one + 1e-10) << MethodName(m) << " one mass: " << r_one;
    if (m != Method::kRkf78) {
      EXPECT_LT(r_chain, 1e-8) << MethodName(m);
    }
    EXPECT_GT(chain.LargestCoilSpeed(end_chain), 1e-4) << MethodName(m);
    EXPECT_GT(end_chain[3], 0.0) << MethodName(m);
  }
}

TEST(NeedleTrainTest, TheChainsParametersAreValidatedByName) {
  TrainParameters p = ChainTrain(41);
  try {
    p.Validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "TrainParameters.coil_masses = 41.000000: must be in [1, 40]");
  }
  p.coil_masses = 3;
  p.spring_mass_kg = 2.5;  // > 3 mass_kg: no needle left
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.spring_mass_kg = 0.6;
  p.surge_damping_ratio = 1.5;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.surge_damping_ratio = 0.0;
  p.rate_N_m = 0.0;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
}

// ChainTrain(masses) whose segments go solid at travel_m / masses and then meet through the
// clash law (k_cl = 1e8 N/m, ζ_cl = 5 %).
TrainParameters ClashTrain(int masses, double travel_m) {
  TrainParameters p = ChainTrain(masses);
  p.coil_travel_m = travel_m;
  p.coil_clash = true;
  return p;
}

TEST(NeedleTrainTest, TheClashingChainsJacobianMatchesCentralDifferences) {
  // Four segments compressed 0.2, 0.4, 0.1 and 0.3 of u beyond installed, solid at 0.25 u: the
  // second and fourth penetrate. Every clash mode of segments 1–4 that the driver can set (none,
  // 2 and 4, 1 and 3, all) with all four contact modes.
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  const double t = 0.0071, u = cam.U(60.0 * t);
  const NeedleTrain train(cam, ClashTrain(4, u), 60.0, 0.0);
  ASSERT_EQ(train.ClashSegments(), 4);
  const TrainState x = {u - 2e-6, 0.05, 0.3, 0.1, 0.8 * u, 0.4 * u, 0.3 * u, -0.02, 0.03, 0.01};
  int checked = 0;
  for (std::uint64_t clash : {0b0000u, 0b1010u, 0b0101u, 0b1111u}) {
    for (int mode = 0; mode < 4; ++mode) {
      Phase phase;
      phase.mode = {(mode & 1) != 0, (mode & 2) != 0, clash};
      checked += ExpectChainJacobianMatches(
          train, x, t, phase, "clash " + std::to_string(clash) + " mode " + std::to_string(mode));
    }
  }
  EXPECT_EQ(checked, 4 * 4 * 100);
  // A solid segment pushes: the clash mode changes the coils' accelerations.
  Phase none, all;
  all.mode.clash = 0b1111u;
  TrainState f0, f1;
  train.Derivative(x, t, none, f0);
  train.Derivative(x, t, all, f1);
  EXPECT_GT(std::abs(f1[7] - f0[7]), 1.0);
}

TEST(NeedleTrainTest, ClashingCoilsStiffenTheSpringAsTheClosedFormSays) {
  // The bump driven slowly (ω = 1 rad/s: the masses' inertia m ω² u'' is 0.03 N, 4e-5 of the
  // force without clash, 3e-6 with it, inside the tolerances): six segments evenly
  // compressed by y/6 go solid past δ = 1.5 mm/6, and each then carries
  // S = P₀ + k y + k_cl (y/6 − δ). At the top of the bump (u = 2 mm) the cam pushes F = S − F_g
  // into its compliant contact, y = u − F/k_c:
  //     F = (P₀ − F_g − k_cl δ + B u) / (1 + B/k_c),   B = k + k_cl/6,
  // and without clash (B = k, no k_cl δ) F = (P₀ − F_g + k u)/(1 + k/k_c). Either way the
  // segments are even, so the least gap to solid is the travel less y.
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  const double travel = 1.5e-3, omega = 1.0, n = 6.0, u = 2e-3;
  const TrainParameters p = ClashTrain(6, travel);
  const NeedleTrain clash(cam, p, omega, 0.0);
  TrainParameters q = p;
  q.coil_clash = false;
  const NeedleTrain chain(cam, q, omega, 0.0);
  IntegratorOptions o;
  o.rtol = 1e-9;
  const auto run = [&](const NeedleTrain& train, Recorder& recorder) {
    return Integrate(Method::kDopri5, train, train.EquilibriumStart(), 1.4 / omega, recorder, o);
  };
  Recorder with(clash, false), without(chain, false);
  const IntegrationStats s = run(clash, with);
  run(chain, without);
  const double kc = p.contact_stiffness_N_m, kcl = p.clash_stiffness_N_m;
  const double b = p.rate_N_m + kcl / n;
  const double f_solid = (p.preload_N - p.gas_force_N - kcl * travel / n + b * u) / (1.0 + b / kc);
  const double f_free = (p.preload_N - p.gas_force_N + p.rate_N_m * u) / (1.0 + p.rate_N_m / kc);
  EXPECT_NEAR(with.max_contact_force_N() / f_solid, 1.0, 1e-5);
  EXPECT_NEAR(without.max_contact_force_N() / f_free, 1.0, 1e-4);
  // Each segment clashed once; with the law the coils pass solid by F/k_cl-ish, without it they
  // pass through each other by the lift's excess over the travel.
  EXPECT_EQ(with.coil_clashes(), 6);
  EXPECT_EQ(without.coil_clashes(), 0);
  EXPECT_NEAR(*with.min_coil_gap_m(), travel - (u - f_solid / kc), 1e-3 * travel);
  EXPECT_NEAR(*without.min_coil_gap_m(), travel - (u - f_free / kc), 1e-3 * travel);
  EXPECT_LT(clash.EnergyResidual(clash.EquilibriumStart(), s.final_state, s.final_time), 1e-8);
  // The audit with the coils solid (stopped at the top of the bump): the clash law's potential
  // holds a part of E there (θ = 0.7 rad).
  Recorder top(clash, false);
  const IntegrationStats at_top =
      Integrate(Method::kDopri5, clash, clash.EquilibriumStart(), 0.7 / omega, top, o);
  EXPECT_EQ(top.coil_clashes(), 6);
  EXPECT_LT(clash.EnergyResidual(clash.EquilibriumStart(), at_top.final_state, at_top.final_time),
            1e-8);
}

TEST(NeedleTrainTest, TheEnergyAuditClosesWithClashingCoilsThroughACamEvent) {
  // The chain of the audit test above with its six segments solid at 1.2 mm / 6: at 60 rad/s
  // the coils clash and rebound; the clash law's potential and loss close the audit with every
  // stepper that carries chains.
  const LiftLaw law = Bump();
  const CamInput cam(law, 0.0, RampKind::kLinear, 0.1);
  const NeedleTrain train(cam, ClashTrain(6, 1.2e-3), 60.0, 0.0);
  IntegratorOptions o;
  o.rtol = 1e-10;
  o.atol_m = 1e-13;
  for (Method m : {Method::kDopri5, Method::kRosenbrock4, Method::kCvodeBdf}) {
    const TrainState x0 = train.EquilibriumStart();
    Recorder recorder(train, false);
    const IntegrationStats s = Integrate(m, train, x0, 0.03, recorder, o);
    EXPECT_LT(train.EnergyResidual(x0, s.final_state, s.final_time), 1e-8) << MethodName(m);
    EXPECT_GE(recorder.coil_clashes(), 6) << MethodName(m);
    EXPECT_GT(s.final_state[3], 0.0) << MethodName(m);
  }
}

TEST(NeedleTrainTest, TheClashParametersAreValidatedByName) {
  TrainParameters p = ClashTrain(1, 1e-3);
  try {
    p.Validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "TrainParameters.coil_masses = 1.000000: must be at least 2 for coil_clash (the "
                 "coils that meet)");
  }
  p = ClashTrain(3, 0.0);
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.coil_travel_m = 1e-3;
  p.clash_stiffness_N_m = 0.0;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.clash_stiffness_N_m = 1e8;
  p.clash_damping_ratio = -0.1;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.clash_damping_ratio = 0.05;
  EXPECT_NO_THROW(p.Validate());
  p.coil_travel_m = -1e-3;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace needle
