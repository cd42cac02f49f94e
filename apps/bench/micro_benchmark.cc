// Google Benchmark micro-benchmarks of needle's hot paths: spline construction per kind,
// a 1000-row kinematics table, one right-hand-side evaluation, one dynamic run, a coil chain's
// modes.
//   ./build/needle-micro-bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/chain_modes.h"
#include "lib/kinematics.h"
#include "lib/units.h"

namespace needle {
namespace {

const Case& Cam4() {
  static const Case c = LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-cam4.toml");
  return c;
}

void BM_SplineBuild(benchmark::State& state) {
  SplineOptions o = Cam4().lift.spline;
  o.kind = AllSplineKinds()[state.range(0)];
  state.SetLabel(SplineKindName(o.kind));
  for (auto _ : state) benchmark::DoNotOptimize(LiftLaw(Cam4().lift.table, o));
}
BENCHMARK(BM_SplineBuild)->DenseRange(0, 7);

void BM_Table1000(benchmark::State& state) {
  SplineOptions o = Cam4().lift.spline;
  o.kind = AllSplineKinds()[state.range(0)];
  state.SetLabel(SplineKindName(o.kind));
  const LiftLaw law(Cam4().lift.table, o);
  const Kinematics kin(law, 400);
  for (auto _ : state) {
    for (int i = 0; i < 1000; ++i) {
      benchmark::DoNotOptimize(
          kin.At(law.start_rad() + (law.end_rad() - law.start_rad()) * i / 999.0));
    }
  }
}
BENCHMARK(BM_Table1000)->DenseRange(0, 7);

void BM_RightHandSide(benchmark::State& state) {
  const BoundCase c = Bind(LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example2.toml"));
  const Scene s = *c.scene;
  NeedleTrain train(*s.cam, s.train, 41.9, -0.5);
  Phase phase;
  phase.mode = {true, false};
  TrainState x{1e-3, 0.1, 0.0, 0.0}, d;
  double t = 0.01;
  for (auto _ : state) {
    train.Derivative(x, t, phase, d);
    benchmark::DoNotOptimize(d);
    t += 1e-9;
  }
}
BENCHMARK(BM_RightHandSide);

void BM_SimulateExample1(benchmark::State& state) {
  const BoundCase c = Bind(LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1.toml"));
  const Scene s = *c.scene;
  SimulationOptions o;
  o.method = "dopri5";
  o.force_dynamic = true;
  o.integrator.rtol = 1e-4;
  o.integrator.atol_m = 1e-7;
  for (auto _ : state) benchmark::DoNotOptimize(Simulate(s, 125, o));
}
BENCHMARK(BM_SimulateExample1)->Unit(benchmark::kMicrosecond);

// One dynamic run as `needle simulate --method M` makes it (forced dynamic, no series), on the
// scenes of issue 33: Example 2 at 1100 rpm (the lash impact, a needle ringing on its seat) and
// the bench's soft and lift-off scenes; exact against dopri5 at rtol 1e-8 in one process.
struct RunScene {
  const char* label;
  const char* file;
  double rpm;
};
constexpr RunScene kRunScenes[] = {{"lash-1100", "basu-example2.toml", 1100},
                                   {"example1-125", "basu-example1.toml", 125},
                                   {"light-spring-900", "basu-cam4-light-spring.toml", 900}};

void RunOnce(benchmark::State& state, const char* method, double rtol) {
  const RunScene& rs = kRunScenes[state.range(0)];
  const BoundCase c = Bind(LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/" + rs.file));
  const Scene s = *c.scene;
  SimulationOptions o = c.run;
  o.method = method;
  o.force_dynamic = true;
  o.integrator.rtol = rtol;
  o.integrator.atol_m = DefaultAtol(rtol);
  long steps = 0;
  for (auto _ : state) {
    const SimulationResult r = Simulate(s, rs.rpm, o);
    steps = r.stats.steps;
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(std::string(rs.label) + ", " + std::to_string(steps) + " steps");
}
void BM_Exact(benchmark::State& state) { RunOnce(state, "exact", 1e-8); }
void BM_Dopri5_1e8(benchmark::State& state) { RunOnce(state, "dopri5", 1e-8); }
BENCHMARK(BM_Exact)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dopri5_1e8)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// The coil chain's modes in one contact mode (the cam's), as method exact makes them once per
// chain and thread: `basu-example1-surge`'s spring as 5-40 coil masses, its eigenvalues by
// Aberth's O(N²) iteration (tridiagonal_qep.h) against the dense O(N³) QR alone (the before).
void ChainModesOnce(benchmark::State& state, ChainEigenvalues eigenvalues) {
  static const BoundCase c =
      Bind(LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml"));
  const Scene& s = *c.scene;
  TrainParameters p = s.train;
  p.coil_masses = static_cast<int>(state.range(0));
  const NeedleTrain train(*s.cam, p, OmegaFromRpm(125), DefaultRunWindow(s).start_rad);
  for (auto _ : state) benchmark::DoNotOptimize(ChainModes(train, {true, false}, eigenvalues));
  state.SetLabel(std::to_string(state.range(0)) + " coil masses");
}
void BM_ChainModesAberth(benchmark::State& state) {
  ChainModesOnce(state, ChainEigenvalues::kAberth);
}
void BM_ChainModesDense(benchmark::State& state) {
  ChainModesOnce(state, ChainEigenvalues::kDense);
}
BENCHMARK(BM_ChainModesDense)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ChainModesAberth)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);

// One revolution of `basu-example1-surge`'s chain (5-40 coil masses) at its rated 125 rpm and
// near its n_dyn, 520 rpm, as the surge study runs it (forced dynamic, no series): exact against
// dopri5 at rtol 1e-8, auto's pick for chains. The modes are made once per thread (Shared): a
// check pays them once per N, outside these times.
void SurgeChainRun(benchmark::State& state, const char* method) {
  static const BoundCase c =
      Bind(LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1-surge.toml"));
  Scene s = *c.scene;
  s.train.coil_masses = static_cast<int>(state.range(0));
  SimulationOptions o = c.run;
  o.cycles = 1;
  o.steady_state = false;
  o.method = method;
  o.force_dynamic = true;
  o.record_series = false;
  long steps = 0;
  for (auto _ : state) {
    const SimulationResult r = Simulate(s, static_cast<double>(state.range(1)), o);
    steps = r.stats.steps;
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(std::to_string(steps) + " steps");
}
void BM_SurgeChainExact(benchmark::State& state) { SurgeChainRun(state, "exact"); }
void BM_SurgeChainDopri5(benchmark::State& state) { SurgeChainRun(state, "dopri5"); }
BENCHMARK(BM_SurgeChainExact)
    ->ArgsProduct({{5, 10, 20, 40}, {125, 520}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SurgeChainDopri5)
    ->ArgsProduct({{5, 10, 20, 40}, {125, 520}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace needle

BENCHMARK_MAIN();
