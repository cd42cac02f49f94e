// Boost.Odeint integrators with event location on their dense output. Inside every step the
// contact mode is fixed, so the right-hand side is smooth; a step in which a mode function
// changes sign is cut at its root (bracketed by 16 samples of the dense output, refined by
// TOMS 748 to machine precision) and integration restarts there in the new mode. Steps are
// shortened to end exactly on every break of the cam input.
//
//   Dormand–Prince 5(4)   odeint's dense output (4th-order continuous extension)
//   Rosenbrock 4          odeint's rosenbrock4_dense_output, analytic Jacobian (stiff)
//   Fehlberg 7(8)         no dense output in odeint: states inside a step are recomputed by
//                         one 7(8) step from its start (exact to the method's order)
//   baseline              Dormand–Prince with F = max(0, k g + c ġ) inside the right-hand side
//                         and no event location (integrate_times on the dense output)
// GCC 12 reports -Wmaybe-uninitialized inside Boost.Odeint's own copy constructor of the
// Fehlberg stepper (its scratch buffers are sized on first use); a false positive there.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "dynamics/integrator.h"
#include "lib/units.h"

namespace needle {

namespace odeint = boost::numeric::odeint;
namespace ublas = boost::numeric::ublas;

std::string MethodName(Method m) {
  switch (m) {
    case Method::kDopri5:
      return "dopri5";
    case Method::kRkf78:
      return "rkf78";
    case Method::kRosenbrock4:
      return "rosenbrock4";
    case Method::kCvodeBdf:
      return "cvode-bdf";
    case Method::kCvodeAdams:
      return "cvode-adams";
    case Method::kBaselineDopri5:
      return "baseline-dopri5";
  }
  return "?";
}

std::optional<Method> ParseMethod(const std::string& name) {
  for (Method m : {Method::kDopri5, Method::kRkf78, Method::kRosenbrock4, Method::kCvodeBdf,
                   Method::kCvodeAdams, Method::kBaselineDopri5}) {
    if (MethodName(m) == name) return m;
  }
  return std::nullopt;
}

std::string MethodList() {
  return "auto, dopri5, rkf78, rosenbrock4, cvode-bdf, cvode-adams or baseline-dopri5";
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
  if (!(settle_limit_s >= 0.0) || !std::isfinite(settle_limit_s))
    throw std::invalid_argument("IntegratorOptions.settle_limit_s must be finite and ≥ 0");
}

std::array<int, kEventCount> Signs(const EventValues& v) {
  std::array<int, kEventCount> s{};
  for (int i = 0; i < kEventCount; ++i) s[i] = v[i] > 0.0 ? 1 : -1;
  return s;
}

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

bool RunIsOver(double t, const TrainState& x, const Recorder& recorder, double t_end,
               double t_limit, double& horizon, bool& extended) {
  extended = false;
  if (t < t_end) return false;
  if (recorder.AtRest(t, x)) return true;
  if (horizon < t_limit) {
    horizon = t_limit;
    extended = true;
  }
  return false;
}

void ThrowOverBudget(const std::string& what, long budget, const NeedleTrain& train, double t) {
  throw BudgetExceeded("simulation stopped at " + std::to_string(train.Angle(t) / kDeg) +
                           " deg after " + std::to_string(budget) + " " + what +
                           " (the budget [solver] max_" + what +
                           "): the scene may chatter or be too stiff for this method; try "
                           "method = \"cvode-bdf\", a looser rtol, or raise max_" +
                           what,
                       train.Angle(t));
}

IntegrationStats Integrate(Method method, NeedleTrain& train, const TrainState& x0, double t_end,
                           Recorder& recorder, const IntegratorOptions& options) {
  switch (method) {
    case Method::kDopri5:
    case Method::kRkf78:
    case Method::kRosenbrock4:
      return IntegrateOdeint(method, train, x0, t_end, recorder, options);
    case Method::kCvodeBdf:
      return IntegrateCvode(true, train, x0, t_end, recorder, options);
    case Method::kCvodeAdams:
      return IntegrateCvode(false, train, x0, t_end, recorder, options);
    case Method::kBaselineDopri5:
      return IntegrateBaseline(train, x0, t_end, recorder, options);
  }
  throw std::logic_error("Integrate: unknown method");
}

namespace {

// ---- Dense steppers behind one small interface (TrainState in and out) ----

class Dopri5Dense {
 public:
  Dopri5Dense(NeedleTrain& train, const IntegratorOptions& o)
      : train_(train),
        dense_(odeint::make_dense_output(o.atol_m, o.rtol,
                                         odeint::runge_kutta_dopri5<TrainState>())) {}
  void Initialize(const TrainState& x, double t, double dt) { dense_.initialize(x, t, dt); }
  std::pair<double, double> DoStep() { return dense_.do_step(std::ref(train_)); }
  void CalcState(double t, TrainState& x) { dense_.calc_state(t, x); }
  TrainState CurrentState() const { return dense_.current_state(); }
  double CurrentTime() const { return dense_.current_time(); }
  double CurrentStep() const { return dense_.current_time_step(); }

 private:
  NeedleTrain& train_;
  odeint::result_of::make_dense_output<odeint::runge_kutta_dopri5<TrainState>>::type dense_;
};

class Rkf78Dense {
 public:
  Rkf78Dense(NeedleTrain& train, const IntegratorOptions& o)
      : train_(train),
        controlled_(odeint::make_controlled(o.atol_m, o.rtol,
                                            odeint::runge_kutta_fehlberg78<TrainState>())) {}
  void Initialize(const TrainState& x, double t, double dt) {
    x1_ = x;
    t1_ = t;
    dt_ = dt;
  }
  std::pair<double, double> DoStep() {
    x0_ = x1_;
    t0_ = t1_;
    TrainState x = x1_;
    double t = t1_;
    int tries = 0;
    while (controlled_.try_step(std::ref(train_), x, t, dt_) == odeint::fail) {
      if (++tries > 500) throw std::runtime_error("rkf78: step size underflow");
    }
    x1_ = x;
    t1_ = t;
    return {t0_, t1_};
  }
  // One 7(8) step from the start of the last step: exact to the method's order.
  void CalcState(double t, TrainState& x) {
    if (t == t1_) {
      x = x1_;
      return;
    }
    if (t == t0_) {
      x = x0_;
      return;
    }
    TrainState in = x0_;
    controlled_.stepper().do_step(std::ref(train_), in, t0_, x, t - t0_);
  }
  TrainState CurrentState() const { return x1_; }
  double CurrentTime() const { return t1_; }
  double CurrentStep() const { return dt_; }

 private:
  NeedleTrain& train_;
  odeint::result_of::make_controlled<odeint::runge_kutta_fehlberg78<TrainState>>::type controlled_;
  TrainState x0_{}, x1_{};
  double t0_ = 0.0, t1_ = 0.0, dt_ = 0.0;
};

// Boost 1.74's rosenbrock4 loses order on non-autonomous systems: with the exact ∂f/∂t its
// embedded error estimate of a forced oscillator scales as h² instead of h⁴ (measured), and
// the controller then creeps at tiny steps. The standard cure is applied: time is carried as
// a fifth state τ (τ' = 1), the system is autonomous, and ∂f/∂t becomes the Jacobian's last
// column.
class Rosenbrock4Dense {
 public:
  using Vector = ublas::vector<double>;
  using Matrix = ublas::matrix<double>;
  Rosenbrock4Dense(NeedleTrain& train, const IntegratorOptions& o)
      : train_(train),
        dense_(odeint::make_dense_output(o.atol_m, o.rtol, odeint::rosenbrock4<double>())),
        v_(5) {}
  void Initialize(const TrainState& x, double t, double dt) {
    for (int i = 0; i < 4; ++i) v_(i) = x[i];
    v_(4) = t;  // τ
    dense_.initialize(v_, t, dt);
  }
  std::pair<double, double> DoStep() {
    NeedleTrain& train = train_;
    auto system = [&train](const Vector& x, Vector& dxdt, double /*t*/) {
      TrainState a{x(0), x(1), x(2), x(3)}, d;
      train(a, d, x(4));
      for (int i = 0; i < 4; ++i) dxdt(i) = d[i];
      dxdt(4) = 1.0;  // τ' = 1
    };
    auto jacobian = [&train](const Vector& x, Matrix& J, double /*t*/, Vector& dfdt) {
      TrainState a{x(0), x(1), x(2), x(3)}, ft;
      std::array<double, 16> j;
      train.Jacobian(a, x(4), j, ft);
      for (int r = 0; r < 5; ++r) {
        dfdt(r) = 0.0;  // autonomous
        for (int c = 0; c < 5; ++c) J(r, c) = 0.0;
      }
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) J(r, c) = j[r * 4 + c];
        J(r, 4) = ft[r];  // ∂f/∂τ
      }
    };
    return dense_.do_step(std::make_pair(system, jacobian));
  }

  void CalcState(double t, TrainState& x) {
    dense_.calc_state(t, v_);
    for (int i = 0; i < 4; ++i) x[i] = v_(i);
  }
  TrainState CurrentState() const {
    const Vector& v = dense_.current_state();
    return {v(0), v(1), v(2), v(3)};
  }
  double CurrentTime() const { return dense_.current_time(); }
  double CurrentStep() const { return dense_.current_time_step(); }

 private:
  NeedleTrain& train_;
  odeint::result_of::make_dense_output<odeint::rosenbrock4<double>>::type dense_;
  Vector v_;
};

// ---- The event loop, shared by the dense steppers ----

template <class Dense>
IntegrationStats RunWithEvents(Dense& dense, NeedleTrain& train, const TrainState& x0, double t_end,
                               Recorder& recorder, const IntegratorOptions& o) {
  IntegrationStats stats;
  const long rhs_before = train.evaluations();
  const double t_limit = t_end + o.settle_limit_s;
  const Breaks all_breaks = BreakTimes(train, t_limit);
  const std::vector<double>& breaks = all_breaks.times;
  const std::vector<double>& grid = recorder.grid_times();
  size_t next_break = 0, next_grid = 0;
  double horizon = t_end;  // t_limit once the run goes on to let the needle settle

  std::array<int, kEventCount> signs = Signs(Events(train, train.mode(), x0, 0.0));
  ContactMode mode = ModeFromSigns(signs);
  train.set_mode(mode);
  signs = Signs(Events(train, mode, x0, 0.0));  // event 5 depends on the mode
  recorder.Start(0.0, x0);
  while (next_grid < grid.size() && grid[next_grid] <= 0.0)
    recorder.GridSample(grid[next_grid++], x0);

  // First step: a small fraction of the fastest contact period; the stepper adapts.
  const TrainParameters& p = train.parameters();
  const double fastest =
      std::sqrt((p.contact_stiffness_N_m + p.seat_stiffness_N_m + p.rate_N_m) / p.mass_kg);
  double t = 0.0;
  TrainState x = x0, xs;
  dense.Initialize(x, t, std::min(t_end, 0.01 / fastest));

  while (t < horizon) {
    while (next_break < breaks.size() && breaks[next_break] <= t) ++next_break;
    const double segment_end =
        next_break < breaks.size() ? std::min(breaks[next_break], horizon) : horizon;
    train.set_segment_end(next_break < breaks.size() ? all_breaks.angles[next_break]
                                                     : std::numeric_limits<double>::infinity());
    if (dense.CurrentTime() + dense.CurrentStep() > segment_end) {
      dense.Initialize(dense.CurrentState(), dense.CurrentTime(),
                       segment_end - dense.CurrentTime());
    }
    const auto step = dense.DoStep();
    if (++stats.steps > o.max_steps) ThrowOverBudget("steps", o.max_steps, train, step.first);
    const double t0 = step.first;
    double t1 = step.second;
    const bool at_segment_end = t1 >= segment_end - 1e-14 * std::max(1.0, std::abs(segment_end));
    if (at_segment_end) t1 = segment_end;

    // Events, earliest first. A function has crossed when its sign at the step end differs
    // from its stored sign; the bracket is the last of 16 samples that keeps the stored sign.
    auto value = [&](int i, double at) {
      dense.CalcState(at, xs);
      return Events(train, mode, xs, at)[i];
    };
    double restart = -1.0;
    double from = t0;
    const TrainState x_end = dense.CurrentState();
    while (true) {
      const EventValues end_values = Events(train, mode, x_end, step.second);
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
      if (++stats.events > o.max_events) ThrowOverBudget("events", o.max_events, train, first_t);
      while (next_grid < grid.size() && grid[next_grid] <= first_t) {
        dense.CalcState(grid[next_grid], xs);
        recorder.GridSample(grid[next_grid++], xs);
      }
      signs[first] = -signs[first];
      dense.CalcState(first_t, xs);
      const ContactMode next = ModeFromSigns(signs);
      const bool switched = next.cam != mode.cam || next.seat != mode.seat;
      if (switched) {
        mode = next;
        train.set_mode(mode);
        signs[5] = Events(train, mode, xs, first_t)[5] > 0.0 ? 1 : -1;  // depends on the mode
      }
      recorder.Crossing(first, signs[first], first_t, xs);
      if (switched) {
        restart = first_t;
        break;
      }
      from = first_t;
    }
    if (restart >= 0.0) {
      t = restart;
      x = xs;
      dense.Initialize(x, t, std::max(dense.CurrentStep(), 1e-3 * (t1 - t0)));
      continue;
    }
    while (next_grid < grid.size() && grid[next_grid] <= t1) {
      dense.CalcState(grid[next_grid], xs);
      recorder.GridSample(grid[next_grid++], xs);
    }
    // A few dense samples for the extremes, then the step end.
    for (int k = 1; k <= 3; ++k) {
      const double tk = t0 + (t1 - t0) * k / 4.0;
      dense.CalcState(tk, xs);
      recorder.Sample(tk, xs);
    }
    t = t1;
    x = x_end;
    recorder.Sample(t, x);
    bool extended;  // the horizon moved past t_end: the stepper restarts as past a break
    if (RunIsOver(t, x, recorder, t_end, t_limit, horizon, extended)) break;
    if ((at_segment_end || extended) && t < horizon)
      dense.Initialize(x, t, dense.CurrentStep());  // past the break
  }
  recorder.Finish(t, x);
  train.set_segment_end(std::numeric_limits<double>::infinity());
  stats.rhs_evaluations = train.evaluations() - rhs_before;
  stats.final_state = x;
  stats.final_time = t;
  return stats;
}

}  // namespace

IntegrationStats IntegrateOdeint(Method method, NeedleTrain& train, const TrainState& x0,
                                 double t_end, Recorder& recorder, const IntegratorOptions& o) {
  o.Validate();
  train.set_gated(false);
  switch (method) {
    case Method::kDopri5: {
      Dopri5Dense dense(train, o);
      return RunWithEvents(dense, train, x0, t_end, recorder, o);
    }
    case Method::kRkf78: {
      Rkf78Dense dense(train, o);
      return RunWithEvents(dense, train, x0, t_end, recorder, o);
    }
    case Method::kRosenbrock4: {
      Rosenbrock4Dense dense(train, o);
      return RunWithEvents(dense, train, x0, t_end, recorder, o);
    }
    default:
      throw std::logic_error("IntegrateOdeint: not an Odeint method");
  }
}

IntegrationStats IntegrateDopri5(NeedleTrain& train, const TrainState& x0, double t_end,
                                 Recorder& recorder, const IntegratorOptions& o) {
  return IntegrateOdeint(Method::kDopri5, train, x0, t_end, recorder, o);
}

IntegrationStats IntegrateBaseline(NeedleTrain& train, const TrainState& x0, double t_end,
                                   Recorder& recorder, const IntegratorOptions& o) {
  o.Validate();
  IntegrationStats stats;
  const long rhs_before = train.evaluations();
  train.set_gated(true);
  recorder.Start(0.0, x0);
  // Output times: the grid, or else 400 points; the integrator does not stop at breaks or
  // switches: that is what the baseline is for.
  std::vector<double> times = recorder.grid_times();
  if (times.empty()) {
    for (int i = 0; i <= 400; ++i) times.push_back(t_end * i / 400.0);
  }
  if (times.front() > 0.0) times.insert(times.begin(), 0.0);
  if (times.back() < t_end) times.push_back(t_end);
  const std::vector<double>& grid = recorder.grid_times();
  size_t next_grid = 0;
  TrainState x = x0, last = x0;
  double last_t = 0.0;
  const auto observer = [&](const TrainState& s, double t) {
    while (next_grid < grid.size() && grid[next_grid] <= t + 1e-15)
      recorder.GridSample(grid[next_grid++], s);
    recorder.Sample(t, s);
    last = s;
    last_t = t;
  };
  auto dense =
      odeint::make_dense_output(o.atol_m, o.rtol, odeint::runge_kutta_dopri5<TrainState>());
  const TrainParameters& p = train.parameters();
  const double fastest =
      std::sqrt((p.contact_stiffness_N_m + p.seat_stiffness_N_m + p.rate_N_m) / p.mass_kg);
  stats.steps = static_cast<long>(
      odeint::integrate_times(dense, std::ref(train), x, times.begin(), times.end(),
                              std::min(t_end, 0.01 / fastest), observer));
  if (stats.steps > o.max_steps) ThrowOverBudget("steps", o.max_steps, train, t_end);
  recorder.Finish(last_t, last);
  train.set_gated(false);
  stats.rhs_evaluations = train.evaluations() - rhs_before;
  stats.final_state = last;
  stats.final_time = last_t;
  return stats;
}

}  // namespace needle
