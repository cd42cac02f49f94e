#pragma once
/// @file
/// Internal to the solver (not installed): the one event driver, declared for its two files —
/// event_driver.cc (the run: steps, events, resets, rest) and event_certification.cc (the
/// closed form's certified crossings, quiet stretches and located extremes).
///
/// The one event driver (after Drake's Simulator with witness functions). It owns, for every
/// backend alike:
///   - the contact mode: the witnesses' signs decide it (ModeFromSigns); inside a step the mode
///     is fixed, so the right-hand side is smooth;
///   - event location: a witness whose sign at the step's end differs from its stored sign is
///     bracketed by 16 samples of the dense output and refined by TOMS 748 to machine
///     precision; the earliest crossing is taken first;
///   - reset maps: at an impact of a law that has one, the state jumps (NeedleTrain::Reset);
///   - restarts: after a mode switch or a reset the backend restarts at the event;
///   - the cam input's breaks: steps end exactly on every break, the cam is evaluated on the
///     segment's own side of it, and the backend restarts past it;
///   - budgets (steps, events), recording (Recorder) and the end of the run (docs/model.md §5).
#include <array>
#include <boost/math/tools/roots.hpp>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "dynamics/solver/contact_events.h"
#include "dynamics/solver/integrator.h"
#include "dynamics/solver/stepper.h"

namespace needle {
namespace internal {

// Halvings one certified search may spend (ClosedFormPiece bounds are tight enough that a
// simple crossing takes a few dozen; only a witness pinned at zero by round-off runs out).
inline constexpr int kIsolationBudget = 256;

// The sign a witness value counts as: +1 above zero, −1 at or below it.
inline int SignOf(double v) { return v > 0.0 ? 1 : -1; }

inline EventSigns Signs(const EventValues& v) {
  EventSigns s(v.size());
  for (size_t i = 0; i < v.size(); ++i) s[i] = SignOf(v[i]);
  return s;
}

class EventDriver {
 public:
  EventDriver(Method method, const NeedleTrain& train, Recorder& recorder,
              const IntegratorOptions& o)
      : train_(train), recorder_(recorder), o_(o), system_(train, o), method_(method) {
    stepper_ = MakeStepper(method, system_, o);
    if (MethodIsClosedForm(method)) {
      // The scales of the cam input and its rate, for RecordExtremes' round-off allowance.
      const LiftLaw& law = train.cam().law();
      lift_scale_ = std::abs(train.cam().top().value) + train.cam().play_m();
      rate_scale_ = train.omega() * lift_scale_ / (law.end_rad() - law.start_rad());
    }
    stepper_->SetLongest([this](const ClosedFormPiece& piece, double t, double cap, double limit) {
      return LongestQuiet(piece, t, cap, limit);
    });
  }

  IntegrationStats Run(const TrainState& x0, double t_end);

 private:
  // The contacts at a step's end (x, t) in the current phase: those its last stage computed
  // there (TrainSystem::LastContacts, an FSAL method's), else evaluated.
  Contacts EndContacts(const TrainState& x, double t) const {
    const Contacts* kept = system_.LastContacts(x, t);
    return kept ? *kept : train_.Evaluate(x, t, system_.phase);
  }
  // The state at t from the backend's dense output.
  TrainState At(double t) {
    stepper_->CalcState(t, z_);
    return system_.FromScaled(z_);
  }
  // y and ẏ at t (W and D may be left out): for witnesses and samples. Without
  // `coil_speeds` (a record's sample), a chain's coils from the second on have no velocity (NaN).
  TrainState Motion(double t, bool coil_speeds = true) {
    if (const ClosedFormPiece* piece = stepper_->ClosedForm()) {
      // The closed form's y and ẏ without ÿ and the state's copies: the bits the backend's
      // scaled state would give (one mass: y, ẏ, and W, D left at 0; the one-mass path kept
      // apart, this is the certified search's hot path).
      if (piece->Chain()) {  // the coils' lifts and velocities too
        TrainState x = piece->MotionState(t, coil_speeds);
        for (size_t i = 0; i < x.size(); ++i) x[i] = system_.RoundTrip(static_cast<int>(i), x[i]);
        return x;
      }
      const std::array<double, 2> yv = piece->LiftAndSpeed(t);
      return {system_.RoundTrip(0, yv[0]), system_.RoundTrip(1, yv[1]), 0.0, 0.0};
    }
    stepper_->CalcMotion(t, z_);
    return system_.FromScaled(z_);
  }
  void Restart(const TrainState& x, double t, double dt) {
    stepper_->Initialize(system_.ToScaled(x), t, dt);
  }
  // At a state reached without integration (the start, a reset, a rigid contact letting go):
  // the mode its witnesses imply, and their signs in that mode (witness 5 depends on the mode).
  // Rigid contacts stick by NeedleTrain::StickingMode, and x is put on their surfaces.
  EventSigns SettleMode(TrainState& x, double t) {
    Phase& phase = system_.phase;
    phase.mode = ModeFromSigns(train_, Signs(Events(train_, phase, x, t)));
    if (train_.HasConstraint()) {
      phase.mode = train_.StickingMode(x, t, phase);
      x = train_.Project(x, t, phase);
    }
    return Signs(Events(train_, phase, x, t));
  }
  // After an impact of a rigid contact (`cam` or the seat) at t with approach speed ġ⁻ > 0,
  // the state xs after its reset: when the impacts form a geometric series (this one's speed
  // is e times the last one's, to 10 %) whose remaining flights, 2 e ġ⁻/(a (1 − e)) under the
  // pressing acceleration a = λ/m, end within kAccumulationTime of a cam revolution, the
  // accumulation point t∞ (at most `limit`) with the needle sticking there; else nullopt.
  // A series at the touch tolerance's floor (AtTouchFloor) counts as geometric.
  std::optional<double> Accumulate(bool cam, double t, double approach, double limit,
                                   TrainState& xs, EventSigns& signs);

  // At t, the end of a segment where the cam's slope may jump, a rigid cam contact that is
  // open and closing with its gap within the touch tolerance (the surface arrives exactly at
  // the corner; the witness, which fires at a penetration of the tolerance, would see it only
  // beyond, at the far side's slope): the impact, recorded and reset into x with the near
  // side's surface speed, the contacts' modes settled against it. False (x unchanged)
  // otherwise.
  bool StrikeAtCorner(double t, TrainState& x);

  // Chattering ends in sticking when its remaining flights last less than this fraction of a
  // cam revolution (2π/ω).
  static constexpr double kAccumulationTime = 1e-6;
  // True when an impact of approach ġ⁻ m/s with restitution e under the pressing acceleration
  // a = λ/m m/s² is within kTouchFloorFactor of the speed sqrt(2 a δ/(1 − e²)) at which the
  // touch tolerance δ (GapTolerance) feeds the series as much as each impact takes: there the
  // series has accumulated, whatever the ratio of its last two approaches.
  bool AtTouchFloor(double approach, double e, double pressing) const;
  static constexpr double kTouchFloorFactor = 2.0;
  void GridUpTo(double t) {
    const std::vector<double>& grid = recorder_.grid_times();
    while (next_grid_ < grid.size() && grid[next_grid_] <= t) {
      recorder_.GridSample(grid[next_grid_], Motion(grid[next_grid_]), system_.phase);
      ++next_grid_;
    }
  }

  double Value(int i, double t) {
    if (value_form_) return value_piece_->FormValue(*value_form_, t);
    return ValuesAt(t)[i];
  }
  // Every witness at t (the last time asked is kept: the certified search asks each witness at
  // the same ends).
  const EventValues& ValuesAt(double t) {
    if (!(t == values_t_ && values_valid_)) {
      values_ = Events(train_, system_.phase, Motion(t), t);
      values_t_ = t;
      values_valid_ = true;
    }
    return values_;
  }
  // The root of witness i inside a bracket [a, b] where it leaves sign s, by TOMS 748 to
  // machine precision: the side past the crossing.
  double Refine(int i, double a, double fa, double b, double fb) {
    std::uintmax_t iterations = 100;
    // A chain's search on its Taylor polynomials where Certified made them (the closed form's
    // values to its round-off, without a mode's sine and exponential a value); the crossing is
    // then passed on the closed form itself (past).
    const auto search = [&](double at) {
      if (value_form_ && value_taylor_)
        return value_piece_->FormValue(*value_form_, at, value_taylor_->LiftAndSpeed(at));
      return Value(i, at);
    };
    const auto r = boost::math::tools::toms748_solve(
        search, a, b, fa, fb, boost::math::tools::eps_tolerance<double>(52), iterations);
    // TOMS 748 may end on an exact zero, which counts as the negative side, or inside the
    // round-off band of the function: then the earliest time found past the crossing, by
    // bisection between its answer and b (which is past).
    const int s = SignOf(fa);
    const auto past = [&](double at) { return SignOf(Value(i, at)) != s; };
    if (past(r.second)) return r.second;
    double lo = std::max(a, r.second), hi = b;
    while (true) {
      const double mid = lo + 0.5 * (hi - lo);
      if (!(mid > lo && mid < hi)) break;
      (past(mid) ? hi : lo) = mid;
    }
    return hi;
  }
  // The time steppers: witness i keeps sign s at `from` (value wa) and not at the step end
  // (t_end, the dense output's end t_dense): the first of 16 samples without sign s brackets
  // the crossing.
  std::optional<double> Sampled(int i, int s, double from, double wa, double t_end,
                                double t_dense) {
    const int n = 16;
    double a = from, fa = wa;
    for (int k = 1; k <= n; ++k) {
      const double b = k == n ? t_dense : from + (t_end - from) * k / n;
      const double fb = Value(i, b);
      if (SignOf(fb) == s) {
        a = b;
        fa = fb;
        continue;
      }
      return Refine(i, a, fa, b, fb);
    }
    return std::nullopt;
  }
  // The closed form: the earliest time in [a, b] where witness i (values wa at a, of sign s,
  // and wb at b) leaves sign s, or nullopt, certified by the bounds of its linear form on the
  // piece.
  std::optional<double> Certified(const ClosedFormPiece& piece, int i, int s, double a, double wa,
                                  double b, double wb);
  // A bracket [a, b] of one crossing with the witness's values at its ends.
  struct Bracket {
    double a, wa, b, wb;
  };
  // `q0`: the form's polynomial part in τ = t − t₀ (ClosedFormPiece::FormPolynomial).
  std::optional<Bracket> Isolate(const ClosedFormPiece& piece, const LinearForm& form,
                                 const ClosedFormPiece::Poly& q0, int i, int s, const Bracket& in,
                                 int& budget);

  // Whether a jump episode has lasted at least o_.stop_jump_rad by t (closed ones, and the open
  // one up to t); false when that option is off. Episodes before jump_checked_ are done with.
  bool JumpReached(double t);

  // Whether every sample of a closed-form piece over [t0, t1] repeats its start, which the record
  // holds: the piece is frozen (its y and ẏ keep their bits) and the train's own evaluation
  // (cam input, forces, spring) is the same at both ends, so in between (the cam input is
  // constant there, or monotone: the base circle's ramp clipped at the play), and no series or
  // open episode needs the repeats.
  bool Frozen(const ClosedFormPiece& piece, double t0, double t1) const;
  // The ranges of what the record sees over [t0, t1] of a closed-form piece.
  StretchRanges Ranges(const ClosedFormPiece& piece, double t0, double t1) const;
  // For the record only (Recorder::MayChange): a chain at rest up to round-off (a constant
  // forcing, its homogeneous part within 1e-12 of the cam's scale) has its ranges narrowed by
  // what that ringing can move, a record moving within it being no change.
  void RestAllowance(const ClosedFormPiece& piece, StretchRanges& r) const;
  // Ranges() narrowed by what RecordExtremes knows of the stretch: the witnesses' `signs` bound
  // the lift, and a lift that rises (falls) throughout, from a sample the record holds to the
  // `covering` one, sets no extreme before that sample does (then *lift_covered).
  StretchRanges SettledRanges(const ClosedFormPiece& piece, double t0, double t1,
                              std::optional<double> covering, const EventSigns& signs,
                              bool* lift_covered);
  // The end of a closed-form piece from t past its cap, up to `limit` and the run's end t_end_:
  // on a constant or linear cam input, the farthest of t + 2ᵏ (cap − t) (k ≥ 1) and that end
  // whose stretch from t is Quiet (a needle resting on its seat or hanging in its play, the
  // base circle or a ramp under it), else the cap.
  double LongestQuiet(const ClosedFormPiece& piece, double t, double cap, double limit) const;
  // Whether [t, end] of the piece cannot change the record (Recorder::MayChange) and every
  // witness's range keeps its sign over it (no crossing, certified without halving). `now`: the
  // witnesses at t, made at the first stretch that needs them and kept for the longer ones.
  bool Quiet(const ClosedFormPiece& piece, double t, double end,
             std::optional<EventValues>& now) const;

  // A budget stops the run with the work done so far (its statistics go with the message).
  [[noreturn]] void OverBudget(const char* what, double budget, double at, IntegrationStats& stats);
  // One more step (at its start `at`), against the steps' and the wall clock's budgets.
  void CountStep(double at, std::chrono::steady_clock::time_point started, IntegrationStats& stats);
  // Records the step [t0, t1] after its last crossing at `from` (x_end at t1): the grid, the
  // samples or located extremes, and the step's end. True when the run stops there (its first
  // lift-off, or past the lift without one, as asked).
  bool RecordStep(double t0, double t1, double from, const TrainState& x_end,
                  const EventSigns& signs, IntegrationStats& stats);
  // The earliest witness crossing after `from` and up to t1 in the last step (its ends `step`,
  // x_end the state at its end; `piece` the closed form's, else nullptr): (i, t) of the first
  // witness to leave its stored sign, i = −1 when none does.
  std::pair<int, double> EarliestCrossing(const ClosedFormPiece* piece, const EventSigns& signs,
                                          double from, double t1, std::pair<double, double> step,
                                          const TrainState& x_end);
  // Witness `first` crossed at first_t, the state there xs: its sign flips, the mode switches,
  // a rigid contact releases or an impact's reset map applies (xs, signs, the restart time and
  // the counts updated). Whether the mode switched or a reset applied.
  bool Cross(int first, double first_t, double segment_end, TrainState& xs, EventSigns& signs,
             double& restart, IntegrationStats& stats);
  // A rigid contact sticking across a break at t where the cam's slope may jump: the needle on
  // the surface as it arrives, the next break's angle the phase's, and the mode settled against
  // the surface beyond (an impact or a release).
  void CrossSlopeJump(double t, const std::vector<double>& break_times,
                      const std::vector<double>& break_angles, size_t& next_break, TrainState& x,
                      EventSigns& signs, IntegrationStats& stats);
  // Samples a stretch (t0, t1) of a closed-form step at 16 points for the record, and where a
  // sample sets a new largest contact or seat force, or a new least contact force, locates that
  // extreme by Brent's method between the samples around it and records it there (a lift-off
  // run, Recorder::set_liftoff_only: the least contact force only).
  // An interior sample that provably changes nothing recorded (Recorder::SampleMayChange, its
  // cam force from the piece's own polynomials within a round-off allowance of the train's) and
  // cannot start a located extreme is left out: the same record, one train evaluation and one
  // record update less. `covering`: the lift the driver records right after the stretch.
  // `signs`: the witnesses' signs, which (certified) none leaves inside the stretch: the seat's
  // gap and witness 4 bound the lift there.
  void RecordExtremes(double t0, double t1, std::optional<double> covering,
                      const EventSigns& signs);
  // RecordExtremes samples a stretch at this many intervals.
  static constexpr int kStretchSamples = 16;
  // RecordExtremes' samples of a stretch: their times, and at each the values ExtremeValue
  // takes (which = 0 … 6).
  static constexpr int kExtremes = 7;
  struct StretchSamples {
    std::array<double, kStretchSamples + 1> ts;
    std::array<std::array<double, kStretchSamples + 1>, kExtremes> f;
  };
  // At x: the three forces, each signed so that its extreme is a minimum, (which = 3) a chain's
  // largest segment compression (the least coil gap, where the run reports it), negated, and
  // (which = 4) the contact force's share of the holding load (Recorder::ForceShare), (which = 5) a
  // chain's spring force on the needle (the surge study's peak), negated, and (which = 6) the
  // needle's gap above the cam while separated (the cam not pushing, the lift above 1 µm),
  // negated; +∞ where the cam pushes or the lift is within 1 µm of the seat.
  double ExtremeValue(int which, double t, const TrainState& x) const;
  // The state the cam and seat forces read at t: Motion(t), or a chain piece's needle alone
  // (Motion()'s bits for y and ẏ, the coils at 0), which is all linear contact laws read.
  TrainState ForceState(double t);
  // Where a sampled value, which = first … last − 1, passes its record (`record`, signed as
  // ExtremeValue) inside the stretch or next to a chain's end sample: its minimum located by
  // Brent's method between the samples around it, and recorded.
  void LocateExtremes(const StretchSamples& samples, const std::array<double, kExtremes>& record,
                      int first, int last);
  // One of them about sample k (its neighbours, or the end's): Brent's least value, recorded;
  // `record` where nothing is searched (the end sample is the bracket's least, or a least
  // contact force not while pushing).
  double LocateExtreme(const StretchSamples& samples, int which, int k, double record);
  // The earliest time in [lo, hi] at which the needle is at rest (Recorder::AtRest), on the
  // step's dense output, or nullopt: 64 samples and the end, then bisection between the last
  // moving sample and the first at rest (the closed form under a constant forcing and input:
  // FirstClosedFormRest first).
  std::optional<double> FirstRest(double lo, double hi, const Phase& phase);
  // The same on the closed form under a constant forcing and input, by steps that pass no time
  // at rest however briefly (the needle's rate bounds: a chain's
  // ClosedFormPiece::ChainNeedleRateBounds, one mass's from its homogeneous energy): the time,
  // or nullopt with `lo` moved past hi (none at rest) or to where its step budget ended.
  std::optional<double> FirstClosedFormRest(const ClosedFormPiece& piece, double& lo, double hi,
                                            const Phase& phase);
  // Between `moving` (not at rest) and `rest` (at rest), the time it comes to rest, by bisection
  // to 1e-12 of it.
  double RestOnset(double moving, double rest, const Phase& phase);

  const NeedleTrain& train_;
  Recorder& recorder_;
  const IntegratorOptions& o_;
  TrainSystem system_;
  Method method_;  // for the budget's advice
  std::unique_ptr<Stepper> stepper_;
  TrainState z_{};
  size_t next_grid_ = 0;
  // The approach speed of the last impact of each rigid contact while it chatters (cam, seat).
  std::array<std::optional<double>, 2> last_approach_;
  size_t jump_checked_ = 0;  // episodes closed and shorter than o_.stop_jump_rad
  double t_end_ = 0.0;       // the run's window (pieces are not stretched past it)
  double lift_scale_ = 0.0;  // the cam input's scale, m (method "exact")
  // Of the cam's scale (and its rate's): what the record's samples cannot tell from their own
  // round-off (SettledRanges' lift, a chain at rest: RestAllowance).
  static constexpr double kRoundoffFraction = 1e-12;
  double rate_scale_ = 0.0;  // its rate's, m/s
  // While a certified search runs: the witness as a linear form on the piece (Value).
  const LinearForm* value_form_ = nullptr;
  const ClosedFormPiece* value_piece_ = nullptr;
  const ChainTaylor* value_taylor_ = nullptr;  // Refine's search on a chain (Certified)
  EventValues values_;  // ValuesAt's last answer, at values_t_ in the current step
  double values_t_ = 0.0;
  bool values_valid_ = false;
};

}  // namespace internal
}  // namespace needle
