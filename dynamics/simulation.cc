#include "dynamics/simulation.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "lib/units.h"
#include "spring/quasi_static.h"

namespace needle {
namespace {

// Above this many contact oscillations per cam event the train is stiff: BDF.
constexpr double kStiffOscillations = 2000.0;
// The rigid answer stands in when contact oscillates this often per event and the
// quasi-static force never falls below this fraction of the preload.
constexpr double kRigidOscillations = 500.0;
constexpr double kRigidMargin = 0.5;

}  // namespace

std::string RunStatusName(RunStatus s) {
  switch (s) {
    case RunStatus::kComplete:
      return "complete";
    case RunStatus::kUnsettled:
      return "unsettled";
    case RunStatus::kBudget:
      return "budget";
  }
  return "?";
}

bool SimulationResult::liftoff() const {
  for (const Episode& e : episodes) {
    if (e.kind == "jump") return true;
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

std::vector<Column> SeriesColumns() {
  using namespace display;
  return {{"crank", kDegree}, {"time", kS},          {"lift", kMm},     {"velocity", kMPerS},
          {"cam", kMm},       {"contact_force", kN}, {"seat_force", kN}};
}

std::vector<std::vector<double>> SeriesRows(const SimulationResult& r) {
  std::vector<std::vector<double>> rows;
  rows.reserve(r.series.size());
  for (const SeriesPoint& p : r.series) {
    rows.push_back({p.crank_rad, p.time_s, p.lift_m, p.velocity_m_s, p.cam_m, p.contact_force_N,
                    p.seat_force_N});
  }
  return rows;
}

RunWindow DefaultRunWindow(const Scene& scene) {
  RunWindow w;
  w.start_rad = scene.start_rad.value_or(scene.cam->rise_start_rad() - 5.0 * kDeg);
  w.end_rad = scene.end_rad.value_or(scene.cam->fall_end_rad() + 20.0 * kDeg);
  return w;
}

double ContactOscillationsPerEvent(const Scene& scene, double speed_rpm) {
  const double omega_c =
      std::sqrt((scene.train.contact_stiffness_N_m + scene.train.rate_N_m) / scene.train.mass_kg);
  const double event_s = (scene.law->end_rad() - scene.law->start_rad()) / OmegaFromRpm(speed_rpm);
  return omega_c * event_s / (2.0 * kPi);
}

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
  if (!(o.settle_limit_deg > 0.0 && o.settle_limit_deg <= 36000.0)) {
    throw std::invalid_argument("SimulationOptions.settle_limit_deg = " +
                                std::to_string(o.settle_limit_deg) + ": must be in (0, 36000]");
  }
  const double oscillations = ContactOscillationsPerEvent(scene, speed_rpm);
  const std::string stiffness = "the contact oscillates " +
                                std::to_string(static_cast<long>(std::lround(oscillations))) +
                                " times per cam event";

  // Skip the dynamics where the rigid answer is the answer.
  const RigidTrain rigid = RigidTrainOf(scene);
  const ForceMinimum fmin = MinQuasiStaticForce(*scene.law, rigid, omega);
  if (!o.force_dynamic && scene.cam->play_m() == 0.0 && oscillations >= kRigidOscillations &&
      fmin.force_N >= kRigidMargin * scene.train.preload_N && scene.train.preload_N > 0.0) {
    r.skipped = true;
    r.method = "rigid";
    r.method_reason = "dynamic run skipped: " + stiffness +
                      " and the quasi-static contact force never falls below " +
                      std::to_string(static_cast<int>(kRigidMargin * 100)) +
                      " % of the preload (min " + std::to_string(fmin.force_N) +
                      " N); no roller play; use --dynamic to run it";
    const Extremum top = scene.law->Max(0);
    r.max_lift_m = top.value;
    r.max_lift_rad = top.crank_rad;
    r.min_contact_force_during_lift_N = fmin.force_N;
    // Largest F_qs over the lift: −min of −F_qs (sampled finely; F_qs is smooth).
    double fmax = 0.0;
    for (int k = 0; k <= 2000; ++k) {
      const double th =
          scene.law->start_rad() + (scene.law->end_rad() - scene.law->start_rad()) * k / 2000.0;
      fmax = std::max(fmax, QuasiStaticForce(*scene.law, rigid, omega, th));
    }
    r.max_contact_force_N = fmax;
    r.max_seat_force_N = scene.train.preload_N - scene.train.gas_force_N;
    return r;
  }

  NeedleTrain train(*scene.cam, scene.train, omega, theta_a);
  Method method;
  if (o.method == "auto") {
    if (train.HasConstraint()) {
      method = Method::kDopri5;
      r.method_reason =
          "auto: rigid contacts (restitution and sticking): explicit Dormand–Prince, a one-step "
          "method that restarts at full order after every impact";
    } else if (const std::optional<std::string> refusal = ExactRefusal(train)) {
      method = oscillations > kStiffOscillations ? Method::kCvodeBdf : Method::kDopri5;
      r.method_reason = "auto: " + *refusal + "; " + stiffness +
                        (method == Method::kCvodeBdf ? " (> 2000: stiff, BDF)"
                                                     : " (≤ 2000: explicit Dormand–Prince)");
    } else {
      method = Method::kExact;
      r.method_reason = "auto: the train is linear in every contact mode, solved in closed form";
    }
  } else if (auto m = ParseMethod(o.method)) {
    method = *m;
    r.method_reason = "asked for";
  } else {
    throw std::invalid_argument("unknown method \"" + o.method + "\"; expected " + MethodList());
  }

  r.method = MethodName(method);

  const TrainState x0 = train.EquilibriumStart();
  Recorder recorder(train, o.record_series);
  const double t_end = (theta_b - theta_a) / omega;
  IntegratorOptions io = o.integrator;
  io.settle_limit_s = o.settle_limit_deg * kDeg / omega;
  try {
    r.stats = Integrate(method, train, x0, t_end, recorder, io);
    r.run_end_rad = train.Angle(r.stats.final_time);
    r.energy_residual = train.EnergyResidual(x0, r.stats.final_state, r.stats.final_time);
    if (!recorder.AtRest(r.stats.final_time, r.stats.final_state, r.stats.final_phase)) {
      r.status = RunStatus::kUnsettled;
      std::ostringstream why;
      why << "the needle is still moving " << o.settle_limit_deg
          << " deg past the window's end (the settle budget, [solver] settle_deg)";
      r.status_reason = why.str();
    }
  } catch (const BudgetExceeded& e) {
    recorder.Stopped(e.crank_rad);
    r.run_end_rad = e.crank_rad;
    r.status = RunStatus::kBudget;
    r.status_reason = e.what();
    r.energy_residual = std::numeric_limits<double>::quiet_NaN();
  }

  r.episodes = recorder.episodes();
  r.impacts = recorder.impacts();
  r.series = recorder.series();
  r.max_lift_m = recorder.max_lift_m();
  r.max_lift_rad = recorder.max_lift_rad();
  r.max_contact_force_N = recorder.max_contact_force_N();
  r.min_contact_force_during_lift_N = recorder.min_contact_force_during_lift_N();
  r.max_seat_force_N = recorder.max_seat_force_N();
  r.jump_rad = recorder.jump_rad();
  r.longest_jump_rad = recorder.longest_jump_rad();
  return r;
}

}  // namespace needle
