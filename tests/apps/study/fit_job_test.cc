// needle fit's job (apps/study/fit_job.h) on traces the model makes with known parameters plus
// Gaussian noise: recovery within the stated intervals, two speeds separating what one cannot,
// a model that misses something said so, and the keys and bounds refused with one line.
#include "apps/study/fit_job.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "apps/case/case_file.h"
#include "lib/case_error.h"

namespace needle {
namespace {

const std::string kExample1 = std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1.toml";

// The needle lift case `b` gives at `rpm` on a crank grid of `step_deg` from `from_deg` to
// `to_deg`, plus N(0, sigma_mm²) noise: a trace as a bench records it.
MeasuredTrace MakeTrace(const BoundCase& b, double rpm, double sigma_mm, uint64_t seed,
                        double step_deg = 0.1, double from_deg = -30.0, double to_deg = 70.0) {
  Scene scene = BindScene(b, b.lift.law);
  SimulationOptions o = b.run;
  o.force_dynamic = true;
  o.cycles = 1;
  o.steady_state = false;
  for (double th = from_deg; th <= to_deg + 1e-9; th += step_deg) o.grid_rad.push_back(th * kDeg);
  scene.start_rad = o.grid_rad.front() - 1.0 * kDeg;
  const SimulationResult r = Simulate(scene, rpm, o);
  EXPECT_EQ(r.grid.size(), o.grid_rad.size());
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> noise(0.0, sigma_mm * 1e-3);
  MeasuredTrace t;
  t.path = "trace-" + std::to_string(static_cast<int>(rpm)) + ".csv";
  t.speed_rpm = rpm;
  for (size_t i = 0; i < r.grid.size(); ++i) {
    t.table.crank_rad.push_back(o.grid_rad[i]);
    t.table.lift_m.push_back(r.grid[i].lift_m + noise(gen));
  }
  return t;
}

BoundCase Example1() { return Bind(LoadCase(kExample1)); }

FitOptions Free(std::initializer_list<const char*> keys) {
  FitOptions o;
  for (const char* k : keys) o.free.push_back(ParseFitKey(k));
  o.predict_liftoff = false;
  o.starts = 2;
  return o;
}

const FittedValue& Value(const FitResult& r, const std::string& key) {
  for (const FittedValue& v : r.parameters) {
    if (v.key.name == key) return v;
  }
  throw std::logic_error("no " + key);
}

TEST(FitJob, RecoversPreloadAndDampingWithinTheirIntervals) {
  BoundCase truth = Example1();
  truth.spring->preload_N *= 0.9;
  truth.train->contact_damping_ratio = 0.1;
  const std::vector<MeasuredTrace> traces = {MakeTrace(truth, 700.0, 0.005, 7)};
  const FitResult r =
      FitCase(Example1(), traces, Free({"spring.preload_kgf", "train.contact_damping_ratio"}));
  const FittedValue& preload = Value(r, "spring.preload_kgf");
  const FittedValue& zeta = Value(r, "train.contact_damping_ratio");
  std::cerr << "preload " << preload.value << " [" << preload.low << ", " << preload.high
            << "] zeta " << zeta.value << " [" << zeta.low << ", " << zeta.high << "] chi2 "
            << r.chi2_reduced << " runs " << r.model_runs << " s " << r.seconds << "\n";
  EXPECT_LE(preload.low, 0.9 * 790);
  EXPECT_GE(preload.high, 0.9 * 790);
  EXPECT_LE(zeta.low, 0.1);
  EXPECT_GE(zeta.high, 0.1);
  EXPECT_FALSE(r.model_misses);
}

// Above a few hundredths of a millimetre, a play taken up on tangent ramps leaves the needle's
// lift unchanged: the fit must say the trace does not pin it down, not give the slope's interval.
TEST(FitJob, SaysAPlayTheTraceCannotSeeIsNotIdentified) {
  BoundCase truth = Example1();
  truth.train->play_m = 0.8e-3;
  const std::vector<MeasuredTrace> traces = {MakeTrace(truth, 700.0, 0.005, 7)};
  const FitResult r = FitCase(Example1(), traces, Free({"train.play_mm"}));
  const FittedValue& play = Value(r, "train.play_mm");
  std::cerr << "play " << play.value << " [" << play.low << ", " << play.high << "]\n";
  EXPECT_FALSE(play.identified);
  EXPECT_LE(play.low, 0.8);
  EXPECT_GE(play.high, 0.8);
}

// The intervals are 95 % ones: over 50 noise seeds each holds the true value at least 45 times.
TEST(FitJob, IntervalsCoverTheTrueValuesInAtLeast90PercentOf50Seeds) {
  BoundCase truth = Example1();
  truth.spring->preload_N *= 0.9;
  truth.train->contact_damping_ratio = 0.1;
  const BoundCase start = Example1();
  const std::vector<MeasuredTrace> clean = {MakeTrace(truth, 700.0, 0.0, 0, 0.2)};
  int preload_in = 0, zeta_in = 0;
  std::mt19937_64 gen(2026);
  std::normal_distribution<double> noise(0.0, 0.005e-3);
  for (int seed = 0; seed < 50; ++seed) {
    std::vector<MeasuredTrace> traces = clean;
    for (double& y : traces[0].table.lift_m) y += noise(gen);
    const FitResult r =
        FitCase(start, traces, Free({"spring.preload_kgf", "train.contact_damping_ratio"}));
    const FittedValue& p = Value(r, "spring.preload_kgf");
    const FittedValue& z = Value(r, "train.contact_damping_ratio");
    preload_in += p.low <= 0.9 * 790 && 0.9 * 790 <= p.high;
    zeta_in += z.low <= 0.1 && 0.1 <= z.high;
  }
  std::cerr << "covered: preload " << preload_in << "/50, damping " << zeta_in << "/50\n";
  EXPECT_GE(preload_in, 45);
  EXPECT_GE(zeta_in, 45);
}

// At 400 rpm, where the needle does not lift off, preload and mass show only together; the fit
// says so and names a second speed, and a trace at that speed narrows both intervals as said.
TEST(FitJob, TwoSpeedsSeparateWhatOneCannot) {
  BoundCase truth = Example1();
  truth.spring->preload_N *= 0.9;
  truth.needle->mass_kg = 13.0;
  truth.train->contact_stiffness_N_m = 3e8;
  FitOptions o = Free({"spring.preload_kgf", "needle.mass_kg", "train.contact_stiffness_N_m"});
  const MeasuredTrace slow = MakeTrace(truth, 400.0, 0.005, 11, 0.05);
  const FitResult one = FitCase(Example1(), {slow}, o);
  ASSERT_EQ(one.unseparated.size(), 1u);
  const UnseparatedPair& pair = one.unseparated[0];
  EXPECT_EQ(one.parameters[pair.a].key.name, "spring.preload_kgf");
  EXPECT_EQ(one.parameters[pair.b].key.name, "needle.mass_kg");
  EXPECT_GT(std::abs(pair.correlation), kUnseparatedCorrelation);
  ASSERT_TRUE(pair.separating_rpm.has_value());
  const FitResult two =
      FitCase(Example1(), {slow, MakeTrace(truth, *pair.separating_rpm, 0.005, 12, 0.05)}, o);
  for (const char* key : {"spring.preload_kgf", "needle.mass_kg"}) {
    const double narrowing =
        (Value(one, key).high - Value(one, key).low) / (Value(two, key).high - Value(two, key).low);
    std::cerr << key << " narrowed " << narrowing << " times\n";
    EXPECT_GT(narrowing, 3.0) << key;
  }
  EXPECT_LE(Value(two, "needle.mass_kg").low, 13.0);
  EXPECT_GE(Value(two, "needle.mass_kg").high, 13.0);
}

// A trace made by the spring as 20 coil masses, fitted with a massless spring: the residual is
// well above the noise and runs in long stretches, and the fit says the model misses something.
TEST(FitJob, SaysTheModelMissesTheSurgeOfASpringItTakesAsMassless) {
  const std::string surge = std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml";
  const BoundCase truth = Bind(LoadCase(surge));
  BoundCase massless = truth;
  massless.spring->masses = 1;
  massless.scene.reset();
  const std::vector<MeasuredTrace> traces = {MakeTrace(truth, 700.0, 0.005, 3)};
  const FitResult r =
      FitCase(massless, traces, Free({"spring.preload_kgf", "train.contact_damping_ratio"}));
  std::cerr << r.model_note << " chi2 " << r.chi2_reduced << " rms/noise "
            << r.traces[0].rms_m / r.traces[0].noise_m << " z " << r.traces[0].runs_z << "\n";
  EXPECT_TRUE(r.model_misses);
  EXPECT_NE(r.model_note.find("runs in long stretches"), std::string::npos);
  // The same trace fitted with the chain it was made with: no miss.
  const FitResult right =
      FitCase(truth, traces, Free({"spring.preload_kgf", "train.contact_damping_ratio"}));
  EXPECT_FALSE(right.model_misses) << right.model_note;
}

// The trace's own offsets: a sensor 0.02 mm off and an encoder 0.7° off are recovered.
TEST(FitJob, RecoversTheTracesCrankAngleAndSensorOffsets) {
  MeasuredTrace t = MakeTrace(Example1(), 700.0, 0.005, 5);
  for (double& th : t.table.crank_rad) th -= 0.7 * kDeg;  // y(θ + 0.7°) read at θ
  for (double& y : t.table.lift_m) y += 0.02e-3;
  const FitResult r = FitCase(Example1(), {t}, Free({"trace.offset_deg", "trace.offset_mm"}));
  const FittedValue& deg = Value(r, "trace.offset_deg");
  const FittedValue& mm = Value(r, "trace.offset_mm");
  EXPECT_LE(deg.low, 0.7);
  EXPECT_GE(deg.high, 0.7);
  EXPECT_LE(mm.low, 0.02);
  EXPECT_GE(mm.high, 0.02);
  EXPECT_LT(deg.high - deg.low, 0.05);
}

// A user's trial: a light-spring engine's play of 0.1 mm fits as well as its optimum 0.035 mm
// (the lift is the same for any play on the plateau beyond): the slope at the optimum gives
// ±0.003 mm, the scan of the cost must widen the interval over the plateau.
TEST(FitJob, TheScanWidensAnIntervalOverAPlateauTheSlopeCannotSee) {
  const std::string path = std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-cam4-light-spring.toml";
  BoundCase truth = Bind(LoadCase(path));
  truth.spring->rate_N_m = 25e3;
  truth.train->play_m = 0.1e-3;
  truth.train->seat_damping_ratio = 0.2;
  const std::vector<MeasuredTrace> traces = {MakeTrace(truth, 500.0, 0.003, 2500, 0.05, -20, 50),
                                             MakeTrace(truth, 750.0, 0.003, 2750, 0.05, -20, 50)};
  const FitResult r = FitCase(Bind(LoadCase(path)), traces,
                              Free({"spring.rate_N_mm", "train.play_mm",
                                    "train.seat_damping_ratio"}));
  const FittedValue& play = Value(r, "train.play_mm");
  std::cerr << "play " << play.value << " [" << play.low << ", " << play.high << "]\n";
  EXPECT_LE(play.low, 0.1);
  EXPECT_GE(play.high, 0.1);
  EXPECT_TRUE(play.widened || !play.identified);
}

// Five 1 mm spikes in a 5 µm trace: Huber's loss keeps the values, the robust scale keeps the
// intervals, and the fit calls them outliers, not a local minimum.
TEST(FitJob, OutliersNeitherMoveTheValuesNorWidenTheIntervals) {
  BoundCase truth = Example1();
  truth.spring->preload_N *= 0.9;
  MeasuredTrace t = MakeTrace(truth, 700.0, 0.005, 9);
  for (size_t i : {100, 300, 500, 700, 900}) t.table.lift_m[i] += 1e-3;
  const FitResult r = FitCase(Example1(), {t}, Free({"spring.preload_kgf"}));
  const FittedValue& p = Value(r, "spring.preload_kgf");
  EXPECT_LE(p.low, 0.9 * 790);
  EXPECT_GE(p.high, 0.9 * 790);
  EXPECT_LT(r.scale2, 1.2);
  EXPECT_GT(r.chi2_reduced, 2.0);
  EXPECT_NE(r.residual_note.find("a few readings stand far out"), std::string::npos)
      << r.residual_note;
}

TEST(FitJob, RefusesKeysItCannotFreeWithOneLine) {
  try {
    ParseFitKey("train.stiffness_N_m");
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--free: 'train.stiffness_N_m' is not a key needle fit can free; expected one of "
              "needle.mass_kg, spring.preload_N, spring.rate_N_mm, train.contact_stiffness_N_m, "
              "train.seat_stiffness_N_m, train.contact_damping_ratio, train.seat_damping_ratio, "
              "train.play_mm, trace.offset_deg, trace.offset_mm (any unit suffix of the case "
              "file's)");
  }
  EXPECT_THROW(ParseFitKey("needle.mass_lb"), CaseError);
  EXPECT_EQ(ParseFitKey("needle.mass_g").unit, "g");
  EXPECT_EQ(ParseFitKey("trace.offset_rad").dimension, Dimension::kAngle);
  EXPECT_EQ(ParseFitKey("trace.offset_um").dimension, Dimension::kLength);
  EXPECT_THROW(ParseFitBound("train.play_mm=0.5:0.1"), CaseError);
  EXPECT_THROW(ParseFitBound("train.play_mm=a:1"), CaseError);
  EXPECT_THROW(ParseFitBound("train.play_mm"), CaseError);
  const FitBound b = ParseFitBound("train.play_um=0:500");
  EXPECT_EQ(b.key.unit, "um");
  EXPECT_EQ(b.high, 500.0);
  const std::vector<MeasuredTrace> traces = {MakeTrace(Example1(), 700.0, 0.005, 1, 0.5)};
  // Example 1's rate comes from its coil geometry.
  try {
    FitCase(Example1(), traces, Free({"spring.rate_N_mm"}));
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("[spring] rate: the case's rate comes from its coil "
                                         "geometry; state rate_N_mm in [spring] to fit it"),
              std::string::npos)
        << e.what();
  }
  FitOptions o = Free({"train.play_mm"});
  o.bounds.push_back(ParseFitBound("spring.preload_N=1:2"));
  EXPECT_THROW(FitCase(Example1(), traces, o), CaseError);
  o = Free({"train.play_mm", "train.play_um"});
  EXPECT_THROW(FitCase(Example1(), traces, o), CaseError);
  o = Free({"train.play_mm"});
  o.bounds.push_back(ParseFitBound("train.play_mm=0:0.5"));
  o.bounds.push_back(ParseFitBound("train.play_um=0:400"));  // the same quantity bounded twice
  EXPECT_THROW(FitCase(Example1(), traces, o), CaseError);
  o = Free({"train.contact_damping_ratio"});
  o.bounds.push_back(ParseFitBound("train.contact_damping_ratio=-1:1"));  // below the range
  try {
    FitCase(Example1(), traces, o);
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--bounds: train.contact_damping_ratio=-1:1 reaches outside the plausible range 0 "
              "to 1 (docs/ranges.md)");
  }
  // Bounds that leave out the case's value: the search starts inside them.
  o = Free({"spring.preload_kgf"});
  o.starts = 1;
  o.bounds.push_back(ParseFitBound("spring.preload_kgf=600:700"));
  const FitResult bounded = FitCase(Example1(), traces, o);
  EXPECT_EQ(Value(bounded, "spring.preload_kgf").start, 790.0);
  EXPECT_LE(Value(bounded, "spring.preload_kgf").value, 700.0);
  // A rigid contact has no stiffness to fit.
  BoundCase rigid = Example1();
  rigid.train->contact = ContactKind::kRigid;
  try {
    FitCase(rigid, traces, Free({"train.contact_stiffness_N_m"}));
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("the case's contacts are rigid"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace needle
