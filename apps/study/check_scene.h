#pragma once
/// @file
/// "Check a scene" as a library function: what `needle check` decides, with the pass/fail
/// policy in one place (docs/model.md §8). A scene passes when every part it has passes:
///
///   - the spring check ([needle] and [spring], a C² lift law): spring/spring_check.h;
///   - the dynamics at the rated speed n ([train]): no lift-off, and the run complete (the
///     needle at rest before the run window's end);
///   - the overspeed sweep: n_dyn above f·n (f = [spring] overspeed_factor, 1.2), and the
///     sweep decided (neither budget ended it);
///   - the cam profile ([profile]): no undercut (a flat face: no cusp), the contact on the face;
///   - the limits table ([limits], cited defaults): every row that can be judged within its
///     limit; a row the scene cannot judge says why and is named among the skipped.
///
/// A part the scene does not have is skipped and named, never passed silently. The command
/// only formats the result (text, JSON, the HTML report).

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "dynamics/overspeed.h"
#include "dynamics/simulation.h"
#include "lib/cam_profile.h"
#include "lib/kinematics.h"
#include "lib/result_fields.h"
#include "spring/resonance.h"
#include "spring/spring_check.h"
#include "spring/verdict_row.h"

namespace needle {

/// The overspeed sweep's range, rpm.
struct SweepRange {
  double from_rpm = 0.0;  ///< > 0
  double to_rpm = 0.0;    ///< > from_rpm for a non-empty sweep
};

/// The default sweep of a case, used by `check` and `overspeed` alike: from [overspeed]
/// from_rpm, else the rated speed; to [overspeed] to_rpm, else max(2·n_qs, 2·rated) when n_qs
/// is finite and 4·rated when it is not (a lift law that never decelerates).
SweepRange DefaultSweepRange(const BoundCase& c, double rated_rpm, double n_qs_rpm);

/// One row of the limits table (case [limits]): value against limit, in display units.
using LimitRow = VerdictRow;

/// A failing row as one line, its parts apart: "limits: NAME: measured V, limit >= L, margin M
/// (where/why); rule: SOURCE" — the finding first, the rule's source last.
std::string FailureLine(const LimitRow& row);

/// Surge judged by its effect (docs/model.md §8): the scene run with its helical spring as N
/// coil masses, at the rated speed and at f·n, beside the massless spring.
struct SurgeStudy {
  /// N, the first of 5, 10, 20, 40 at which the least contact force (share of the holding
  /// load) and the peak spring force at the needle both move by less than kSurgeConvergence
  /// (of the holding load / of the peak) from the N before; 40 when none does.
  int masses = 0;
  double change = NAN;           ///< that last move, the larger of the two, as a fraction
  bool converged = false;        ///< below kSurgeConvergence at `masses`
  double damping_ratio = 0.0;    ///< ζ of the first surge mode used
  bool damping_assumed = false;  ///< the case gives none: needle's 1 %
  /// With coil masses at the rated speed; it and `massless` keep their series when
  /// CheckOptions::record_series (the report's surge figure).
  SimulationResult rated;
  SimulationResult overspeed;  ///< with coil masses, at f·n
  SimulationResult massless;   ///< the massless spring at the rated speed
  /// The massless spring at f·n (a note of the report; not run with CheckOptions::verdict_only).
  SimulationResult massless_overspeed;
};
/// The convergence rule of SurgeStudy::masses.
constexpr double kSurgeConvergence = 0.01;

/// The failing lines of a table that does not reach the seat at an end (its lift there above
/// kOpenEndFraction of `top_m`, its largest lift, m): "lift table: undecided, it starts at …".
/// `needle check` and `needle spring` fail the table so (a follower's position exported for its
/// lift, 15 mm at the seat, passed `needle spring` with a required preload of 0 N). Where both
/// ends stand at one lift (within 1 % of `top_m`) the lines say the readings may carry an offset.
std::vector<std::string> TableEndFailures(const LiftLaw& law, double top_m);

/// Options of CheckScene; every field has a default.
struct CheckOptions {
  std::optional<double> speed_rpm;  ///< rated speed, rpm; default [engine] speed_rpm
  /// Called after each overspeed run with (done, total estimate); may be empty.
  std::function<void(int, int)> progress;
  /// Threads (0: all cores): with two or more the surge study runs beside the overspeed sweep,
  /// which has the others; the result is the same with any number.
  int threads = 0;
  bool record_series = true;  ///< keep the rated-speed run's time series (the report's figures)
  // What a check may take from a check of a nearby scene (a tolerance study's nominal,
  // docs/commands.md, "What a sample takes from the nominal"): the verdict stays this scene's own,
  // but see each.
  /// A nearby scene's n_dyn, where the overspeed scan goes on once it has passed f·n (1 + the
  /// separation margin) without lift-off (OverspeedOptions::start_rpm, start_after_rpm): every
  /// speed up to there is run as without it, so a lift-off the verdict reads is the full scan's.
  /// A search that does not end "found" so is run again from the sweep's start. The speeds
  /// between that point and the guess are not run: a run there that would end on its budget or
  /// not follow its cam (which makes a full check's search undecided) is not seen, and n_dyn
  /// and scanned_to may differ from the full scan's where it steps over a window above f·n.
  std::optional<double> overspeed_start_rpm;
  /// Compute what the verdict reads, no more: no massless spring's run at f·n (SurgeStudy, a
  /// note of the report) and no lift harmonics (CheckResult::harmonics). Every limits row and
  /// verdict is the full check's.
  bool verdict_only = false;
  /// Called on the calling thread once the spring check and the rated-speed run are done, before
  /// the overspeed sweep, while the surge study may be running on another thread (a report draws
  /// their figures beside the rest: CheckReportWriter::RatedRun); may be empty.
  std::function<void(const SpringCheckResult& spring, const SimulationResult& run,
                     const SimulationOptions& options)>
      rated_run_done;
};

/// What `needle check` found. All SI except speeds (rpm).
struct CheckResult {
  double speed_rpm = 0.0;                   ///< the rated speed checked
  LiftLawChoice choice;                     ///< the spline and why
  KinematicsSummary kinematics;             ///< open lift, extremes at the rated speed
  std::optional<SpringCheckResult> spring;  ///< with [needle], [spring] and a C² law
  std::optional<SimulationResult> run;      ///< the dynamic run at the rated speed
  SimulationOptions run_options;            ///< the options it ran with
  std::optional<OverspeedResult> sweep;     ///< the overspeed sweep
  SweepRange sweep_range;                   ///< its range
  std::optional<CamProfile> profile;        ///< with [profile]
  double cam_zero_crank_rad = 0.0;          ///< the crank angle of its cam angle 0 (CrankOfCam)
  double n_qs_rpm = NAN;                    ///< quasi-static lift-off; NaN without a spring
  double overspeed_rpm = 0.0;               ///< f·n, the speed n_dyn must exceed
  std::vector<LimitRow> limits;             ///< the limits table, every row (judged or not)
  std::optional<CamHarmonics> harmonics;    ///< the lift's harmonics (with a helical spring)
  std::vector<double> surge_modes_hz;       ///< the spring's first three modes (helical)
  std::optional<SurgeStudy> surge;          ///< with a helical spring and the dynamics
  std::string surge_reason;                 ///< why the surge study was not run, if it was not
  /// Rows that warn (verdict "warning"), and what the verdict cannot vouch for, one line each.
  std::vector<std::string> warnings;
  bool pass = true;                  ///< no part failed
  std::vector<std::string> failing;  ///< one line per failing item, named
  std::vector<std::string> skipped;  ///< one line per part not run, and why
  /// The limit rows not judged, grouped by reason ("Hertz stress cam-roller (no [profile] …)");
  /// empty when every row was judged. Shown beside the overall verdict.
  std::string not_judged;
};

/// The result's fields, described once, by part (kinematics, spring, dynamics, overspeed,
/// profile; a part the scene lacks is absent): its numbers, and the verdicts, statuses and
/// counts `check --json` shows (a tolerance study takes the numbers only).
std::vector<FieldGroup> CheckFields(const CheckResult& r);

/// One limits row as fields: its key (as `name`), unit, direction, verdict, note, source, and
/// its value, limit and margin in the row's own unit (none when not judged).
std::vector<Field> LimitRowFields(const LimitRow& row);

/// Checks bound case `c` on its own lift law and scene. Throws CaseError on a case that cannot
/// be checked (a section that is present but invalid).
CheckResult CheckScene(const BoundCase& c, const CheckOptions& options = {});
/// The same on another law of the case's table (`law`; the choice reported stays the case's).
CheckResult CheckScene(const BoundCase& c, const LiftLaw& law, const CheckOptions& options = {});
/// The same on a shared law: the check's scene and its surge study's scenes share it.
CheckResult CheckScene(const BoundCase& c, std::shared_ptr<const LiftLaw> law,
                       const CheckOptions& options = {});

/// Where the rated-speed run lifts off with jumps all shorter than the 0.1° that n_dyn counts
/// (any jump fails at the rated speed, docs/model.md §8), the words that say so — " (a jump of
/// 0.040°, shorter …)" — else empty: the lift-off and an n_dyn above the rated speed agree.
std::string ShortJumpNote(const SimulationResult& run);

/// Where the rated-speed run, complete, does not lift off but its needle leaves the cam after
/// an impact (bounces: none reaches the deceleration zone, docs/model.md §6), the words that say
/// so — " (the cam loses the needle in 2 bounces after impacts, from -14.91 deg, …)" — else
/// empty: a "no" beside a least contact force of 0 N reads as its contradiction without them.
std::string BounceNote(const SimulationResult& run);

/// Whether the coils' dynamics show harm: the surge rows' contact force, jump or stress, or the
/// coil gap, fails. A failing f_1/f_cam screen (13, the classic rule) only warns when they
/// show none (docs/model.md §8): the screen judges a frequency, the rows its effect.
bool SurgeShowsHarm(const LimitRow& force, const LimitRow& jump, const LimitRow& stress,
                    const LimitRow& gap);

}  // namespace needle
