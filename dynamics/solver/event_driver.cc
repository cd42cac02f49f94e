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
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

#include "dynamics/solver/stepper.h"

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

std::array<int, kEventCount> Signs(const EventValues& v) {
  std::array<int, kEventCount> s{};
  for (int i = 0; i < kEventCount; ++i) s[i] = v[i] > 0.0 ? 1 : -1;
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
  }

  IntegrationStats Run(const TrainState& x0, double t_end);

 private:
  // The state at t from the backend's dense output.
  TrainState At(double t) {
    stepper_->CalcState(t, z_);
    return system_.FromScaled(z_);
  }
  void Restart(const TrainState& x, double t, double dt) {
    stepper_->Initialize(system_.ToScaled(x), t, dt);
  }
  // At a state reached without integration (the start, a reset): the mode its witnesses
  // imply, and their signs in that mode (witness 5 depends on the mode).
  std::array<int, kEventCount> SettleMode(const TrainState& x, double t) {
    system_.phase.mode = ModeFromSigns(train_, Signs(Events(train_, system_.phase, x, t)));
    return Signs(Events(train_, system_.phase, x, t));
  }
  void GridUpTo(double t) {
    const std::vector<double>& grid = recorder_.grid_times();
    while (next_grid_ < grid.size() && grid[next_grid_] <= t) {
      recorder_.GridSample(grid[next_grid_], At(grid[next_grid_]), system_.phase);
      ++next_grid_;
    }
  }

  const NeedleTrain& train_;
  Recorder& recorder_;
  const IntegratorOptions& o_;
  TrainSystem system_;
  std::unique_ptr<Stepper> stepper_;
  TrainState z_{};
  size_t next_grid_ = 0;
};

IntegrationStats EventDriver::Run(const TrainState& x0, double t_end) {
  IntegrationStats stats;
  Phase& phase = system_.phase;
  const double t_limit = t_end + o_.settle_limit_s;
  const Breaks all_breaks = BreakTimes(train_, t_limit);
  const std::vector<double>& breaks = all_breaks.times;
  const std::vector<double>& grid = recorder_.grid_times();
  size_t next_break = 0;
  double horizon = t_end;  // t_limit once the run goes on to let the needle settle

  std::array<int, kEventCount> signs = SettleMode(x0, 0.0);
  recorder_.Start(0.0, x0, phase);
  while (next_grid_ < grid.size() && grid[next_grid_] <= 0.0)
    recorder_.GridSample(grid[next_grid_++], x0, phase);

  // First step: a small fraction of the fastest contact period; the backend adapts.
  double t = 0.0;
  TrainState x = x0, xs;
  Restart(x, t, std::min(t_end, 0.01 / train_.FastestAngularFrequency()));

  while (t < horizon) {
    while (next_break < breaks.size() && breaks[next_break] <= t) ++next_break;
    const double segment_end =
        next_break < breaks.size() ? std::min(breaks[next_break], horizon) : horizon;
    phase.segment_end_rad = next_break < breaks.size() ? all_breaks.angles[next_break]
                                                       : std::numeric_limits<double>::infinity();
    stepper_->LimitTo(segment_end);
    const auto step = stepper_->DoStep();
    if (++stats.steps > o_.max_steps) ThrowOverBudget("steps", o_.max_steps, train_, step.first);
    const double t0 = step.first;
    double t1 = step.second;
    const bool at_segment_end = t1 >= segment_end - 1e-14 * std::max(1.0, std::abs(segment_end));
    if (at_segment_end) t1 = segment_end;

    // Witness crossings, earliest first. A function has crossed when its sign at the step end
    // differs from its stored sign; the bracket is the last of 16 samples that keeps the
    // stored sign.
    auto value = [&](int i, double at) { return Events(train_, phase, At(at), at)[i]; };
    double restart = -1.0;
    double from = t0;
    const TrainState x_end = system_.FromScaled(stepper_->CurrentState());
    while (true) {
      const EventValues end_values = Events(train_, phase, x_end, step.second);
      int first = -1;
      double first_t = t1;
      for (int i = 0; i < kEventCount; ++i) {
        if ((end_values[i] > 0.0 ? 1 : -1) == signs[i]) continue;
        const int n = 16;
        double a = from, fa = value(i, from);
        double root = from;  // roundoff at a restart: the function is already past zero
        if ((fa > 0.0 ? 1 : -1) == signs[i]) {
          for (int k = 1; k <= n; ++k) {
            const double b = k == n ? step.second : from + (t1 - from) * k / n;
            const double fb = value(i, b);
            if ((fb > 0.0 ? 1 : -1) == signs[i]) {
              a = b;
              fa = fb;
              continue;
            }
            std::uintmax_t iterations = 100;
            const auto r = boost::math::tools::toms748_solve(
                [&](double at) { return value(i, at); }, a, b, fa, fb,
                boost::math::tools::eps_tolerance<double>(52), iterations);
            root = r.second;  // the side past the crossing
            break;
          }
        }
        if (first < 0 || root < first_t) {
          first = i;
          first_t = root;
        }
      }
      if (first < 0) break;
      if (++stats.events > o_.max_events) ThrowOverBudget("events", o_.max_events, train_, first_t);
      GridUpTo(first_t);
      signs[first] = -signs[first];
      xs = At(first_t);
      const ContactMode next = ModeFromSigns(train_, signs);
      bool switched = next.cam != phase.mode.cam || next.seat != phase.mode.seat;
      if (switched) {
        phase.mode = next;
        signs[5] = Events(train_, phase, xs, first_t)[5] > 0.0 ? 1 : -1;  // depends on the mode
      }
      recorder_.Crossing(first, signs[first], first_t, xs, phase);
      // An impact (the gap witness of a contact crossing upward) under a law with a reset map.
      if ((first == kCamGap || first == kSeatGap) && signs[first] > 0) {
        if (auto after = train_.Reset(first == kCamGap, xs, first_t, phase)) {
          ++stats.resets;
          xs = *after;
          signs = SettleMode(xs, first_t);
          switched = true;
        }
      }
      if (switched) {
        restart = first_t;
        break;
      }
      from = first_t;
    }
    if (restart >= 0.0) {
      t = restart;
      x = xs;
      Restart(x, t, std::max(stepper_->CurrentStep(), 1e-3 * (t1 - t0)));
      continue;
    }
    GridUpTo(t1);
    // A few dense samples for the extremes, then the step end.
    for (int k = 1; k <= 3; ++k) {
      const double tk = t0 + (t1 - t0) * k / 4.0;
      recorder_.Sample(tk, At(tk), phase);
    }
    t = t1;
    x = x_end;
    recorder_.Sample(t, x, phase);
    bool extended;  // the horizon moved past t_end: the backend restarts as past a break
    if (RunIsOver(t, x, phase, recorder_, t_end, t_limit, horizon, extended)) break;
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

IntegrationStats Integrate(Method method, const NeedleTrain& train, const TrainState& x0,
                           double t_end, Recorder& recorder, const IntegratorOptions& options) {
  options.Validate();
  if (method == Method::kBaselineDopri5) {
    return IntegrateBaseline(train, x0, t_end, recorder, options);
  }
  EventDriver driver(method, train, recorder, options);
  return driver.Run(x0, t_end);
}

}  // namespace needle
