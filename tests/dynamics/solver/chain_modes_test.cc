// The coil chain in closed form (dynamics/solver/chain_modes.h, closed_form.h): its modes give
// back the train's own Jacobian, a piece's motion satisfies the train's own right-hand side, and
// whole runs agree with dopri5 at rtol 1e-12 in every impact and episode, the audit closing.
#include "dynamics/solver/chain_modes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

// The bundled 20-mass chain at 400 rpm, and a start 40 % into its lift: the needle 2 µm into
// the cam (or 1 µm into the seat) and moving off it, the coils off their even compression.
struct SurgeChain {
  SurgeChain()
      : c(LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml")),
        s(MakeScene(c)),
        omega(OmegaFromRpm(400)),
        train(*s.cam, s.train, omega, DefaultRunWindow(s).start_rad) {}
  double Angle() const {
    const LiftLaw& law = s.cam->law();
    return law.start_rad() + 0.4 * (law.end_rad() - law.start_rad());
  }
  TrainState Start(const ContactMode& mode) const {
    const double th = Angle();
    const int coils = train.Coils();
    TrainState x0(train.StateSize(), 0.0);
    x0[0] = mode.seat ? -1e-6 : s.cam->U(th) - 2e-6;
    x0[1] = mode.seat ? 0.02 : omega * s.cam->Slope(th) + 0.05;
    for (int i = 1; i <= coils; ++i) {
      x0[3 + i] = x0[0] * (coils + 1 - i) / (coils + 1.0) + 2e-6 * (i % 3);
      x0[3 + coils + i] = 0.02 * std::sin(i);
    }
    return x0;
  }
  // f(mode, piece, t0) for the piece in each of `modes` from Start(mode) at Angle(), time t0.
  template <class F>
  void ForEachPiece(std::initializer_list<ContactMode> modes, F f) const {
    for (const ContactMode& mode : modes) {
      const ChainModes chain_modes(train, mode);
      const double th = Angle(), t0 = train.Time(th);
      f(mode, ClosedFormPiece(train, mode, th, t0, Start(mode), &chain_modes), t0);
    }
  }
  Case c;
  Scene s;
  double omega;
  NeedleTrain train;
};

constexpr std::initializer_list<ContactMode> kEveryMode = {
    ContactMode{true, false}, ContactMode{false, false}, ContactMode{false, true},
    ContactMode{true, true}};

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
    // Entry by entry, to 1e-10 of its row's scale in the entry's own units: a lift column (1/s
    // or 1/s² per m) against the row's largest lift entry and its largest velocity entry times
    // the fastest |λ|, a velocity column the other way round.
    const double w = modes.Fastest();
    for (int r = 0; r < 2 * n; ++r) {
      double lifts = 0.0, speeds = 0.0;
      for (int k = 0; k < 2 * n; ++k)
        (k < n ? lifts : speeds) =
            std::max(k < n ? lifts : speeds, std::abs(J[entry(r) * size + entry(k)]));
      for (int k = 0; k < 2 * n; ++k) {
        double a = 0.0;
        for (Eigen::Index m = 0; m < modes.Lambda().size(); ++m)
          a += modes.Weight()[m] * (V(r, m) * modes.Lambda()[m] * W(m, k)).real();
        const double scale = k < n ? std::max(lifts, speeds * w) : std::max(speeds, lifts / w);
        EXPECT_NEAR(a, J[entry(r) * size + entry(k)], 1e-10 * scale)
            << "row " << r << " column " << k << " mode " << mode.cam << mode.seat;
      }
    }
    for (Eigen::Index m = 0; m < modes.Lambda().size(); ++m) {
      EXPECT_LT(modes.Lambda()[m].real(), 0.0);  // every mode decays (the chain is damped)
    }
  }
}

// The eigenvalues by Aberth's iteration (tridiagonal_qep.h) are the dense QR's, mode by mode, on
// the bundled 20-mass chain in every contact mode (its cam and seat at 1e9 N/m, ζ 0.05: damping
// that is not proportional) and on a 6-mass chain with its coils near critical damping (ζ_s 0.9).
TEST(ChainModesTest, TheAberthEigenvaluesAreTheDenseQrs) {
  const SurgeChain surge;
  const Chain heavy(6, 0.9);
  const NeedleTrain heavy_train(heavy.cam, heavy.p, 60.0, 0.0);
  for (const NeedleTrain* train : {&surge.train, &heavy_train}) {
    for (const ContactMode& mode : kEveryMode) {
      const ChainModes aberth(*train, mode), dense(*train, mode, ChainEigenvalues::kDense);
      ASSERT_EQ(aberth.Lambda().size(), dense.Lambda().size());
      for (Eigen::Index i = 0; i < aberth.Lambda().size(); ++i) {
        double nearest = INFINITY;
        for (Eigen::Index j = 0; j < dense.Lambda().size(); ++j)
          nearest = std::min(nearest, std::abs(aberth.Lambda()[i] - dense.Lambda()[j]));
        EXPECT_LT(nearest, 1e-12 * dense.Fastest()) << i << " mode " << mode.cam << mode.seat;
      }
      EXPECT_EQ(aberth.Weight().sum(), dense.Weight().sum());
    }
  }
}

// ChainModes::Shared: one chain per set of its numbers and mode, on a thread. A train at another
// speed (the chain does not read it) shares it; one that differs in any number the chain is made
// of, or in the mode, does not; the kSharedKept chains last asked are kept (the one asked longest
// ago is made again, whatever was made first); a shared chain is the constructor's, bit for bit.
TEST(ChainModesTest, SharedModesAreMadeOncePerChainOnAThread) {
  const Chain c(6);
  const NeedleTrain train(c.cam, c.p, 60.0, 0.0), faster(c.cam, c.p, 90.0, 0.0);
  const ContactMode cam{true, false};
  const std::shared_ptr<const ChainModes> first = ChainModes::Shared(train, cam);
  EXPECT_EQ(ChainModes::Shared(faster, cam), first);
  EXPECT_NE(ChainModes::Shared(train, ContactMode{false, true}), first);
  const ChainModes made(train, cam);
  EXPECT_EQ(made.Lambda(), first->Lambda());
  EXPECT_EQ(made.Vectors(), first->Vectors());
  EXPECT_EQ(made.Inverse(), first->Inverse());
  // Each number the chain is made of, changed alone: another chain. (kSharedKept of them: with
  // `first` asked again after the first six, it is still kept after all eight; a cache that
  // dropped the first made would have dropped it.)
  const std::vector<std::pair<const char*, void (*)(TrainParameters&)>> changes = {
      {"coil masses", [](TrainParameters& p) { p.coil_masses = 7; }},
      {"spring mass", [](TrainParameters& p) { p.spring_mass_kg = 0.61; }},
      {"spring rate", [](TrainParameters& p) { p.rate_N_m = 5.1e4; }},
      {"surge damping", [](TrainParameters& p) { p.surge_damping_ratio = 0.06; }},
      {"needle mass", [](TrainParameters& p) { p.mass_kg = 0.81; }},
      {"contact stiffness", [](TrainParameters& p) { p.contact_stiffness_N_m = 2e8; }},
      {"contact damping", [](TrainParameters& p) { p.contact_damping_ratio = 0.3; }},
      {"seat damping", [](TrainParameters& p) { p.seat_damping_ratio = 0.3; }},
  };
  ASSERT_EQ(static_cast<int>(changes.size()), ChainModes::kSharedKept);
  for (size_t i = 0; i < changes.size(); ++i) {
    if (i == 6) {
      EXPECT_EQ(ChainModes::Shared(train, cam), first);  // asked again: kept
    }
    Chain other(6);
    changes[i].second(other.p);
    const NeedleTrain changed(other.cam, other.p, 60.0, 0.0);
    EXPECT_NE(ChainModes::Shared(changed, cam), first) << changes[i].first;
  }
  EXPECT_EQ(ChainModes::Shared(train, cam), first);  // asked 3 chains ago, of 8 kept
  for (int i = 0; i < ChainModes::kSharedKept; ++i) {
    Chain other(6);
    other.p.mass_kg = 0.9 + 0.01 * i;
    ChainModes::Shared(NeedleTrain(other.cam, other.p, 60.0, 0.0), cam);
  }
  const std::shared_ptr<const ChainModes> again = ChainModes::Shared(train, cam);
  EXPECT_NE(again, first);  // 8 others asked since: made again
  EXPECT_EQ(again->Lambda(), first->Lambda());
}

// V and the rows of V⁻¹ invert each other, Σ_k w_k Re(V_k W_k) = I to 1e-10 in balanced units
// (lifts by √m, velocities by √m/ω_max), where the rows are made mode by mode (O(N) each) and
// where that would lose digits: over-damped chains with real λ (weight 1), a damped pair, 40
// masses, and a flight mode within 1e-12 of critical damping (ζ_s = 0.92224 in this chain: the
// dense eigenvectors are taken there, and the chain refused as near critical when even they do
// not invert to 1e-10).
// auto takes the closed form for a chain it can carry, and a time stepper, saying why, for one
// with a flight mode within 1e-12 of critical damping (refused above).
TEST(ChainModesTest, AutoLeavesANearCriticalChainToATimeStepper) {
  for (const double zeta : {0.05, 0.9222386481970474 * (1 + 1e-12)}) {
    const Chain c(10, zeta);
    const NeedleTrain train(c.cam, c.p, 60.0, 0.0);
    const MethodChoice choice = AutoMethod(train, 100.0, 1e-8);
    if (zeta < 0.5) {
      EXPECT_EQ(MethodName(choice.method), "exact");
      continue;
    }
    EXPECT_EQ(MethodName(choice.method), "dopri5");
    EXPECT_TRUE(std::regex_match(
        choice.reason, std::regex("auto: method \"exact\": a mode of the coil chain is at or "
                                  "near critical damping \\([^;]*\\); the contact oscillates "
                                  "100 times per cam event \\(≤ 2000: explicit Dormand–Prince\\)")))
        << choice.reason;
  }
}

// auto leaves a chain whose fastest mode is overdamped far past its fastest oscillation to a time
// stepper (helper-59: 40 masses at surge ζ 0.4 took 3757 pieces of π/|λ| by exact, 15 times the
// time stepper's run); at surge ζ 0.01 the same chain's fastest mode oscillates: exact.
TEST(ChainModesTest, AutoLeavesAChainWithAFastOverdampedModeToATimeStepper) {
  for (const double zeta : {0.01, 0.4}) {
    const Chain c(40, zeta);
    const NeedleTrain train(c.cam, c.p, 60.0, 0.0);
    const MethodChoice choice = AutoMethod(train, 100.0, 1e-8);
    EXPECT_EQ(MethodName(choice.method), zeta < 0.1 ? "exact" : "dopri5") << zeta;
    if (zeta < 0.1) continue;
    EXPECT_TRUE(std::regex_match(
        choice.reason,
        std::regex("auto: the coil chain's fastest mode is overdamped \\(\\|λ\\| [0-9.e+]+ 1/s "
                   "against its fastest oscillation's [0-9.e+]+ rad/s\\), which would cap method "
                   "\"exact\"'s pieces; the contact oscillates 100 times per cam event .*")))
        << choice.reason;
  }
}

TEST(ChainModesTest, TheModesAndTheirInverseRowsInvertEachOther) {
  struct Variant {
    int coils;
    double zeta;
  };
  int real_modes = 0, refused = 0;
  for (const Variant v : {Variant{2, 0.9}, Variant{40, 0.05}, Variant{40, 0.95},
                          Variant{10, 0.9222386481970474 * (1 + 1e-12)},
                          Variant{10, 0.9222386481970474 * (1 - 1e-12)}}) {
    for (const ContactMode mode : {ContactMode{false, false}, ContactMode{true, true}}) {
      const Chain c(v.coils, v.zeta);
      const NeedleTrain train(c.cam, c.p, 60.0, 0.0);
      std::optional<ChainModes> modes;
      try {
        modes.emplace(train, mode);
      } catch (const std::invalid_argument& e) {
        // One line, its figure to 3 digits (std::to_string printed 1e-9 as "0.000000").
        EXPECT_TRUE(std::regex_match(
            e.what(),
            std::regex("method \"exact\": a mode of the coil chain is at or near critical "
                       "damping \\(its (modal sum inverts to [0-9.]+e-[0-9]+, beyond 1e-10|"
                       "eigenvectors' reciprocal condition [0-9.]+e-[0-9]+ < 1e-8)\\); take "
                       "dopri5")))
            << e.what();
        ++refused;
        continue;
      }
      const int n = modes->Dofs();
      Eigen::VectorXd s(2 * n);  // the balancing scale of each state entry
      for (int i = 0; i < n; ++i) {
        const double m = i == 0 ? train.NeedleMassKg() : train.CoilMassKg();
        s[i] = std::sqrt(m);
        s[n + i] = std::sqrt(m) / modes->Fastest();
      }
      Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(2 * n, 2 * n);
      for (Eigen::Index k = 0; k < modes->Lambda().size(); ++k) {
        if (modes->Lambda()[k].imag() == 0.0) ++real_modes;
        sum += modes->Weight()[k] * (modes->Vectors().col(k) * modes->Inverse().row(k)).real();
      }
      const Eigen::MatrixXd balanced = s.asDiagonal() * sum * s.cwiseInverse().asDiagonal();
      const double off = (balanced - Eigen::MatrixXd::Identity(2 * n, 2 * n)).cwiseAbs().maxCoeff();
      EXPECT_LT(off, 1e-10) << v.coils << " masses, zeta " << v.zeta << ", mode " << mode.cam
                            << mode.seat;
    }
  }
  EXPECT_GT(real_modes, 0);  // the over-damped modes' weight-1 path is taken
  // The near-critical chain in flight is refused (its modal sum, dense or not, inverts to 1e-9
  // and 1e-5 only), and no other.
  EXPECT_GE(refused, 1);
  EXPECT_LE(refused, 2);
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
  // Undamped: the real parts are 0 exactly (round-off's are dropped, so no term grows).
  for (Eigen::Index m = 0; m < 2; ++m) EXPECT_EQ(modes.Lambda()[m].real(), 0.0);
}

// The bounds the certified search stands on: over [t_a, t_b] inside a piece, |ẏ| and |ÿ| stay
// within Bounds() of the lift's form and y within its Range(), on 2001 points, for pieces on the
// cam, in flight and on the seat of the bundled chain.
TEST(ChainModesTest, TheModalBoundsHoldAlongAPiece) {
  const SurgeChain chain;
  chain.ForEachPiece(
      {ContactMode{true, false}, ContactMode{false, false}, ContactMode{false, true}},
      [](const ContactMode& mode, const ClosedFormPiece& piece, double t0) {
        const LinearForm lift{1.0, 0.0, 0.0, 0.0, 0.0};
        for (const double ta : {0.0, 2e-4}) {
          const double a = t0 + ta, b = a + 3.0 * piece.LongestStep();
          const FormBounds bounds = piece.Bounds(lift, a, b);
          const FormRange range = piece.Range(lift, a, b);
          EXPECT_NEAR(bounds.slope_at_start, piece.Motion(a)[1], 1e-9 * bounds.slope_bound);
          double slope = 0.0, curvature = 0.0;
          for (int i = 0; i <= 2000; ++i) {
            const std::array<double, 3> m = piece.Motion(a + (b - a) * i / 2000.0);
            slope = std::max(slope, std::abs(m[1]));
            curvature = std::max(curvature, std::abs(m[2]));
            EXPECT_GE(m[0], range.lo) << i;
            EXPECT_LE(m[0], range.hi) << i;
          }
          EXPECT_LE(slope, bounds.slope_bound) << mode.cam << mode.seat << " " << ta;
          EXPECT_LE(curvature, bounds.curvature_bound) << mode.cam << mode.seat << " " << ta;
          // Bounds, not wild guesses: within a few times what the piece reaches.
          EXPECT_GT(slope, 0.01 * bounds.slope_bound) << mode.cam << mode.seat << " " << ta;
        }
      });
}

// The rates EventDriver::FirstClosedFormRest steps by (ClosedFormPiece::ChainNeedleRateBounds): on
// a piece under a constant forcing, |ÿ| = |dẏ/dt| ≤ B₂ and |dÿ/dt| ≤ B₃ (the differences of Motion
// on 2001 points over three of the fastest half oscillations), and not wild guesses.
TEST(ChainModesTest, TheNeedlesRateBoundsHoldUnderAConstantForcing) {
  const SurgeChain chain;
  int pieces = 0;
  chain.ForEachPiece(kEveryMode,
                     [&](const ContactMode& mode, const ClosedFormPiece& piece, double t0) {
                       if (!piece.ForcingConstant()) return;
                       ++pieces;
                       const auto [b2, b3] = piece.ChainNeedleRateBounds();
                       const double dt = 3.0 * piece.LongestStep() / 2000.0;
                       double acceleration = 0.0, jerk = 0.0;
                       std::array<double, 3> last = piece.Motion(t0);
                       for (int i = 1; i <= 2000; ++i) {
                         const std::array<double, 3> m = piece.Motion(t0 + dt * i);
                         acceleration = std::max(acceleration, std::abs(m[2]));
                         jerk = std::max(jerk, std::abs(m[2] - last[2]) / dt);
                         last = m;
                       }
                       EXPECT_LE(acceleration, b2) << mode.cam << mode.seat;
                       EXPECT_LE(jerk, b3) << mode.cam << mode.seat;
                       EXPECT_GT(acceleration, 0.01 * b2) << mode.cam << mode.seat;
                       EXPECT_GT(jerk, 0.01 * b3) << mode.cam << mode.seat;
                     });
  EXPECT_GT(pieces, 0);
}

// The chain's bounds on its largest segment compression and on the spring's force on the needle
// (ClosedFormPiece::ChainUpperBounds, which let the record leave a stretch's samples out) hold
// at 2000 points of stretches of one and of three steps, and are not wild guesses.
TEST(ChainModesTest, TheCompressionAndSpringForceBoundsHold) {
  const SurgeChain chain;
  const NeedleTrain& train = chain.train;
  chain.ForEachPiece(
      kEveryMode, [&](const ContactMode& mode, const ClosedFormPiece& piece, double t0) {
        for (const double ta : {0.0, 2e-4}) {
          for (const double steps : {1.0, 3.0}) {
            const double a = t0 + ta, b = a + steps * piece.LongestStep();
            const std::array<double, 2> bound = piece.ChainUpperBounds(a, b);
            double compression = -1e300, spring = -1e300;
            for (int i = 0; i <= 2000; ++i) {
              const double t = a + (b - a) * i / 2000.0;
              const TrainState x = piece.MotionState(t);
              compression = std::max(compression, train.LargestSegmentCompression(x));
              spring = std::max(spring, train.Evaluate(x, t, Phase{mode}).spring_N);
            }
            EXPECT_LE(compression, bound[0]) << mode.cam << mode.seat << " " << ta << " " << steps;
            EXPECT_LE(spring, bound[1]) << mode.cam << mode.seat << " " << ta << " " << steps;
            // Not wild guesses: the compression's within 3 times what the stretch reaches, or than
            // the coils' own ringing (0.02 m/s over a coil period: 10 µm) on the seat (the modal
            // sum's terms at their full size: this start, off every mode, rings in all of them).
            // (Cam and seat both pushing, this start is the seat's, 5 mm into the cam: it rings
            // at 5 mm, and only the bounds' validity is asked.)
            if (mode.cam && mode.seat) continue;
            EXPECT_LT(bound[0] - compression, 3.0 * std::max(compression, 1e-5)) << ta;
            EXPECT_LT(bound[1] - spring, 0.05 * spring) << mode.cam << mode.seat << " " << ta;
          }
        }
      });
}

// Over a stretch of one sample interval (a sixteenth of a step) the bounds follow what the
// stretch reaches, in every mode, at the piece's start and later (the modes decayed): above it
// by less than the stretch's own change plus 3 % of the coils' ringing, where the modal sum's
// terms at their full size (a bound from the terms alone) are above it by some of the ringing
// itself. The record then leaves out the samples of every stretch that stays below it. Over
// half a step (the fastest modes taken whole) they hold, and follow to 60 % of the ringing.
TEST(ChainModesTest, TheBoundsOfAShortStretchFollowItsStart) {
  const SurgeChain chain;
  const NeedleTrain& train = chain.train;
  chain.ForEachPiece(
      kEveryMode, [&](const ContactMode& mode, const ClosedFormPiece& piece, double t0) {
        const double ringing = piece.ChainStartRinging()[0];
        for (const double ta : {0.0, 2e-4, 2.0 * piece.LongestStep()}) {
          for (const double part : {1.0 / 16.0, 0.5}) {
            const double a = t0 + ta, b = a + piece.LongestStep() * part;
            const std::array<double, 2> bound = piece.ChainUpperBounds(a, b);
            double lo = 1e300, hi = -1e300, spring_lo = 1e300, spring_hi = -1e300;
            for (int i = 0; i <= 200; ++i) {
              const double t = a + (b - a) * i / 200.0;
              const TrainState x = piece.MotionState(t);
              const double s = train.LargestSegmentCompression(x);
              const double f = train.Evaluate(x, t, Phase{mode}).spring_N;
              lo = std::min(lo, s);
              hi = std::max(hi, s);
              spring_lo = std::min(spring_lo, f);
              spring_hi = std::max(spring_hi, f);
            }
            const std::string where =
                std::to_string(mode.cam) + std::to_string(mode.seat) + " " + std::to_string(ta);
            EXPECT_LE(hi, bound[0]) << where;
            EXPECT_LE(spring_hi, bound[1]) << where;
            // Over half a step the fastest modes are bounded by their sizes (|λ| span > 1): within
            // 60 % of the ringing (cam and seat both pushing, its 5 mm ringing: validity only).
            const double share = part < 0.1 ? 0.03 : 0.6;
            if (part > 0.1 && mode.cam && mode.seat) continue;
            EXPECT_LT(bound[0] - hi, (hi - lo) + share * ringing) << where << " " << part;
            EXPECT_LT(bound[1] - spring_hi,
                      (spring_hi - spring_lo) + share * ringing * train.SegmentRateNm())
                << where << " " << part;
          }
        }
      });
}

// A record's sample state (MotionState without the coils' speeds) is the whole state's to the
// bit where a record reads it, the lifts, the needle's speed and coil 1's (the spring's force on
// the needle), and carries no other speed: NaN (a reader that sums or compares one shows it; one
// that takes a std::max over them, as NeedleTrain::LargestCoilSpeed, would not: none is reached
// from a record's sample).
TEST(ChainModesTest, ARecordsSampleStateIsTheWholeStatesLiftsAndSpringForce) {
  const SurgeChain chain;
  const NeedleTrain& train = chain.train;
  const int coils = train.Coils();
  chain.ForEachPiece(kEveryMode, [&](const ContactMode& mode, const ClosedFormPiece& piece,
                                     double t0) {
    for (const double ta : {0.0, 2e-4}) {
      const TrainState whole = piece.MotionState(t0 + ta);
      const TrainState sample = piece.MotionState(t0 + ta, false);
      ASSERT_EQ(sample.size(), whole.size());
      for (int i = 0; i < 3 + coils + 2; ++i) EXPECT_EQ(sample[i], whole[i]) << i;
      for (int i = 3 + coils + 2; i < 3 + 2 * coils + 1; ++i) EXPECT_TRUE(std::isnan(sample[i]));
      EXPECT_EQ(train.Evaluate(sample, t0 + ta, Phase{mode}).spring_N,
                train.Evaluate(whole, t0 + ta, Phase{mode}).spring_N);
      EXPECT_EQ(train.LargestSegmentCompression(sample), train.LargestSegmentCompression(whole));
    }
  });
}

// The Taylor polynomials a bracket's search reads (ClosedFormPiece::ChainTaylorAt: an extreme's,
// and a witness's crossing's before it is passed on the closed form): over a
// bracket of two of a stretch's 16 samples they are the closed form's lifts and needle speed to
// its round-off, at t_c to the bit, in every contact mode; a reach of several oscillations of
// the fastest mode is refused; a witness's wider bracket (ρ = 1.3) holds too.
TEST(ChainModesTest, TheTaylorPolynomialsAreTheClosedFormOverABracket) {
  const SurgeChain chain;
  const NeedleTrain& train = chain.train;
  chain.ForEachPiece(
      kEveryMode, [&](const ContactMode& /*mode*/, const ClosedFormPiece& piece, double t0) {
        const double reach = piece.LongestStep() / 16.0;  // ρ = π/16
        for (const double tc : {t0, t0 + 3e-4}) {
          for (const bool coils : {false, true}) {
            const ChainTaylor taylor = piece.ChainTaylorAt(tc, reach, coils);
            ASSERT_TRUE(taylor.valid);
            EXPECT_LE(taylor.coef.cols(), 13);  // degree 11 at ρ = π/16, or P's
            const TrainState at_c = taylor.At(tc, train.StateSize()), x_c = piece.MotionState(tc);
            EXPECT_EQ(at_c[0], x_c[0]);
            EXPECT_EQ(at_c[1], x_c[1]);
            for (int i = -10; i <= 10; ++i) {
              const double t = std::max(t0, tc + reach * i / 10.0);
              const TrainState a = taylor.At(t, train.StateSize()), x = piece.MotionState(t);
              EXPECT_NEAR(a[0], x[0], 1e-14 * std::abs(x[0]) + 1e-18) << i;
              EXPECT_NEAR(a[1], x[1], 1e-13 * std::abs(x[1]) + 1e-15) << i;
              // The needle alone (a witness's search, Refine) reads the same polynomials.
              const std::array<double, 2> yv = taylor.LiftAndSpeed(t);
              EXPECT_EQ(yv[0], a[0]) << i;
              EXPECT_EQ(yv[1], a[1]) << i;
              for (int c = 1; c <= train.Coils(); ++c) {
                if (coils) {
                  EXPECT_NEAR(a[3 + c], x[3 + c], 1e-14 * std::abs(x[3 + c]) + 1e-18) << i << c;
                } else {
                  EXPECT_EQ(a[3 + c], 0.0);
                }
              }
            }
          }
        }
        // A witness's bracket in the certified search may be wider: ρ = 1.3, the needle alone.
        const double wide = 1.3 / kPi * piece.LongestStep();
        const ChainTaylor taylor = piece.ChainTaylorAt(t0 + wide, wide, false);
        ASSERT_TRUE(taylor.valid);
        // To round-off of the modal sum's terms (the start's ringing).
        const std::array<double, 2> ringing = piece.ChainStartRinging();
        for (int i = -10; i <= 10; ++i) {
          const double t = t0 + wide + wide * i / 10.0;
          const std::array<double, 2> yv = taylor.LiftAndSpeed(t);
          const TrainState x = piece.MotionState(t);
          EXPECT_NEAR(yv[0], x[0], 1e-14 * std::abs(x[0]) + 1e-14 * ringing[0]) << i;
          EXPECT_NEAR(yv[1], x[1], 1e-13 * std::abs(x[1]) + 1e-14 * ringing[1]) << i;
        }
        EXPECT_FALSE(piece.ChainTaylorAt(t0 + 1e-3, 4.0 * piece.LongestStep(), false).valid);
      });
}

// A stretch's equally spaced samples from one e^{λΔ} per mode and a recurrence
// (ClosedFormPiece::ChainSampleTimes) are the closed form's states at those times, node by node,
// in every contact mode, over a stretch of four of the piece's caps (64 samples) right after the
// piece's start: to 1e-13 of the homogeneous part's size; not the direct formula's bits (the
// samples are the recurrence's); and forgotten on request.
TEST(ChainModesTest, TheSamplesByRecurrenceAreTheClosedFormsStates) {
  const SurgeChain chain;
  chain.ForEachPiece(kEveryMode, [&](const ContactMode& mode, const ClosedFormPiece& piece,
                                     double t0) {
    constexpr int n = 64;
    std::array<double, n + 1> ts;
    const double from = t0 + 1e-5, to = from + 4.0 * piece.LongestStep();
    for (int k = 0; k <= n; ++k) ts[k] = from + (to - from) * k / n;
    std::vector<TrainState> direct;
    for (double t : ts) direct.push_back(piece.MotionState(t));
    // The homogeneous part's size (ChainStartRinging), which the recurrence's round-off scales
    // with: lifts m, velocities m/s.
    const std::array<double, 2> ringing = piece.ChainStartRinging();
    const auto size = [&](size_t i) {
      return i == 1 || i >= 4 + static_cast<size_t>(chain.train.Coils()) ? ringing[1] : ringing[0];
    };
    piece.ChainSampleTimes(ts.data(), n + 1);
    int differing = 0;
    for (int k = 0; k <= n; ++k) {
      const TrainState x = piece.MotionState(ts[k]);
      for (size_t i = 0; i < x.size(); ++i) {
        if (i == 2 || i == 3) continue;
        EXPECT_NEAR(x[i], direct[k][i], 1e-13 * size(i))
            << "mode " << mode.cam << mode.seat << ", sample " << k << ", entry " << i;
        differing += x[i] != direct[k][i];
      }
    }
    EXPECT_GT(differing, 0) << "mode " << mode.cam << mode.seat;
    piece.ChainSampleTimes(nullptr, 0);
    const TrainState again = piece.MotionState(ts[n / 2]);
    for (size_t i = 0; i < again.size(); ++i) EXPECT_EQ(again[i], direct[n / 2][i]) << i;
  });
}

// What the bounds leave out cannot change the run: the bundled chain with the record screened
// and pieces run on (leave_out) against every sample taken and every piece capped, two
// revolutions (the second starts on the seat) at 125 rpm (the needle long on its seat while the
// cam's tangent ramp takes up the play), 520 rpm (lash, seating) and 900 rpm (a jump): the same
// impacts, episodes and records. At 125 rpm the ramp's pieces run on, the ramp's witness keeping
// its sign only short of the lash (EventDriver::LongestQuiet), and the first revolution's rest
// rings at round-off (EventDriver::Ranges): 568 pieces against the full run's 6046 (1036 where
// round-off counts as a change; 1510 at 40c3d30, a piece running on only on a constant input).
TEST(ChainModesTest, TheScreenedChainRecordsWhatTheFullRunDoes) {
  const Case k = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml");
  const Scene s = MakeScene(k);
  for (const double rpm : {125.0, 520.0, 900.0}) {
    SimulationOptions o;
    o.force_dynamic = true;
    o.cycles = 2;
    o.method = "exact";
    o.integrator.leave_out = false;
    const SimulationResult full = Simulate(s, rpm, o);
    o.integrator.leave_out = true;
    const SimulationResult screened = Simulate(s, rpm, o);
    EXPECT_LT(screened.stats.steps, full.stats.steps) << rpm;
    if (rpm == 125.0) {
      EXPECT_LT(8 * screened.stats.steps, full.stats.steps);
    }
    ASSERT_EQ(full.impacts.size(), screened.impacts.size()) << rpm;
    for (size_t i = 0; i < full.impacts.size(); ++i) {
      EXPECT_EQ(full.impacts[i].kind, screened.impacts[i].kind) << i;
      EXPECT_NEAR(full.impacts[i].crank_rad / kDeg, screened.impacts[i].crank_rad / kDeg, 1e-9);
    }
    ASSERT_EQ(full.episodes.size(), screened.episodes.size()) << rpm;
    const auto same = [&](double a, double b, const char* what) {
      EXPECT_NEAR(a, b, 1e-10 * std::max(std::abs(a), 1e-3)) << what << " at " << rpm;
    };
    same(full.max_lift_m, screened.max_lift_m, "largest lift");
    same(full.min_lift_m, screened.min_lift_m, "least lift");
    same(full.max_contact_force_N, screened.max_contact_force_N, "cam force");
    same(full.max_seat_force_N, screened.max_seat_force_N, "seat force");
    same(full.max_spring_force_N, screened.max_spring_force_N, "spring force");
    same(full.min_contact_force_during_lift_N, screened.min_contact_force_during_lift_N,
         "least cam force");
    ASSERT_TRUE(full.min_coil_gap_m && screened.min_coil_gap_m);
    same(*full.min_coil_gap_m, *screened.min_coil_gap_m, "least coil gap");
    EXPECT_LT(screened.energy_residual, 1e-12) << rpm;
  }
}

// Along a piece, ẏ, ÿ and the coils' rates are those the train's right-hand side gives at the
// piece's own state (centred differences of the closed form against NeedleTrain::Derivative), on
// the cam in its rise (a forcing polynomial of degree 5) and in flight; and the piece starts on
// its start state to the bit.
TEST(ChainModesTest, APieceSolvesTheTrainsOwnEquations) {
  const SurgeChain chain;
  const NeedleTrain& train = chain.train;
  for (const ContactMode mode : {ContactMode{true, false}, ContactMode{false, false}}) {
    const ChainModes modes(train, mode);
    const double th = chain.Angle(), t0 = train.Time(th);
    const TrainState x0 = chain.Start(mode);
    const ClosedFormPiece piece(train, mode, th, t0, x0, &modes);
    const TrainState start = piece.MotionState(t0);
    for (int i = 0; i < train.StateSize(); ++i) {
      if (i != 2 && i != 3) {
        EXPECT_EQ(start[i], x0[i]) << i;
      }
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

// The audit's W and D in closed form (ClosedFormPiece::ChainAudit) against the 10-point rule on
// 400 parts of the train's own Ẇ and Ḋ, over a third of and a whole step of the fastest mode:
// on the cam (the cam works), in flight, on the seat; with the coils damped and undamped. The
// gaps keep their signs and the cam stays on its segment (the rule would meet a kink there).
TEST(ChainModesTest, TheChainsAuditInClosedFormIsTheQuadratures) {
  for (const double zeta : {0.01, 0.0}) {
    SurgeChain chain;
    chain.s.train.surge_damping_ratio = zeta;
    const NeedleTrain train(*chain.s.cam, chain.s.train, chain.omega,
                            DefaultRunWindow(chain.s).start_rad);
    for (const ContactMode mode :
         {ContactMode{true, false}, ContactMode{false, false}, ContactMode{false, true}}) {
      const ChainModes modes(train, mode);
      const double th = chain.Angle(), t0 = train.Time(th);
      TrainState x0 = chain.Start(mode);
      const double u = chain.s.cam->U(th), u_rate = chain.omega * chain.s.cam->Slope(th);
      // Into the cam and closing on it; off it and opening; into the seat and closing.
      if (mode.cam) x0[1] = u_rate - 0.002;
      if (!mode.cam && !mode.seat) x0[0] = u + 2e-4, x0[1] = u_rate + 0.2;
      if (mode.seat) x0[1] = -0.002;
      const ClosedFormPiece piece(train, mode, th, t0, x0, &modes);
      const auto signs = [&](double t) {
        const double y = piece.Motion(t)[0];
        return std::array<int, 2>{piece.Input(t)[0] - y > 0.0, -y > 0.0};
      };
      for (const double span : {0.3, 1.0}) {
        const double t1 = t0 + span * piece.LongestStep();
        for (int i = 0; i <= 1000; ++i) ASSERT_EQ(signs(t0 + (t1 - t0) * i / 1000), signs(t0));
        ASSERT_NEAR(piece.Input(t1)[0], chain.s.cam->U(train.Angle(t1)), 1e-12);
        const TrainState closed = piece.State(t1), quad = piece.StateByQuadrature(t1, 400);
        const double scale = std::max({std::abs(quad[2]), std::abs(quad[3]), 1e-9});
        EXPECT_NEAR(closed[2], quad[2], 1e-10 * scale) << mode.cam << mode.seat << " " << zeta;
        EXPECT_NEAR(closed[3], quad[3], 1e-10 * scale) << mode.cam << mode.seat << " " << zeta;
        if (mode.cam) {
          EXPECT_GT(std::abs(quad[2]), 1e-6) << span;  // the cam works
        }
        if (zeta > 0.0 || mode.cam || mode.seat) {
          EXPECT_GT(std::abs(quad[3]), 1e-9) << span;
        }
        for (int i = 4; i < train.StateSize(); ++i) EXPECT_EQ(closed[i], quad[i]) << i;
      }
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
// A chain at rest on its seat runs its seated stretches whole: Example 1's spring as 5 coil
// masses (its bound and record of the spring force differ by P₀'s round-off, 7.7e-9 of 7746 N)
// takes as many pieces as with 10 (267), not one every half oscillation (729; seen with only k
// and c's share of the lift's round-off allowed, EventDriver::RestAllowance).
TEST(ChainModesTest, ASeatedChainAtRestIsNotCappedPieceByPiece) {
  const Case k = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml");
  Scene s = MakeScene(k);
  SimulationOptions o;
  o.force_dynamic = true;
  o.cycles = 1;
  o.method = "exact";
  std::vector<long> steps;
  for (int n : {5, 10}) {
    s.train.coil_masses = n;
    steps.push_back(Simulate(s, 125.0, o).stats.steps);
  }
  EXPECT_LE(steps[0], steps[1] + 10);
  EXPECT_LT(steps[0], 300);
}

// A new user's chain (tests/data/light3000-chain.toml) at 1200 and 1500 rpm: its largest contact
// force has two near-equal peaks, and with undamped contacts at 4000 rpm its seat force peaks
// between two samples of a long seated stretch. exact locates each: never below dopri5 at rtol
// 1e-12 and within 1e-6 (seen failing with only the least sample searched: 464.3148 against
// 464.6318 N, 1418.30 against 1419.40 N).
TEST(ChainModesTest, ExactLocatesAPeakBetweenTwoSamples) {
  const Case c = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/tests/data/light3000-chain.toml");
  struct Run {
    double rpm;
    bool undamped;
  };
  for (const Run run : {Run{1200, false}, Run{1500, false}, Run{4000, true}}) {
    Scene s = MakeScene(c);
    if (run.undamped) s.train.contact_damping_ratio = s.train.seat_damping_ratio = 0.0;
    SimulationOptions o = OptionsFromCase(c);
    const SimulationResult e = Simulate(s, run.rpm, o);
    EXPECT_EQ(e.method, "exact");
    o.method = "dopri5";
    o.integrator.rtol = 1e-12;
    o.integrator.atol_m = DefaultAtol(1e-12);
    const SimulationResult d = Simulate(s, run.rpm, o);
    for (const auto& [closed, sampled] : {std::pair{e.max_contact_force_N, d.max_contact_force_N},
                                          std::pair{e.max_seat_force_N, d.max_seat_force_N}}) {
      EXPECT_GE(closed, sampled * (1.0 - 1e-9)) << run.rpm;
      EXPECT_NEAR(closed, sampled, 1e-6 * sampled) << run.rpm;
    }
  }
}

TEST(ChainModesTest, ExactAgreesWithDopri5OnTheBundledChain) {
  const Case k = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml");
  Scene s = MakeScene(k);
  // Its own ζ_s = 0.01 at three speeds (no separation, lash, a jump), then ζ_s = 0 (only the
  // contacts' dashpots damp) and ζ_s = 0.2 (the upper modes overdamped: real λ) at 900 rpm.
  struct Run {
    double zeta, rpm;
  };
  for (const Run run :
       {Run{0.01, 125.0}, Run{0.01, 520.0}, Run{0.01, 900.0}, Run{0.0, 900.0}, Run{0.2, 900.0}}) {
    s.train.surge_damping_ratio = run.zeta;
    const double rpm = run.rpm;
    if (run.zeta == 0.2) {  // real modes in flight: an overdamped λ, weight 1
      const NeedleTrain train(*s.cam, s.train, OmegaFromRpm(rpm), 0.0);
      const ChainModes flight(train, ContactMode{false, false});
      EXPECT_TRUE((flight.Weight().array() == 1.0).any());
    }
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
    // The largest forces: the closed form locates them (Brent between its samples, also next
    // to a stretch's end sample), dopri5 samples them: never below dopri5's, within 1e-6.
    for (const auto& [closed, sampled] : {std::pair{e.max_contact_force_N, d.max_contact_force_N},
                                          std::pair{e.max_seat_force_N, d.max_seat_force_N},
                                          std::pair{e.max_spring_force_N, d.max_spring_force_N}}) {
      EXPECT_GE(closed, sampled * (1.0 - 1e-9)) << rpm;
      EXPECT_NEAR(closed, sampled, 1e-6 * sampled) << rpm;
    }
    std::printf(
        "zeta_s %g, %g rpm: %zu impacts, %zu episodes, dopri5 %ld steps, exact %ld steps, "
        "residual %.2e vs %.2e\n",
        run.zeta, rpm, e.impacts.size(), e.episodes.size(), d.stats.steps, e.stats.steps,
        d.energy_residual, e.energy_residual);
  }
}

}  // namespace
}  // namespace needle
