// The one event driver (after Drake's Simulator with witness functions). It owns, for every
// backend alike:
//   - the contact mode: the witnesses' signs decide it (ModeFromSigns); inside a step the mode
//     is fixed, so the right-hand side is smooth;
//   - event location: a witness whose sign at the step's end differs from its stored sign is
//     bracketed by 16 samples of the dense output and refined by TOMS 748 to machine
//     precision; the earliest crossing is taken first;
//   - reset maps: at an impact of a law that has one, the state jumps (NeedleTrain::Reset);
//   - restarts: after a mode switch or a reset the backend restarts at the event;
//   - the cam input's breaks: steps end exactly on every break, the cam is evaluated on the
//     segment's own side of it, and the backend restarts past it;
//   - budgets (steps, events), recording (Recorder) and the end of the run (docs/model.md §5).
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "dynamics/solver/stepper.h"
#include "lib/units.h"

namespace needle {
namespace {

// The cam input's breaks strictly inside (0, t_end), sorted: times (s from θ_a) and the exact
// break angles (rad) they stand for.
struct Breaks {
  std::vector<double> times, angles;
};

// Halvings one certified search may spend (ClosedFormPiece bounds are tight enough that a
// simple crossing takes a few dozen; only a witness pinned at zero by round-off runs out).
constexpr int kIsolationBudget = 256;

Breaks BreakTimes(const NeedleTrain& train, double t_end) {
  Breaks out;
  for (double th : train.cam().Breaks()) {  // sorted
    const double t = train.Time(th);
    if (t > 0.0 && t < t_end) {
      out.times.push_back(t);
      out.angles.push_back(th);
    }
  }
  return out;
}

// The sign a witness value counts as: +1 above zero, −1 at or below it.
int SignOf(double v) { return v > 0.0 ? 1 : -1; }

EventSigns Signs(const EventValues& v) {
  EventSigns s(v.size());
  for (size_t i = 0; i < v.size(); ++i) s[i] = SignOf(v[i]);
  return s;
}

// The end of a run (docs/model.md §5), after a step ending at t: true when the run is over (at or
// past t_end with the needle at rest). The first time past t_end with the needle still moving,
// `horizon` moves from t_end to `t_limit` and `extended` is set.
bool RunIsOver(double t, const TrainState& x, const Phase& phase, const Recorder& recorder,
               double t_end, double t_limit, double& horizon, bool& extended) {
  extended = false;
  if (t < t_end) return false;
  if (recorder.AtRest(t, x, phase)) return true;
  if (horizon < t_limit) {
    horizon = t_limit;
    extended = true;
  }
  return false;
}

class EventDriver {
 public:
  EventDriver(Method method, const NeedleTrain& train, Recorder& recorder,
              const IntegratorOptions& o)
      : train_(train), recorder_(recorder), o_(o), system_(train, o) {
    stepper_ = MakeStepper(method, system_, o);
    stepper_->SetLongest([this](const ClosedFormPiece& piece, double t, double cap, double limit) {
      return LongestQuiet(piece, t, cap, limit);
    });
  }

  IntegrationStats Run(const TrainState& x0, double t_end);

 private:
  // The state at t from the backend's dense output.
  TrainState At(double t) {
    stepper_->CalcState(t, z_);
    return system_.FromScaled(z_);
  }
  // y and ẏ at t (W and D may be left out): for witnesses and samples.
  TrainState Motion(double t) {
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
  std::optional<double> Accumulate(bool cam, double t, double approach, double limit,
                                   TrainState& xs, EventSigns& signs);

  // Chattering ends in sticking when its remaining flights last less than this fraction of a
  // cam revolution (2π/ω).
  static constexpr double kAccumulationTime = 1e-6;
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
    const auto r = boost::math::tools::toms748_solve(
        [&](double at) { return Value(i, at); }, a, b, fa, fb,
        boost::math::tools::eps_tolerance<double>(52), iterations);
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
  std::optional<Bracket> Isolate(const ClosedFormPiece& piece, const LinearForm& form, int i, int s,
                                 const Bracket& in, int& budget);

  // Whether a jump episode has lasted at least o_.stop_jump_rad by t (closed ones, and the open
  // one up to t); false when that option is off. Episodes before jump_checked_ are done with.
  bool JumpReached(double t);

  // The ranges of what the record sees over [t0, t1] of a closed-form piece.
  StretchRanges Ranges(const ClosedFormPiece& piece, double t0, double t1) const;
  // The end of a closed-form piece from t past its cap, up to `limit` and the run's end t_end_:
  // the limit where the stretch cannot change the record (Recorder::MayChange), the cam input
  // is constant on it (a needle resting on its seat, or hanging in its play) and every witness's
  // range keeps its sign over it (no crossing, certified without halving), else the cap.
  double LongestQuiet(const ClosedFormPiece& piece, double t, double cap, double limit) const;

  // Samples a stretch (t0, t1) of a closed-form step at 16 points for the record, and where a
  // sample sets a new largest contact or seat force, or a new least contact force, locates that
  // extreme by Brent's method between the samples around it and records it there.
  void RecordExtremes(double t0, double t1);
  // The earliest time in [lo, hi] at which the needle is at rest (Recorder::AtRest), on the
  // step's dense output, or nullopt: 64 samples and the end, then bisection between the last
  // moving sample and the first at rest.
  std::optional<double> FirstRest(double lo, double hi, const Phase& phase);

  const NeedleTrain& train_;
  Recorder& recorder_;
  const IntegratorOptions& o_;
  TrainSystem system_;
  std::unique_ptr<Stepper> stepper_;
  TrainState z_{};
  size_t next_grid_ = 0;
  // The approach speed of the last impact of each rigid contact while it chatters (cam, seat).
  std::array<std::optional<double>, 2> last_approach_;
  size_t jump_checked_ = 0;  // episodes closed and shorter than o_.stop_jump_rad
  double t_end_ = 0.0;       // the run's window (pieces are not stretched past it)
  // While a certified search runs: the witness as a linear form on the piece (Value).
  const LinearForm* value_form_ = nullptr;
  const ClosedFormPiece* value_piece_ = nullptr;
  EventValues values_;  // ValuesAt's last answer, at values_t_ in the current step
  double values_t_ = 0.0;
  bool values_valid_ = false;
};

bool EventDriver::JumpReached(double t) {
  if (!(o_.stop_jump_rad > 0.0)) return false;
  const std::vector<Episode>& episodes = recorder_.episodes();
  for (; jump_checked_ < episodes.size(); ++jump_checked_) {
    const Episode& e = episodes[jump_checked_];
    const bool open = jump_checked_ + 1 == episodes.size() && recorder_.separated();
    const double end = open ? train_.Angle(t) : e.end_rad;
    if (e.kind == "jump" && end - e.start_rad >= o_.stop_jump_rad) return true;
    if (open) break;  // it may yet become a jump, or grow
  }
  return false;
}

std::optional<double> EventDriver::Accumulate(bool cam, double t, double approach, double limit,
                                              TrainState& xs, EventSigns& signs) {
  Phase& phase = system_.phase;
  std::optional<double>& last = last_approach_[cam ? 0 : 1];
  const bool stuck = cam ? phase.mode.cam : phase.mode.seat;
  const std::optional<double> before = last;
  last = stuck ? std::nullopt : std::optional<double>(approach);
  if (stuck || !before || !(approach > 0.0)) return std::nullopt;
  const Contacts c = train_.Evaluate(xs, t, phase);
  const double departure = -(cam ? c.g_c_rate : c.g_s_rate);  // e ġ⁻
  const double lambda = cam ? c.f_c_raw : c.f_s_raw;          // λ were it to stick
  const double e = departure / approach;
  if (!(e > 0.0 && e < 1.0 && lambda > 0.0)) return std::nullopt;
  if (std::abs(approach / *before - e) > 0.1 * e) return std::nullopt;  // not geometric
  const double m = train_.NeedleMassKg();
  const double remaining = 2.0 * departure / (lambda / m * (1.0 - e));
  if (!(remaining <= kAccumulationTime * 2.0 * kPi / train_.omega())) return std::nullopt;
  const double t_inf = std::min(t + remaining, limit);
  // The needle on the surface at t∞. The skipped flights are booked, not integrated: the
  // relative kinetic energy ½ m (e ġ⁻)² the series dissipates on D, and W takes the rest of the
  // change in E, so the audit closes across the jump.
  Phase stick = phase;
  (cam ? stick.mode.cam : stick.mode.seat) = true;
  TrainState xa = train_.Project(xs, t_inf, stick);
  const double lost = 0.5 * m * departure * departure;
  xa[3] = xs[3] + lost;
  xa[2] = xs[2] + train_.Energy(xa, t_inf) - train_.Energy(xs, t) + lost;
  xs = xa;
  signs = SettleMode(xs, t_inf);
  last.reset();
  recorder_.Accumulation(cam, t_inf, xs, phase, departure, lost);
  return t_inf;
}

std::optional<double> EventDriver::Certified(const ClosedFormPiece& piece, int i, int s, double a,
                                             double wa, double b, double wb) {
  if (!(b > a)) return std::nullopt;
  // Witnesses 5 and 6 are gated by y > 1 µm; on [a, b] (up to witness 4's crossing) the gate
  // is the one in the middle.
  const bool lifted = piece.Motion(0.5 * (a + b))[0] > kSeparationLift_m;
  const std::optional<LinearForm> form = WitnessForm(train_, system_.phase, i, lifted);
  if (!form) throw std::logic_error("exact: a witness without a linear form");
  int budget = kIsolationBudget;
  // Inside the search the witness is evaluated on the piece's own polynomials, where they agree
  // in sign with the train's own evaluation at both ends (they differ by round-off: a witness at
  // zero on a break, or just after a restart, is left to the train's).
  value_form_ = &*form;
  value_piece_ = &piece;
  struct Reset {
    EventDriver* d;
    ~Reset() { d->value_form_ = nullptr; }
  } reset{this};
  const std::optional<Bracket> bracket = Isolate(piece, *form, i, s, {a, wa, b, wb}, budget);
  if (!bracket) return std::nullopt;
  const double root = Refine(i, bracket->a, bracket->wa, bracket->b, bracket->wb);
  // The root must be past the crossing for the train's own evaluation too (the two differ by
  // round-off): else it is refined again on the train's.
  value_form_ = nullptr;
  if (SignOf(Value(i, root)) != s) return root;
  const double fa = Value(i, bracket->a), fb = Value(i, bracket->b);
  if (SignOf(fa) == s && SignOf(fb) != s) return Refine(i, bracket->a, fa, bracket->b, fb);
  return Refine(i, a, wa, b, wb);
}

// On [a, b], w(a) = wa of sign s and w(b) = wb: the earliest sub-interval [lo, hi] where w
// leaves sign s, holding exactly one crossing, or nullopt when w keeps sign s on [a, b]. With
// |w'| ≤ L₁ and |w''| ≤ L₂ on [a, b] (ClosedFormPiece::Bounds):
//   no crossing   when |w(a)| + |w(b)| > L₁ (b − a) (a root would need more slope), or when w is
//                 monotone (|w'(a)| > L₂ (b − a)) and keeps its sign at both ends;
//   one crossing  when w is monotone and changes sign;
//   otherwise the interval is halved, the left half first. Below the time's round-off, or past
//   kIsolationBudget halvings, an interval without a sign change at its ends counts as none (a
//   tangency, or a witness pinned at zero by round-off).
std::optional<EventDriver::Bracket> EventDriver::Isolate(const ClosedFormPiece& piece,
                                                         const LinearForm& form, int i, int s,
                                                         const Bracket& in, int& budget) {
  const bool change = SignOf(in.wb) != s;
  if (!change) {
    // The values' range over the whole interval: no crossing where it keeps sign s.
    const FormRange range = piece.Range(form, in.a, in.b);
    if (s > 0 ? range.lo > 0.0 : range.hi <= 0.0) return std::nullopt;
  }
  const FormBounds bounds = piece.Bounds(form, in.a, in.b);
  const double h = in.b - in.a;
  const bool monotone = std::abs(bounds.slope_at_start) > bounds.curvature_bound * h;
  if (!change && (monotone || std::abs(in.wa) + std::abs(in.wb) > bounds.slope_bound * h))
    return std::nullopt;
  if (change && monotone) return in;
  const double mid = in.a + 0.5 * h;
  // The time's round-off, or a witness that stays within its own round-off of zero (a needle
  // resting on its seat without load): the ends decide, as on the time steppers.
  if (--budget < 0 || !(mid > in.a && mid < in.b)) {
    return change ? std::optional<Bracket>(in) : std::nullopt;
  }
  const double wm = Value(i, mid);
  if (auto left = Isolate(piece, form, i, s, {in.a, in.wa, mid, wm}, budget)) return left;
  return Isolate(piece, form, i, s, {mid, wm, in.b, in.wb}, budget);
}

StretchRanges EventDriver::Ranges(const ClosedFormPiece& piece, double t0, double t1) const {
  const Phase& phase = system_.phase;
  StretchRanges r;
  const FormRange y = piece.Range(LinearForm{1.0, 0.0, 0.0, 0.0, 0.0}, t0, t1);
  r.y_lo = y.lo;
  r.y_hi = y.hi;
  r.u_hi = piece.Range(LinearForm{0.0, 0.0, 1.0, 0.0, 0.0}, t0, t1).hi;
  // The applied forces of linear laws: k g + c ġ in mode, with g_c = u − y, g_s = −y.
  if (phase.mode.cam) {
    const double k = train_.cam_law().ForceStiffness(), c = train_.cam_law().ForceDamping();
    const FormRange f = piece.Range(LinearForm{-k, -c, k, c, 0.0}, t0, t1);
    r.fc_lo = f.lo;
    r.fc_hi = f.hi;
  }
  if (phase.mode.seat) {
    const double k = train_.seat_law().ForceStiffness(), c = train_.seat_law().ForceDamping();
    r.fs_hi = piece.Range(LinearForm{-k, -c, 0.0, 0.0, 0.0}, t0, t1).hi;
  }
  return r;
}

double EventDriver::LongestQuiet(const ClosedFormPiece& piece, double t, double cap,
                                 double limit) const {
  const double end = std::min(limit, t_end_);
  if (!(end > cap) || !piece.InputConstant()) return cap;
  const StretchRanges ranges = Ranges(piece, t, end);
  if (recorder_.MayChange(ranges)) return cap;
  // Every witness's range over the whole stretch keeps the sign it has at t: the certified
  // search then ends at its first test, without halving a long interval.
  const bool lifted = ranges.y_lo > kSeparationLift_m;
  if (lifted != (ranges.y_hi > kSeparationLift_m)) return cap;  // the gate may change
  const EventValues now = Events(train_, system_.phase, piece.State(t), t);
  for (int i = 0; i < static_cast<int>(now.size()); ++i) {
    const std::optional<LinearForm> form = WitnessForm(train_, system_.phase, i, lifted);
    if (!form) return cap;
    const FormRange range = piece.Range(*form, t, end);
    if (!(SignOf(now[i]) > 0 ? range.lo > 0.0 : range.hi <= 0.0)) return cap;
  }
  return end;
}

void EventDriver::RecordExtremes(double t0, double t1) {
  constexpr int n = 16;
  const Phase& phase = system_.phase;
  // Nothing recorded can change inside the stretch: its interior samples are left out.
  if (!recorder_.MayChange(Ranges(*stepper_->ClosedForm(), t0, t1))) return;
  const double max_fc = recorder_.max_contact_force_N(), max_fs = recorder_.max_seat_force_N();
  const double min_fc = recorder_.min_contact_force_during_lift_N();
  // The three forces at x, each signed so that its extreme is a minimum.
  const auto forces = [&](double t, const TrainState& x) {
    const Contacts c = train_.Evaluate(x, t, phase);
    const double fc = train_.AppliedCamForce(c, phase);
    return std::array<double, 3>{-fc, -train_.AppliedSeatForce(c, phase), fc};
  };
  std::array<double, n + 1> ts;
  std::array<std::array<double, n + 1>, 3> f;
  for (int k = 0; k <= n; ++k) {
    ts[k] = t0 + (t1 - t0) * k / n;
    const TrainState x = Motion(ts[k]);
    const Contacts c = train_.Evaluate(x, ts[k], phase);
    const double fc = train_.AppliedCamForce(c, phase);
    f[0][k] = -fc;
    f[1][k] = -train_.AppliedSeatForce(c, phase);
    f[2][k] = fc;
    if (k > 0 && k < n) recorder_.Sample(ts[k], x, phase, c);
  }
  const std::array<double, 3> record = {-max_fc, -max_fs, min_fc};
  for (int which = 0; which < 3; ++which) {
    const auto& v = f[which];
    const int k = static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
    // Only a new record inside the step, and for the least contact force one while pushing.
    if (k == 0 || k == n || !(v[k] < record[which])) continue;
    if (which == 2 && !(v[k] > 0.0)) continue;
    std::uintmax_t iterations = 60;
    // In the fraction of the bracket: Brent's tolerance has an absolute part.
    const double base = ts[k - 1], width = ts[k + 1] - ts[k - 1];
    const auto at = [&](double d) { return base + d * width; };
    const auto best = boost::math::tools::brent_find_minima(
        [&](double d) { return forces(at(d), Motion(at(d)))[which]; }, 0.0, 1.0,
        std::numeric_limits<double>::digits / 2, iterations);
    recorder_.Sample(at(best.first), Motion(at(best.first)), phase);
  }
}

std::optional<double> EventDriver::FirstRest(double lo, double hi, const Phase& phase) {
  if (!(hi > lo))
    return recorder_.AtRest(hi, At(hi), phase) ? std::optional<double>(hi) : std::nullopt;
  constexpr int kSamples = 64;
  double moving = lo;
  for (int k = 0; k <= kSamples; ++k) {
    const double tk = lo + (hi - lo) * k / kSamples;
    if (!recorder_.AtRest(tk, At(tk), phase)) {
      moving = tk;
      continue;
    }
    if (k == 0) return tk;
    double a = moving, b = tk;  // moving at a, at rest at b
    for (int i = 0; i < 60 && b - a > 1e-12 * (1.0 + std::abs(b)); ++i) {
      const double m = 0.5 * (a + b);
      (recorder_.AtRest(m, At(m), phase) ? b : a) = m;
    }
    return b;
  }
  return std::nullopt;
}

IntegrationStats EventDriver::Run(const TrainState& x0, double t_end) {
  IntegrationStats stats;
  t_end_ = t_end;
  const auto started = std::chrono::steady_clock::now();
  Phase& phase = system_.phase;
  const double t_limit = t_end + o_.settle_limit_s;
  const Breaks all_breaks = BreakTimes(train_, t_limit);
  const std::vector<double>& breaks = all_breaks.times;
  const std::vector<double>& grid = recorder_.grid_times();
  size_t next_break = 0;
  double horizon = t_end;  // t_limit once the run goes on to let the needle settle

  TrainState x = x0, xs;
  EventSigns signs = SettleMode(x, 0.0);
  recorder_.Start(0.0, x, phase);
  while (next_grid_ < grid.size() && grid[next_grid_] <= 0.0)
    recorder_.GridSample(grid[next_grid_++], x, phase);

  // First step: a small fraction of the fastest contact period; the backend adapts.
  double t = 0.0;
  Restart(x, t, std::min(t_end, 0.01 / train_.FastestAngularFrequency()));

  while (t < horizon) {
    while (next_break < breaks.size() && breaks[next_break] <= t) ++next_break;
    const double segment_end =
        next_break < breaks.size() ? std::min(breaks[next_break], horizon) : horizon;
    phase.segment_end_rad = next_break < breaks.size() ? all_breaks.angles[next_break]
                                                       : std::numeric_limits<double>::infinity();
    stepper_->LimitTo(segment_end);
    const auto step = stepper_->DoStep();
    values_valid_ = false;  // a new dense output (and a new phase after a switch)
    if (++stats.steps > o_.max_steps) ThrowOverBudget("steps", o_.max_steps, train_, step.first);
    // The wall clock, every 64 steps (a clock read costs ~20 ns; a step ~100 ns or more).
    if (o_.max_seconds > 0.0 && stats.steps % 64 == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() >
            o_.max_seconds) {
      ThrowOverBudget("seconds", o_.max_seconds, train_, step.first);
    }
    const double t0 = step.first;
    double t1 = step.second;
    recorder_.Commit(t0);  // nothing is recorded before the step any more
    const bool at_segment_end = t1 >= segment_end - 1e-14 * std::max(1.0, std::abs(segment_end));
    if (at_segment_end) t1 = segment_end;

    // Witness crossings, earliest first. A function has crossed when it leaves its stored sign
    // inside the step: on the time steppers, seen at the step's end and bracketed by the last
    // of 16 samples that keeps the stored sign; on the closed form, certified (Certified).
    double restart = -1.0;
    double from = t0;
    const TrainState x_end = system_.FromScaled(stepper_->CurrentState());
    const ClosedFormPiece* piece = stepper_->ClosedForm();
    while (true) {
      int first = -1;
      double first_t = t1;
      const EventValues end_values = Events(train_, phase, x_end, step.second);
      // The values at `from`, taken once, and only when a witness is searched.
      std::optional<EventValues> from_values;
      double gate_end = t1;  // 5 and 6 are gated by witness 4: searched up to its crossing
      for (int i = 0; i < static_cast<int>(end_values.size()); ++i) {
        if (!piece && SignOf(end_values[i]) == signs[i]) continue;
        if (!from_values) from_values = Events(train_, phase, Motion(from), from);
        std::optional<double> root;
        if (SignOf((*from_values)[i]) != signs[i]) {
          root = from;  // roundoff at a restart: the function is already past zero
        } else if (piece) {
          // The closed form's step ends at t1 itself (no snapping): its end values serve. Only
          // a crossing before the earliest found so far matters: the search ends there.
          const double b = std::min((i == 5 || i == 6) ? gate_end : t1, first_t);
          root = Certified(*piece, i, signs[i], from, (*from_values)[i], b,
                           b == step.second ? end_values[i] : Value(i, b));
          if (root && first >= 0 && !(*root < first_t)) root.reset();
        } else {
          root = Sampled(i, signs[i], from, (*from_values)[i], t1, step.second);
        }
        if (i == 4 && root) gate_end = *root;
        if (root && (first < 0 || *root < first_t)) {
          first = i;
          first_t = *root;
        }
      }
      if (first < 0) break;
      if (++stats.events > o_.max_events) ThrowOverBudget("events", o_.max_events, train_, first_t);
      if (piece) RecordExtremes(from, first_t);  // the closed form: the stretch before it
      GridUpTo(first_t);
      signs[first] = -signs[first];
      xs = At(first_t);
      const ContactMode was = phase.mode;
      // An impact (the gap witness of a contact crossing upward); on a rigid contact the mode
      // waits for the reset map (the approach is read in the mode before it).
      const bool impact = (first == kCamGap || first == kSeatGap) && signs[first] > 0;
      const bool cam = first == kCamGap;
      const bool rigid_impact = impact && (cam ? train_.cam_law() : train_.seat_law()).Constraint();
      const ContactMode next = rigid_impact ? was : ModeFromSigns(train_, signs);
      bool switched = next != phase.mode;
      if (switched) {
        phase.mode = next;
        values_valid_ = false;
        signs[5] = SignOf(Events(train_, phase, xs, first_t)[5]);  // depends on the mode
        // A rigid contact lets go: the needle leaves its surface from on it (integration
        // drift removed), and the other contact settles against the new state.
        const bool released = (train_.cam_law().Constraint() && was.cam && !next.cam) ||
                              (train_.seat_law().Constraint() && was.seat && !next.seat);
        if (released) {
          Phase on = phase;
          on.mode = was;
          xs = train_.Project(xs, first_t, on);
          signs = SettleMode(xs, first_t);
        }
      }
      recorder_.Crossing(first, signs[first], first_t, xs, phase, !rigid_impact);
      restart = first_t;
      // An impact under a law with a reset map.
      if (impact) {
        // A rigid impact's approach speed, for the chattering test after the reset.
        double approach = 0.0;
        if (rigid_impact) {
          const Contacts before = train_.Evaluate(xs, first_t, phase);
          approach = cam ? before.g_c_rate : before.g_s_rate;
        }
        if (auto after = train_.Reset(cam, xs, first_t, phase)) {
          ++stats.resets;
          recorder_.ImpactLoss((*after)[3] - xs[3]);
          xs = *after;
          signs = SettleMode(xs, first_t);
          switched = true;
          if (rigid_impact) {
            if (auto t_inf = Accumulate(cam, first_t, approach, segment_end, xs, signs)) {
              ++stats.accumulations;
              restart = *t_inf;
            }
          }
        }
      }
      // The closed form restarts at every event: its audit quadrature then never spans the kink
      // of a contact's potential ½k(g⁺)² where a gap crosses zero without a mode switch.
      if (switched || piece) break;
      restart = -1.0;
      from = first_t;
    }
    if (restart >= 0.0) {
      t = restart;
      x = xs;
      Restart(x, t, std::max(stepper_->CurrentStep(), 1e-3 * (t1 - t0)));
      continue;
    }
    GridUpTo(t1);
    // A few dense samples for the extremes, then the step end; the closed form's steps are
    // long, and the largest forces inside them are located instead.
    if (piece) {
      RecordExtremes(from, t1);
    } else {
      for (int k = 1; k <= 3; ++k) {
        const double tk = t0 + (t1 - t0) * k / 4.0;
        recorder_.Sample(tk, At(tk), phase);
      }
    }
    t = t1;
    x = x_end;
    recorder_.Sample(t, x, phase);
    if (JumpReached(t)) {
      stats.stopped_at_jump = true;
      break;
    }
    if (o_.stop_after_lift && train_.Angle(t) > train_.cam().law().end_rad() &&
        !recorder_.separated()) {
      stats.stopped_after_lift = true;
      break;
    }
    bool extended;  // the horizon moved past t_end: the backend restarts as past a break
    if (t >= t_end) {
      // The run ends where the needle came to rest, wherever in the step that was (a step of
      // the closed form may span many oscillations of a needle ringing down on its seat).
      if (const std::optional<double> rest = FirstRest(std::max(t0, t_end), t1, phase)) {
        t = *rest;
        x = At(t);
        break;
      }
    }
    if (RunIsOver(t, x, phase, recorder_, t_end, t_limit, horizon, extended)) break;
    if (at_segment_end && t < horizon && train_.HasConstraint() &&
        train_.cam().SlopeMayJump(phase.segment_end_rad)) {
      // A rigid contact sticking across a break where the cam's slope may jump: the needle on
      // the surface as it arrives (from the left), the mode settled against the surface beyond,
      // so that the jump is an impact (the surface turns into the needle) or a release (it
      // drops away).
      x = train_.Project(x, t, phase);
      while (next_break < breaks.size() && breaks[next_break] <= t) ++next_break;
      phase.segment_end_rad = next_break < breaks.size() ? all_breaks.angles[next_break]
                                                         : std::numeric_limits<double>::infinity();
      signs = SettleMode(x, t);
    }
    if ((at_segment_end || extended) && t < horizon)
      Restart(x, t, stepper_->CurrentStep());  // past the break
  }
  recorder_.Finish(t, x, phase);
  phase.segment_end_rad = std::numeric_limits<double>::infinity();
  stats.rhs_evaluations = system_.evaluations();
  stats.final_state = x;
  stats.final_time = t;
  stats.final_phase = phase;
  return stats;
}

}  // namespace

std::optional<std::string> RigidRefusal(Method method, const NeedleTrain& train) {
  if (!train.HasConstraint()) return std::nullopt;
  return MethodRigidRefusal(method);  // the method table says which methods take one
}

IntegrationStats Integrate(Method method, const NeedleTrain& train, const TrainState& x0,
                           double t_end, Recorder& recorder, const IntegratorOptions& options) {
  options.Validate();
  if (const std::optional<std::string> why = RigidRefusal(method, train)) {
    throw std::invalid_argument(*why);
  }
  if (method == Method::kBaselineDopri5) {
    return IntegrateBaseline(train, x0, t_end, recorder, options);
  }
  EventDriver driver(method, train, recorder, options);
  return driver.Run(x0, t_end);
}

}  // namespace needle
