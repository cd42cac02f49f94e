// Dormand–Prince 5(4) with dense output (Boost.Odeint) and event location on the dense
// output. Inside every step the contact mode is fixed, so the right-hand side is smooth; a
// step in which a mode function changes sign is cut at its root (TOMS 748 on the dense
// output, to machine precision) and integration restarts there in the new mode. Steps are
// shortened to end exactly on every break of the cam input.
#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "dynamics/integrator.h"
#include "lib/units.h"

namespace needle {

namespace odeint = boost::numeric::odeint;

std::string MethodName(Method m) {
  switch (m) {
    case Method::kDopri5:
      return "dopri5";
    case Method::kCvodeBdf:
      return "cvode-bdf";
    case Method::kCvodeAdams:
      return "cvode-adams";
  }
  return "?";
}

void IntegratorOptions::Validate() const {
  if (!(rtol >= 1e-14 && rtol <= 1e-2)) {
    throw std::invalid_argument("IntegratorOptions.rtol = " + std::to_string(rtol) +
                                ": must be in [1e-14, 1e-2]");
  }
  if (!(atol_m > 0.0)) throw std::invalid_argument("IntegratorOptions.atol_m must be positive");
  if (max_steps < 1) throw std::invalid_argument("IntegratorOptions.max_steps must be at least 1");
  if (max_events < 1)
    throw std::invalid_argument("IntegratorOptions.max_events must be at least 1");
}

std::array<int, kEventCount> Signs(const EventValues& v) {
  std::array<int, kEventCount> s{};
  for (int i = 0; i < kEventCount; ++i) s[i] = v[i] > 0.0 ? 1 : -1;
  return s;
}

std::vector<double> BreakTimes(const NeedleTrain& train, double t_end) {
  std::vector<double> out;
  for (double th : train.cam().Breaks()) {
    const double t = train.Time(th);
    if (t > 0.0 && t < t_end) out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

IntegrationStats Integrate(Method method, NeedleTrain& train, const TrainState& x0, double t_end,
                           Recorder& recorder, const IntegratorOptions& options) {
  switch (method) {
    case Method::kDopri5:
      return IntegrateDopri5(train, x0, t_end, recorder, options);
    case Method::kCvodeBdf:
      return IntegrateCvode(true, train, x0, t_end, recorder, options);
    case Method::kCvodeAdams:
      return IntegrateCvode(false, train, x0, t_end, recorder, options);
  }
  throw std::logic_error("Integrate: unknown method");
}

namespace {

[[noreturn]] void OverBudget(const std::string& what, long budget, const NeedleTrain& train,
                             double t) {
  throw std::runtime_error("simulation stopped at " + std::to_string(train.Angle(t) / kDeg) +
                           " deg after " + std::to_string(budget) + " " + what +
                           " (the budget [solver] max_" + what +
                           "): the scene may chatter or be "
                           "too stiff for this method; try method = \"cvode-bdf\", a looser rtol, "
                           "or raise max_" +
                           what);
}

}  // namespace

IntegrationStats IntegrateDopri5(NeedleTrain& train, const TrainState& x0, double t_end,
                                 Recorder& recorder, const IntegratorOptions& o) {
  o.Validate();
  IntegrationStats stats;
  const long rhs_before = train.evaluations();
  const std::vector<double> breaks = BreakTimes(train, t_end);
  size_t next_break = 0;

  std::array<int, kEventCount> signs = Signs(Events(train, train.mode(), x0, 0.0));
  ContactMode mode = ModeFromSigns(signs);
  train.set_mode(mode);
  signs = Signs(Events(train, mode, x0, 0.0));  // event 5 depends on the mode
  recorder.Start(0.0, x0, mode);

  auto dense =
      odeint::make_dense_output(o.atol_m, o.rtol, odeint::runge_kutta_dopri5<TrainState>());
  // First step: a small fraction of the contact period, the stepper adapts from there.
  const TrainParameters& p = train.parameters();
  const double fastest =
      std::sqrt((p.contact_stiffness_N_m + p.seat_stiffness_N_m + p.rate_N_m) / p.mass_kg);
  double dt = std::min(t_end, 0.01 / fastest);
  double t = 0.0;
  TrainState x = x0;
  dense.initialize(x, t, dt);
  const auto system = std::ref(train);
  TrainState xs;

  while (t < t_end) {
    while (next_break < breaks.size() && breaks[next_break] <= t) ++next_break;
    const double segment_end = next_break < breaks.size() ? breaks[next_break] : t_end;
    if (dense.current_time() + dense.current_time_step() > segment_end) {
      dense.initialize(dense.current_state(), dense.current_time(),
                       segment_end - dense.current_time());
    }
    const auto step = dense.do_step(system);
    if (++stats.steps > o.max_steps) OverBudget("steps", o.max_steps, train, step.first);
    const double t0 = step.first;
    double t1 = step.second;
    const bool at_segment_end = t1 >= segment_end - 1e-14 * std::max(1.0, std::abs(segment_end));
    if (at_segment_end) t1 = segment_end;

    // Events: one at a time, earliest first. A function counts as crossed when its sign at
    // the step end differs from its stored sign; its root is bracketed by 16 samples of the
    // dense output and refined by TOMS 748. A mode switch cuts the step at the root.
    auto value = [&](int i, double at) {
      dense.calc_state(at, xs);
      return Events(train, mode, xs, at)[i];
    };
    double restart_time = -1.0;
    double from = t0;
    while (true) {
      const EventValues end_values = Events(train, mode, dense.current_state(), step.second);
      int first = -1;
      double first_t = t1;
      for (int i = 0; i < kEventCount; ++i) {
        if ((end_values[i] > 0.0 ? 1 : -1) == signs[i]) continue;
        const int n = 16;
        double a = from, fa = value(i, from);
        double root = from;  // roundoff at a restart: the function is already past zero
        if ((fa > 0.0 ? 1 : -1) == signs[i]) {
          for (int k = 1; k <= n; ++k) {
            const double b = k == n ? t1 : from + (t1 - from) * k / n;
            const double fb = k == n ? value(i, t1) : value(i, b);
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
      if (++stats.events > o.max_events) OverBudget("events", o.max_events, train, first_t);
      signs[first] = -signs[first];
      dense.calc_state(first_t, xs);
      const ContactMode next = ModeFromSigns(signs);
      recorder.Crossing(first, signs[first], first_t, xs, next);
      if (next.cam != mode.cam || next.seat != mode.seat) {
        mode = next;
        train.set_mode(mode);
        signs[5] =
            Events(train, mode, xs, first_t)[5] > 0.0 ? 1 : -1;  // event 5 depends on the mode
        restart_time = first_t;
        break;
      }
      from = first_t;
    }
    if (restart_time >= 0.0) {
      t = restart_time;
      x = xs;
      dense.initialize(x, t, std::max(dense.current_time_step(), 1e-3 * (t1 - t0)));
      continue;
    }
    // A few dense samples for the extremes, then the step end.
    for (int k = 1; k <= 3; ++k) {
      const double tk = t0 + (t1 - t0) * k / 4.0;
      dense.calc_state(tk, xs);
      recorder.Sample(tk, xs, mode);
    }
    t = t1;
    x = dense.current_state();
    recorder.Sample(t, x, mode);
    if (at_segment_end && t < t_end) {
      dense.initialize(x, t, dense.current_time_step());  // restart on the far side of the break
    }
  }
  recorder.Finish(t, x, mode);
  stats.rhs_evaluations = train.evaluations() - rhs_before;
  stats.final_state = x;
  stats.final_time = t;
  return stats;
}

}  // namespace needle
