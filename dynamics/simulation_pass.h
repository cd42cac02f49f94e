#pragma once
/// @file
/// Internal to Simulate (dynamics/simulation.cc): one pass of the train from a state over a time
/// span, its records merged into the run's result, and the revolutions of [solver] cycles
/// (docs/model.md §5), each a pass from the state the last one ended in.

#include "dynamics/simulation.h"

namespace needle {
namespace internal {

/// Integrates `train` by `method` from x0 (t = 0) to t_end, recording into `r` (its records
/// moved by shift_rad, the `cycle`-th revolution's); settle_deg > 0 asks for the needle at rest
/// that far past the end, else the status says unsettled. Returns the pass's summary.
CycleSummary RunPass(const NeedleTrain& train, Method method, const TrainState& x0, double t_end,
                     double settle_deg, const SimulationOptions& o, int cycle, double shift_rad,
                     SimulationResult& r);

/// [solver] cycles = N: revolutions until N have run or the cycle-end state repeats.
void RunCycles(const Scene& scene, const NeedleTrain& train, Method method,
               const SimulationOptions& o, SimulationResult& r);

}  // namespace internal
}  // namespace needle
