// The no-event baseline of the benchmarks: Dormand–Prince with F = max(0, F) inside the
// right-hand side (Phase::gated), no event location, no stops at breaks (integrate_times on
// odeint's dense output). It reports grid samples and step ends. What the event driver's
// location is measured against; not a backend of the driver.
#include <boost/numeric/odeint.hpp>
#include <functional>

#include "dynamics/solver/odeint_state.h"
#include "dynamics/solver/stepper.h"

namespace needle {

namespace odeint = boost::numeric::odeint;

IntegrationStats IntegrateBaseline(Method method, const NeedleTrain& train, const TrainState& x0,
                                   double t_end, Recorder& recorder, const IntegratorOptions& o) {
  IntegrationStats stats;
  TrainSystem system(train, o);
  system.phase.gated = true;
  const Phase& phase = system.phase;
  recorder.Start(0.0, x0, phase);
  // Output times: the grid, or else 400 points; the integrator does not stop at breaks or
  // switches: that is what the baseline is for.
  std::vector<double> times = recorder.grid_times();
  if (times.empty()) {
    for (int i = 0; i <= 400; ++i) times.push_back(t_end * i / 400.0);
  }
  if (times.front() > 0.0) times.insert(times.begin(), 0.0);
  if (times.back() < t_end) times.push_back(t_end);
  const std::vector<double>& grid = recorder.grid_times();
  size_t next_grid = 0;
  TrainState z = system.ToScaled(x0), last = x0;
  double last_t = 0.0;
  const auto observer = [&](const TrainState& s, double t) {
    const TrainState x = system.FromScaled(s);
    while (next_grid < grid.size() && grid[next_grid] <= t + 1e-15)
      recorder.GridSample(grid[next_grid++], x, phase);
    recorder.Sample(t, x, phase);
    last = x;
    last_t = t;
  };
  auto dense =
      odeint::make_dense_output(o.atol_m, o.rtol, odeint::runge_kutta_dopri5<TrainState>());
  stats.steps = static_cast<long>(
      odeint::integrate_times(dense, std::ref(system), z, times.begin(), times.end(),
                              std::min(t_end, 0.01 / train.FastestAngularFrequency()), observer));
  if (stats.steps > o.max_steps) ThrowOverBudget("steps", o.max_steps, train, t_end, stats, method);
  recorder.Finish(last_t, last, phase);
  stats.End(last_t, last, phase, system.evaluations());
  return stats;
}

}  // namespace needle
