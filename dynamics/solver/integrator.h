#pragma once
/// @file
/// The integration of a NeedleTrain with events: one event driver (dynamics/solver/
/// event_driver.cc, after Drake's Simulator) owns the contact mode, the witness functions and
/// their location, reset maps, the cam input's breaks, the budgets, the recording and the end
/// of the run; the integrator backends only step, evaluate their dense output and restart
/// (dynamics/solver/stepper.h). Backends, one row each in the method table (methods.cc):
///
///   dopri5       Boost.Odeint Dormand–Prince 5(4), dense output (4th-order extension)
///   rkf78        Boost.Odeint Fehlberg 7(8); states inside a step recomputed by one 7(8) step
///   rosenbrock4  Boost.Odeint Rosenbrock 4 (stiff), analytic Jacobian, dense output
///   cvode-bdf    SUNDIALS CVODE, BDF, dense linear solver with the analytic Jacobian; its
///                Hermite interpolant (CVodeGetDky) is the dense output
///   cvode-adams  the same with Adams–Moulton (non-stiff)
///   exact        the motion in closed form on every piece between breaks and events
///                (dynamics/solver/closed_form.h): exact to round-off, for linear contact laws
///   baseline-dopri5  Dormand–Prince with F = max(0, F) inside the right-hand side, no events,
///                no breaks: the baseline event location is measured against (benchmarks)
///
/// Events are located by the driver on every backend alike: a witness whose sign at a step's
/// end differs from its stored sign is bracketed by 16 samples of the dense output and refined
/// by TOMS 748 to machine precision; at a mode switch (or a reset) the backend restarts there.
/// On the closed form of "exact" the driver also certifies the rest: every witness is bounded
/// on the step (|w'|, |w''|) and the step is split until each part is proved free of crossings
/// or holds exactly one, so a pair of crossings inside one step is found too; only a tangency
/// (a root of even multiplicity, or two roots closer than the time's round-off) is passed.

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/model/needle_train.h"
#include "dynamics/solver/contact_events.h"

namespace needle {

enum class Method {
  kDopri5,
  kRkf78,
  kRosenbrock4,
  kCvodeBdf,
  kCvodeAdams,
  kExact,
  kBaselineDopri5
};

/// Every method, in the method table's order.
const std::vector<Method>& AllMethods();
/// "dopri5", "rkf78", "rosenbrock4", "cvode-bdf", "cvode-adams", "exact", "baseline-dopri5".
std::string MethodName(Method m);
std::optional<Method> ParseMethod(const std::string& name);
/// "auto, dopri5, rkf78, …" for messages.
std::string MethodList();
/// Why `name` names no method: "unknown method \"foo\"; expected auto, dopri5, … or
/// baseline-dopri5"; empty for "auto" and each method's name. The one rule of every place a
/// method is read (--method, Simulate, Python's method=, whose messages are this one; [solver]
/// method, which words it as the case file's keys are: "expected one of …; got \"foo\"").
std::string MethodNameFault(const std::string& name);
/// Why method `m` does not take a rigid contact, from the method table, or nullopt when it does.
std::optional<std::string> MethodRigidRefusal(Method m);
/// Whether `m` solves each contact mode in closed form (the event driver then certifies its
/// crossings), from the method table; else it is a time stepper.
bool MethodIsClosedForm(Method m);
/// Whether `m` is a backend of the event driver (its witnesses, reset maps and budgets); the
/// baseline gates compliant forces in a loop of its own.
bool MethodIsEventDriven(Method m);

/// The trains `auto` tells apart (dynamics/simulation.h AutoMethod).
enum class AutoCase {
  kRigid,     ///< a rigid contact: restarts at full order after every impact
  kNonStiff,  ///< not linear in every mode, ≤ kStiffOscillations contact oscillations an event
  kStiff,     ///< not linear in every mode, more
  kLinear,    ///< linear in every contact mode
};
/// The method the method table gives `auto` for trains of kind `c`.
Method AutoMethodFor(AutoCase c);

/// Why method "exact" cannot solve `train` (a contact law not linear in the gap and its rate, a
/// coil chain that may clash or has no spring rate), or nullopt when it can. A chain whose modes
/// are at or near critical damping is refused when the run starts (ChainModes).
std::optional<std::string> ExactRefusal(const NeedleTrain& train);
/// ExactRefusal, and for a coil chain its modes made in the four contact modes
/// (ChainModes::Shared: kept for the thread's runs): the reason where one is refused (at or
/// near critical damping). What `auto` asks before it takes "exact"; a time stepper then.
std::optional<std::string> ExactRefusalWithModes(const NeedleTrain& train);

/// The relative tolerance's range, [kMinRtol, kMaxRtol].
constexpr double kMinRtol = 1e-14;
constexpr double kMaxRtol = 1e-2;
/// "[1e-14, 1e-2]": the range as messages print it (both ends are powers of ten).
std::string RtolRangeText();
/// The default absolute tolerance on the lift is this fraction of rtol, m.
constexpr double kAtolPerRtol_m = 1e-3;

/// Options of one integration. Every field has a default; Validate() checks them.
struct IntegratorOptions {
  double rtol = 1e-8;     ///< relative tolerance, [kMinRtol, kMaxRtol]
  double atol_m = 1e-11;  ///< absolute tolerance on the lift y, m, > 0
  /// Absolute tolerance on the velocity ẏ, m/s, > 0; 0: the number atol_m (the default).
  double atol_m_s = 0.0;
  /// Absolute tolerance on the audit integrals W and D, J, > 0; 0: the number atol_m.
  double atol_J = 0.0;
  long max_steps = 2000000;  ///< step budget; exceeding it stops the run (BudgetExceeded)
  long max_events = 100000;  ///< event budget (located witness crossings)
  /// Wall-time budget of one run, s: exceeding it stops the run (BudgetExceeded, status
  /// `budget`), so no run computes for minutes in silence; 0: none. ≥ 0 and finite.
  double max_seconds = 60.0;
  /// Past t_end the run goes on until the recorder finds the needle at rest
  /// (Recorder::AtRest), for at most this long, s (docs/model.md §5); 0: stop at t_end. ≥ 0.
  double settle_limit_s = 0.0;
  /// The run stops at the end of the first step where a jump episode (Recorder) has lasted at
  /// least this much crank angle, rad: a run that asks only whether the needle lifts off
  /// (SimulationOptions::stop_at_liftoff). 0: never (the default); ≥ 0 and finite.
  double stop_jump_rad = 0.0;
  /// The run also stops at the end of the first step past the lift law's end θ_N with the needle
  /// not separated: no episode can begin after it, so its lift-off verdict and its least contact
  /// force over the lift are final. For one-window runs only (a revolution that carries its end
  /// state on must run to its end).
  bool stop_after_lift = false;
  /// Integrate the energy audit's W and D (docs/model.md §6). Method "exact" does not integrate
  /// them when false (only a reset map's loss is still added to D), and the run's energy
  /// residual is not computed: a run that answers only whether the needle lifts off reports
  /// none. The time steppers always integrate them (they are states of their error control).
  bool audit_energy = true;
  /// Method "exact" leaves out the work that cannot change its result (docs/exact.md): samples
  /// that cannot move a record or repeat one it holds, rest tests on a needle whose energy shows
  /// it moving. False: all of it is done, for the tests that compare the two bit for bit.
  bool leave_out = true;
  /// Throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
  /// Per-state absolute tolerances (y, ẏ, W, D) with the defaults filled in.
  std::array<double, 4> AbsoluteTolerances() const;
};

/// The default absolute tolerance on the lift for a relative tolerance, m.
inline double DefaultAtol(double rtol) { return rtol * kAtolPerRtol_m; }

struct IntegrationStats {
  long steps = 0;            ///< accepted steps
  long rhs_evaluations = 0;  ///< right-hand-side evaluations
  long events = 0;           ///< located events (mode switches and observations)
  long resets = 0;           ///< reset maps applied (impacts of a restitution law)
  /// Chattering resolved (docs/model.md §4): accumulation points of rigid impacts the driver
  /// stepped to, the needle sticking there.
  long accumulations = 0;
  TrainState final_state{};
  double final_time = 0.0;
  Phase final_phase{};  ///< the contact mode at the end
  /// The run stopped at a jump of IntegratorOptions::stop_jump_rad (final_time is there).
  bool stopped_at_jump = false;
  /// The run stopped past the lift without a jump (IntegratorOptions::stop_after_lift).
  bool stopped_after_lift = false;

  /// Records how the run ended: at time `t` (s) in state `x` and contact mode `phase`, after
  /// `evaluations` right-hand sides. The one place both drivers end a run.
  void End(double t, const TrainState& x, const Phase& phase, long evaluations) {
    final_time = t;
    final_state = x;
    final_phase = phase;
    rhs_evaluations = evaluations;
  }
};

/// A step or event budget ran out: the run stopped at `crank_rad`. The message names the angle
/// and what to do; the recorder holds the run up to there.
struct BudgetExceeded : std::runtime_error {
  BudgetExceeded(const std::string& message, double crank, const IntegrationStats& done)
      : std::runtime_error(message), crank_rad(crank), stats(done) {}
  double crank_rad;
  IntegrationStats stats;  ///< the work done up to the stop (steps, events, evaluations)
};

/// Why `method` cannot integrate `train` with a rigid contact (docs/model.md §4), or nullopt:
/// the closed form (ExactRefusal), the no-event baseline and the CVODE methods refuse it.
std::optional<std::string> RigidRefusal(Method method, const NeedleTrain& train);

/// Integrates `train` from `x0` over [0, t_end], then on while the needle is not at rest, up
/// to t_end + settle_limit_s. Throws BudgetExceeded when a budget is exceeded.
IntegrationStats Integrate(Method method, const NeedleTrain& train, const TrainState& x0,
                           double t_end, Recorder& recorder, const IntegratorOptions& options);

}  // namespace needle
