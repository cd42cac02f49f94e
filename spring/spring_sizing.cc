#include "spring/spring_sizing.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "lib/units.h"
#include "spring/resonance.h"

namespace needle {
namespace {

// The installed length is made this much longer than the gap needs, so that round-off in
// L₁ = L₀ − P₀/k cannot fail the check's gap by 1e-17 m.
constexpr double kLengthSlack_m = 1e-9;

SizingRule Rule(std::string key, std::string name, std::string unit, double value, double limit,
                bool at_most) {
  SizingRule r =
      VerdictRow::Unjudged(std::move(key), std::move(name), std::move(unit), at_most, limit);
  r.Judge(value);
  return r;
}

// The fatigue rule: the criterion's n_f at least the duty's factor (and 1).
SizingRule FatigueRule(const FatigueCheck& f, const SizingDuty& duty, const std::string& where) {
  return Rule("fatigue",
              std::string("spring fatigue safety factor (") + CriterionInfo(f.criterion).title +
                  where + ")",
              "", f.safety_factor, std::max(1.0, duty.min_fatigue_factor), false);
}

// L₀ = L₁ + P₀/k (the preload's deflection), rounded up to the space's free-length step.
double FreeLength(const SizingSpace& space, double installed_m, double preload_deflection_m) {
  const double free = installed_m + preload_deflection_m;
  if (!(space.free_length_step_m > 0.0)) return free;
  // Whole nanometres, so that the written free length is the step's decimal.
  return std::round(std::ceil(free / space.free_length_step_m - 1e-9) * space.free_length_step_m *
                    1e9) /
         1e9;
}

// The check's own lengths, coil counts, S_a and surge of `g` (its free length aside): a probe
// with a free length no preload reaches.
HelicalSpringCheck Probe(HelicalGeometry g, double stroke_m, double speed_rpm, EngineCycle cycle) {
  g.free_length_m = 1e3;
  return CheckHelicalSpring(g, 0.0, stroke_m, speed_rpm, cycle);
}

std::vector<double> CoilCounts(const SizingSpace& s) {
  std::vector<double> out;
  for (int i = 0;; ++i) {
    const double n = s.min_active_coils + i * s.active_coil_step;
    if (n > s.max_active_coils + 1e-9) break;
    out.push_back(n);
    if (!(s.active_coil_step > 0.0)) break;
  }
  return out;
}

// The candidate's geometry, its free length aside.
HelicalGeometry CandidateGeometry(const SizingSpace& space, int wire_index, double coil_m,
                                  double active_coils) {
  const SizingWire& w = space.wires[wire_index];
  HelicalGeometry g;
  g.wire_m = w.wire_m;
  g.coil_m = coil_m;
  g.active_coils = active_coils;
  g.shear_modulus_Pa = w.shear_modulus_Pa;
  g.density_kg_m3 = w.density_kg_m3;
  g.tensile_Pa = w.tensile_Pa;
  g.grade = w.grade;
  g.shot_peened = space.shot_peened;
  g.ends = space.ends;
  g.stress_factor = space.stress_factor;
  g.fatigue_criterion = space.fatigue_criterion;
  g.allowable_fraction = space.allowable_fraction;
  return g;
}

struct Group {
  int wire = 0;
  double coil_m = 0.0;
  double bound = 0.0;         // a lower bound of the objective over the group's coil counts
  std::vector<double> coils;  // the counts to try: the space's, or the one a stated rate asks
};

// The coil counts of (wire, D): the space's; with a stated rate k, the fewest on the space's
// steps whose rate G d⁴/(8 D³ n) is at most k (the textbooks round n up), within one step of
// the exact count: none when that count lies outside the space's range (far too soft a spring
// at its fewest coils is not the stated one).
std::vector<double> GroupCoils(const SizingSpace& space, const SizingDuty& duty,
                               const std::vector<double>& coils, int wire, double coil_m) {
  if (!duty.rate_N_m) return coils;
  HelicalGeometry one = CandidateGeometry(space, wire, coil_m, 1.0);
  const double needed = HelicalRate(one) / *duty.rate_N_m;  // n at exactly the rate
  for (double n : coils) {
    if (n >= needed * (1.0 - 1e-12)) {
      if (n - space.active_coil_step >= needed * (1.0 + 1e-12)) return {};  // below the range
      return {n};
    }
  }
  return {};
}

// The objective's value of a (wire, D) group at its fewest coils: a lower bound over the group.
double GroupBound(const SizingSpace& space, const SizingDuty& duty, SizingObjective objective,
                  const Group& gr) {
  const HelicalGeometry low = CandidateGeometry(space, gr.wire, gr.coil_m, gr.coils.front());
  const HelicalSpringCheck p = Probe(low, duty.stroke_m, 0.0, duty.cycle);
  switch (objective) {
    case SizingObjective::kMass:
      return CoilMassKg(low, p.total_coils);
    case SizingObjective::kHeight: {
      const double gap = duty.min_gap_m ? *duty.min_gap_m : p.min_clearance_m;
      return std::max(space.min_installed_m, p.solid_length_m + duty.stroke_m + gap);
    }
    case SizingObjective::kDiameter:
      return (gr.coil_m + low.wire_m) * 1e3;  // the outer diameter, exact for the group
    case SizingObjective::kStress:
      break;
  }
  return -INFINITY;
}

}  // namespace

const std::vector<double>& R40PreferredNumbers() {
  static const std::vector<double> r40 = {
      1.00, 1.06, 1.12, 1.18, 1.25, 1.32, 1.40, 1.50, 1.60, 1.70, 1.80, 1.90, 2.00, 2.12,
      2.24, 2.36, 2.50, 2.65, 2.80, 3.00, 3.15, 3.35, 3.55, 3.75, 4.00, 4.25, 4.50, 4.75,
      5.00, 5.30, 5.60, 6.00, 6.30, 6.70, 7.10, 7.50, 8.00, 8.50, 9.00, 9.50};
  return r40;
}

std::vector<double> PreferredWireDiameters(double lo_m, double hi_m) {
  std::vector<double> out;
  for (double decade = 1e-5; decade <= 1.0; decade *= 10.0) {
    for (double r : R40PreferredNumbers()) {
      const double d = std::round(r * decade * 1e9) / 1e9;  // whole nanometres: 0.0045 exactly
      if (d >= lo_m * (1 - 1e-12) && d <= hi_m * (1 + 1e-12)) out.push_back(d);
    }
  }
  return out;
}

std::string SizingObjectiveName(SizingObjective o) {
  switch (o) {
    case SizingObjective::kMass:
      return "mass";
    case SizingObjective::kHeight:
      return "height";
    case SizingObjective::kStress:
      return "stress";
    case SizingObjective::kDiameter:
      return "diameter";
  }
  return "?";
}

bool BetterSpring(const SizedSpring& a, const SizedSpring& b) {
  if (a.objective != b.objective) return a.objective < b.objective;
  if (a.mass_kg != b.mass_kg) return a.mass_kg < b.mass_kg;
  if (a.wire_index != b.wire_index) return a.wire_index < b.wire_index;
  if (a.geometry.coil_m != b.geometry.coil_m) return a.geometry.coil_m < b.geometry.coil_m;
  return a.geometry.active_coils < b.geometry.active_coils;
}

SizedSpring EvaluateSpring(const SizingSpace& space, const SizingDuty& duty, int wire_index,
                           double coil_m, double active_coils, SizingObjective objective,
                           bool full) {
  if (wire_index < 0 || wire_index >= static_cast<int>(space.wires.size()))
    throw std::invalid_argument("EvaluateSpring: wire index out of range");
  const SizingWire& w = space.wires[wire_index];
  SizedSpring s;
  s.wire_index = wire_index;
  s.geometry = CandidateGeometry(space, wire_index, coil_m, active_coils);
  HelicalGeometry& g = s.geometry;
  s.rate_N_m = HelicalRate(g);
  s.active_mass_kg = ActiveSpringMassKg(g);
  const HelicalSpringCheck probe = Probe(g, duty.stroke_m, duty.speed_rpm, duty.cycle);
  s.total_coils = probe.total_coils;
  s.mass_kg = CoilMassKg(g, s.total_coils);
  s.objective = s.mass_kg;
  double h = duty.stroke_m;
  if (duty.closed_load_N && duty.open_load_N)  // judged at P₂, as the books judge a design
    h = std::max(h, (*duty.open_load_N - *duty.closed_load_N) / s.rate_N_m);
  const double gap = duty.min_gap_m ? *duty.min_gap_m : probe.min_clearance_m;
  const std::string gap_name =
      duty.min_gap_m ? "coil gap at full lift (stated)" : "coil gap at full lift (S_a, EN 13906-1)";
  const double need = probe.solid_length_m + h + gap;  // the shortest L₁ that keeps the gap
  const auto done = [&](SizingRule r) {
    const bool ok = r.passes();
    s.rules.push_back(std::move(r));
    return !ok && !full;
  };
  // Fewer coils or a longer space only: monotone in n.
  if (need > space.max_installed_m) {
    if (done(Rule("coil_gap", gap_name, "mm",
                  (space.max_installed_m - probe.solid_length_m - h) * 1e3, gap * 1e3, false)))
      return s;
  }
  if (duty.speed_rpm > 0.0) {
    if (done(Rule("surge_ratio", "first surge mode over the cam frequency f_1/f_cam", "",
                  probe.surge_ratio, duty.min_surge_ratio, false)))
      return s;
  }
  if (!full && duty.preload_floor_N > 0.0) {
    // The screen at the floor preload: stress and fatigue only worsen above it.
    HelicalGeometry long_one = g;
    long_one.free_length_m = 1e3;
    const HelicalSpringCheck f =
        CheckHelicalSpring(long_one, duty.preload_floor_N, h, duty.speed_rpm, duty.cycle);
    if (done(Rule("stress", "shear stress at full lift (at the floor preload)", "MPa",
                  f.stress_full_lift_Pa * 1e-6, f.allowable_stress_Pa * 1e-6, true)))
      return s;
    if (f.fatigue_judged && done(FatigueRule(f.fatigue, duty, ", at the floor preload"))) return s;
    s.rules.clear();
    if (duty.speed_rpm > 0.0) {  // the surge rule judged above, kept
      s.rules.push_back(Rule("surge_ratio", "first surge mode over the cam frequency f_1/f_cam", "",
                             probe.surge_ratio, duty.min_surge_ratio, false));
    }
  }
  const PreloadNeed p = duty.preload(s.rate_N_m, s.active_mass_kg);
  s.preload_N = std::ceil(p.preload_N * 10.0 - 1e-9) / 10.0;  // up to 0.1 N, as written
  s.preload_rule = p.rule;
  if (p.required_N && done(Rule("preload", "stated preload against the duty's " + p.required_rule,
                                "N", s.preload_N, *p.required_N, false)))
    return s;
  if (duty.closed_load_N && duty.open_load_N &&
      done(Rule("open_load", "force after the stroke P1 + k h (judged at the stated P2)", "N",
                s.preload_N + s.rate_N_m * duty.stroke_m, *duty.open_load_N, true)))
    return s;
  g.free_length_m = FreeLength(space, std::max(space.min_installed_m, need + kLengthSlack_m),
                               s.preload_N / s.rate_N_m);
  s.installed_m = g.free_length_m - s.preload_N / s.rate_N_m;
  if (objective == SizingObjective::kHeight) s.objective = s.installed_m;
  if (objective == SizingObjective::kDiameter) s.objective = (g.coil_m + g.wire_m) * 1e3;
  if (s.installed_m > space.max_installed_m && need <= space.max_installed_m) {
    if (done(Rule("installed_length", "installed length (free length rounded up)", "mm",
                  s.installed_m * 1e3, space.max_installed_m * 1e3, true)))
      return s;
  }
  s.check = CheckHelicalSpring(g, s.preload_N, h, duty.speed_rpm, duty.cycle);
  const HelicalSpringCheck& c = *s.check;
  if (objective == SizingObjective::kStress) s.objective = c.stress_full_lift_Pa * 1e-6;
  if (need <= space.max_installed_m) {
    if (done(Rule("coil_gap", gap_name, "mm", c.clearance_full_lift_m * 1e3, gap * 1e3, false)))
      return s;
  }
  if (done(Rule("stress", "shear stress at full lift", "MPa", c.stress_full_lift_Pa * 1e-6,
                c.allowable_stress_Pa * 1e-6, true)))
    return s;
  if (c.fatigue_judged) {
    if (done(FatigueRule(c.fatigue, duty, ""))) return s;
  }
  s.buckling_m = BucklingDeflection(g, w.elastic_modulus_Pa, space.end_fixation);
  if (duty.buckling) {
    const double deflection = g.free_length_m - s.installed_m + h;
    if (done(Rule("buckling", "buckling deflection s_K over the deflection at full lift", "mm",
                  s.buckling_m * 1e3, deflection * 1e3, false)))
      return s;
  }
  s.pass = std::all_of(s.rules.begin(), s.rules.end(), std::mem_fn(&SizingRule::passes));
  return s;
}

namespace {

// After a spring fails: whether more coils can only fail too (the surge ratio f_e ∝ 1/n, and the
// length needed, which grows with n).
bool MoreCoilsOnlyWorse(const SizedSpring& s) {
  const std::string& failed = s.rules.back().key;
  return failed == "surge_ratio" || (failed == "coil_gap" && !s.check);
}

// The (wire, D) groups of the space, each with its coil counts and its objective's lower bound,
// counting the candidates and the groups no coil count gives the stated rate.
std::vector<Group> SpaceGroups(const SizingSpace& space, const SizingDuty& duty,
                               SizingObjective objective, const std::vector<double>& coils,
                               SizingResult& r) {
  std::vector<Group> groups;
  for (int wi = 0; wi < static_cast<int>(space.wires.size()); ++wi) {
    const double d = space.wires[wi].wire_m;
    double lo = space.min_index * d, hi = space.max_index * d;
    if (space.min_inner_m) lo = std::max(lo, *space.min_inner_m + d);
    if (space.max_outer_m) hi = std::min(hi, *space.max_outer_m - d);
    const long first = static_cast<long>(std::ceil(lo / space.coil_step_m - 1e-9));
    const long last = static_cast<long>(std::floor(hi / space.coil_step_m + 1e-9));
    for (long k = first; k <= last; ++k) {
      Group gr;
      gr.wire = wi;
      gr.coil_m = std::round(k * space.coil_step_m * 1e9) / 1e9;
      if (!(gr.coil_m > d)) continue;
      gr.coils = GroupCoils(space, duty, coils, wi, gr.coil_m);
      r.candidates += static_cast<long>(gr.coils.size());
      if (gr.coils.empty()) {
        ++r.rate_misses;
        continue;
      }
      gr.bound = GroupBound(space, duty, objective, gr);
      groups.push_back(gr);
    }
  }
  return groups;
}

// Every passing spring of the space, for the front (the same early exits as the search).
std::vector<SizedSpring> PassingSprings(const SizingSpace& space, const SizingDuty& duty,
                                        SizingObjective objective, const std::vector<Group>& groups,
                                        SizingResult& r) {
  std::vector<SizedSpring> passing;
  for (const Group& gr : groups) {
    for (double n : gr.coils) {
      SizedSpring s = EvaluateSpring(space, duty, gr.wire, gr.coil_m, n, objective, false);
      ++r.front_evaluated;
      if (s.pass) {
        passing.push_back(std::move(s));
        continue;
      }
      if (MoreCoilsOnlyWorse(s)) break;
    }
  }
  return passing;
}

// Nothing passes: the candidate whose worst rule fails least, every rule evaluated.
void FindClosest(const SizingSpace& space, const SizingDuty& duty, SizingObjective objective,
                 const std::vector<Group>& groups, SizingResult& r) {
  double least = INFINITY;
  for (const Group& gr : groups) {
    for (double n : gr.coils) {
      SizedSpring s = EvaluateSpring(space, duty, gr.wire, gr.coil_m, n, objective, true);
      double worst = 0.0;
      const SizingRule* rule = nullptr;
      for (const SizingRule& x : s.rules) {
        if (x.Violation() > worst) {
          worst = x.Violation();
          rule = &x;
        }
      }
      if (rule && worst < least) {
        least = worst;
        r.binding = *rule;
        r.closest = std::move(s);
      }
    }
  }
}

}  // namespace

SizingResult SizeSpring(const SizingSpace& space, const SizingDuty& duty,
                        const SizingOptions& options) {
  if (space.wires.empty()) throw std::invalid_argument("SizeSpring: the space has no wire");
  if (!duty.preload) throw std::invalid_argument("SizeSpring: the duty has no preload rule");
  const SizingObjective objective = options.objective;
  const std::vector<double> coils = CoilCounts(space);
  SizingResult r;
  if (coils.empty()) return r;
  std::vector<Group> groups = SpaceGroups(space, duty, objective, coils, r);
  r.groups = static_cast<long>(groups.size());
  std::stable_sort(groups.begin(), groups.end(),
                   [](const Group& a, const Group& b) { return a.bound < b.bound; });
  const auto insert = [&](const SizedSpring& s) {
    r.best.insert(std::upper_bound(r.best.begin(), r.best.end(), s, BetterSpring), s);
    if (static_cast<int>(r.best.size()) > options.keep) r.best.pop_back();
  };
  const bool monotone = objective == SizingObjective::kMass;  // mass grows with n
  for (const Group& gr : groups) {
    const bool full_list = static_cast<int>(r.best.size()) >= options.keep;
    if (!options.exhaustive && full_list && gr.bound > r.best.back().objective) break;
    std::optional<SizedSpring> group_best;
    for (double n : gr.coils) {
      SizedSpring s =
          EvaluateSpring(space, duty, gr.wire, gr.coil_m, n, objective, options.exhaustive);
      ++r.evaluated;
      if (s.pass) {
        ++r.passed;
        if (!group_best || BetterSpring(s, *group_best)) group_best = std::move(s);
        if (monotone && !options.exhaustive) break;
        continue;
      }
      if (options.exhaustive) continue;
      if (MoreCoilsOnlyWorse(s)) break;
      if (monotone && static_cast<int>(r.best.size()) >= options.keep &&
          s.mass_kg > r.best.back().objective)
        break;
    }
    if (group_best) insert(*group_best);
  }
  if (options.front && !r.best.empty())
    r.front = MassFatigueFront(PassingSprings(space, duty, objective, groups, r));
  if (r.best.empty()) FindClosest(space, duty, objective, groups, r);
  return r;
}

double CoilMassKg(const HelicalGeometry& g, double coils) {
  return g.density_kg_m3 * kPi * kPi * g.wire_m * g.wire_m * g.coil_m * coils / 4.0;
}

std::vector<SizedSpring> MassFatigueFront(const std::vector<SizedSpring>& springs) {
  std::vector<SizedSpring> sorted = springs;
  std::stable_sort(sorted.begin(), sorted.end(), [](const SizedSpring& a, const SizedSpring& b) {
    return a.mass_kg < b.mass_kg;
  });
  std::vector<SizedSpring> front;
  double best = -INFINITY;
  for (const SizedSpring& s : sorted) {
    if (!s.check || !s.check->fatigue_judged) continue;  // no factor to trade against
    const double f = s.check->fatigue.safety_factor;
    if (f > best) {
      front.push_back(s);
      best = f;
    }
  }
  return front;
}

std::vector<Field> SizingRuleFields(const SizingRule& x) {
  return {TextField("key", x.key),
          TextField("unit", x.unit),
          {"value", display::kNone, FiniteOrNone(x.value), 2},
          {"limit", display::kNone, x.limit, 2},
          FlagField("at_most", x.at_most),
          {"margin", display::kNone, FiniteOrNone(x.margin), 2},
          FlagField("pass", x.passes())};
}

std::vector<Field> SizedSpringFields(const SizedSpring& s, const SizingSpace& space) {
  using namespace display;
  const HelicalGeometry& g = s.geometry;
  std::vector<Field> f = {TextField("wire", space.wires[s.wire_index].label),
                          {"wire", kMm, g.wire_m, 2},
                          {"coil", kMm, g.coil_m, 1},
                          {"active_coils", kNone, g.active_coils, 1},
                          {"total_coils", kNone, s.total_coils, 1},
                          {"free_length", kMm, g.free_length_m, 2},
                          {"installed_length", kMm, s.installed_m, 2},
                          {"preload", kN, s.preload_N, 1},
                          TextField("preload_rule", s.preload_rule),
                          {"rate", kNPerMm, s.rate_N_m, 2},
                          {"mass", kKg, s.mass_kg, 3},
                          FlagField("pass", s.pass)};
  if (s.check) {
    // None where the criterion does not judge the wire (Zimmerli's data: below 10 mm).
    f.push_back(
        {"fatigue_safety_factor", kNone,
         s.check->fatigue_judged ? FiniteOrNone(s.check->fatigue.safety_factor) : std::nullopt, 2});
  }
  return f;
}

}  // namespace needle
