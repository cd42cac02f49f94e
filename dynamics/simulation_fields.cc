// The run's field tables (dynamics/simulation.h): the result's scalars, its series' columns,
// and its episodes, impacts and revolutions, each in the unit it is shown in.
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "dynamics/simulation.h"
#include "lib/result_fields.h"

namespace needle {

std::vector<Field> SimulationFields(const SimulationResult& r) {
  using namespace display;
  std::vector<Field> f = {
      {"max_lift", kMm, r.max_lift_m, 4},
      {"max_lift", kDegree, r.max_lift_rad, 2},
      {"max_contact_force", kN, r.max_contact_force_N, 1},
      {"min_contact_force_during_lift", kN, r.min_contact_force_during_lift_N, 1},
      {"max_seat_force", kN, r.max_seat_force_N, 1},
      {"secondary_lift", kMm, r.secondary_lift_m, 4},
      {"secondary_lift", kDegree, r.secondary_lift_rad, 2},
      {"secondary_open", kDegree, r.secondary_open_rad, 2},
  };
  if (r.min_coil_gap_m) {  // a chain of coil masses with a travel to solid
    f.push_back({"min_coil_gap", kMm, *r.min_coil_gap_m, 3});
    f.push_back(CountField("coil_clashes", r.coil_clashes));
  }
  f.push_back({"energy_residual", kNone,
               r.skipped ? std::nullopt : std::optional<double>(r.energy_residual), 3});
  f.push_back(CountField("steps", r.stats.steps));
  f.push_back(CountField("rhs_evaluations", r.stats.rhs_evaluations));
  f.push_back(CountField("accumulations", r.stats.accumulations));
  f.push_back(CountField("events", r.stats.events));
  f.push_back({"window_start", kDegree, r.window_start_rad, 2});
  f.push_back({"window_end", kDegree, r.window_end_rad, 2});
  f.push_back({"run_end", kDegree, r.run_end_rad, 2});
  return f;
}

std::vector<Column> SeriesColumns() {
  using namespace display;
  return {{"crank", kDegree}, {"time", kS},          {"lift", kMm},     {"velocity", kMPerS},
          {"cam", kMm},       {"contact_force", kN}, {"seat_force", kN}};
}

std::array<double, 7> SeriesRow(const SeriesPoint& p) {
  return {p.crank_rad, p.time_s,          p.lift_m,      p.velocity_m_s,
          p.cam_m,     p.contact_force_N, p.seat_force_N};
}

std::vector<Field> EpisodeFields(const Episode& e, bool with_cycle) {
  using namespace display;
  std::vector<Field> f = {TextField("kind", e.kind),      {"start", kDegree, e.start_rad, 3},
                          {"end", kDegree, e.end_rad, 3}, {"max_gap", kMm, e.max_gap_m, 4},
                          CountField("impact", e.impact), FlagField("open", e.open)};
  if (with_cycle) f.push_back(CountField("cycle", e.cycle));
  return f;
}

std::vector<Field> ImpactFields(const Impact& i, bool with_cycle) {
  using namespace display;
  std::vector<Field> f = {TextField("kind", i.kind),
                          {"crank", kDegree, i.crank_rad, 4},
                          {"speed", kMPerS, i.speed_m_s, 4},
                          {"energy_lost", kJoule, i.energy_lost_J, 4}};
  if (with_cycle) f.push_back(CountField("cycle", i.cycle));
  return f;
}

std::vector<Field> CycleFields(const CycleSummary& c) {
  using namespace display;
  return {CountField("index", c.index),
          {"start", kDegree, c.start_rad, 1},
          CountField("impacts", c.impacts),
          CountField("jumps", c.jumps),
          {"jump", kDegree, c.jump_rad, 3},
          {"max_gap", kMm, c.max_gap_m, 4},
          {"end_lift", kMm, FiniteOrNone(c.end_lift_m), 6},
          {"end_velocity", kMPerS, FiniteOrNone(c.end_velocity_m_s), 6},
          {"energy_residual", kNone, FiniteOrNone(c.energy_residual), 3}};
}

}  // namespace needle
