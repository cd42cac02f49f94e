#pragma once
/// @file
/// The integrators behind one interface. Each integrates a NeedleTrain from its static
/// equilibrium over [0, t_end] with event location, stepping exactly to every break of the
/// cam input, and feeds a Recorder:
///
///   kDopri5   Boost.Odeint Dormand–Prince 5(4), dense output; events located by TOMS 748 on
///             the dense output to machine precision, integration restarted there
///   kCvodeBdf SUNDIALS CVODE, BDF with a dense linear solver; CVodeRootInit rootfinding and
///             CVodeReInit after each switch; CVodeSetStopTime at every break
///   kCvodeAdams  the same with Adams–Moulton (non-stiff)

#include <optional>
#include <stdexcept>
#include <string>

#include "dynamics/contact_events.h"

namespace needle {

enum class Method { kDopri5, kRkf78, kRosenbrock4, kCvodeBdf, kCvodeAdams, kBaselineDopri5 };

/// "dopri5", "rkf78", "rosenbrock4", "cvode-bdf", "cvode-adams", "baseline-dopri5".
std::string MethodName(Method m);
std::optional<Method> ParseMethod(const std::string& name);
/// "auto, dopri5, rkf78, …" for messages.
std::string MethodList();

/// Options of one integration. Every field has a default; Validate() checks them.
struct IntegratorOptions {
  double rtol = 1e-8;        ///< relative tolerance, 1e-14 … 1e-2
  double atol_m = 1e-11;     ///< absolute tolerance on the states (lift scale), > 0
  long max_steps = 2000000;  ///< step budget; exceeding it throws with a message
  long max_events = 100000;  ///< event budget (mode switches); exceeding it throws
  /// Past t_end the run goes on until the recorder finds the needle at rest
  /// (Recorder::AtRest), for at most this long, s (model.md §5); 0: stop at t_end. ≥ 0.
  double settle_limit_s = 0.0;
  void Validate() const;
};

struct IntegrationStats {
  long steps = 0;            ///< accepted steps
  long rhs_evaluations = 0;  ///< right-hand-side evaluations
  long events = 0;           ///< located events (mode switches and observations)
  TrainState final_state{};
  double final_time = 0.0;
};

/// A step or event budget ran out: the run stopped at `crank_rad`. The message names the angle
/// and what to do; the recorder holds the run up to there.
struct BudgetExceeded : std::runtime_error {
  BudgetExceeded(const std::string& message, double crank)
      : std::runtime_error(message), crank_rad(crank) {}
  double crank_rad;
};

/// Integrates `train` from `x0` over [0, t_end], then on while the needle is not at rest, up
/// to t_end + settle_limit_s. Throws BudgetExceeded when a budget is exceeded.
IntegrationStats Integrate(Method method, NeedleTrain& train, const TrainState& x0, double t_end,
                           Recorder& recorder, const IntegratorOptions& options);

IntegrationStats IntegrateDopri5(NeedleTrain& train, const TrainState& x0, double t_end,
                                 Recorder& recorder, const IntegratorOptions& options);
/// Dopri5, Rkf78 or Rosenbrock4 with event location.
IntegrationStats IntegrateOdeint(Method method, NeedleTrain& train, const TrainState& x0,
                                 double t_end, Recorder& recorder,
                                 const IntegratorOptions& options);
/// Dormand–Prince with max(0, …) inside the right-hand side, no events, no breaks: the
/// baseline the event location is measured against. Reports grid samples and step ends.
IntegrationStats IntegrateBaseline(NeedleTrain& train, const TrainState& x0, double t_end,
                                   Recorder& recorder, const IntegratorOptions& options);
IntegrationStats IntegrateCvode(bool bdf, NeedleTrain& train, const TrainState& x0, double t_end,
                                Recorder& recorder, const IntegratorOptions& options);

/// The cam input's breaks strictly inside (0, t_end), sorted: times (s from θ_a) and the
/// exact break angles (rad) they stand for.
struct Breaks {
  std::vector<double> times, angles;
};
Breaks BreakTimes(const NeedleTrain& train, double t_end);

/// The end of a run (model.md §5), as both integrators apply it after a step ending at t: true
/// when the run is over (at or past t_end with the needle at rest). The first time past t_end
/// with the needle still moving, it moves `horizon` from t_end to `t_limit` and sets `extended`.
bool RunIsOver(double t, const TrainState& x, const Recorder& recorder, double t_end,
               double t_limit, double& horizon, bool& extended);

/// Signs of the event functions (v > 0 → +1, else −1).
std::array<int, kEventCount> Signs(const EventValues& v);

/// Throws the budget message (shared by the integrators).
[[noreturn]] void ThrowOverBudget(const std::string& what, long budget, const NeedleTrain& train,
                                  double t);

}  // namespace needle
