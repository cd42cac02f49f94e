// The coil chain in closed form (dynamics/solver/chain_modes.h, closed_form.h): its modes give
// back the train's own Jacobian, a piece's motion satisfies the train's own right-hand side, and
// whole runs agree with dopri5 at rtol 1e-12 in every impact and episode, the audit closing.
#include "dynamics/solver/chain_modes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

#include "apps/case/case_scene.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/closed_form.h"
#include "dynamics/solver/integrator.h"
#include "lib/units.h"
#include "tests/dynamics/test_laws.h"

namespace needle {
namespace {

// A 0.8 kg needle on a 5e4 N/m spring of 0.6 kg in `coils` masses, damped, under a cam far away.
struct Chain {
  explicit Chain(int coils, double zeta = 0.05)
      : law(FarLaw(1e-3)), cam(law, 0.0, RampKind::kLinear, 0.1) {
    p.mass_kg = 0.8;
    p.preload_N = 900.0;
    p.rate_N_m = 5e4;
    p.coil_masses = coils;
    p.spring_mass_kg = 0.6;
    p.surge_damping_ratio = zeta;
    p.contact_damping_ratio = 0.2;
  }
  LiftLaw law;
  CamInput cam;
  TrainParameters p;
};

// V Λ V⁻¹ over both members of each pair, against ∂f/∂x of the train's own right-hand side
// (NeedleTrain::Jacobian: the same equations, written out a second time, by rows).
TEST(ChainModesTest, TheModesGiveTheTrainsJacobianBack) {
  for (const ContactMode mode : {ContactMode{false, false}, ContactMode{true, false},
                                 ContactMode{false, true}, ContactMode{true, true}}) {
    const Chain c(6);
    const NeedleTrain train(c.cam, c.p, 60.0, 0.0);
    const ChainModes modes(train, mode);
    const int n = modes.Dofs(), size = train.StateSize(), coils = train.Coils();
    ASSERT_EQ(n, 6);
    TrainState x(size, 0.0), dfdt;
    TrainJacobian J;
    train.Jacobian(x, 0.001, Phase{mode}, J, dfdt);
    // State entry of the chain's z index: q = [y, x_1 …], q̇ = [ẏ, v_1 …].
    const auto entry = [&](int z) {
      if (z == 0) return 0;
      if (z == n) return 1;
      return z < n ? 3 + z : 3 + coils + (z - n);
    };
    const Eigen::MatrixXcd& V = modes.Vectors();
    const Eigen::MatrixXcd& W = modes.Inverse();
    double largest = 0.0, misfit = 0.0;
    for (int r = 0; r < 2 * n; ++r) {
      for (int k = 0; k < 2 * n; ++k) {
        std::complex<double> a = 0.0;
        for (Eigen::Index m = 0; m < modes.Lambda().size(); ++m) {
          const std::complex<double> term = V(r, m) * modes.Lambda()[m] * W(m, k);
          a += modes.Weight()[m] == 2.0 ? 2.0 * term.real() : term.real();
        }
        const double want = J[entry(r) * size + entry(k)];
        largest = std::max(largest, std::abs(want));
        misfit = std::max(misfit, std::abs(a.real() - want));
      }
    }
    EXPECT_LT(misfit, 1e-10 * largest) << mode.cam << mode.seat;
    // Every mode decays (the chain is damped) and the fastest is |λ|'s largest.
    double fastest = 0.0;
    for (Eigen::Index m = 0; m < modes.Lambda().size(); ++m) {
      EXPECT_LT(modes.Lambda()[m].real(), 0.0);
      fastest = std::max(fastest, std::abs(modes.Lambda()[m]));
    }
    EXPECT_EQ(modes.Fastest(), fastest);
  }
}

// An undamped chain of two masses in flight: ω² are the roots of det(K − ω²M) = 0.
TEST(ChainModesTest, TwoMassesInFlightRingAtTheTextbookFrequencies) {
  Chain c(2, 0.0);
  const NeedleTrain train(c.cam, c.p, 60.0, 0.0);
  const ChainModes modes(train, ContactMode{false, false});
  const double m1 = train.NeedleMassKg(), m2 = train.CoilMassKg(), k = train.SegmentRateNm();
  // K = [[k, −k], [−k, 2k]]: m1 m2 ω⁴ − (2k m1 + k m2) ω² + k² = 0.
  const double a = m1 * m2, b = -(2.0 * k * m1 + k * m2), cc = k * k;
  const double d = std::sqrt(b * b - 4.0 * a * cc);
  const double slow = std::sqrt((-b - d) / (2.0 * a)), fast = std::sqrt((-b + d) / (2.0 * a));
  ASSERT_EQ(modes.Lambda().size(), 2);
  std::vector<double> found = {std::abs(modes.Lambda()[0].imag()),
                               std::abs(modes.Lambda()[1].imag())};
  std::sort(found.begin(), found.end());
  EXPECT_NEAR(found[0], slow, 1e-12 * fast);
  EXPECT_NEAR(found[1], fast, 1e-12 * fast);
  for (Eigen::Index m = 0; m < 2; ++m) EXPECT_NEAR(modes.Lambda()[m].real(), 0.0, 1e-12 * fast);
}

// Along a piece, ẏ, ÿ and the coils' rates are those the train's right-hand side gives at the
// piece's own state (centred differences of the closed form against NeedleTrain::Derivative), on
// the cam in its rise (a forcing polynomial of degree 5) and in flight; and the piece starts on
// its start state to the bit.
TEST(ChainModesTest, APieceSolvesTheTrainsOwnEquations) {
  const Case k = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml");
  const Scene s = MakeScene(k);
  const double omega = OmegaFromRpm(400), theta_a = DefaultRunWindow(s).start_rad;
  const NeedleTrain train(*s.cam, s.train, omega, theta_a);
  const LiftLaw& law = s.cam->law();
  for (const ContactMode mode : {ContactMode{true, false}, ContactMode{false, false}}) {
    const ChainModes modes(train, mode);
    const double th = law.start_rad() + 0.4 * (law.end_rad() - law.start_rad());
    const double t0 = train.Time(th);
    TrainState x0(train.StateSize(), 0.0);
    x0[0] = s.cam->U(th) - 2e-6;
    x0[1] = omega * s.cam->Slope(th) + (mode.cam ? 0.0 : 0.05);
    for (int i = 1; i <= train.Coils(); ++i) {
      x0[3 + i] = x0[0] * (train.Coils() + 1 - i) / (train.Coils() + 1.0) + 1e-6 * (i % 3);
      x0[3 + train.Coils() + i] = 0.01 * std::sin(i);
    }
    const ClosedFormPiece piece(train, mode, th, t0, x0, &modes);
    const TrainState start = piece.MotionState(t0);
    for (int i = 0; i < train.StateSize(); ++i) {
      if (i != 2 && i != 3) EXPECT_EQ(start[i], x0[i]) << i;
    }
    for (double dt : {3e-6, 4e-5, 2e-4}) {
      const double t = t0 + dt, h = 1e-8;
      const TrainState x = piece.MotionState(t);
      const TrainState xp = piece.MotionState(t + h), xm = piece.MotionState(t - h);
      TrainState dxdt;
      train.Derivative(x, t, Phase{mode}, dxdt);
      for (int i = 0; i < train.StateSize(); ++i) {
        if (i == 2 || i == 3) continue;
        const double rate = (xp[i] - xm[i]) / (2.0 * h);
        const double scale = i == 1 || i >= 4 + train.Coils() ? 100.0 : 1.0;  // m/s², m/s
        EXPECT_NEAR(rate, dxdt[i], 1e-5 * scale) << "entry " << i << " at " << dt;
      }
      EXPECT_NEAR(piece.Motion(t)[2], dxdt[1], 1e-9 * std::abs(dxdt[1]) + 1e-6) << dt;
    }
  }
}

TEST(ChainModesTest, CoilClashIsRefusedWithTheReason) {
  Chain c(4);
  c.p.coil_travel_m = 0.02;
  c.p.coil_clash = true;
  const NeedleTrain train(c.cam, c.p, 60.0, 0.0);
  ASSERT_TRUE(ExactRefusal(train).has_value());
  EXPECT_EQ(*ExactRefusal(train),
            "method \"exact\" carries no coil clash; the spring's coils may clash ([spring] "
            "clash = true)");
  c.p.coil_clash = false;
  const NeedleTrain free(c.cam, c.p, 60.0, 0.0);
  EXPECT_FALSE(ExactRefusal(free).has_value());
}

// Whole runs of the bundled chain: the same impacts to 1e-6°, the same episodes, lift and least
// coil gap (to 10 nm) as dopri5 at rtol 1e-12, and the audit closing to 1e-10 of the work put
// in.
TEST(ChainModesTest, ExactAgreesWithDopri5OnTheBundledChain) {
  const Case k = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml");
  const Scene s = MakeScene(k);
  for (const double rpm : {125.0, 520.0, 900.0}) {
    SimulationOptions o;
    o.force_dynamic = true;
    o.cycles = 1;
    o.method = "dopri5";
    o.integrator.rtol = 1e-12;
    o.integrator.atol_m = DefaultAtol(1e-12);
    const SimulationResult d = Simulate(s, rpm, o);
    o.method = "exact";
    const SimulationResult e = Simulate(s, rpm, o);
    EXPECT_EQ(e.method, "exact");
    ASSERT_EQ(d.impacts.size(), e.impacts.size()) << rpm;
    for (size_t i = 0; i < d.impacts.size(); ++i) {
      EXPECT_EQ(d.impacts[i].kind, e.impacts[i].kind) << i;
      EXPECT_NEAR(d.impacts[i].crank_rad / kDeg, e.impacts[i].crank_rad / kDeg, 1e-6) << i;
    }
    ASSERT_EQ(d.episodes.size(), e.episodes.size()) << rpm;
    EXPECT_NEAR(d.max_lift_m * 1e3, e.max_lift_m * 1e3, 1e-9) << rpm;
    ASSERT_EQ(d.min_coil_gap_m.has_value(), e.min_coil_gap_m.has_value());
    if (d.min_coil_gap_m) {
      // dopri5 samples the compression (three points a step), the closed form locates its
      // largest: its gap is the smaller, by what dopri5's sampling misses.
      EXPECT_LE(*e.min_coil_gap_m, *d.min_coil_gap_m + 1e-12) << rpm;
      EXPECT_NEAR(*d.min_coil_gap_m * 1e3, *e.min_coil_gap_m * 1e3, 1e-5) << rpm;
    }
    EXPECT_LT(e.energy_residual, 1e-10) << rpm;
    std::printf(
        "%g rpm: %zu impacts, %zu episodes, dopri5 %ld steps, exact %ld steps, "
        "residual %.2e vs %.2e\n",
        rpm, e.impacts.size(), e.episodes.size(), d.stats.steps, e.stats.steps, d.energy_residual,
        e.energy_residual);
  }
}

}  // namespace
}  // namespace needle
