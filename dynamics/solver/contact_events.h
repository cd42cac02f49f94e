#pragma once
/// @file
/// Events of the needle train, written as signed witness functions of the state (SUNDIALS
/// style), and the record they feed (docs/model.md §6):
///
///   0  g_c            cam penetration          (upward crossing: an impact on the cam)
///   1  the cam law's force branch (compliant: k_c g_c + c_c ġ_c; the cam pushes iff the law
///                     says so from the signs of 0 and 1: compliant, both > 0)
///   2  g_s            seat penetration         (upward crossing: an impact on the seat)
///   3  the seat law's force branch
///   4  y − 1 µm       the separation threshold of an episode
///   5  ġ_c            while the cam does not push and y > 1 µm: its upward crossing is the
///                     largest gap (+1 otherwise)
///   6  ẏ              while y > 1 µm: its downward crossing is a local maximum of the lift
///   7 + 2(j − 1), 8 + 2(j − 1)   with coil clash (NeedleTrain::ClashSegments), the clash law's
///                     gap g_j = s_j − δ and force branch of segment j = 1…N
///
/// Functions 0–3 and the clash witnesses decide the contact mode; 4–6 only observe. The record
/// keeps separation episodes (jump or bounce), impacts (lash, recontact, seat, seat-bounce),
/// extremes, and the time series only when asked.

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/model/needle_train.h"

namespace needle {

/// The witnesses every train has (0–6); a chain with coil clash appends two per segment.
constexpr int kEventCount = 7;
/// The most witnesses a train has.
constexpr int kMaxEventCount = kEventCount + 2 * kMaxCoilMasses;
/// The witnesses of the two contacts: gap and force branch of the cam (0, 1) and the seat (2, 3).
constexpr int kCamGap = 0, kCamBranch = 1, kSeatGap = 2, kSeatBranch = 3;
/// y − 1 µm: the gate of witnesses 5 (ġ_c off the cam) and 6 (ẏ), which observe a lifted needle
/// only (+1 below it).
constexpr int kLiftGate = 4;
/// Lift above which a needle off the cam counts as separated, m (docs/model.md §6: 1 µm).
constexpr double kSeparationLift_m = 1e-6;

/// Rest after the lift (docs/model.md §5): speed below this, m/s …
constexpr double kRestSpeed_m_s = 1e-4;
/// … and net force below this fraction of P₀ + |F_g| (or of m·1 m/s² without loads).
constexpr double kRestForceFraction = 1e-3;

/// Witness values, and their signs (+1 above zero, −1 at or below it); inline, no allocation.
using EventValues = boost::container::static_vector<double, kMaxEventCount>;
using EventSigns = boost::container::static_vector<int, kMaxEventCount>;

/// The event functions at (t, x) in `phase` (its mode and its segment of the cam input).
EventValues Events(const NeedleTrain& train, const Phase& phase, const TrainState& x, double t);
/// The same from the contacts at (x, t), `c` = train.Evaluate(x, t, phase).
EventValues Events(const NeedleTrain& train, const Phase& phase, const TrainState& x,
                   const Contacts& c);

/// A linear form of the state and the cam input, w = y·y + v·ẏ + u·u + u_rate·u̇ + constant
/// (u̇ = du/dt = ω u'), SI: how method "exact" sees a witness to bound it.
struct LinearForm {
  double y = 0.0, v = 0.0, u = 0.0, u_rate = 0.0, constant = 0.0;
};

/// Witness `index` of Events() as a linear form in `phase`, with the gate of witnesses 5 and 6
/// taken as `lifted` (y > kSeparationLift_m); nullopt when a contact law is not linear
/// (ContactLaw::Linear). Equal to Events() wherever the gate holds.
std::optional<LinearForm> WitnessForm(const NeedleTrain& train, const Phase& phase, int index,
                                      bool lifted);

/// The mode implied by the signs of witnesses 0–3 and the clash witnesses, by the train's contact
/// laws.
ContactMode ModeFromSigns(const NeedleTrain& train, const EventSigns& signs);

struct Episode {
  /// "jump" (any part of it where s'' < 0 inside [θ_0, θ_N], docs/model.md §6, or at θ_N when the
  /// cam input's slope drops there, an impulsive deceleration), "bounce", or "rebound" (it began
  /// after the needle first seated past the cam's top: a secondary opening, never a jump)
  std::string kind;
  double start_rad = 0.0;
  double end_rad = 0.0;
  double max_gap_m = 0.0;  ///< largest y − u
  int impact = -1;         ///< index of the impact that ends it, −1 if none
  bool open = false;       ///< still separated when the run ended (end_rad = the run's end)
  int cycle = 0;           ///< the cam revolution it began in, 0-based ([solver] cycles)
};

struct Impact {
  /// "lash", "recontact", "seat", "seat-bounce"; "cam-sticking" and "seat-sticking" for the
  /// accumulation point of a chattering sequence (speed: the departure speed of its last
  /// impact; energy: what the rest of the geometric series dissipates)
  std::string kind;
  double crank_rad = 0.0;
  double speed_m_s = 0.0;      ///< approach speed ġ at onset, ≥ 0
  double energy_lost_J = 0.0;  ///< kinetic energy the reset map took, J (0: no reset)
  int cycle = 0;               ///< the cam revolution it happened in, 0-based ([solver] cycles)
};

struct SeriesPoint {
  double crank_rad, time_s, lift_m, velocity_m_s, cam_m, contact_force_N, seat_force_N;
};

/// The state at one requested time (benchmarks compare runs on a common grid).
struct GridPoint {
  double time_s = 0.0, lift_m = 0.0, contact_force_N = 0.0;
};

/// Bounds on what a stretch of a run can show, for Recorder::MayChange: lift, cam input, and the
/// contact and seat forces the mode applies (0 when it does not push), each over the stretch.
struct StretchRanges {
  double y_lo = 0.0, y_hi = 0.0;    ///< lift, m
  double u_hi = 0.0;                ///< cam input, m
  double fc_lo = 0.0, fc_hi = 0.0;  ///< applied cam force, N
  double fs_hi = 0.0;               ///< applied seat force, N
  /// A coil chain's largest segment compression, m, and the spring's force on the needle, N:
  /// upper bounds (+∞: not bounded; one mass: not read, both follow the lift). For the record a
  /// chain at rest up to round-off has every range narrowed (EventDriver::RestAllowance).
  double compression_hi = std::numeric_limits<double>::infinity();
  double spring_hi = std::numeric_limits<double>::infinity();
};

/// What a run records. Observers keep output apart from integration: the event driver calls
/// Sample() at step ends (and a few dense points) and Crossing() at located events, each with
/// the phase the train is in there (the record takes the forces of its mode).
class Recorder {
 public:
  /// `sink` (with record_series): every series point goes to it once no earlier point can
  /// follow (Commit), in time order, instead of being kept: a streamed series.
  Recorder(const NeedleTrain& train, bool record_series,
           std::function<void(const SeriesPoint&)> sink = {});

  /// The initial state: a needle already on the cam has no lash to take up.
  void Start(double t, const TrainState& x, const Phase& phase);
  void Sample(double t, const TrainState& x, const Phase& phase);
  /// The same with the train's contacts at (t, x) in `phase` already evaluated.
  void Sample(double t, const TrainState& x, const Phase& phase, const Contacts& c);
  /// An event function `index` crossed zero at t in direction ±1; `phase` is the one after
  /// the crossing. `sample` false: an impact whose reset map follows (a rigid contact; its
  /// impulsive force is not a sample of the contact force), recorded without a sample.
  void Crossing(int index, int direction, double t, const TrainState& x, const Phase& phase,
                bool sample = true);
  /// The last impact's reset map took this much kinetic energy, J.
  void ImpactLoss(double energy_J);
  /// A chattering sequence on the cam (`cam`) or the seat ended in sticking at t: the
  /// accumulation point, with the departure speed of the last impact resolved and the energy
  /// the rest of the series dissipates.
  void Accumulation(bool cam, double t, const TrainState& x, const Phase& phase, double speed_m_s,
                    double energy_J);
  /// No point before time t will be recorded any more (the driver is past it): with a sink,
  /// the points kept before t go to it.
  void Commit(double t);
  /// Closes an open episode at the end of the run.
  void Finish(double t, const TrainState& x, const Phase& phase);
  /// The run stopped on a budget at this angle: an open episode ends there, marked open.
  void Stopped(double crank_rad);
  /// The needle has landed and come to rest (docs/model.md §5): not separated, the cam input no
  /// longer moving, a contact pushing, |ẏ| ≤ kRestSpeed_m_s and the net force on the needle
  /// below kRestForceFraction of the spring and gas loads (so a contact oscillation caught at
  /// its turning point is not taken for rest).
  bool AtRest(double t, const TrainState& x, const Phase& phase) const;
  /// The net force on the needle below which AtRest may hold, N (kRestForceFraction of the
  /// spring and gas loads, or of m·1 m/s² without loads).
  double RestForceTolerance() const;
  /// Whether samples inside a stretch with these ranges could change anything recorded (a
  /// series is kept, an episode is open, or a range reaches past an extreme recorded so far);
  /// false: the stretch's interior samples may be left out (method "exact").
  /// `lift_covered`: the lift's own extremes are left out (the driver knows the stretch's lift to
  /// run between two lifts the record holds or is about to hold). `reported`: only what the run
  /// reports counts (set_liftoff_only); else everything recorded.
  bool MayChange(const StretchRanges& r, bool lift_covered = false, bool reported = false) const;
  /// Whether a sample repeating one already recorded could still change anything: a series is
  /// kept, or an episode is open.
  bool RepeatsMatter() const { return record_series_ || separated_; }
  /// A run that answers only "lift-off?" (SimulationOptions::stop_at_liftoff) reports its
  /// episodes, impacts, largest lift and least contact force over the lift; samples need not
  /// keep its other extremes (largest forces, least lift, the contact force's least share of
  /// the holding load), which are then partial.
  void set_liftoff_only(bool on) { liftoff_only_ = on; }
  bool liftoff_only() const { return liftoff_only_; }
  /// The same for one sample inside a stretch (method "exact"): lift y, the cam input below
  /// u_hi, the applied cam force within [fc_lo, fc_hi] and the seat force fs. With `covering`,
  /// the lift the driver records next after the stretch: a sample whose lift it passes the same
  /// way (y below it where y sets a new largest lift, above it where a new least) leaves the
  /// same record behind, and counts as changing nothing there. A chain's sample takes the
  /// stretch's bounds on its compression and spring force (StretchRanges).
  bool SampleMayChange(double y, std::optional<double> covering, double u_hi, double fc_lo,
                       double fc_hi, double fs, const StretchRanges& stretch) const;

  const std::vector<Episode>& episodes() const { return episodes_; }
  const std::vector<Impact>& impacts() const { return impacts_; }
  /// Wall time spent in the sink, s (writing a streamed series is not the run's work: the
  /// driver's wall-clock budget leaves it out).
  double sink_seconds() const { return sink_seconds_; }
  /// The series (with a sink: the points not yet sent, none after Finish or Stopped).
  const std::vector<SeriesPoint>& series() const { return series_; }
  /// Off the cam in the last episode, which is still open (as of the last sample or event).
  bool separated() const { return separated_; }
  /// The largest gap of the open separation episode, m; 0 where none is open.
  double open_gap_m() const { return separated_ ? episodes_.back().max_gap_m : 0.0; }

  /// Asks integrators to report the state at these times (sorted); empty: none.
  void set_grid(std::vector<double> times) { grid_times_ = std::move(times); }
  const std::vector<double>& grid_times() const { return grid_times_; }
  /// The driver calls this for every grid time, in order, with the dense state there.
  void GridSample(double t, const TrainState& x, const Phase& phase);
  /// Index of the next grid time not yet reported.
  size_t next_grid() const { return grid_.size(); }
  const std::vector<GridPoint>& grid() const { return grid_; }
  double max_lift_m() const { return max_lift_; }
  /// The largest compression of one segment of the chain beyond its installed length, m.
  double max_segment_compression_m() const { return max_segment_compression_m_; }
  double max_lift_rad() const { return max_lift_rad_; }
  double max_contact_force_N() const { return max_fc_; }
  /// The least cam contact force while the cam lifts the needle (OnCamWindow, until the needle
  /// first seats past the cam's top), N; 0 when the needle was never lifted.
  double min_contact_force_during_lift_N() const { return lifted_ ? min_fc_lift_ : 0.0; }
  /// The least contact force over the static load that holds the needle on the cam there,
  /// F_c / (P₀ + k y − F_g), in the same window until the needle first seats past the cam's top
  /// (0 where that load is not positive); NaN when the needle was never lifted. Its crank
  /// angle, rad, and the force there, N.
  double min_contact_force_ratio() const { return lifted_ ? min_ratio_ : NAN; }
  /// The contact force `fc` (N) over the holding load P₀ + k y − F_g at lift `y` (m), cam input
  /// `u` (m), as min_contact_force_ratio records it; +inf where it records none (the cam or the
  /// needle within 1 µm of the seat, or the needle seated past the cam's top).
  double ForceShare(double fc, double u, double y) const;
  double min_contact_force_ratio_rad() const { return min_ratio_rad_; }
  double min_contact_force_ratio_force_N() const { return min_ratio_force_; }
  /// The largest force of the spring on the needle, N (P₀ + k y, or the chain's S₁).
  double max_spring_force_N() const { return max_spring_; }
  /// Whether the cam ever lifted the needle off its seat (the window was entered).
  bool lifted() const { return lifted_; }
  /// After the needle first seats following the lift (its seat gap's first onset once lifted):
  /// the largest lift it reopens to, m (0: none above 1 µm), its crank angle, rad, and the
  /// crank angle it spends above 1 µm, rad (witness kLiftGate's crossings: located).
  double secondary_lift_m() const { return secondary_lift_; }
  double secondary_lift_rad() const { return secondary_lift_rad_; }
  double secondary_open_rad() const { return secondary_open_rad_; }
  /// The least lift of the needle in the run, m (< 0: into its seat).
  double min_lift_m() const { return min_lift_; }
  double max_seat_force_N() const { return max_fs_; }
  /// The least gap to solid in the run, m: the spring's travel to solid less N times the most
  /// compressed segment's compression (for N = 1, less the lift), over the samples and events;
  /// nullopt when the train has no travel (TrainParameters::coil_travel_m = 0).
  std::optional<double> min_coil_gap_m() const;
  /// Onsets of coil clash (a segment's clash gap witness crossing upward).
  int coil_clashes() const { return coil_clashes_; }
  /// Total length of jump episodes, rad.
  double jump_rad() const;
  /// Longest jump episode, rad.
  double longest_jump_rad() const;

 private:
  /// The holding load P₀ + k y − F_g at lift `y` (m), N: what the least contact force's share
  /// is taken of (RigidTrain::SpringForceN).
  double HoldingLoadN(double y) const;
  /// `fc` (N, a pulling one as 0) over the holding load at `y`; 0 where that load is not positive.
  double HoldShare(double fc, double y) const;
  /// A series point: kept (with a sink, until committed); throws std::logic_error for one
  /// before the committed time (a driver that broke its promise).
  void Keep(const SeriesPoint& p);
  /// With a sink: every point kept goes to it (the run is over).
  void SendAll();
  /// Sends the first n points kept (a point repeating the last one sent is not sent again) and
  /// drops them; the time spent in the sink counts in sink_seconds().
  void Send(size_t n);
  void Update(double t, const TrainState& x, const Phase& phase);
  void Update(double t, const TrainState& x, const Phase& phase, const Contacts& c);
  /// Inside [θ_0, θ_N], up to the roundoff of θ = θ_a + ω t.
  bool InLift(double crank_rad) const;
  /// The window the least contact force is taken over (docs/model.md §6): the cam above the
  /// play (u > 1 µm) and the needle off its seat (y > 1 µm), so the cam is lifting it — the same
  /// for an exact and a measured table of one cam, whatever its detected open lift.
  /// Both least-force windows (in N, the overspeed scan's margin, and the ratio the limits' rows
  /// judge) also close when the needle first seats past the cam's top: a rebound off the seat is
  /// a secondary opening (secondary_lift_m, episodes of kind "rebound"), not a cam losing the
  /// needle it lifts.
  static bool OnCamWindow(const Contacts& c, const TrainState& x);
  /// Inside the deceleration zone at this angle (docs/model.md §6).
  bool Decelerating(double crank_rad) const;

  const NeedleTrain& train_;
  bool record_series_;
  std::function<void(const SeriesPoint&)> sink_;
  double committed_t_ = -1e300;  // with a sink: the points before this time went to it
  SeriesPoint last_sent_{};
  bool sent_any_ = false;
  double sink_seconds_ = 0.0;
  std::vector<Episode> episodes_;
  std::vector<Impact> impacts_;
  std::vector<SeriesPoint> series_;
  std::vector<double> grid_times_;
  std::vector<GridPoint> grid_;

  bool separated_ = false;
  bool liftoff_only_ = false;    // set_liftoff_only
  bool end_slope_drop_ = false;  // the cam input's slope drops at θ_N
  bool cam_touched_ = false;     // any cam onset yet (lash vs recontact)
  bool seat_landed_ = false;     // any seat onset yet (seat vs seat-bounce)
  double max_lift_ = -1e300, max_lift_rad_ = 0.0;
  double max_fc_ = 0.0, min_fc_lift_ = 1e300, max_fs_ = 0.0;
  bool lifted_ = false;
  bool at_lift_edge_ = false;  // Update of a crossing of the lift's 1 µm level
  bool seated_ = false;        // seated after the lift (the least ratio's window closed)
  bool reopened_ = false;      // above 1 µm after seating, since reopen_rad_
  double reopen_rad_ = 0.0;
  double secondary_lift_ = 0.0, secondary_lift_rad_ = 0.0, secondary_open_rad_ = 0.0;
  double last_t_ = -1e300;  // the latest time the episodes have seen
  double min_ratio_ = 1e300, min_ratio_rad_ = 0.0, min_ratio_force_ = 0.0;
  double min_lift_ = 1e300;
  double max_spring_ = -1e300;
  double max_segment_compression_m_ = -1e300;
  int coil_clashes_ = 0;
};

}  // namespace needle
