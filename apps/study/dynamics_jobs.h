#pragma once
/// @file
/// The dynamics jobs over a case: one run at a speed (dynamics/simulation.h: the train
/// m·x'' = F_contact − P₀ − k·x − c·x' … integrated over the lift, its lift-off episodes and
/// impacts) and the overspeed search for n_dyn (dynamics/overspeed.h). `needle simulate`,
/// `needle overspeed` and the Python module call them; the writers are in
/// apps/report/dynamics_writer.h. Messages name the command's options (--rpm, --method, …).

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "dynamics/overspeed.h"
#include "dynamics/simulation.h"

namespace needle {

/// What a run is made with, over the case's [solver].
struct SimulateJobOptions {
  std::optional<double> speed_rpm;    ///< crank speed, rpm (default: [engine] speed_rpm)
  std::optional<std::string> method;  ///< a method of MethodList() or "auto" ([solver] method)
  std::optional<double> rtol;         ///< relative tolerance in [kMinRtol, kMaxRtol] ([solver])
  bool dynamic = false;               ///< run the dynamics even where the rigid answer stands
  std::optional<int> cycles;          ///< cam revolutions back to back ([solver] cycles)
  bool series = false;                ///< keep the time series as SI columns (Python)
  bool quasi_static = true;  ///< also n_qs of the scene (the JSON object has it; the text not)
  /// Crank angles, deg, increasing: the needle's lift there (CaseRun::result.grid), as a lift
  /// sensor sampled against an encoder reads it (`needle.simulate(grid_deg=…)`). Empty: none.
  std::vector<double> grid_deg;
};

/// A run of a case and what it was made with.
struct CaseRun {
  BoundCase c;                            ///< the case
  double speed_rpm = 0.0;                 ///< the speed run, rpm
  double rtol = 0.0;                      ///< the tolerance it ran with
  double liftoff_rpm_quasi_static = NAN;  ///< n_qs, rpm (∞ when none; NaN when not asked)
  SimulationResult result;                ///< the run
  /// The time series as SI columns in SeriesColumns()'s order, when `series` was asked and the
  /// dynamics ran; else empty.
  std::vector<std::vector<double>> series_si;
};

/// One run of a loaded case; each series point also goes to `series_sink` (when given) as the
/// run makes it. Throws CaseError on bad input.
CaseRun SimulateCase(const BoundCase& c, const SimulateJobOptions& options,
                     const std::function<void(const SeriesPoint&)>& series_sink = {});

/// What the search is made with, over the case's [overspeed] and [solver].
struct OverspeedJobOptions {
  std::optional<double> from_rpm;     ///< start, rpm (default: DefaultSweepRange)
  std::optional<double> to_rpm;       ///< end, rpm (default: DefaultSweepRange)
  std::optional<std::string> method;  ///< as SimulateJobOptions::method
  std::optional<double> rtol;         ///< as SimulateJobOptions::rtol
  int threads = 0;                    ///< threads, 0: all cores
  std::optional<double> step_rpm;     ///< scan step where the force gives no guidance, rpm
};

/// The search of a case and what it was made with.
struct CaseOverspeed {
  BoundCase c;                            ///< the case
  OverspeedOptions options;               ///< the search's options, its range resolved
  double liftoff_rpm_quasi_static = 0.0;  ///< n_qs, rpm (∞ when none)
  OverspeedResult result;                 ///< the search
};

/// The overspeed search of a loaded case; `progress` (may be empty) hears of every run done.
/// Throws CaseError on bad input (an option out of range, an empty range).
CaseOverspeed OverspeedOfCase(const BoundCase& c, const OverspeedJobOptions& options,
                              const std::function<void(int, int)>& progress = {});

}  // namespace needle
