// Method "exact" (dynamics/solver/closed_form.h, docs/model.md §9): the closed form against the
// textbook solutions in every damping regime, free fall, switches the time steppers can miss,
// a switch next to a break, the refusal of a nonlinear law, and agreement with dopri5 at
// rtol 1e-12 on every bundled scene that runs the dynamics.
#include "dynamics/solver/closed_form.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "apps/case/case_scene.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/units.h"
#include "tests/dynamics/test_laws.h"

namespace needle {
namespace {

// A needle on its seat alone (the cam far away): m ÿ + c ẏ + k_s y = 0 with ω_n = 100 rad/s.
struct SeatOnly {
  explicit SeatOnly(double zeta) : law(FarLaw()), cam(law, 0.5e-3, RampKind::kLinear, 0.1) {
    p.mass_kg = 1.0;
    p.seat_stiffness_N_m = 1e4;
    p.seat_damping_ratio = zeta;
  }
  LiftLaw law;
  CamInput cam;
  TrainParameters p;
};

// The textbook free response from (y₀, v₀) for ω_n, ζ.
double Textbook(double y0, double v0, double wn, double zeta, double t) {
  const double s = zeta * wn;
  if (zeta < 1.0) {
    const double wd = wn * std::sqrt(1.0 - zeta * zeta);
    return std::exp(-s * t) * (y0 * std::cos(wd * t) + (v0 + s * y0) / wd * std::sin(wd * t));
  }
  if (zeta == 1.0) return std::exp(-s * t) * (y0 + (v0 + s * y0) * t);
  const double mu = wn * std::sqrt(zeta * zeta - 1.0), r1 = -s + mu, r2 = -s - mu;
  const double b = (v0 - r1 * y0) / (r2 - r1);
  return (y0 - b) * std::exp(r1 * t) + b * std::exp(r2 * t);
}

TEST(ClosedFormTest, EveryDampingRegimeMatchesTheTextbookSolution) {
  const double y0 = -1e-5, v0 = 2e-3;  // pressed 10 µm into the seat, moving up
  for (double zeta : {0.0, 0.05, 0.5, 0.999, 1.0, 1.001, 3.0, 50.0}) {
    SeatOnly s(zeta);
    const NeedleTrain train(s.cam, s.p, 10.0, 0.0);
    const ClosedFormPiece piece(train, ContactMode{false, true}, 0.0, 0.0, {y0, v0, 0.0, 0.0});
    for (double t : {1e-4, 3e-3, 2e-2, 0.1}) {
      const double want = Textbook(y0, v0, 100.0, zeta, t);
      EXPECT_NEAR(piece.Motion(t)[0], want, 1e-14 * 1e-5 + 1e-12 * std::abs(want))
          << "zeta " << zeta << " t " << t;
    }
  }
}

TEST(ClosedFormTest, CriticalDampingIsContinuousFromBothSides) {
  // ζ = 1 ± 1e-9 against ζ = 1.
  const TrainState x0 = {-1e-5, 2e-3, 0.0, 0.0};
  SeatOnly critical(1.0);
  const NeedleTrain tc(critical.cam, critical.p, 10.0, 0.0);
  const ClosedFormPiece pc(tc, ContactMode{false, true}, 0.0, 0.0, x0);
  // The two sides straddle the critical motion symmetrically: their mean is it to round-off
  // (a naive form, dividing by ω_d or μ ≈ 100·√2e-9, keeps only half the digits), and their
  // half-difference is the motion's first-order sensitivity to ζ, O(1e-9).
  SeatOnly below(1.0 - 1e-9), above(1.0 + 1e-9);
  const NeedleTrain tb(below.cam, below.p, 10.0, 0.0), ta(above.cam, above.p, 10.0, 0.0);
  const ClosedFormPiece pb(tb, ContactMode{false, true}, 0.0, 0.0, x0);
  const ClosedFormPiece pa(ta, ContactMode{false, true}, 0.0, 0.0, x0);
  for (double t : {1e-3, 1e-2, 5e-2}) {
    for (int k : {0, 1}) {
      const double lo = pb.Motion(t)[k], hi = pa.Motion(t)[k], mid = pc.Motion(t)[k];
      const double scale = k == 0 ? 1e-5 : 2e-3;
      EXPECT_NEAR(0.5 * (lo + hi), mid, 1e-15 * scale) << t << " " << k;
      EXPECT_LT(std::abs(hi - lo), 1e-8 * scale) << t << " " << k;
    }
  }
}

TEST(ClosedFormTest, HeavyDampingNeitherOverflowsNorCancels) {
  // ζ = 1e4: decay rates 5e-3 and 2e6 per s. cosh(μτ) alone would overflow past τ ≈ 3.5e-4 s;
  // the slow exponent r₁ = −(K/m)/(σ + μ) keeps its digits.
  SeatOnly s(1e4);
  const NeedleTrain train(s.cam, s.p, 10.0, 0.0);
  const TrainState x0 = {-1e-5, 0.0, 0.0, 0.0};
  const ClosedFormPiece piece(train, ContactMode{false, true}, 0.0, 0.0, x0);
  const double sigma = 1e4 * 100.0, mu = 100.0 * std::sqrt(1e8 - 1.0);
  const double r1 = -1e4 / (sigma + mu), r2 = -sigma - mu;
  const double b = (x0[1] - r1 * x0[0]) / (r2 - r1);  // the fast mode's share, 2.5e-14 m
  for (double t : {1e-3, 1.0, 100.0}) {
    const double y = piece.Motion(t)[0];
    ASSERT_TRUE(std::isfinite(y)) << t;
    // The fast mode is gone: y = (y₀ − b) e^{r₁ t}.
    EXPECT_NEAR(y, (x0[0] - b) * std::exp(r1 * t), 1e-15 * 1e-5) << t;
  }
}

TEST(ClosedFormTest, FreeFlightWithoutSpringIsAParabola) {
  // K = c = 0: m ÿ = F_g − P₀, integrated twice.
  SeatOnly s(0.05);
  s.p.preload_N = 30.0;
  s.p.gas_force_N = 10.0;
  const NeedleTrain train(s.cam, s.p, 10.0, 0.0);
  const ClosedFormPiece piece(train, ContactMode{}, 0.0, 0.0, {1e-3, 0.5, 0.0, 0.0});
  for (double t : {1e-3, 1e-2, 4e-2}) {
    EXPECT_NEAR(piece.Motion(t)[0], 1e-3 + 0.5 * t - 10.0 * t * t, 1e-18) << t;
    EXPECT_NEAR(piece.Motion(t)[1], 0.5 - 20.0 * t, 1e-15) << t;
    EXPECT_DOUBLE_EQ(piece.Motion(t)[2], -20.0);
  }
}

// A needle in free flight under a net upward load dips 1 pm into its seat for under a
// microsecond: the seat gap crosses zero twice inside one step. The closed form's bounds find
// the first crossing; the time steppers look at the step's end, where the gap is open again.
struct Dip {
  explicit Dip(double depth_m) : law(FarLaw()), cam(law, 0.5e-3, RampKind::kLinear, 0.1) {
    p.mass_kg = 1.0;
    p.gas_force_N = 10.0;  // a = +10 m/s², no spring
    p.seat_stiffness_N_m = 1e8;
    // y = y₀ + v₀ t + 5 t², lowest at t* = 1 ms, depth below the seat `depth_m`.
    x0 = {v0 * v0 / 20.0 - depth_m, v0, 0.0, 0.0};
  }
  LiftLaw law;
  CamInput cam;
  TrainParameters p;
  const double v0 = -0.01;
  TrainState x0;
};

TEST(ClosedFormTest, TwoSwitchesInsideOneStepAreFound) {
  Dip d(1e-12);
  const NeedleTrain train(d.cam, d.p, 10.0, 0.0);
  Recorder recorder(train, false);
  Integrate(Method::kExact, train, d.x0, 2e-3, recorder, IntegratorOptions{});
  ASSERT_FALSE(recorder.impacts().empty());
  const Impact& first = recorder.impacts().front();
  EXPECT_EQ(first.kind, "seat");
  // y = 0 at t* − √(depth/5): the approach speed is √(2·10·1e-12) = 4.47 µm/s.
  const double t_c = 1e-3 - std::sqrt(1e-12 / 5.0);
  EXPECT_NEAR(first.crank_rad, 10.0 * t_c, 10.0 * 1e-12);
  EXPECT_NEAR(first.speed_m_s, std::sqrt(2.0 * 10.0 * 1e-12), 1e-10);
  // dopri5 on the same flight (printed: it may step over the dip).
  Recorder sampled(train, false);
  Integrate(Method::kDopri5, train, d.x0, 2e-3, sampled, IntegratorOptions{});
  std::printf("dopri5 finds %zu impacts on the 1 pm dip, exact %zu\n", sampled.impacts().size(),
              recorder.impacts().size());
}

TEST(ClosedFormTest, AGrazingTouchIsPassedWithoutHarm) {
  // The lowest point exactly on the seat (a root of even multiplicity, up to round-off): at most
  // a touch at zero speed, and the run ends normally.
  Dip d(0.0);
  const NeedleTrain train(d.cam, d.p, 10.0, 0.0);
  Recorder recorder(train, false);
  const IntegrationStats s =
      Integrate(Method::kExact, train, d.x0, 2e-3, recorder, IntegratorOptions{});
  EXPECT_NEAR(s.final_time, 2e-3, 1e-15);
  for (const Impact& i : recorder.impacts()) EXPECT_LT(i.speed_m_s, 1e-9);
}

TEST(ClosedFormTest, ASwitchOneFemtosecondFromABreakIsPlacedOnItsSide) {
  // The cam's ramp foot (a break of u) at θ = 0.9 rad, t = 0.09 s at ω = 10 rad/s; the needle
  // falls at a constant 10 mm/s onto its seat 1e-12 s before and after it.
  for (double offset : {-1e-12, 1e-12}) {
    Dip d(0.0);
    d.p.gas_force_N = 0.0;  // no load: y = y₀ + v₀ t
    const double t_c = 0.09 + offset;
    d.x0 = {-d.v0 * t_c, d.v0, 0.0, 0.0};
    const NeedleTrain train(d.cam, d.p, 10.0, 0.0);
    Recorder recorder(train, false);
    Integrate(Method::kExact, train, d.x0, 0.1, recorder, IntegratorOptions{});
    ASSERT_FALSE(recorder.impacts().empty()) << offset;
    EXPECT_NEAR(recorder.impacts().front().crank_rad / 10.0, t_c, 2e-16) << offset;
    EXPECT_NEAR(recorder.impacts().front().speed_m_s, 0.01, 1e-15) << offset;
  }
}

// A law outside the linear class: a Hertzian point contact, F = k g^1.5.
class Hertzian : public ContactLaw {
 public:
  std::string name() const override { return "hertz"; }
  ContactWitnesses Witnesses(double g, double) const override { return {g, g}; }
  bool Pushes(int a, int) const override { return a > 0; }
  double Force(double g, double) const override { return g > 0 ? 1e9 * g * std::sqrt(g) : 0.0; }
  double ForceStiffness() const override { return 0.0; }
  double ForceDamping() const override { return 0.0; }
  double Potential(double g) const override { return g > 0 ? 0.4e9 * g * g * std::sqrt(g) : 0; }
  double ConservativeForce(double g) const override { return Force(g, 0.0); }
  double ConservativeStiffness(double g) const override {
    return g > 0 ? 1.5e9 * std::sqrt(g) : 0.0;
  }
};

TEST(ClosedFormTest, ANonlinearLawIsRefusedWithTheReason) {
  SeatOnly s(0.05);
  const NeedleTrain train(s.cam, s.p, 10.0, 0.0, nullptr, std::make_shared<Hertzian>());
  const std::string why =
      "method \"exact\" needs contact laws linear in the gap and its rate; the seat law "
      "\"hertz\" is not";
  ASSERT_TRUE(ExactRefusal(train).has_value());
  EXPECT_EQ(*ExactRefusal(train), why);
  Recorder recorder(train, false);
  try {
    Integrate(Method::kExact, train, {0.0, 0.0, 0.0, 0.0}, 1e-3, recorder, IntegratorOptions{});
    FAIL() << "no refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), why);
  }
  const NeedleTrain linear(s.cam, s.p, 10.0, 0.0);
  EXPECT_FALSE(ExactRefusal(linear).has_value());
}

TEST(ClosedFormTest, WitnessFormsAreTheWitnesses) {
  // The bounds are taken on WitnessForm: it must equal Events() wherever its gate holds.
  const LiftLaw law = FarLaw();
  const CamInput cam(law, 0.0, RampKind::kTangent, 0.0);
  TrainParameters p;
  p.contact_damping_ratio = 0.3;
  p.seat_damping_ratio = 0.2;
  const NeedleTrain train(cam, p, 37.0, 0.9);
  for (const TrainState& x :
       {TrainState{2e-6, 0.3, 0, 0}, TrainState{-3e-6, -0.2, 0, 0}, TrainState{6e-4, 0.01, 0, 0}}) {
    for (bool pushing : {false, true}) {
      const Phase phase{ContactMode{pushing, !pushing}};
      const double t = 0.004;
      const EventValues v = Events(train, phase, x, t);
      const Contacts c = train.Evaluate(x, t, phase);
      for (int i = 0; i < kEventCount; ++i) {
        const LinearForm f = *WitnessForm(train, phase, i, x[0] > kSeparationLift_m);
        const double w =
            f.y * x[0] + f.v * x[1] + f.u * c.u + f.u_rate * train.omega() * c.u_slope + f.constant;
        EXPECT_NEAR(w, v[i], 1e-12 * (1.0 + std::abs(v[i]))) << i;
      }
    }
  }
}

// The audit integrals W and D in closed form against a composite Gauss–Legendre rule (400 parts
// of 10 points) on pieces of Example 2's train over tens of contact oscillations: pressed into
// the cam inside the lift (a cam polynomial of degree 5), in flight above it, and ringing on the
// seat before the lift; each piece keeps its gaps' signs (as the driver's pieces do: they end
// at every crossing), so the quadrature's integrand is smooth.
TEST(ClosedFormTest, TheAuditIntegralsInClosedFormAreTheQuadrature) {
  const Case c = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example2.toml");
  const Scene s = MakeScene(c);
  const double omega = OmegaFromRpm(1100), theta_a = DefaultRunWindow(s).start_rad;
  const NeedleTrain train(*s.cam, s.train, omega, theta_a);
  const LiftLaw& law = s.cam->law();
  struct Case {
    double frac;  // of the lift; < 0: before it
    ContactMode mode;
    double dy, dv;  // from the cam (in contact, in flight) or absolute (on the seat)
  };
  const Case cases[] = {{0.3, {true, false}, -2e-6, 0.0},
                        {0.12, {true, false}, -2e-6, 0.0},
                        {0.3, {false, false}, 2e-5, 0.05},
                        {0.7, {false, false}, 2e-5, 0.05},
                        {-0.5, {false, true}, -1e-6, 0.01}};
  for (const Case& k : cases) {
    const double th = law.start_rad() + k.frac * (law.end_rad() - law.start_rad());
    const double t0 = (th - theta_a) / omega, t1 = t0 + 2e-4;
    const double u = s.cam->U(th), u_rate = omega * s.cam->Slope(th);
    const TrainState x0 = k.mode.seat ? TrainState{k.dy, k.dv, 0.0, 0.0}
                                      : TrainState{u + k.dy, u_rate + k.dv, 0.0, 0.0};
    const ClosedFormPiece piece(train, k.mode, th, t0, x0);
    const auto gaps = [&](double t) {
      const double y = piece.Motion(t)[0];
      return std::array<int, 2>{s.cam->U(train.Angle(t)) - y > 0.0, -y > 0.0};
    };
    for (int i = 0; i <= 1000; ++i) {  // the gaps keep their signs
      ASSERT_EQ(gaps(t0 + (t1 - t0) * i / 1000), gaps(t0)) << k.frac << " at " << i;
    }
    const TrainState closed = piece.State(t1), quad = piece.StateByQuadrature(t1, 400);
    const double scale = std::max({std::abs(quad[2]), std::abs(quad[3]), 1e-9});
    EXPECT_NEAR(closed[2], quad[2], 1e-11 * scale) << k.frac << " " << k.mode.cam << k.mode.seat;
    EXPECT_NEAR(closed[3], quad[3], 1e-11 * scale) << k.frac << " " << k.mode.cam << k.mode.seat;
    if (k.mode.cam) {
      EXPECT_GT(std::abs(quad[2]), 1e-4) << k.frac;  // the cam works
    }
    if (k.mode.cam || k.mode.seat) {
      EXPECT_GT(quad[3], 1e-9) << k.frac;  // a dashpot dissipates
    }
  }
}

// Every bundled scene that runs the dynamics, at its rated speed, by dopri5 at rtol 1e-12 and
// by the closed form: the same impacts to 1e-9°, the same largest lift to 1e-9 mm.
class AgreementTest : public testing::TestWithParam<const char*> {};

TEST_P(AgreementTest, ExactAgreesWithDopri5AtTheTightestTolerance) {
  const Case c = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/" + GetParam());
  const Scene s = MakeScene(c);
  SimulationOptions o;
  o.force_dynamic = true;
  o.method = "dopri5";
  o.integrator.rtol = 1e-12;
  o.integrator.atol_m = DefaultAtol(1e-12);
  const double rpm = c.engine.speed_rpm;
  const SimulationResult d = Simulate(s, rpm, o);
  o.method = "exact";
  const SimulationResult e = Simulate(s, rpm, o);
  ASSERT_EQ(d.impacts.size(), e.impacts.size());
  for (size_t i = 0; i < d.impacts.size(); ++i) {
    EXPECT_EQ(d.impacts[i].kind, e.impacts[i].kind) << i;
    EXPECT_NEAR(d.impacts[i].crank_rad / kDeg, e.impacts[i].crank_rad / kDeg, 1e-9) << i;
  }
  ASSERT_EQ(d.episodes.size(), e.episodes.size());
  EXPECT_NEAR(d.max_lift_m * 1e3, e.max_lift_m * 1e3, 1e-9);
  // The audit closes to round-off: W and D in closed form (docs/exact.md; issue 33: ≤ 1e-12).
  EXPECT_LT(e.energy_residual, 1e-12);
  std::printf("%s: %zu impacts, dopri5 %ld steps, exact %ld steps, residual %.2e vs %.2e\n",
              GetParam(), e.impacts.size(), d.stats.steps, e.stats.steps, d.energy_residual,
              e.energy_residual);
}

INSTANTIATE_TEST_SUITE_P(BundledScenes, AgreementTest,
                         testing::Values("basu-example1.toml", "basu-example2.toml",
                                         "basu-cam4-light-spring.toml",
                                         "basu-cam4-stiff-train.toml"));

}  // namespace
}  // namespace needle
