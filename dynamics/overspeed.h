#pragma once
/// @file
/// The overspeed search (docs/model.md §6): the dynamic lift-off speed n_dyn is the lowest speed
/// at which a `jump` episode at least kMinJump_rad (0.1°) long appears, above a speed where none
/// does, found to `resolution_rpm`. Each speed is one run that asks only that question
/// (SimulationOptions::stop_at_liftoff: a run stops at its first lift-off, or just past the
/// lift where its verdict and its least contact force are final).
///
/// Upward scan from `from`, led by the margin f(n) = F_min(n)/P₀, the least contact force over
/// the lift as a fraction of the preload. From a speed n without lift-off the next is n + Δ,
/// with Δ_max = max(Δn, `max_step_fraction`·n) and Δn = `step_rpm` (default 2.5 % of `from`, at
/// least 1 rpm):
///   - f ≤ 0 (the force reaches zero without a jump, or a rigid contact records none): Δ = Δn,
///     but no larger than the last step where f has just reached zero (the lift-off is near);
///   - f > 0 and fallen since the last speed: Δ = the distance to the zero of the secant of f
///     against n² through the two, plus the resolution, at most Δ_max;
///   - f > 0 otherwise: Δ = Δ_max·min(1, f/0.5), so the steps shrink as the force nears zero;
///     where f rose, at most half the distance over which it would fall back to zero at the rate
///     it rose (out of one dip, perhaps into the next);
///   - Δ at least the resolution.
/// A lift-off at n + Δ gives the bracket; bisection narrows it (its first probe just past the
/// secant's zero while f at the low end is positive; plain halving once a probe fails to halve). So
/// the answer does not depend on `to` for any `to` above it, nor on the thread count (the speeds
/// asked are the same: threads only run ahead the speeds a bisection may ask next). A lift-off
/// window that the force does not approach within one step (a window, and the dip of f around it,
/// narrower than Δ_max) can be missed.
///
/// With `start_rpm` (a guess, such as a nearby scene's n_dyn: a tolerance study's nominal) the
/// scan starts there instead of at `from`: where the needle lifts off there, it goes down in
/// steps of 5 % of `start_rpm` (at least Δn), doubling, until a speed without lift-off (or
/// `from`, where the search goes on as below), and scans up from there as from `from`. The
/// bracket is run at both ends as always (no lift-off at its low end, lift-off at its high end),
/// so n_dyn is a lift-off onset of the scene; but a lift-off window below the speed the scan
/// starts from is not looked for (the search from `from` may find one). With `start_after_rpm`
/// too, the scan first runs from `from` exactly as without a guess, up to the first speed at or
/// above `start_after_rpm` without lift-off, and only then goes to the guess (down from it, not
/// below that speed): a lift-off up to there — where a check's verdict reads it, below f·n — is
/// found exactly as without a guess.
///
/// When the needle lifts off already at `from`, the search goes down: from/2, from/4, … (not
/// below `floor_rpm`) until a speed without lift-off, then scans up from there; lifting off at
/// every speed down to the floor is the status `floor`, without a value.
///
/// At most `max_speeds` speeds are scanned: past that the search ends with the status `budget`
/// and the speed it reached. A run stopped by its step or event budget before it showed lift-off
/// leaves the speed undecided: the scan ends there with the status `run-budget` (that row says
/// why), since a lift-off above it could not be claimed the lowest.

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
  double jump_rad = 0.0;             ///< total length of jump episodes, crank rad
  double longest_jump_rad = 0.0;     ///< the longest, crank rad
  double max_gap_m = 0.0;            ///< largest separation from the cam, m
  double max_impact_speed_m_s = 0.0;
  bool lifts_off = false;                   ///< a jump of at least 0.1°
  RunStatus status = RunStatus::kComplete;  ///< how the run at this speed ended
  std::string status_reason;                ///< for unsettled and budget runs
};

struct OverspeedOptions {
  double from_rpm = 0.0;        ///< start of the range, > 0
  double to_rpm = 0.0;          ///< end, > from
  double resolution_rpm = 0.5;  ///< bracket width at which the search stops
  /// Scan step Δn where the contact force gives no guidance, rpm, ≥ 0; 0: 2.5 % of from_rpm,
  /// at least 1.
  double step_rpm = 0.0;
  /// Largest scan step as a fraction of the speed (at least Δn), (0, 1].
  double max_step_fraction = 0.1;
  /// Lowest speed searched down to when the needle lifts off at from_rpm, rpm, [0, from_rpm);
  /// 0: from_rpm / 16.
  double floor_rpm = 0.0;
  /// Where the upward scan starts (see above); used when from_rpm < start_rpm < to_rpm.
  std::optional<double> start_rpm;
  /// With start_rpm: scan from from_rpm as without a guess until a speed at or above this one
  /// without lift-off, then go on from the guess (see above); rpm. Every speed up to it is the
  /// scan's without a guess, so a lift-off found up to there is the same.
  std::optional<double> start_after_rpm;
  int max_speeds = 5000;  ///< scan budget (speeds), ≥ 1
  int threads = 0;        ///< 0: all cores; more than the cores are capped to them
  SimulationOptions simulation;
  void Validate() const;
};

struct OverspeedResult {
  std::vector<OverspeedRow> rows;   ///< every speed the search asked about, sorted
  std::optional<double> n_dyn_rpm;  ///< lowest lift-off speed found (upper end of the bracket)
  double bracket_low_rpm = 0.0, bracket_high_rpm = 0.0;
  bool lifts_off_at_start = false;  ///< already lifts off at from_rpm (searched down)
  double floor_rpm = 0.0;           ///< the floor of the downward search used
  int threads = 1;
  double step_rpm = 0.0;  ///< the scan step Δn used
  /// "found", "none" (none up to to_rpm), "floor" (lifts off at every speed tried down to
  /// floor_rpm), "budget" (scan budget), "not-following" (the run at scanned_to_rpm did not follow
  /// its cam, RunStatus::kNotFollowing) or "run-budget" (a run at scanned_to_rpm stopped on its
  /// budget without lift-off)
  std::string status = "found";
  double scanned_to_rpm = 0.0;  ///< highest speed scanned
};

/// n_dyn as words, for every status: "650.4 rpm", "none up to 1000.0 rpm", or "undecided: …"
/// (floor, budget, run-budget, not-following), naming the speed.
std::string OverspeedOutcome(const OverspeedResult& r);
/// Whether the search decided (status "found" or "none").
inline bool Decided(const OverspeedResult& r) { return r.status == "found" || r.status == "none"; }

/// `progress(done, total_estimate)` is called after each run or batch (from the calling thread).
OverspeedResult OverspeedSearch(const Scene& scene, const OverspeedOptions& options,
                                const std::function<void(int, int)>& progress = {});

/// One row from one run.
OverspeedRow RowFromResult(const SimulationResult& r);

/// The search's outcome as fields (lib/result_fields.h): n_dyn (`liftoff_rpm_dynamic`, none
/// when not found), its bracket, whether it lifts off at the start, the floor, threads, the
/// scan step, the status and the highest speed scanned.
std::vector<Field> OverspeedFields(const OverspeedResult& r);
/// One speed's row as fields: speed, least contact force, jump length (deg), largest gap (mm),
/// largest impact speed, whether it lifts off, and how its run ended.
std::vector<Field> OverspeedRowFields(const OverspeedRow& row);
/// The rows' numeric columns: speed, least contact force, jump (deg), largest gap (mm), largest
/// impact speed, lift-off (1 or 0).
const std::vector<Column>& OverspeedColumns();
/// One row's values in OverspeedColumns()' order (SI; speed in rpm).
std::vector<double> OverspeedRowSi(const OverspeedRow& row);

}  // namespace needle
