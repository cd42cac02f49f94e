// The sizing's JSON object and text, and the sized case: size_writer.h.
#include "apps/report/size_writer.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/report/result_writers.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {
namespace {

nlohmann::json SpringJson(const SizedSpring& s, const SizingSpace& space) {
  nlohmann::json j = nlohmann::json::object();
  PutFields(j, SizedSpringFields(s, space));
  if (!s.rules.empty()) j["rules"] = RecordList(s.rules, SizingRuleFields);
  return j;
}

std::string SpringLine(const SizedSpring& s, const SizingSpace& space) {
  const std::vector<Field> f = SizedSpringFields(s, space);
  return space.wires[s.wire_index].label + " d " + TextAt(f, "wire_mm") + ", D " +
         TextAt(f, "coil_mm") + ", " + TextAt(f, "active_coils") + " active coils, " +
         TextAt(f, "mass_kg") + ", n_f " +
         (s.check && s.check->fatigue_judged ? Fixed(s.check->fatigue.safety_factor, 2)
                                             : std::string("not judged"));
}

// "  NAME: VALUE <= LIMIT, margin M, VERDICT" (an infinite value: buckling's imaginary root).
std::string RowText(const std::string& name, double value, double limit, bool at_most,
                    double margin, const std::string& unit, const std::string& verdict) {
  const std::string u = unit.empty() ? "" : " " + unit;
  if (!std::isfinite(value)) return "  " + name + ": none at any deflection, " + verdict + "\n";
  const int d = DecimalsApart(value, limit, 2);
  return "  " + name + ": " + Fixed(value, d) + u + (at_most ? " <= " : " >= ") + Fixed(limit, d) +
         u + ", margin " + Fixed(margin, d) + u + ", " + verdict + "\n";
}

// The JSON object of a sizing (size --json).
nlohmann::json SizeJson(const BoundCase& c, const SizeResult& r, const SizedSpring* chosen,
                        const CheckResult* check) {
  const SizingSpace& sp = r.space;
  nlohmann::json j;
  j = {{"case", c.path},
       {"objective", r.objective},
       {"space", r.space_note},
       {"mass_without_spring_kg", r.mass_without_spring_kg},
       {"mass_without_spring_source", r.mass_note},
       {"pass", r.pass}};
  PutFields(j, {{"stroke", display::kMm, r.stroke_m}});
  if (!r.stroke_note.empty()) j["stroke_source"] = r.stroke_note;
  if (!r.stages.empty()) j["stages"] = RecordList(r.stages, SizeStageFields);
  j["no_fit"] = r.no_fit.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.no_fit);
  j["spring"] = chosen ? SpringJson(*chosen, sp) : nullptr;
  if (r.case_spring_mass_kg) j["case_spring_mass_kg"] = *r.case_spring_mass_kg;
  if (check) {
    j["check"] = {
        {"pass", check->pass}, {"failing", check->failing}, {"warnings", check->warnings}};
    for (const LimitRow& x : check->limits) {
      j["check"]["limits"].push_back({{"key", x.key},
                                      {"value", Finite(x.value)},
                                      {"limit", Finite(x.limit)},
                                      {"margin", Finite(x.margin)},
                                      {"verdict", x.verdict}});
    }
    if (check->sweep && check->sweep->n_dyn_rpm) j["check"]["n_dyn_rpm"] = *check->sweep->n_dyn_rpm;
  }
  for (const SizedSpring& s : r.closed_form.best) j["candidates"].push_back(SpringJson(s, sp));
  for (const VerifiedSpring& v : r.verified) {
    j["verified"].push_back({{"spring", SpringJson(v.spring, sp)},
                             {"pass", v.check.pass},
                             {"failing", v.check.failing},
                             {"seconds", v.seconds}});
  }
  for (const SizedSpring& s : r.closed_form.front) j["front"].push_back(SpringJson(s, sp));
  return j;
}

// The text of a sizing.
std::string SizeText(const BoundCase& c, const SizeResult& r, const SizedSpring* chosen,
                     const CheckResult* check) {
  const SizingSpace& sp = r.space;
  const std::vector<SizedSpring>& front = r.closed_form.front;
  std::ostringstream t;
  if (!c.title.empty()) t << c.title << '\n';
  t << "space: " << r.space_note << "; objective: least " << r.objective << '\n';
  t << "duty: stroke " << FieldText({"stroke", display::kMm, r.stroke_m, 3})
    << (r.stroke_note.empty() ? "" : " (" + r.stroke_note + ")")
    << "; moving mass without the spring " << Fixed(r.mass_without_spring_kg, 4) << " kg ("
    << r.mass_note << ")\n";
  for (const SizeStage& s : r.stages) {
    t << "stage " << s.name << ": " << s.in << " in, " << s.kept << " kept, "
      << Fixed(s.seconds * 1e3, 1) << " ms (" << s.note << ")\n";
  }
  if (chosen) {
    const HelicalGeometry& g = chosen->geometry;
    const std::vector<Field> f = SizedSpringFields(*chosen, sp);
    t << (r.pass ? "spring: " : "closest spring: ") << sp.wires[chosen->wire_index].label
      << ", wire " << TextAt(f, "wire_mm") << ", coil " << TextAt(f, "coil_mm") << " (OD "
      << FieldText({"outer_diameter", display::kMm, g.coil_m + g.wire_m, 1}) << "), "
      << TextAt(f, "active_coils") << " active / " << TextAt(f, "total_coils")
      << " total coils, free length " << TextAt(f, "free_length_mm") << ", installed "
      << TextAt(f, "installed_length_mm") << '\n';
    t << "  preload " << TextAt(f, "preload_N") << " ("
      << FieldText({"preload", display::kKgForce, chosen->preload_N, 1}) << "; set by "
      << chosen->preload_rule << "), rate " << TextAt(f, "rate_N_mm") << ", mass "
      << TextAt(f, "mass_kg")
      << (r.case_spring_mass_kg ? " (the case's spring " + Fixed(*r.case_spring_mass_kg, 3) + " kg)"
                                : "")
      << '\n';
    t << (chosen->rules.empty()
              ? "rules: not applied (the case's own spring as stated; the check below judges it)\n"
              : "rules (value, limit, margin):\n");
    for (const SizingRule& x : chosen->rules)
      t << RowText(x.name, x.value, x.limit, x.at_most, x.margin, x.unit, x.Shouted());
  }
  if (check) {
    t << "check of the sized case (limits, as needle check):\n";
    for (const LimitRow& x : check->limits)
      t << (x.verdict == "not judged"
                ? "  " + x.name + ": not judged (" + x.note + ")\n"
                : RowText(x.name, x.value, x.limit, x.at_most, x.margin, x.unit, x.verdict));
  }
  for (const VerifiedSpring& v : r.verified) {
    if (!v.check.pass)
      t << "rejected by the check: " << SpringLine(v.spring, sp) << ": "
        << (v.check.failing.empty() ? "fails" : v.check.failing.front()) << '\n';
  }
  for (size_t i = 1; i < r.closed_form.best.size(); ++i)
    t << "next best: " << SpringLine(r.closed_form.best[i], sp) << '\n';
  const size_t every = front.size() / 8 + 1;  // at most 8 and the last (--json: all)
  for (size_t i = 0; i < front.size(); ++i)
    if (i % every == 0 || i + 1 == front.size())
      t << "front (mass, n_f) " << i + 1 << "/" << front.size() << ": " << SpringLine(front[i], sp)
        << '\n';
  if (!r.pass) t << "no fit: " << r.no_fit << '\n';
  t << "overall: " << (r.pass ? "pass" : "FAIL") << '\n';
  return t.str();
}

}  // namespace

CommandOutput WriteSize(const BoundCase& c, const SizeResult& r, const SizeWriting& w) {
  const SizingSpace& sp = r.space;
  const SizedSpring* chosen = r.winner ? &r.verified[*r.winner].spring
                              : r.pass && !r.closed_form.best.empty() ? &r.closed_form.best[0]
                              : r.closed_form.closest                 ? &*r.closed_form.closest
                                                                      : nullptr;
  const CheckResult* check = r.winner ? &r.verified[*r.winner].check : nullptr;
  CommandOutput out;
  out.status = r.pass ? 0 : 1;
  if (r.pass && chosen && w.case_text) {
    const BoundCase sized = CaseWithSpring(c, *chosen, sp, r.mass_without_spring_kg);
    out.case_file = SizedCaseText(*w.case_text, sized.needle->mass_kg, *chosen, sp);
  }
  if (w.json) {
    out.json = SizeJson(c, r, chosen, check);
  } else {
    out.text = SizeText(c, r, chosen, check);
  }
  return out;
}

}  // namespace needle
