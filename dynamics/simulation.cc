#include "dynamics/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "dynamics/simulation_pass.h"
#include "dynamics/solver/chain_modes.h"
#include "lib/field_error.h"
#include "lib/name_table.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/quasi_static.h"

namespace needle {
namespace {

using internal::RunCycles;
using internal::RunPass;

// Above this many contact oscillations per cam event the train is stiff: BDF.
constexpr double kStiffOscillations = 2000.0;
// A coil chain whose fastest |λ| is above this many times its fastest oscillation goes to a time
// stepper (AutoMethod): an overdamped mode caps exact's pieces.
constexpr double kOverdampedFactor = 2.0;
// The rigid answer stands in when contact oscillates this often per event and the
// quasi-static force never falls below this fraction of the preload.
constexpr double kRigidOscillations = 500.0;
constexpr double kRigidMargin = 0.5;

// A complete run checked against its scene (docs/model.md §6): a needle whose largest lift
// falls short of the cam's, or that sinks into its seat, by more than kFollowFraction of the
// cam's lift did not follow it, whatever key caused it (a sign-typo'd stiffness, a seat that
// cannot hold the spring).
void JudgeFollowing(const Scene& scene, SimulationResult& r) {
  // A run stopped past the lift with the needle on the cam has seen the whole lift; one stopped
  // at its first jump, or on a budget, has not.
  const bool stopped_past_lift = r.status == RunStatus::kStopped && !r.liftoff();
  if (r.status != RunStatus::kComplete && !stopped_past_lift) return;
  const double cam_lift = scene.cam->top().value;  // the law's Max(0)
  // Where the needle rests at the end: a landing may press it deeper for an instant.
  const double rest_lift = r.stats.final_state.empty() ? 0.0 : r.stats.final_state[0];
  const auto mm = [](double m) { return Fixed(m * 1e3, 3) + " mm"; };
  std::string why;
  if (r.max_lift_m < (1.0 - kFollowFraction) * cam_lift) {
    why = "the needle does not follow the cam: its largest lift " + mm(r.max_lift_m) + " is " +
          Fixed(100 * r.max_lift_m / cam_lift, 1) + " % of the cam's " + mm(cam_lift);
  } else if (r.status == RunStatus::kComplete && rest_lift < -kFollowFraction * cam_lift) {
    why = "the needle rests " + mm(-rest_lift) + " into its seat, more than " +
          Fixed(100 * kFollowFraction, 0) + " % of the cam's lift";
  } else {
    return;
  }
  std::ostringstream keys;
  keys << " (seat " << scene.train.seat_stiffness_N_m << " N/m, cam contact "
       << scene.train.contact_stiffness_N_m << " N/m, preload " << scene.train.preload_N
       << " N: look at the stiffness keys, the preload and the mass)";
  r.status = RunStatus::kNotFollowing;
  r.status_reason = why + keys.str();
}

}  // namespace

namespace {

// The one name table.
constexpr NameRow<RunStatus> kRunStatusNames[] = {
    {RunStatus::kComplete, "complete"}, {RunStatus::kUnsettled, "unsettled"},
    {RunStatus::kBudget, "budget"},     {RunStatus::kNotFollowing, "not-following"},
    {RunStatus::kStopped, "stopped"},
};

}  // namespace

std::string RunStatusName(RunStatus s) { return NameOf(kRunStatusNames, s); }

bool SimulationResult::liftoff() const {
  for (const Episode& e : episodes) {
    if (e.kind == "jump" && e.cycle >= judged_from) return true;
  }
  return false;
}

RigidTrain RigidTrainOf(const Scene& scene) {
  return RigidTrain{scene.train.mass_kg, scene.train.preload_N, scene.train.rate_N_m,
                    scene.train.gas_force_N};
}

double QuasiStaticLiftoffRpm(const Scene& scene) {
  return QuasiStaticLiftoffRpm(*scene.law, RigidTrainOf(scene));
}

RunWindow DefaultRunWindow(const Scene& scene) {
  RunWindow w;
  w.start_rad = scene.start_rad.value_or(scene.cam->rise_start_rad() - kRunWindowLead_rad);
  w.end_rad = scene.end_rad.value_or(scene.cam->fall_end_rad() + kRunWindowTail_rad);
  return w;
}

std::optional<std::string> CyclesRefusal(const Scene& scene) {
  const RunWindow w = DefaultRunWindow(scene);
  if (w.end_rad <= w.start_rad + scene.revolution_rad) return std::nullopt;
  std::ostringstream out;
  out << "the run window (" << w.start_rad / kDeg << " to " << w.end_rad / kDeg
      << " deg) is longer than one cam revolution (" << scene.revolution_rad / kDeg << " deg)";
  return out.str();
}

double ContactOscillationsPerEvent(const Scene& scene, double speed_rpm) {
  const double omega_c =
      std::sqrt((scene.train.contact_stiffness_N_m + scene.train.rate_N_m) / scene.train.mass_kg);
  const double event_s = (scene.law->end_rad() - scene.law->start_rad()) / OmegaFromRpm(speed_rpm);
  return omega_c * event_s / (2.0 * kPi);
}

namespace {

// "the contact oscillates N times per cam event": why auto and the rigid skip decide as they do.
std::string StiffnessText(double oscillations) {
  return "the contact oscillates " + std::to_string(static_cast<long>(std::lround(oscillations))) +
         " times per cam event";
}

}  // namespace

MethodChoice AutoMethod(const NeedleTrain& train, double oscillations, double /*rtol*/) {
  if (train.HasConstraint()) {
    return {AutoMethodFor(AutoCase::kRigid),
            "auto: rigid contacts (restitution and sticking): explicit Dormand–Prince, a one-step "
            "method that restarts at full order after every impact"};
  }
  const std::string stiffness = StiffnessText(oscillations);
  // A coil chain without clash: "exact" carries it (docs/exact.md, "The coil chain"), unless a
  // mode is at or near critical damping.
  std::optional<std::string> refusal = ExactRefusalWithModes(train);
  // Nor one whose fastest mode is overdamped far past its fastest oscillation: that mode caps
  // exact's pieces at π/|λ|, some 20 times more of them (helper-59: 40 masses at surge ζ 0.4,
  // 3757 pieces, 15 times the time stepper's run).
  if (!refusal && train.Coils() > 0) {
    double fastest = 0.0, oscillation = 0.0;
    for (const auto& modes : ChainModes::SharedEveryMode(train)) {  // made by the refusal's ask
      fastest = std::max(fastest, modes->Fastest());
      oscillation = std::max(oscillation, modes->FastestOscillation());
    }
    if (fastest > kOverdampedFactor * oscillation) {
      refusal = "the coil chain's fastest mode is overdamped (|λ| " + Significant(fastest, 3) +
                " 1/s against its fastest oscillation's " + Significant(oscillation, 3) +
                " rad/s), which would cap method \"exact\"'s pieces";
    }
  }
  if (refusal) {
    const bool stiff = oscillations > kStiffOscillations;
    return {AutoMethodFor(stiff ? AutoCase::kStiff : AutoCase::kNonStiff),
            "auto: " + *refusal + "; " + stiffness +
                (stiff ? " (> 2000: stiff, BDF)" : " (≤ 2000: explicit Dormand–Prince)")};
  }
  // The closed form at every tolerance (simulation.h).
  return {AutoMethodFor(AutoCase::kLinear),
          "auto: the train is linear in every contact mode, solved in closed form"};
}

MethodChoice AutoMethod(const Scene& scene, double speed_rpm, double rtol) {
  const RunWindow window = DefaultRunWindow(scene);
  const NeedleTrain train(*scene.cam, scene.train, OmegaFromRpm(speed_rpm), window.start_rad);
  return AutoMethod(train, ContactOscillationsPerEvent(scene, speed_rpm), rtol);
}

void SimulationOptions::Validate() const {
  integrator.Validate();
  const FieldRules require{"SimulationOptions"};
  require(settle_limit_deg > 0.0 && settle_limit_deg <= 36000.0, "settle_limit_deg",
          settle_limit_deg, "must be in (0, 36000] deg");
  require(cycles >= 1 && cycles <= kMaxCycles, "cycles", static_cast<long>(cycles),
          "must be in [1, " + std::to_string(kMaxCycles) + "]");
  require(period_tolerance > 0.0 && period_tolerance <= 1e-2, "period_tolerance", period_tolerance,
          "must be in (0, 1e-2]");
  if (!grid_rad.empty() && cycles != 1) {
    throw std::invalid_argument("SimulationOptions.grid_rad needs cycles = 1, got " +
                                std::to_string(cycles));
  }
  if (!std::is_sorted(grid_rad.begin(), grid_rad.end())) {
    throw std::invalid_argument("SimulationOptions.grid_rad must be sorted");
  }
  if (steady_state && cycles < 2) {
    throw std::invalid_argument("SimulationOptions.steady_state needs cycles >= 2, got " +
                                std::to_string(cycles));
  }
}

namespace {

// The rigid answer of a run whose dynamics are skipped (Simulate): the quasi-static forces of
// the law, `fmin` their least.
SimulationResult RigidAnswer(const Scene& scene, const RigidTrain& rigid, double omega,
                             const ForceMinimum& fmin, const std::string& stiffness,
                             SimulationResult r) {
  r.skipped = true;
  r.method = "rigid";
  r.method_reason = "dynamic run skipped: " + stiffness +
                    " and the quasi-static contact force never falls below " +
                    std::to_string(static_cast<int>(kRigidMargin * 100)) +
                    " % of the preload (min " + std::to_string(fmin.force_N) +
                    " N); no roller play; use --dynamic to run it";
  const Extremum top = scene.cam->top();  // the law's Max(0)
  r.max_lift_m = top.value;
  r.max_lift_rad = top.crank_rad;
  r.min_contact_force_during_lift_N = fmin.force_N;
  // Largest F_qs over the lift: −min of −F_qs (sampled finely; F_qs is smooth).
  // … and the least F_qs / (P₀ + k s − F_g) where the needle is lifted (s > 1 µm).
  double fmax = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double th =
        scene.law->start_rad() + (scene.law->end_rad() - scene.law->start_rad()) * k / 2000.0;
    const double f = QuasiStaticForce(*scene.law, rigid, omega, th);
    fmax = std::max(fmax, f);
    const double s = scene.law->Lift(th);
    const double hold = rigid.SpringForceN(s);
    const double ratio = hold > 0.0 ? std::max(0.0, f) / hold : 0.0;
    if (s > kSeparationLift_m && !(ratio >= r.min_contact_force_ratio)) {
      r.min_contact_force_ratio = ratio;
      r.min_contact_force_ratio_rad = th;
      r.min_contact_force_ratio_force_N = std::max(0.0, f);
    }
  }
  r.max_contact_force_N = fmax;
  r.max_seat_force_N = scene.train.preload_N - scene.train.gas_force_N;
  r.max_spring_force_N = scene.train.preload_N + scene.train.rate_N_m * top.value;
  return r;
}

// The method of o.method ("auto": AutoMethod's for the train), its reason into `reason`.
Method ChosenMethod(const NeedleTrain& train, const SimulationOptions& o, double oscillations,
                    std::string* reason) {
  if (o.method == "auto") {
    const MethodChoice choice = AutoMethod(train, oscillations, o.integrator.rtol);
    *reason = choice.reason;
    return choice.method;
  }
  if (auto m = ParseMethod(o.method)) {
    *reason = "asked for";
    return *m;
  }
  throw std::invalid_argument(MethodNameFault(o.method));
}

}  // namespace

SimulationResult Simulate(const Scene& scene, double speed_rpm, const SimulationOptions& o) {
  if (!(speed_rpm > 0.0) || !std::isfinite(speed_rpm)) {
    throw std::invalid_argument("speed must be positive, got " + std::to_string(speed_rpm) +
                                " rpm");
  }
  SimulationResult r;
  r.speed_rpm = speed_rpm;
  const double omega = OmegaFromRpm(speed_rpm);
  const RunWindow window = DefaultRunWindow(scene);
  const double theta_a = window.start_rad, theta_b = window.end_rad;
  r.window_start_rad = theta_a;
  r.window_end_rad = theta_b;
  r.run_end_rad = theta_b;
  o.Validate();
  const double oscillations = ContactOscillationsPerEvent(scene, speed_rpm);
  const std::string stiffness = StiffnessText(oscillations);

  // Skip the dynamics where the rigid answer is the answer.
  // The quasi-static minimum is searched only where it can decide (issue 33: an overspeed
  // search's runs are forced dynamic); its checks of the law and the train are made for every
  // run, as before.
  const RigidTrain rigid = RigidTrainOf(scene);
  RequireAcceleration(*scene.law);
  rigid.Validate();
  const bool may_skip = !o.force_dynamic && scene.cam->play_m() == 0.0 &&
                        scene.train.coil_masses == 1 && oscillations >= kRigidOscillations &&
                        scene.train.preload_N > 0.0;
  const ForceMinimum fmin =
      may_skip ? MinQuasiStaticForce(*scene.law, rigid, omega) : ForceMinimum{};
  if (may_skip && fmin.force_N >= kRigidMargin * scene.train.preload_N) {
    return RigidAnswer(scene, rigid, omega, fmin, stiffness, std::move(r));
  }

  NeedleTrain train(*scene.cam, scene.train, omega, theta_a);
  const Method method = ChosenMethod(train, o, oscillations, &r.method_reason);

  r.method = MethodName(method);
  SimulationOptions run = o;
  if (o.stop_at_liftoff && !o.steady_state) run.integrator.stop_jump_rad = kMinJump_rad;
  run.integrator.stop_after_lift = o.stop_at_liftoff && o.cycles == 1;
  // A run that answers only "lift-off?" reports no energy residual: the closed form leaves the
  // audit's W and D out (issue 33: computed only where reported).
  run.integrator.audit_energy = !o.stop_at_liftoff;

  if (o.cycles == 1) {
    RunPass(train, method, train.EquilibriumStart(), (theta_b - theta_a) / omega,
            o.settle_limit_deg, run, 0, 0.0, r);
  } else {
    RunCycles(scene, train, method, run, r);
  }
  JudgeFollowing(scene, r);
  if (o.stop_at_liftoff) {
    // What a lift-off run does not keep (Recorder::set_liftoff_only) is not reported.
    const double none = std::numeric_limits<double>::quiet_NaN();
    r.max_contact_force_N = r.max_seat_force_N = r.max_spring_force_N = r.min_lift_m = none;
    r.min_contact_force_ratio = r.min_contact_force_ratio_rad = none;
    r.min_contact_force_ratio_force_N = none;
    r.secondary_lift_m = r.secondary_lift_rad = r.secondary_open_rad = none;
  }
  return r;
}

}  // namespace needle
