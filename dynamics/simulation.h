#pragma once
/// @file
/// One dynamic run of a scene at one speed (docs/model.md §5–6): window [θ_a, θ_b] with
/// θ_a = rise start − 5°, θ_b = fall end + 20°, and past θ_b on until the needle has landed
/// and come to rest (within settle_limit_deg); static-equilibrium start; `auto` takes the
/// closed form ("exact") when the contact laws are linear, else a method by the scene's
/// stiffness; the rigid answer reported instead of a dynamic
/// run when the scene does not need one, with the reason, unless the dynamics is forced.

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/model/cam_input.h"
#include "dynamics/model/needle_train.h"
#include "dynamics/solver/contact_events.h"
#include "dynamics/solver/integrator.h"
#include "lib/result_fields.h"
#include "lib/rigid_train.h"
#include "lib/units.h"

namespace needle {

/// Shortest jump that counts as lift-off, rad (0.1°): SimulationOptions::stop_at_liftoff and the
/// overspeed search (dynamics/overspeed.h).
constexpr double kMinJump_rad = 0.1 * kPi / 180.0;

/// Everything a run needs that does not depend on the speed. Shares its lift law and cam
/// input (neither changes once built): a copy of a scene with other train parameters costs
/// no rebuilding.
struct Scene {
  std::shared_ptr<const LiftLaw> law;
  std::shared_ptr<const CamInput> cam;  ///< on *law
  TrainParameters train;
  std::optional<double> start_rad, end_rad;  ///< window override
  /// Crank angle of one cam revolution, rad: 4π four-stroke, 2π two-stroke ([solver] cycles).
  double revolution_rad = 4.0 * kPi;
};

/// Options of a run. Every field has a default.
struct SimulationOptions {
  std::string method = "auto";   ///< "auto" or a method name (dynamics/solver/integrator.h)
  IntegratorOptions integrator;  ///< tolerances and budgets
  bool record_series = false;    ///< keep the time series (for --csv)
  /// With record_series: each point of the series, in time order, as soon as no earlier one
  /// can follow, instead of SimulationResult::series (a streamed series: memory independent of
  /// the run's length). Empty: the series is kept.
  std::function<void(const SeriesPoint&)> series_sink;
  bool force_dynamic = false;  ///< never report the rigid answer instead
  /// Past θ_b the run goes on until the needle has landed and come to rest, for at most this
  /// much crank angle, deg (docs/model.md §5); > 0 and ≤ 36000.
  double settle_limit_deg = 3600.0;
  /// Cam revolutions run back to back, each from θ_a to θ_a + one revolution, the state carried
  /// over (docs/model.md §5); 1: the single window above. [1, kMaxCycles].
  int cycles = 1;
  /// A cycle-end state repeats when its lift and velocity are within this fraction of the
  /// largest lift (and of ω times it) of one k revolutions before, k ≤ kMaxPeriod; (0, 1e-2].
  double period_tolerance = 1e-6;
  /// With cycles > 1, lift-off (jump_rad, longest_jump_rad, liftoff()) is judged on the steady
  /// cycles only: the repeating period once found, else every cycle after the first.
  bool steady_state = false;
  /// A run that asks only "does the needle lift off?": it stops at the end of the step where
  /// a jump episode reaches kMinJump_rad, or (one window, cycles = 1) at the end of the first
  /// step past the lift with the needle on the cam, where the verdict and the least contact
  /// force over the lift are final (status kStopped; the record ends there, so the other
  /// extremes and impacts cover the run up to there only; it reports its episodes, impacts,
  /// largest lift and least contact force over the lift, and NaN for the energy residual, the
  /// largest contact, seat and spring forces, the least lift and the force ratio, which the
  /// closed form does not keep for it). The jump stop is ignored
  /// with steady_state (a jump in a transient cycle does not count); baseline-dopri5 ignores
  /// both. Off: the run is unchanged.
  bool stop_at_liftoff = false;
  /// Crank angles, rad, sorted, at which to report the needle's state (SimulationResult::grid):
  /// a measured trace's angles (`needle fit`). One window only (cycles = 1); an angle before θ_a
  /// or past the run's end is not reported. Empty: none.
  std::vector<double> grid_rad;

  /// The rules of the run options, in one place: the integrator's (IntegratorOptions::
  /// Validate), settle_limit_deg, cycles and period_tolerance in their ranges (each a FieldError,
  /// lib/field_error.h, naming the field, its value and the rule), a grid with one window,
  /// sorted, and steady_state with cycles ≥ 2 (std::invalid_argument).
  void Validate() const;
};

/// Most cam revolutions one run may ask for, and the longest period looked for.
constexpr int kMaxCycles = 1000;
constexpr int kMaxPeriod = 8;

/// One cam revolution of a run of several (SimulationOptions::cycles).
struct CycleSummary {
  int index = 0;                  ///< 0-based
  double start_rad = 0.0;         ///< θ_a + index × revolution
  int impacts = 0;                ///< impacts in it (rigid accumulation points included)
  int jumps = 0;                  ///< jump episodes that began in it
  double jump_rad = 0.0;          ///< their total length
  double longest_jump_rad = 0.0;  ///< the longest
  double max_gap_m = 0.0;         ///< largest separation from the cam
  double end_lift_m = 0.0, end_velocity_m_s = 0.0;  ///< the state carried to the next one
  /// … with the coil masses' lifts x_i (m) then velocities v_i (m/s); empty without them.
  std::vector<double> end_coils;
  double energy_residual = 0.0;  ///< the audit over this revolution
};

/// How a run ended.
enum class RunStatus {
  kComplete,   ///< the needle at rest at or after θ_b (or the rigid answer)
  kUnsettled,  ///< still moving at θ_b + settle_limit_deg: the last episode may be open
  kBudget,     ///< a step or event budget stopped it: the record runs up to there
  kStopped,    ///< stopped at its first lift-off or past the lift (stop_at_liftoff)
  /// The needle did not follow its scene (docs/model.md §6): its largest lift short of the
  /// cam's, or its seat penetrated, by more than kFollowFraction of the cam's lift.
  kNotFollowing,
};
/// The share of the cam's largest lift by which a needle's largest lift may fall short of it,
/// or the needle go into its seat, in a run that follows its scene: compliant steel contacts
/// deflect by tens of micrometres, about 1 % of a needle lift.
constexpr double kFollowFraction = 0.10;
/// "complete", "unsettled", "budget", "stopped", "not-following".
std::string RunStatusName(RunStatus s);

struct SimulationResult {
  double speed_rpm = 0.0;
  std::string method;         ///< the method used ("rigid" when skipped)
  std::string method_reason;  ///< why that method
  bool skipped = false;       ///< the rigid answer stands in for a dynamic run
  double window_start_rad = 0.0, window_end_rad = 0.0;
  double run_end_rad = 0.0;  ///< where the run ended: θ_b, later while the needle settled
  RunStatus status = RunStatus::kComplete;
  std::string status_reason;  ///< why it ended so, for unsettled and budget runs
  std::vector<Episode> episodes;
  std::vector<Impact> impacts;
  std::vector<SeriesPoint> series;
  double max_lift_m = 0.0, max_lift_rad = 0.0;
  double max_contact_force_N = 0.0;
  /// The least cam contact force while the cam lifts the needle (the cam above the play and the
  /// needle off its seat, until it first seats past the cam's top: docs/model.md §6), N; 0 when
  /// the needle was never lifted.
  double min_contact_force_during_lift_N = 0.0;
  /// The least ratio of the contact force to the static load holding the needle on the cam
  /// there, F_c / (P₀ + k y − F_g), in the same window until the needle first seats past the
  /// cam's top (a rebound is a secondary opening), and its crank angle (rad) and force (N);
  /// NaN when the needle was never lifted.
  double min_contact_force_ratio = NAN;
  double min_contact_force_ratio_rad = 0.0;
  double min_contact_force_ratio_force_N = 0.0;
  /// The largest force of the spring on the needle, N: P₀ + k y, or with coil masses the first
  /// segment's S₁ (surge shows here).
  double max_spring_force_N = 0.0;
  /// A secondary opening: after the needle first seats following the lift, the largest lift it
  /// reopens to, m (0: none above 1 µm), its crank angle, rad, and the crank angle it stays
  /// above 1 µm, rad (of the revolution with the largest; docs/model.md §6).
  double secondary_lift_m = 0.0, secondary_lift_rad = 0.0, secondary_open_rad = 0.0;
  /// The least lift of the needle, m (< 0: pressed into its seat).
  double min_lift_m = 0.0;
  double max_seat_force_N = 0.0;
  /// With a chain of coil masses and a known travel to solid: the least gap to solid in the
  /// run, m (N times the most compressed segment's, docs/model.md §4a; < 0: the coils passed
  /// solid), and the onsets of coil clash ([spring] clash).
  std::optional<double> min_coil_gap_m;
  int coil_clashes = 0;
  double energy_residual = 0.0;
  double jump_rad = 0.0;  ///< total length of jump episodes (in the judged cycles)
  double longest_jump_rad = 0.0;
  IntegrationStats stats;
  /// The state at SimulationOptions::grid_rad's angles inside the run, in order (time_s from θ_a).
  std::vector<GridPoint> grid;
  /// Runs of several revolutions (SimulationOptions::cycles > 1): one summary each, in order;
  /// the run stops early once the state repeats (the rest would repeat it too).
  std::vector<CycleSummary> cycles;
  int cycles_asked = 1;
  int period_cycles = 0;  ///< k when cycle-end states repeat every k revolutions; 0: not found
  int periodic_from = 0;  ///< the first cycle of the repeating period
  /// The first cycle the lift-off measures count (steady_state), else 0.
  int judged_from = 0;
  bool liftoff() const;  ///< any jump episode (in the judged cycles)
};

/// The scene's train as the quasi-static check sees it: its mass, preload, rate and gas load.
RigidTrain RigidTrainOf(const Scene& scene);

/// The scene's quasi-static lift-off speed n_qs, rpm (spring/quasi_static.h on RigidTrainOf).
double QuasiStaticLiftoffRpm(const Scene& scene);

/// A run's numbers, described once for its writers (lib/result_fields.h): the extremes, the
/// window and where the run ended, the coil gap (with coil masses), the energy residual (none
/// when the run was skipped) and the work done. Episodes, impacts and cycles are lists.
std::vector<Field> SimulationFields(const SimulationResult& r);

/// One separation episode as fields: its kind, start and end (deg), largest gap (mm), the
/// index of the impact that ends it (−1: none), whether it is still open, and with
/// `with_cycle` the revolution it began in.
std::vector<Field> EpisodeFields(const Episode& e, bool with_cycle);
/// One impact as fields: its kind, crank angle (deg), approach speed (m/s), energy lost (J)
/// and with `with_cycle` its revolution.
std::vector<Field> ImpactFields(const Impact& i, bool with_cycle);
/// One revolution of a run of several as fields (CycleSummary); the state it ends in and its
/// energy residual without a value where they are not finite.
std::vector<Field> CycleFields(const CycleSummary& c);

/// The recorded series as a table, described once for its writers: crank_deg, time_s, lift_mm,
/// velocity_m_s, cam_mm, contact_force_N, seat_force_N (columns, and one SI row per point).
std::vector<Column> SeriesColumns();
/// One point as a row of those columns, SI.
std::array<double, 7> SeriesRow(const SeriesPoint& p);
/// Significant digits of the series' CSV.
constexpr int kSeriesCsvPrecision = 10;

/// The run window's margins about the cam input's rise and fall (docs/model.md §5), rad.
constexpr double kRunWindowLead_rad = 5.0 * kPi / 180.0;
constexpr double kRunWindowTail_rad = 20.0 * kPi / 180.0;
/// The run window [θ_a, θ_b] in crank rad (docs/model.md §5): from kRunWindowLead_rad before the
/// cam input's rise to kRunWindowTail_rad after its fall, unless the scene gives its own start or
/// end.
struct RunWindow {
  double start_rad = 0.0;  ///< θ_a
  double end_rad = 0.0;    ///< θ_b
};
RunWindow DefaultRunWindow(const Scene& scene);

/// Why `scene` cannot be run revolution after revolution (its run window is longer than one
/// cam revolution), or nullopt: "the run window (… to … deg) is longer than …".
std::optional<std::string> CyclesRefusal(const Scene& scene);

/// Contact oscillations per cam event, √((k_c + k)/m)·(θ_N − θ_0)/(2π ω): the stiffness measure
/// `auto` decides by.
double ContactOscillationsPerEvent(const Scene& scene, double speed_rpm);

/// What `auto` runs, and why (SimulationResult::method_reason): a rigid contact, dopri5; a
/// nonlinear contact law, dopri5 or (> 2000 contact oscillations per event) CVODE BDF; a train
/// linear in every contact mode, the closed form `exact`, at every tolerance: it costs the same
/// at any rtol and is at the roundoff of its own. BENCHMARKS.md's "auto by tolerance" measures
/// the rule on each bench scene: at equal error no method is faster. (Before issue 33's speed-up
/// dopri5 was taken for rtol in [1e-6, 1e-5], where it reached so loose a tolerance sooner; with
/// the closed form at the cost of what it cannot leave out, dopri5 at 1e-5 took 1.13× and 1.07×
/// exact's time on the soft and stiff scenes at 10⁶ times its error, and 0.9× on the lift-off
/// scene. Looser than 1e-5 the time steppers' errors reach the verdicts: at rtol 3e-3 the stiff
/// train's overspeed search found false separations near 755 rpm and put n_dyn at 786 rpm
/// instead of 1872, and at 1e-4 Example 1 loses a 0.01 m/s seat bounce.)
struct MethodChoice {
  Method method;
  std::string reason;
};
MethodChoice AutoMethod(const NeedleTrain& train, double oscillations_per_event, double rtol);
/// The same for a scene at a speed.
MethodChoice AutoMethod(const Scene& scene, double speed_rpm, double rtol);

/// One run of `scene` at `speed_rpm`. Throws std::invalid_argument (FieldError for a field) when
/// `options` break SimulationOptions::Validate: checked first, also where the rigid answer is
/// reported instead of the dynamics.
SimulationResult Simulate(const Scene& scene, double speed_rpm, const SimulationOptions& options);

}  // namespace needle
