// The event driver's run (event_driver.h): steps, crossings and their events, reset maps,
// accumulation, the run's end where the needle rests; and Integrate, which runs it.
#include "dynamics/solver/event_driver.h"

#include <algorithm>
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

}  // namespace

namespace internal {

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

bool EventDriver::AtTouchFloor(double approach, double e, double pressing) const {
  // A flight from the surface (g = 0) that lands where the witness fires (g = −δ, δ the touch
  // tolerance) gains ½(ġ⁻² − (e ġ⁻)²) = a δ: its impacts settle at this speed instead of
  // shrinking by e, and never form the geometric series below.
  const double floor = std::sqrt(2.0 * pressing * train_.GapTolerance() / (1.0 - e * e));
  return approach <= kTouchFloorFactor * floor;
}

std::optional<double> EventDriver::Accumulate(bool cam, double t, double approach, double limit,
                                              TrainState& xs, EventSigns& signs) {
  Phase& phase = system_.phase;
  std::optional<double>& last = last_approach_[cam ? 0 : 1];
  const bool stuck = cam ? phase.mode.cam : phase.mode.seat;
  const std::optional<double> before = last;
  last = stuck ? std::nullopt : std::optional<double>(approach);
  if (stuck || !(approach > 0.0)) return std::nullopt;
  const Contacts c = train_.Evaluate(xs, t, phase);
  const double departure = -(cam ? c.g_c_rate : c.g_s_rate);  // e ġ⁻
  const double lambda = cam ? c.f_c_raw : c.f_s_raw;          // λ were it to stick
  const double e = departure / approach;
  if (!(e > 0.0 && e < 1.0 && lambda > 0.0)) return std::nullopt;
  const double m = train_.NeedleMassKg();
  const bool geometric = before && std::abs(approach / *before - e) <= 0.1 * e;
  if (!geometric && !AtTouchFloor(approach, e, lambda / m)) return std::nullopt;
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

bool EventDriver::StrikeAtCorner(double t, TrainState& x) {
  const Phase& phase = system_.phase;  // its segment ends at t: u and u' are the near side's
  if (!train_.cam_law().Constraint() || phase.mode.cam) return false;
  const Contacts c = train_.Evaluate(x, t, phase);
  if (!(std::abs(c.g_c) <= train_.GapTolerance() && c.g_c_rate > 0.0)) return false;
  recorder_.Crossing(kCamGap, +1, t, x, phase, false);
  const std::optional<TrainState> after = train_.Reset(true, x, t, phase);
  if (!after) return false;
  recorder_.ImpactLoss((*after)[3] - x[3]);
  x = *after;
  SettleMode(x, t);  // the seat lets go of the struck needle; a plastic impact sticks
  return true;
}

// Rest asks for y and ẏ only (Motion: the closed form skips its energy integrals W and D).
std::optional<double> EventDriver::FirstRest(double lo, double hi, const Phase& phase) {
  if (const ClosedFormPiece* piece = stepper_->ClosedForm()) {
    // The closed form under a constant forcing: the net force on the needle is −(K h + c h′)
    // and its speed h′, so rest (|h′| ≤ v_r, |K h + c h′| ≤ F_r) needs the homogeneous energy
    // H = ½ m h′² + ½ K h² ≤ ½ m v_r² + ½ (F_r + c v_r)²/K. H never grows: above four times
    // that at hi, no time up to hi is at rest, and none is sampled.
    const double K = piece->stiffness(), c = piece->damping(), m = piece->mass();
    // (One mass only: a chain's needle trades energy with its coils.)
    if (o_.leave_out && !phase.gated && !piece->Chain() && K > 0.0 && piece->ForcingConstant()) {
      const double f = recorder_.RestForceTolerance() + c * kRestSpeed_m_s;
      const double rest_energy = 0.5 * m * kRestSpeed_m_s * kRestSpeed_m_s + 0.5 * f * f / K;
      if (piece->HomogeneousEnergy(hi) > 4.0 * rest_energy) return std::nullopt;
    }
  }
  // At rest at t (Recorder::AtRest); a chain's closed form reads the needle's speed first, in
  // O(modes), and its whole state only where that may be at rest.
  const ClosedFormPiece* piece = stepper_->ClosedForm();
  const bool chain = piece && piece->Chain();
  const auto at_rest = [&](double t) {
    if (chain && !(std::abs(ForceState(t)[1]) <= kRestSpeed_m_s)) return false;
    return recorder_.AtRest(t, Motion(t), phase);
  };
  if (!(hi > lo)) return at_rest(hi) ? std::optional<double>(hi) : std::nullopt;
  // The closed form under a constant forcing and input, by its rate bounds (one mass too: a new
  // user's engine ended 2° after every tight time stepper, its 64 samples passing the rest).
  if (piece && piece->ForcingConstant() && piece->InputConstant() &&
      (chain || piece->stiffness() > 0.0)) {
    if (const std::optional<double> rest = FirstClosedFormRest(*piece, lo, hi, phase)) return rest;
    if (lo > hi) return std::nullopt;  // no time in [lo, hi] at rest
  }
  constexpr int kSamples = 64;
  double moving = lo;
  for (int k = 0; k <= kSamples; ++k) {
    const double tk = lo + (hi - lo) * k / kSamples;
    if (!at_rest(tk)) {
      moving = tk;
      continue;
    }
    return k == 0 ? tk : RestOnset(moving, tk, phase);
  }
  return std::nullopt;
}

double EventDriver::RestOnset(double moving, double rest, const Phase& phase) {
  const auto at_rest = [&](double t) { return recorder_.AtRest(t, Motion(t), phase); };
  for (int i = 0; i < 60 && rest - moving > 1e-12 * (1.0 + std::abs(rest)); ++i) {
    const double mid = 0.5 * (moving + rest);
    (at_rest(mid) ? rest : moving) = mid;
  }
  return rest;
}

std::optional<double> EventDriver::FirstClosedFormRest(const ClosedFormPiece& piece, double& lo,
                                                       double hi, const Phase& phase) {
  // |ẏ| and the net force |m ÿ| change no faster than B₂ and m B₃ (constant forcing: the modal
  // sums' alone; one mass: H = ½ m h′² + ½ K h² never grows, so |h″| ≤ (K |h|max + c |h′|max)/m
  // = B₂ and |h‴| ≤ (K |h′|max + c B₂)/m = B₃ from t on). From t, where |ẏ| exceeds v_r by d_v or
  // |m ÿ| exceeds F_r by d_F, no time before t + max(d_v / B₂, d_F / (m B₃)) is at rest.
  const double m = train_.NeedleMassKg(), f_r = recorder_.RestForceTolerance();
  const auto bounds = [&](double t) -> std::array<double, 2> {
    if (piece.Chain()) return piece.ChainNeedleRateBounds();
    const double K = piece.stiffness(), c = piece.damping(), H = piece.HomogeneousEnergy(t);
    const double h = std::sqrt(2.0 * H / K), v = std::sqrt(2.0 * H / m);
    const double b2 = (K * h + c * v) / m;
    return {b2, (K * v + c * b2) / m};
  };
  constexpr double kNever = std::numeric_limits<double>::infinity();
  if (!phase.mode.cam && !phase.mode.seat) {  // in flight on the whole piece: nothing pushes
    lo = kNever;
    return std::nullopt;
  }
  // A window narrower than 1e-7 of the fastest half oscillation may pass (a needle skimming the
  // box's edge would take steps without end). Inside the box but not at rest (at its edge, where
  // AtRest's own state and net force differ from Motion's by round-off), the same least step.
  const double least = 1e-7 * std::min(piece.LongestStep(), hi - lo);
  constexpr int kMaxSteps = 20000;  // then the sampled search from where this stopped
  double moving = lo;               // the last time known not at rest
  for (int k = 0; k < kMaxSteps && lo <= hi; ++k) {
    const std::array<double, 3> yva = piece.Motion(lo);
    const double d_v = std::abs(yva[1]) - kRestSpeed_m_s, d_f = m * std::abs(yva[2]) - f_r;
    if (!(d_v > 0.0 || d_f > 0.0)) {
      // The step that reached it may have passed its start: bisected back, as the samples are.
      if (recorder_.AtRest(lo, Motion(lo), phase))
        return k == 0 ? lo : RestOnset(moving, lo, phase);
      moving = lo;
      lo += least;
      continue;
    }
    moving = lo;
    const auto [b2, b3] = bounds(lo);
    const double wait_v = d_v > 0.0 ? d_v / b2 : 0.0, wait_f = d_f > 0.0 ? d_f / (m * b3) : 0.0;
    if (std::isnan(wait_v) || std::isnan(wait_f)) return std::nullopt;  // the samples from lo
    if (wait_v == kNever || wait_f == kNever) {  // B = 0: that one never comes down
      lo = kNever;
      return std::nullopt;
    }
    lo += std::max({wait_v, wait_f, least});
  }
  return std::nullopt;
}

std::pair<int, double> EventDriver::EarliestCrossing(const ClosedFormPiece* piece,
                                                     const EventSigns& signs, double from,
                                                     double t1, std::pair<double, double> step,
                                                     const TrainState& x_end) {
  const Phase& phase = system_.phase;
  int first = -1;
  double first_t = t1;
  const EventValues end_values = Events(train_, phase, x_end, EndContacts(x_end, step.second));
  // The values at `from`, taken once, and only when a witness is searched.
  std::optional<EventValues> from_values;
  double gate_end = t1;  // 5 and 6 are gated by witness 4: searched up to its crossing
  for (int i = 0; i < static_cast<int>(end_values.size()); ++i) {
    if (!piece && SignOf(end_values[i]) == signs[i]) continue;
    if (!from_values) from_values = Events(train_, phase, Motion(from), from);
    std::optional<double> root;
    if (SignOf((*from_values)[i]) != signs[i]) {
      root = from;  // roundoff at a restart: the function is already past zero
    } else if (piece && o_.leave_out && (i == 5 || i == 6) && !((*from_values)[kLiftGate] > 0.0)) {
      // 5 and 6 observe a lifted needle only: from a needle below the separation lift up
      // to witness 4's crossing (gate_end, the end of their search) they are +1 (Events),
      // so they cannot cross inside it. (A search would find the gate's opening itself at
      // gate_end, which is no earlier than the earliest crossing: some 40 halvings to the
      // time's round-off for nothing.)
      root.reset();
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
  return {first, first_t};
}

bool EventDriver::Cross(int first, double first_t, double segment_end, TrainState& xs,
                        EventSigns& signs, double& restart, IntegrationStats& stats) {
  Phase& phase = system_.phase;
  signs[first] = -signs[first];
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
  return switched;
}

void EventDriver::CrossSlopeJump(double t, const std::vector<double>& break_times,
                                 const std::vector<double>& break_angles, size_t& next_break,
                                 TrainState& x, EventSigns& signs, IntegrationStats& stats) {
  Phase& phase = system_.phase;
  if (StrikeAtCorner(t, x)) {
    ++stats.events;
    ++stats.resets;
  }
  x = train_.Project(x, t, phase);
  while (next_break < break_times.size() && break_times[next_break] <= t) ++next_break;
  phase.segment_end_rad = next_break < break_times.size() ? break_angles[next_break]
                                                          : std::numeric_limits<double>::infinity();
  signs = SettleMode(x, t);
}

void EventDriver::OverBudget(const char* what, double budget, double at, IntegrationStats& stats) {
  stats.rhs_evaluations = system_.evaluations();
  ThrowOverBudget(what, budget, train_, at, stats, method_);
}

void EventDriver::CountStep(double at, std::chrono::steady_clock::time_point started,
                            IntegrationStats& stats) {
  if (stats.steps >= o_.max_steps) OverBudget("steps", o_.max_steps, at, stats);
  ++stats.steps;
  // The wall clock, every 64 steps (a clock read costs ~20 ns; a step ~100 ns or more).
  if (o_.max_seconds > 0.0 && stats.steps % 64 == 0 &&
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() -
              recorder_.sink_seconds() >
          o_.max_seconds) {
    OverBudget("seconds", o_.max_seconds, at, stats);
  }
}

bool EventDriver::RecordStep(double t0, double t1, double from, const TrainState& x_end,
                             const EventSigns& signs, IntegrationStats& stats) {
  const Phase& phase = system_.phase;
  GridUpTo(t1);
  // A few dense samples for the extremes, then the step end; the closed form's steps are
  // long, and the largest forces inside them are located instead.
  if (stepper_->ClosedForm()) {
    RecordExtremes(from, t1, x_end[0], signs);  // x_end is recorded at t1 below
  } else {
    for (int k = 1; k <= 3; ++k) {
      const double tk = t0 + (t1 - t0) * k / 4.0;
      recorder_.Sample(tk, At(tk), phase);
    }
  }
  recorder_.Sample(t1, x_end, phase, EndContacts(x_end, t1));
  if (JumpReached(t1)) {
    stats.stopped_at_jump = true;
    return true;
  }
  if (o_.stop_after_lift && train_.Angle(t1) > train_.cam().law().end_rad() &&
      !recorder_.separated()) {
    stats.stopped_after_lift = true;
    return true;
  }
  return false;
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
    CountStep(step.first, started, stats);
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
      const auto [first, first_t] = EarliestCrossing(piece, signs, from, t1, step, x_end);
      if (first < 0) break;
      if (++stats.events > o_.max_events) OverBudget("events", o_.max_events, first_t, stats);
      xs = At(first_t);
      // The closed form: the stretch before it, whose end (xs) the crossing records below.
      if (piece) RecordExtremes(from, first_t, xs[0], signs);
      GridUpTo(first_t);
      const bool switched = Cross(first, first_t, segment_end, xs, signs, restart, stats);
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
    t = t1;
    x = x_end;
    if (RecordStep(t0, t1, from, x_end, signs, stats)) break;
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
      CrossSlopeJump(t, all_breaks.times, all_breaks.angles, next_break, x, signs, stats);
    }
    if ((at_segment_end || extended) && t < horizon)
      Restart(x, t, stepper_->CurrentStep());  // past the break
  }
  recorder_.Finish(t, x, phase);
  phase.segment_end_rad = std::numeric_limits<double>::infinity();
  stats.End(t, x, phase, system_.evaluations());
  return stats;
}

}  // namespace internal

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
  if (!MethodIsEventDriven(method)) {
    return IntegrateBaseline(method, train, x0, t_end, recorder, options);
  }
  internal::EventDriver driver(method, train, recorder, options);
  return driver.Run(x0, t_end);
}

}  // namespace needle
