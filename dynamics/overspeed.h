#pragma once
/// @file
/// The overspeed search (docs/model.md §6): the dynamic lift-off speed n_dyn is the lowest speed
/// in [from, to] at which a `jump` episode at least 0.1° long appears, found to 0.5 rpm. The
/// speeds are scanned upward from `from` in steps of Δn (`step_rpm`; default 2.5 % of `from`,
/// at least 1 rpm), as many at once as there are threads, until the first lift-off; a
/// k-section (k = the threads) then narrows that bracket. So the answer does not depend on `to`
/// for any `to` above it; a lift-off window narrower than Δn can be missed, and Δn is reported.
/// At most `max_speeds` speeds are scanned: past that the search ends with the status
/// `budget` and the speed it reached. A run stopped by its step or event budget before it
/// showed lift-off leaves the speed undecided: the scan ends there with the status
/// `run-budget` (that row says why), since a lift-off above it could not be claimed the lowest.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/simulation.h"
#include "lib/units.h"

namespace needle {

struct OverspeedRow {
  double speed_rpm = 0.0;
  double min_contact_force_N = 0.0;  ///< during the lift
  double jump_deg = 0.0;             ///< total length of jump episodes
  double longest_jump_deg = 0.0;
  double max_gap_mm = 0.0;
  double max_impact_speed_m_s = 0.0;
  bool lifts_off = false;                   ///< a jump of at least 0.1°
  RunStatus status = RunStatus::kComplete;  ///< how the run at this speed ended
  std::string status_reason;                ///< for unsettled and budget runs
};

struct OverspeedOptions {
  double from_rpm = 0.0;        ///< start of the range, > 0
  double to_rpm = 0.0;          ///< end, > from
  double resolution_rpm = 0.5;  ///< bracket width at which the search stops
  double step_rpm = 0.0;        ///< scan step Δn, rpm; 0: 2.5 % of from_rpm, at least 1
  int max_speeds = 5000;        ///< scan budget (speeds), ≥ 1
  int threads = 0;              ///< 0: all cores; more than the cores are capped to them
  SimulationOptions simulation;
  void Validate() const;
};

struct OverspeedResult {
  std::vector<OverspeedRow> rows;   ///< every speed run, sorted
  std::optional<double> n_dyn_rpm;  ///< lowest lift-off speed found (upper end of the bracket)
  double bracket_low_rpm = 0.0, bracket_high_rpm = 0.0;
  bool lifts_off_at_start = false;  ///< already lifts off at from_rpm
  int threads = 1;
  double step_rpm = 0.0;  ///< the scan step Δn used
  /// "found", "none" (none up to to_rpm), "budget" (scan budget) or "run-budget" (a run at
  /// scanned_to_rpm stopped on its budget without lift-off)
  std::string status = "found";
  double scanned_to_rpm = 0.0;  ///< highest speed scanned
};

/// `progress(done, total_estimate)` is called after each run (from the calling thread).
OverspeedResult OverspeedSearch(const Scene& scene, const OverspeedOptions& options,
                                const std::function<void(int, int)>& progress = {});

/// One row from one run.
OverspeedRow RowFromResult(const SimulationResult& r);

}  // namespace needle
