#pragma once
/// @file
/// Internal to the solver: what the event driver asks of an integrator backend, and the
/// right-hand side it hands them. A backend steps, evaluates its dense output inside the last
/// step and restarts; it knows nothing of events, modes, breaks or budgets.
///
/// Per-state absolute tolerances: backends integrate scaled states z_i = x_i / s_i with
/// s_i = atol_i / atol_m, so one scalar absolute tolerance atol_m on z is atol_i on x_i
/// (s = 1 for every state by default, and then z = x exactly).

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <utility>

#include "dynamics/model/needle_train.h"
#include "dynamics/solver/closed_form.h"
#include "dynamics/solver/integrator.h"

namespace needle {

/// The train's right-hand side in the driver's current phase, on scaled states. The driver
/// changes `phase` at mode switches and breaks; backends call it.
class TrainSystem {
 public:
  TrainSystem(const NeedleTrain& train, const IntegratorOptions& options);
  void operator()(const TrainState& z, TrainState& dzdt, double t) const;
  /// ∂f/∂z and ∂f/∂t on scaled states (not gated).
  void Jacobian(const TrainState& z, double t, TrainJacobian& dfdz, TrainState& dfdt) const;
  TrainState ToScaled(const TrainState& x) const;
  TrainState FromScaled(const TrainState& z) const;
  /// The same into `x` (a state kept between calls: no temporary).
  void FromScaled(const TrainState& z, TrainState& x) const;
  /// State i's value as FromScaled(ToScaled(x)) gives it back (the same bits, without the
  /// states around it).
  double RoundTrip(int i, double x) const { return scaled_ ? (x / scale_[i]) * scale_[i] : x; }
  const NeedleTrain& train() const { return train_; }
  long evaluations() const { return evaluations_; }
  /// The contacts the last right-hand side computed, when it was evaluated at (x, t) in the
  /// current phase to the bit (an FSAL method's last stage is its step's end), else nullptr.
  /// Valid until the next right-hand side (a backend's CalcState may evaluate one).
  const Contacts* LastContacts(const TrainState& x, double t) const;

  Phase phase;

 private:
  const NeedleTrain& train_;
  TrainState scale_;  // s_i, the coils' lifts as y's and their velocities as ẏ's
  bool scaled_;
  mutable long evaluations_ = 0;
  // The last evaluation's state (unscaled), time, phase and contacts.
  mutable TrainState last_x_;
  mutable double last_t_ = std::numeric_limits<double>::quiet_NaN();
  mutable Phase last_phase_;
  mutable Contacts last_contacts_;
};

/// One integrator backend.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// (Re)starts at (t, z) with a first step of about dt (a backend may choose its own).
  virtual void Initialize(const TrainState& z, double t, double dt) = 0;
  /// The next step ends at or before t_stop.
  virtual void LimitTo(double t_stop) = 0;
  /// One accepted step: its start and end times.
  virtual std::pair<double, double> DoStep() = 0;
  /// The dense output at t inside the last step.
  virtual void CalcState(double t, TrainState& z) = 0;
  /// The same for y and ẏ only, where W and D are not needed (witnesses, samples); a backend
  /// whose audit integrals cost extra leaves them at any value.
  virtual void CalcMotion(double t, TrainState& z) { CalcState(t, z); }
  virtual TrainState CurrentState() const = 0;
  virtual double CurrentTime() const = 0;
  virtual double CurrentStep() const = 0;
  /// Method "exact": `longest(piece, t, cap, limit)` gives the end of a piece that starts at t,
  /// between its cap (half an oscillation) and the limit (LimitTo); the time steppers ignore it.
  virtual void SetLongest(std::function<double(const ClosedFormPiece&, double, double, double)>) {}
  /// The last step's motion in closed form (method "exact"), whose bounds let the driver
  /// certify that no witness crossing is missed; nullptr for the time steppers.
  virtual const ClosedFormPiece* ClosedForm() const { return nullptr; }
};

/// A backend's factory: methods.cc's table names each, and each backend's file declares its own
/// with this type (`MakeBackend MakeDopri5;`) before defining it, so that the definition is
/// checked against the table's signature. `system` outlives the stepper.
using MakeBackend = std::unique_ptr<Stepper>(TrainSystem& system, const IntegratorOptions& o);

/// The backend of a method from the method table (methods.cc); nullptr for the baseline.
std::unique_ptr<Stepper> MakeStepper(Method m, TrainSystem& system, const IntegratorOptions& o);

/// The no-event baseline (baseline_integrator.cc) of method `method` (its name in budget
/// messages): not a backend of the driver. Integrate() validates the options before calling it.
IntegrationStats IntegrateBaseline(Method method, const NeedleTrain& train, const TrainState& x0,
                                   double t_end, Recorder& recorder,
                                   const IntegratorOptions& options);

/// Throws the budget message, with the work done up to t; its advice names another method
/// than `method`, the one that ran.
[[noreturn]] void ThrowOverBudget(const std::string& what, double budget, const NeedleTrain& train,
                                  double t, const IntegrationStats& done, Method method);

}  // namespace needle
