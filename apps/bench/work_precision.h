#pragma once
/// @file
/// Work-precision measurement: a run of one method at one tolerance, timed (median over
/// repeats) and compared with a reference run on a common grid of times:
///
///     lift error    max_i |y(t_i) − y_ref(t_i)|          (m)
///     force error   max_i |F_c(t_i) − F_c,ref(t_i)|      (N)
///     event error   max_k |θ_k − θ_k,ref| over impacts matched by order and kind (rad)

#include <optional>
#include <string>
#include <vector>

#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"

namespace needle {

/// One run with its grid samples, impacts and cost.
struct MeasuredRun {
  std::string method;
  double rtol = 0.0;
  double median_seconds = 0.0;
  IntegrationStats stats;
  std::vector<GridPoint> grid;
  std::vector<Impact> impacts;
  double energy_residual = 0.0;
  std::string failure;  ///< non-empty when the run did not finish (budget, solver error)
};

struct RunErrors {
  double lift_m = 0.0;
  double force_N = 0.0;
  std::optional<double> event_rad;  ///< empty when the impact lists differ in number or kind
  int event_count = 0, reference_event_count = 0;
};

/// Runs `method` on the scene at `speed_rpm` with rtol (atol = rtol·1 mm), `repeats` times,
/// recording the state at `grid_times`. The dynamics is always run (no rigid skip).
MeasuredRun MeasureRun(const Scene& scene, double speed_rpm, Method method, double rtol,
                       const std::vector<double>& grid_times, int repeats);

/// Errors of `run` against `reference` (same grid).
RunErrors CompareRuns(const MeasuredRun& run, const MeasuredRun& reference);

/// `n` + 1 grid times inside the scene's window at `speed_rpm` (cell midpoints).
std::vector<double> WindowGrid(const Scene& scene, double speed_rpm, int n);

}  // namespace needle
