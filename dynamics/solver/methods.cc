// The method table (one row per integrator backend), the integrator's options, and the
// scaled right-hand side the backends integrate.
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string>

#include "dynamics/solver/stepper.h"
#include "lib/field_error.h"
#include "lib/units.h"

namespace needle {

// The backends, each in its own file and named only here (a new integrator: its file, its
// enumerator in integrator.h, its factory here and one row below): odeint_steppers.cc,
// cvode_stepper.cc, and the closed-form propagator exact_stepper.cc (which throws
// std::invalid_argument with the reason when the train is outside the linear class).
MakeBackend MakeDopri5, MakeRkf78, MakeRosenbrock4, MakeCvodeBdf, MakeCvodeAdams, MakeExact;

namespace {

struct MethodRow {
  Method method;
  const char* name;
  MakeBackend* make;  ///< nullptr: not a backend of the event driver (the baseline)
  /// Why the method does not take a rigid contact (a train with a constraint), after
  /// `method "NAME" `; nullptr when it does.
  const char* rigid_refusal;
  /// Solves each contact mode's piece in closed form (the driver certifies its crossings and
  /// lets a quiet piece run long); false: a time stepper.
  bool closed_form;
  /// The trains `auto` gives it (AutoCase), none when auto never picks it.
  std::initializer_list<AutoCase> auto_for;
};

// Measured: restarted at every impact, CVODE's low-order start misplaces the short flights of a
// chattering sequence (1e-6 s where the one-step methods give 4e-11 s).
constexpr const char* kCvodeRigid =
    "restarts at first order after every impact and misplaces the short flights of a rigid "
    "contact; use dopri5, rkf78 or rosenbrock4";

const MethodRow kMethodTable[] = {
    {Method::kDopri5,
     "dopri5",
     MakeDopri5,
     nullptr,
     false,
     {AutoCase::kRigid, AutoCase::kNonStiff}},
    {Method::kRkf78, "rkf78", MakeRkf78, nullptr, false, {}},
    {Method::kRosenbrock4, "rosenbrock4", MakeRosenbrock4, nullptr, false, {}},
    {Method::kCvodeBdf, "cvode-bdf", MakeCvodeBdf, kCvodeRigid, false, {AutoCase::kStiff}},
    {Method::kCvodeAdams, "cvode-adams", MakeCvodeAdams, kCvodeRigid, false, {}},
    {Method::kExact, "exact", MakeExact, nullptr, true, {AutoCase::kLinear}},
    {Method::kBaselineDopri5,
     "baseline-dopri5",
     nullptr,
     "gates compliant forces and has no events; a rigid contact needs dopri5, rkf78 or "
     "rosenbrock4",
     false,
     {}},
};

const MethodRow& Row(Method m) {
  for (const MethodRow& r : kMethodTable) {
    if (r.method == m) return r;
  }
  throw std::logic_error("method missing from the method table");
}

}  // namespace

const std::vector<Method>& AllMethods() {
  static const std::vector<Method> all = [] {
    std::vector<Method> v;
    for (const MethodRow& r : kMethodTable) v.push_back(r.method);
    return v;
  }();
  return all;
}

std::string MethodName(Method m) { return Row(m).name; }

std::optional<std::string> MethodRigidRefusal(Method m) {
  const MethodRow& r = Row(m);
  if (r.rigid_refusal == nullptr) return std::nullopt;
  return "method \"" + std::string(r.name) + "\" " + r.rigid_refusal;
}

bool MethodIsClosedForm(Method m) { return Row(m).closed_form; }

bool MethodIsEventDriven(Method m) { return Row(m).make != nullptr; }

Method AutoMethodFor(AutoCase c) {
  for (const MethodRow& r : kMethodTable) {
    for (AutoCase x : r.auto_for)
      if (x == c) return r.method;
  }
  throw std::logic_error("no method of the method table for an auto case");
}

std::optional<Method> ParseMethod(const std::string& name) {
  for (const MethodRow& r : kMethodTable) {
    if (name == r.name) return r.method;
  }
  return std::nullopt;
}

std::string MethodList() {
  std::string out = "auto";
  const size_t n = sizeof(kMethodTable) / sizeof(kMethodTable[0]);
  for (size_t i = 0; i < n; ++i)
    out += (i + 1 == n ? " or " : ", ") + std::string(kMethodTable[i].name);
  return out;
}

std::string MethodNameFault(const std::string& name) {
  if (name == "auto" || ParseMethod(name)) return {};
  return "unknown method \"" + name + "\"; expected " + MethodList();
}

std::unique_ptr<Stepper> MakeStepper(Method m, TrainSystem& system, const IntegratorOptions& o) {
  MakeBackend* const make = Row(m).make;
  return make ? make(system, o) : nullptr;
}

std::string RtolRangeText() {
  const auto power = [](double v) { return "1e" + std::to_string(std::lround(std::log10(v))); };
  return "[" + power(kMinRtol) + ", " + power(kMaxRtol) + "]";
}

void IntegratorOptions::Validate() const {
  const FieldRules require{"IntegratorOptions"};
  require(rtol >= kMinRtol && rtol <= kMaxRtol, "rtol", rtol, "must be in " + RtolRangeText());
  require(atol_m > 0.0 && std::isfinite(atol_m), "atol_m", atol_m, "must be positive");
  require(atol_m_s >= 0.0 && std::isfinite(atol_m_s), "atol_m_s", atol_m_s,
          "must be positive (or 0: atol_m)");
  require(atol_J >= 0.0 && std::isfinite(atol_J), "atol_J", atol_J,
          "must be positive (or 0: atol_m)");
  require(max_steps >= 1, "max_steps", max_steps, "must be at least 1");
  require(max_events >= 1, "max_events", max_events, "must be at least 1");
  require(max_seconds >= 0.0 && std::isfinite(max_seconds), "max_seconds", max_seconds,
          "must be finite and ≥ 0");
  require(settle_limit_s >= 0.0 && std::isfinite(settle_limit_s), "settle_limit_s", settle_limit_s,
          "must be finite and ≥ 0");
  require(stop_jump_rad >= 0.0 && std::isfinite(stop_jump_rad), "stop_jump_rad", stop_jump_rad,
          "must be finite and ≥ 0");
}

std::array<double, 4> IntegratorOptions::AbsoluteTolerances() const {
  const double v = atol_m_s > 0.0 ? atol_m_s : atol_m;
  const double e = atol_J > 0.0 ? atol_J : atol_m;
  return {atol_m, v, e, e};
}

TrainSystem::TrainSystem(const NeedleTrain& train, const IntegratorOptions& o) : train_(train) {
  const std::array<double, 4> atol = o.AbsoluteTolerances();
  scaled_ = false;
  for (int i = 0; i < train.StateSize(); ++i) {
    scale_.push_back(atol[train.MeasuredLike(i)] / atol[0]);
    scaled_ = scaled_ || scale_[i] != 1.0;
  }
}

TrainState TrainSystem::ToScaled(const TrainState& x) const {
  if (!scaled_) return x;
  TrainState z(x.size());
  for (size_t i = 0; i < x.size(); ++i) z[i] = x[i] / scale_[i];
  return z;
}

TrainState TrainSystem::FromScaled(const TrainState& z) const {
  TrainState x;
  FromScaled(z, x);
  return x;
}

void TrainSystem::FromScaled(const TrainState& z, TrainState& x) const {
  if (!scaled_) {
    x = z;
    return;
  }
  x.resize(z.size());
  for (size_t i = 0; i < z.size(); ++i) x[i] = z[i] * scale_[i];
}

void TrainSystem::operator()(const TrainState& z, TrainState& dzdt, double t) const {
  ++evaluations_;
  FromScaled(z, last_x_);  // into the memo, without a temporary
  last_t_ = t;
  last_phase_ = phase;
  train_.Derivative(last_x_, t, phase, dzdt, &last_contacts_);
  if (!scaled_) return;
  for (size_t i = 0; i < z.size(); ++i) dzdt[i] /= scale_[i];
}

const Contacts* TrainSystem::LastContacts(const TrainState& x, double t) const {
  const bool same = SameBits(t, last_t_) && phase.Identical(last_phase_) &&
                    x.size() == last_x_.size() &&
                    std::memcmp(x.data(), last_x_.data(), x.size() * sizeof(double)) == 0;
  return same ? &last_contacts_ : nullptr;
}

void TrainSystem::Jacobian(const TrainState& z, double t, TrainJacobian& J,
                           TrainState& dfdt) const {
  train_.Jacobian(FromScaled(z), t, phase, J, dfdt);
  if (!scaled_) return;
  const size_t n = z.size();
  for (size_t r = 0; r < n; ++r) {  // ∂(f_r/s_r)/∂z_c = J_rc s_c / s_r
    for (size_t c = 0; c < n; ++c) J[r * n + c] *= scale_[c] / scale_[r];
    dfdt[r] /= scale_[r];
  }
}

namespace {
// A budget as written in a case file: 2000000, 60, 0.5.
std::string Shortest(double v) {
  if (v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  std::ostringstream out;
  out << v;
  return out.str();
}
}  // namespace

void ThrowOverBudget(const std::string& what, double budget, const NeedleTrain& train, double t,
                     const IntegrationStats& done, Method method) {
  // A stiff scene wants the implicit method; one that ran it already, the explicit one.
  const bool implicit = method == Method::kCvodeBdf || method == Method::kRosenbrock4;
  const std::string other = train.HasConstraint() ? (method == Method::kDopri5 ? "rkf78" : "dopri5")
                            : implicit            ? "dopri5"
                                                  : "cvode-bdf";
  throw BudgetExceeded(
      "simulation stopped at " + std::to_string(train.Angle(t) / kDeg) + " deg after " +
          Shortest(budget) + " " + what + " (the budget [solver] max_" + what +
          "): the scene may chatter or be too stiff for method \"" + MethodName(method) +
          "\"; try method = \"" + other + "\", a looser rtol, or raise max_" + what,
      train.Angle(t), done);
}

}  // namespace needle
