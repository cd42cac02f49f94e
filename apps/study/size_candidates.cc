// needle size's second stage (apps/study/size_candidates.h).
#include "apps/study/size_candidates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "lib/output.h"
#include "lib/units.h"
#include "spring/helical_spring.h"

namespace needle {

namespace sizing_internal {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::string Mm(double m, int digits) { return Fixed(m * 1e3, digits) + " mm"; }

}  // namespace sizing_internal

namespace {

using sizing_internal::Mm;
using sizing_internal::Seconds;

// Whether two springs are the same spring of the space: one wire (its grade and R_m), D, n.
bool SameSpring(const SizedSpring& a, const SizedSpring& b) {
  const auto same = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::abs(y); };
  return a.wire_index == b.wire_index && same(a.geometry.coil_m, b.geometry.coil_m) &&
         same(a.geometry.active_coils, b.geometry.active_coils);
}

// The case's own helical spring as stated (wire, D, coils, free length, preload), a candidate
// when it fits the space's diameters and installed length (else `why`); its wire is added to
// `sp` when not one of its sizes (the sizes the closed form searched stay as they were).
std::optional<SizedSpring> OwnSpring(const BoundCase& c, SizingSpace& sp, const SizingDuty& duty,
                                     std::string& why) {
  const std::optional<HelicalGeometry>& own = c.spring->helical;
  if (!own) return std::nullopt;
  const double tol = 1e-9, p0 = c.spring->preload_N;
  const double installed = own->free_length_m - p0 / HelicalRate(*own);
  if ((sp.max_outer_m && own->coil_m + own->wire_m > *sp.max_outer_m + tol) ||
      (sp.min_inner_m && own->coil_m - own->wire_m < *sp.min_inner_m - tol) ||
      installed > sp.max_installed_m + tol || installed < sp.min_installed_m - tol) {
    why = "it does not fit the space's diameters or installed length";
    return std::nullopt;
  }
  int wire = -1;
  for (size_t i = 0; i < sp.wires.size(); ++i) {
    const SizingWire& w = sp.wires[i];
    if (std::abs(w.wire_m - own->wire_m) <= 1e-9 * own->wire_m &&
        std::abs(w.tensile_Pa - own->tensile_Pa) <= 1e-6 * own->tensile_Pa)
      wire = static_cast<int>(i);
  }
  if (wire < 0) {  // its own wire, not one of the space's sizes: added for it alone
    SizingWire w;
    w.label = "the case's wire";
    w.grade = own->grade;
    w.wire_m = own->wire_m;
    w.tensile_Pa = own->tensile_Pa;
    w.shear_modulus_Pa = own->shear_modulus_Pa;
    w.density_kg_m3 = own->density_kg_m3;
    sp.wires.push_back(w);
    wire = static_cast<int>(sp.wires.size()) - 1;
  }
  SizedSpring s;
  s.wire_index = wire;
  s.geometry = *own;
  s.preload_N = p0;
  s.preload_rule = "the case's own spring, as stated";
  s.rate_N_m = HelicalRate(*own);
  s.installed_m = installed;
  s.active_mass_kg = ActiveSpringMassKg(*own);
  s.check = CheckHelicalSpring(*own, p0, duty.stroke_m, duty.speed_rpm, duty.cycle);
  s.total_coils = s.check->total_coils;
  s.mass_kg = CoilMassKg(*own, s.total_coils);
  s.objective = s.mass_kg;
  s.buckling_m = BucklingDeflection(*own, sp.wires[wire].elastic_modulus_Pa, sp.end_fixation);
  s.pass = true;  // no closed-form rules: the check judges it
  return s;
}

// The springs the check walks, in order: the closed form's best (objective order), then the
// front between mass and fatigue factor in mass order, each winding once.
std::vector<SizedSpring> Candidates(const SizingResult& closed) {
  std::vector<SizedSpring> out;
  const auto add = [&out](const SizedSpring& s) {
    for (const SizedSpring& o : out)
      if (SameSpring(o, s)) return;
    out.push_back(s);
  };
  for (const SizedSpring& s : closed.best) add(s);
  for (const SizedSpring& s : closed.front) add(s);
  return out;
}

// The no-fit line: the checked spring whose binding row (its worst failing limit) fails least,
// with that row.
std::string NoFitLine(const std::vector<VerifiedSpring>& verified) {
  const VerifiedSpring* best = nullptr;
  const LimitRow* best_row = nullptr;
  double best_violation = INFINITY;
  for (const VerifiedSpring& v : verified) {
    const LimitRow* row = nullptr;
    for (const LimitRow& x : v.check.limits)
      if (x.verdict == "fail" && (!row || x.Violation() > row->Violation())) row = &x;
    const double violation = row ? row->Violation() : INFINITY;
    if (!best || violation < best_violation) {
      best = &v;
      best_row = row;
      best_violation = violation;
    }
  }
  std::ostringstream m;
  m << "none of the " << verified.size() << " springs checked passes; the closest, d "
    << Mm(best->spring.geometry.wire_m) << ", D " << Mm(best->spring.geometry.coil_m, 1) << ", n "
    << Fixed(best->spring.geometry.active_coils, 1) << " (" << best->spring.preload_rule
    << "), binds at ";
  if (best_row) {
    m << best_row->name << ": " << Fixed(best_row->value, 2) << best_row->UnitSuffix()
      << " against " << (best_row->at_most ? "at most " : "at least ") << Fixed(best_row->limit, 2)
      << best_row->UnitSuffix();
  } else {
    m << (best->check.failing.empty() ? "a failing part" : best->check.failing.front());
  }
  return m.str();
}

}  // namespace

// Stage 2 (docs/sizing.md): the candidates checked by CheckScene in order until one passes or
// [sizing] verify are checked; then, if none passed, the case's own spring as stated.
void VerifyCandidates(const BoundCase& c, const LiftLaw& law, const SizingSection& z,
                      const SizingDuty& duty, const SizeOptions& options, SizeResult& r) {
  const auto t1 = std::chrono::steady_clock::now();
  const std::vector<SizedSpring> walk = Candidates(r.closed_form);
  const size_t verify = std::min(static_cast<size_t>(z.verify), walk.size());
  CheckOptions co;
  co.threads = options.threads;
  co.record_series = false;
  const auto check = [&](const SizedSpring& s) {
    const auto tv = std::chrono::steady_clock::now();
    VerifiedSpring v;
    v.spring = s;
    v.sized_case = CaseWithSpring(c, s, r.space, r.mass_without_spring_kg);
    v.check = CheckScene(v.sized_case, law, co);
    v.seconds = Seconds(tv);
    r.verified.push_back(std::move(v));
    if (r.verified.back().check.pass) r.winner = r.verified.size() - 1;
  };
  for (size_t i = 0; i < verify && !r.winner; ++i) check(walk[i]);
  // The case's own spring, as stated, when none passed (also when the closed form kept none).
  std::string own_note;
  if (z.verify > 0 && !r.winner) {
    std::string why;
    if (const std::optional<SizedSpring> own = OwnSpring(c, r.space, duty, why)) {
      check(*own);
      own_note = "; then the case's own spring, as stated";
    } else if (!why.empty()) {
      own_note = "; the case's own spring not checked: " + why;
    }
  }
  const size_t walked = r.verified.size() - (own_note.rfind("; then", 0) == 0 ? 1 : 0);
  SizeStage dyn{"check (dynamics, overspeed, coil masses, limits)",
                static_cast<long>(r.verified.size()), r.winner ? 1 : 0, Seconds(t1), ""};
  if (z.verify == 0) {
    dyn.note = "[sizing] verify = 0: not verified";
  } else if (walk.empty()) {
    dyn.note = "the closed form kept none" + own_note;
  } else {
    dyn.note = std::to_string(walked) + " of the " + std::to_string(walk.size()) +
               " candidates (the closed form's best, then the mass-fatigue front) checked, in "
               "order, until one passed" +
               (walk.size() > verify ? " or [sizing] verify = " + std::to_string(z.verify)
                                     : std::string()) +
               own_note;
  }
  r.stages.push_back(dyn);
  // verify = 0: the closed form's best, unverified (said so).
  r.pass = z.verify == 0 ? !walk.empty() : r.winner.has_value();
  if (r.pass) r.no_fit.clear();
  if (!r.pass && !r.verified.empty()) {
    const std::string closed = r.no_fit;  // the closed form's own diagnosis, when it kept none
    r.no_fit = NoFitLine(r.verified);
    if (!closed.empty()) r.no_fit = closed + "; " + r.no_fit;
  }
}

}  // namespace needle
