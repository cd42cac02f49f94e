// One pass of a run and the revolutions of [solver] cycles (dynamics/simulation_pass.h).
#include "dynamics/simulation_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "lib/units.h"

namespace needle {
namespace internal {
namespace {

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

// Adds one pass's records (its impacts, episodes, series and extremes, moved by shift_rad and
// shift_s) and its work to the run's result (RunPass).
void MergePass(const Recorder& recorder, const IntegrationStats& stats, int cycle, double shift_rad,
               double shift_s, SimulationResult& r) {
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

}  // namespace

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

  MergePass(recorder, stats, cycle, shift_rad, shift_s, r);

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

}  // namespace internal
}  // namespace needle
