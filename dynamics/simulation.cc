#include "dynamics/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "lib/name_table.h"
#include "lib/output.h"
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

// The times of the crank angles `grid_rad` (SimulationOptions::grid_rad) from θ_a on.
std::vector<double> GridTimes(const NeedleTrain& train, const std::vector<double>& grid_rad) {
  std::vector<double> times;
  times.reserve(grid_rad.size());
  for (double th : grid_rad) {
    // An angle at θ_a but for the roundoff of its subtraction is at θ_a.
    const double t = (th - train.Angle(0.0)) / train.omega();
    const double roundoff = 1e-12 * (std::abs(th) + std::abs(train.Angle(0.0))) / train.omega();
    if (t >= -roundoff) times.push_back(std::max(t, 0.0));
  }
  return times;
}

// A streamed series (o.series_sink): each revolution's points shifted as the kept ones are.
std::function<void(const SeriesPoint&)> ShiftedSink(const SimulationOptions& o, double shift_rad,
                                                    double shift_s) {
  if (!o.series_sink) return {};
  return [&o, shift_rad, shift_s](SeriesPoint p) {
    p.crank_rad += shift_rad;
    p.time_s += shift_s;
    o.series_sink(p);
  };
}

// One integration from x0 over [0, t_end] (then on while the needle settles, for at most
// settle_deg past it; 0: stop at t_end) appended to r as cam revolution `cycle`, which begins
// shift_rad after θ_a: its episodes, impacts and series shifted so, its extremes and statistics
// merged, r's status set. Returns the revolution's summary, with the state at its end (NaN
// after a budget stop).
CycleSummary RunPass(const NeedleTrain& train, Method method, const TrainState& x0, double t_end,
                     double settle_deg, const SimulationOptions& o, int cycle, double shift_rad,
                     SimulationResult& r) {
  const double shift_s = shift_rad / train.omega();
  Recorder recorder(train, o.record_series, ShiftedSink(o, shift_rad, shift_s));
  recorder.set_liftoff_only(o.stop_at_liftoff);
  if (cycle == 0 && !o.grid_rad.empty()) recorder.set_grid(GridTimes(train, o.grid_rad));
  IntegratorOptions io = o.integrator;
  io.settle_limit_s = settle_deg * kDeg / train.omega();
  IntegrationStats stats;
  TrainState end(train.StateSize(), std::numeric_limits<double>::quiet_NaN());
  double residual = std::numeric_limits<double>::quiet_NaN();
  try {
    stats = Integrate(method, train, x0, t_end, recorder, io);
    r.run_end_rad = train.Angle(stats.final_time) + shift_rad;
    if (io.audit_energy) residual = train.EnergyResidual(x0, stats.final_state, stats.final_time);
    // What goes on: the needle on the surface it sticks to (a sticking rigid contact's state
    // is the surface's; the integrated one may trail it by a slope jump of the table's end).
    end = train.Project(stats.final_state, stats.final_time, stats.final_phase);
    if (stats.stopped_at_jump) {
      r.status = RunStatus::kStopped;
      std::ostringstream why;
      why << "stopped at its first lift-off (a jump of " << kMinJump_rad / kDeg << " deg at "
          << r.run_end_rad / kDeg << " deg), as asked";
      r.status_reason = why.str();
    } else if (stats.stopped_after_lift) {
      r.status = RunStatus::kStopped;
      r.status_reason = "stopped past the lift without lift-off, as asked";
    } else if (settle_deg > 0.0 &&
               !recorder.AtRest(stats.final_time, stats.final_state, stats.final_phase)) {
      r.status = RunStatus::kUnsettled;
      std::ostringstream why;
      why << "the needle is still moving " << settle_deg
          << " deg past the window's end (the settle budget, [solver] settle_deg)";
      r.status_reason = why.str();
    }
  } catch (const BudgetExceeded& e) {
    stats = e.stats;  // the work done up to the stop
    recorder.Stopped(e.crank_rad);
    r.run_end_rad = e.crank_rad + shift_rad;
    r.status = RunStatus::kBudget;
    r.status_reason = e.what();
  }
  r.energy_residual = cycle == 0 ? residual : std::max(r.energy_residual, residual);
  if (std::isnan(residual)) r.energy_residual = residual;

  const int first_impact = static_cast<int>(r.impacts.size());
  for (Impact i : recorder.impacts()) {
    i.crank_rad += shift_rad;
    i.cycle = cycle;
    r.impacts.push_back(i);
  }
  for (Episode e : recorder.episodes()) {
    e.start_rad += shift_rad;
    e.end_rad += shift_rad;
    if (e.impact >= 0) e.impact += first_impact;
    e.cycle = cycle;
    r.episodes.push_back(e);
  }
  if (cycle == 0) r.grid = recorder.grid();
  if (r.series.empty()) r.series.reserve(recorder.series().size());  // later cycles: doubling
  for (SeriesPoint p : recorder.series()) {
    p.crank_rad += shift_rad;
    p.time_s += shift_s;
    r.series.push_back(p);
  }
  if (cycle == 0 || recorder.max_lift_m() > r.max_lift_m) {
    r.max_lift_m = recorder.max_lift_m();
    r.max_lift_rad = recorder.max_lift_rad() + shift_rad;
  }
  r.max_contact_force_N = std::max(r.max_contact_force_N, recorder.max_contact_force_N());
  r.min_contact_force_during_lift_N =
      cycle == 0
          ? recorder.min_contact_force_during_lift_N()
          : std::min(r.min_contact_force_during_lift_N, recorder.min_contact_force_during_lift_N());
  r.max_seat_force_N = std::max(r.max_seat_force_N, recorder.max_seat_force_N());
  r.min_lift_m = cycle == 0 ? recorder.min_lift_m() : std::min(r.min_lift_m, recorder.min_lift_m());
  r.max_spring_force_N = std::max(r.max_spring_force_N, recorder.max_spring_force_N());
  if (recorder.secondary_lift_m() > r.secondary_lift_m) {
    r.secondary_lift_m = recorder.secondary_lift_m();
    r.secondary_lift_rad = recorder.secondary_lift_rad() + shift_rad;
    r.secondary_open_rad = recorder.secondary_open_rad();
  }
  if (recorder.lifted() && !(recorder.min_contact_force_ratio() >= r.min_contact_force_ratio)) {
    r.min_contact_force_ratio = recorder.min_contact_force_ratio();
    r.min_contact_force_ratio_rad = recorder.min_contact_force_ratio_rad() + shift_rad;
    r.min_contact_force_ratio_force_N = recorder.min_contact_force_ratio_force_N();
  }
  if (const std::optional<double> gap = recorder.min_coil_gap_m()) {
    r.min_coil_gap_m = r.min_coil_gap_m ? std::min(*r.min_coil_gap_m, *gap) : *gap;
  }
  r.coil_clashes += recorder.coil_clashes();
  r.jump_rad += recorder.jump_rad();
  r.longest_jump_rad = std::max(r.longest_jump_rad, recorder.longest_jump_rad());
  r.stats.steps += stats.steps;
  r.stats.rhs_evaluations += stats.rhs_evaluations;
  r.stats.events += stats.events;
  r.stats.resets += stats.resets;
  r.stats.accumulations += stats.accumulations;
  r.stats.final_state = stats.final_state;
  r.stats.final_time = stats.final_time + shift_s;
  r.stats.final_phase = stats.final_phase;

  CycleSummary c;
  c.index = cycle;
  c.start_rad = train.Angle(0.0) + shift_rad;
  c.impacts = static_cast<int>(recorder.impacts().size());
  for (const Episode& e : recorder.episodes()) {
    if (e.kind == "jump") ++c.jumps;
    c.max_gap_m = std::max(c.max_gap_m, e.max_gap_m);
  }
  c.jump_rad = recorder.jump_rad();
  c.longest_jump_rad = recorder.longest_jump_rad();
  c.end_lift_m = end[0];
  c.end_velocity_m_s = end[1];
  c.end_coils.assign(end.begin() + 4, end.end());
  c.energy_residual = residual;
  return c;
}

// Whether cycle-end state b repeats a: lifts (the needle's and the coils') within tol·L,
// velocities within tol·ω·L (L the largest lift). RunCycles asks for the same impacts per
// revolution besides.
bool Repeats(const NeedleTrain& train, const TrainState& a, const TrainState& b, double tol,
             double lift_m) {
  for (size_t i = 0; i < a.size(); ++i) {
    const int like = train.MeasuredLike(static_cast<int>(i));
    if (like == 2 || like == 3) continue;  // W, D
    const double scale = like == 1 ? train.omega() * lift_m : lift_m;
    if (!(std::abs(a[i] - b[i]) <= tol * scale)) return false;
  }
  return true;
}

// [solver] cycles = N (docs/model.md §5): revolutions from θ_a to θ_a + one revolution, each
// from the state the last one ended in (the audit integrals W, D started afresh), until N have
// run or the cycle-end state repeats one k ≤ kMaxPeriod revolutions before (the start counts
// as the end of revolution −1). Lift-off is judged on the repeating period, or every cycle
// after the first, when steady_state asks.
void RunCycles(const Scene& scene, const NeedleTrain& train, Method method,
               const SimulationOptions& o, SimulationResult& r) {
  const double theta_a = r.window_start_rad;
  const double revolution = scene.revolution_rad;
  if (const auto refusal = CyclesRefusal(scene))
    throw std::invalid_argument("[solver] cycles: " + *refusal);

  r.window_end_rad = theta_a + revolution;
  r.cycles_asked = o.cycles;
  const double lift_scale = std::max(scene.cam->top().value + scene.cam->play_m(), 1e-6);
  std::vector<TrainState> ends{train.EquilibriumStart()};  // ends[j + 1]: the end of cycle j
  std::vector<int> impacts{0};
  for (int cycle = 0; cycle < o.cycles; ++cycle) {
    TrainState x0 = ends.back();
    x0[2] = x0[3] = 0.0;  // the audit of each revolution on its own
    const CycleSummary c = RunPass(train, method, x0, revolution / train.omega(), 0.0, o, cycle,
                                   cycle * revolution, r);
    r.cycles.push_back(c);
    if (r.status == RunStatus::kBudget || r.status == RunStatus::kStopped) break;
    TrainState end = {c.end_lift_m, c.end_velocity_m_s, 0.0, 0.0};
    end.insert(end.end(), c.end_coils.begin(), c.end_coils.end());
    ends.push_back(end);
    impacts.push_back(c.impacts);
    const int j = cycle + 1;
    for (int k = 1; k <= kMaxPeriod && k <= j; ++k) {
      bool repeats = Repeats(train, ends[j - k], ends[j], o.period_tolerance, lift_scale);
      // Impacts must repeat too (the start has none before it).
      for (int m = 0; m < k && repeats && j - k - m > 0; ++m)
        repeats = impacts[j - m] == impacts[j - k - m];
      if (repeats) {
        r.period_cycles = k;
        r.periodic_from = j - k;
        break;
      }
    }
    if (r.period_cycles > 0) break;
  }
  if (o.steady_state) {
    r.judged_from =
        r.period_cycles > 0 ? r.periodic_from : std::min(1, static_cast<int>(r.cycles.size()) - 1);
    r.jump_rad = 0.0;
    r.longest_jump_rad = 0.0;
    for (const CycleSummary& c : r.cycles) {
      if (c.index < r.judged_from) continue;
      r.jump_rad += c.jump_rad;
      r.longest_jump_rad = std::max(r.longest_jump_rad, c.longest_jump_rad);
    }
  }
}

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
  if (const std::optional<std::string> refusal = ExactRefusal(train)) {
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

namespace {

// Throws std::invalid_argument naming the field of `o` out of its range.
void ValidateOptions(const SimulationOptions& o) {
  if (!(o.settle_limit_deg > 0.0 && o.settle_limit_deg <= 36000.0)) {
    throw std::invalid_argument("SimulationOptions.settle_limit_deg = " +
                                std::to_string(o.settle_limit_deg) + ": must be in (0, 36000]");
  }
  if (!(o.cycles >= 1 && o.cycles <= kMaxCycles)) {
    throw std::invalid_argument("SimulationOptions.cycles = " + std::to_string(o.cycles) +
                                ": must be in [1, " + std::to_string(kMaxCycles) + "]");
  }
  if (!(o.period_tolerance > 0.0 && o.period_tolerance <= 1e-2)) {
    throw std::invalid_argument("SimulationOptions.period_tolerance = " +
                                std::to_string(o.period_tolerance) + ": must be in (0, 1e-2]");
  }
  if (!o.grid_rad.empty() && o.cycles != 1) {
    throw std::invalid_argument("SimulationOptions.grid_rad needs cycles = 1, got " +
                                std::to_string(o.cycles));
  }
  if (!std::is_sorted(o.grid_rad.begin(), o.grid_rad.end())) {
    throw std::invalid_argument("SimulationOptions.grid_rad must be sorted");
  }
  if (o.steady_state && o.cycles < 2) {
    throw std::invalid_argument("SimulationOptions.steady_state needs cycles >= 2, got " +
                                std::to_string(o.cycles));
  }
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
  ValidateOptions(o);
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

  NeedleTrain train(*scene.cam, scene.train, omega, theta_a);
  Method method;
  if (o.method == "auto") {
    const MethodChoice choice = AutoMethod(train, oscillations, o.integrator.rtol);
    method = choice.method;
    r.method_reason = choice.reason;
  } else if (auto m = ParseMethod(o.method)) {
    method = *m;
    r.method_reason = "asked for";
  } else {
    throw std::invalid_argument("unknown method \"" + o.method + "\"; expected " + MethodList());
  }

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
