// [sizing]: what `needle size` may choose and what the spring must fit (sizing_section.h).
#include "apps/case/sizing_section.h"

#include <cmath>
#include <map>

#include "apps/case/section_reader.h"
#include "spring/wire_material.h"

namespace needle::case_internal {

namespace {

// A positive quantity, named as written when refused.
std::optional<double> PositiveQuantity(SectionReader& r, const std::string& name, Dimension dim,
                                       double scale, const std::string& unit) {
  const std::optional<double> v = r.OptionalQuantity(name, dim);
  if (v && !(*v > 0.0 && std::isfinite(*v)))
    r.Fail(r.last_key(), "must be positive, got " + Number(*v * scale) + " " + unit);
  return v;
}

// The textbook design problem's keys (sizing_section.h): a load pair or a rate, the stroke, a
// stated wire, the stress limit, factor and criterion.
void ReadDesignProblem(SectionReader& r, SizingSection& s) {
  if (auto o = r.OptionalString("objective")) {
    if (*o != "mass" && *o != "height" && *o != "stress" && *o != "diameter")
      r.Fail("objective",
             "expected \"mass\", \"height\", \"stress\" or \"diameter\", got \"" + *o + "\"");
    s.objective = *o;
  }
  s.closed_load_N = PositiveQuantity(r, "closed_load", Dimension::kForce, 1.0, "N");
  const std::string closed_key = s.closed_load_N ? r.last_key() : "closed_load_N";
  s.open_load_N = PositiveQuantity(r, "open_load", Dimension::kForce, 1.0, "N");
  const std::string open_key = s.open_load_N ? r.last_key() : "open_load_N";
  s.rate_N_m = PositiveQuantity(r, "rate", Dimension::kStiffness, 1e-3, "N/mm");
  if (s.closed_load_N && !s.open_load_N && !s.rate_N_m)
    r.Fail(closed_key, "needs open_load_N or rate_N_mm (P1 -> P2 over the stroke sets the rate)");
  if (s.open_load_N && !s.closed_load_N)
    r.Fail(open_key, "needs closed_load_N (P1 at the installed length)");
  if (s.open_load_N && s.rate_N_m)
    r.Fail(open_key, "give the open load or the rate, not both (the load pair sets the rate)");
  if (s.open_load_N && !(*s.open_load_N > *s.closed_load_N))
    r.Fail(open_key, "must be above " + closed_key + " (" + Number(*s.closed_load_N) +
                         " N): the spring is compressed further when open");
  s.stroke_m = PositiveQuantity(r, "stroke", Dimension::kLength, 1e3, "mm");
  s.tensile_Pa = PositiveQuantity(r, "tensile", Dimension::kPressure, 1e-6, "MPa");
  const std::string tensile_key = s.tensile_Pa ? r.last_key() : "tensile_MPa";
  s.shear_modulus_Pa = PositiveQuantity(r, "shear_modulus", Dimension::kPressure, 1e-9, "GPa");
  for (const std::string& g : s.grades) {
    if (s.tensile_Pa && g != "case")
      r.Fail(tensile_key,
             "a stated wire is a wire of its own; leave grades out (or give "
             "[\"case\"]) to size in it, not with grade \"" +
                 g + "\"");
  }
  if (s.tensile_Pa.has_value() != s.shear_modulus_Pa.has_value())
    r.Fail(s.tensile_Pa ? tensile_key : r.last_key(),
           "a stated wire needs both tensile_MPa and shear_modulus_GPa");
  if (auto f = r.OptionalNumber("allowable_stress_fraction")) {
    if (!(*f > 0.0 && *f <= 1.0))
      r.Fail("allowable_stress_fraction", "must be in (0, 1], got " + Number(*f));
    s.allowable_fraction = *f;
  }
  if (auto name = r.OptionalString("stress_correction")) {
    s.stress_factor = ParseStressFactor(*name);
    if (!s.stress_factor)
      r.Fail("stress_correction", "expected " + StressFactorChoice() + ", got \"" + *name + "\"");
  }
  if (auto name = r.OptionalString("fatigue_criterion")) {
    s.fatigue_criterion = ParseFatigueCriterion(*name);
    if (!s.fatigue_criterion)
      r.Fail("fatigue_criterion",
             "expected " + FatigueCriterionChoice() + ", got \"" + *name + "\"");
  }
}

}  // namespace

SizingSection ReadSizing(SectionReader r) {
  SizingSection s;
  std::map<std::string, std::string> written;  // quantity name → its key as written
  const auto key = [&written](const std::string& name) {
    const auto it = written.find(name);
    return it == written.end() ? name : it->second;
  };
  // An optional length in (0, hi] (in [0, hi] when `zero`), named as written.
  const auto length = [&](const std::string& name, double hi_m = 10.0, bool zero = false) {
    const std::optional<double> v = r.OptionalQuantity(name, Dimension::kLength);
    if (!v) return v;
    written[name] = r.last_key();
    if (!((zero ? *v >= 0.0 : *v > 0.0) && *v <= hi_m))
      r.Fail(r.last_key(), std::string("must be ") + (zero ? "≥ 0" : "positive") + " and at most " +
                               Number(hi_m * 1e3) + " mm, got " + Number(*v * 1e3) + " mm");
    return v;
  };
  // An optional plain number read as `v`, in [lo, hi], whole when `whole`.
  const auto number = [&r](std::optional<double> v, const std::string& name, double lo, double hi,
                           bool whole) {
    if (v && (!(*v >= lo && *v <= hi) || (whole && *v != std::floor(*v))))
      r.Fail(name, std::string("must be ") + (whole ? "a whole number " : "") + "in [" +
                       Number(lo) + ", " + Number(hi) + "], got " + Number(*v));
    return v;
  };

  s.grades = r.OptionalStringArray("grades").value_or(std::vector<std::string>{});
  for (const std::string& g : s.grades) {
    if (g != "case" && !ParseWireGrade(g))
      r.Fail("grades", "unknown grade \"" + g + "\"; expected " + WireGradeList() + " or \"case\"");
  }
  if (auto wires = r.OptionalQuantityArray("wire", Dimension::kLength)) {
    for (size_t i = 0; i < wires->size(); ++i) {
      if (!((*wires)[i] > 0.0 && (*wires)[i] <= 0.1))
        r.Fail(r.last_key(), "entry " + std::to_string(i) + " must be in (0, 100] mm, got " +
                                 Number((*wires)[i] * 1e3) + " mm");
    }
    if (wires->empty()) r.Fail(r.last_key(), "expected a non-empty array of wire diameters");
    written["wire"] = r.last_key();
    s.wire_m = *wires;
  }
  s.min_wire_m = length("min_wire", 0.1);
  s.max_wire_m = length("max_wire", 0.1);
  if (s.min_wire_m && s.max_wire_m && *s.min_wire_m > *s.max_wire_m)
    r.Fail(key("min_wire"), "is above " + key("max_wire") + ": the range is empty");
  const std::optional<double> installed = length("installed_length");
  s.min_installed_m = length("min_installed_length");
  s.max_installed_m = length("max_installed_length");
  if (installed && (s.min_installed_m || s.max_installed_m))
    r.Fail(key("installed_length"), "give it or its range (min_/max_installed_length), not both");
  if (installed) s.min_installed_m = s.max_installed_m = installed;
  if (s.min_installed_m && s.max_installed_m && *s.min_installed_m > *s.max_installed_m)
    r.Fail(key("min_installed_length"),
           "is above " + key("max_installed_length") + ": the range is empty");
  s.max_outer_m = length("max_outer_diameter");
  s.min_inner_m = length("min_inner_diameter");
  if (s.max_outer_m && s.min_inner_m && !(*s.min_inner_m < *s.max_outer_m))
    r.Fail(key("min_inner_diameter"),
           "must be below " + key("max_outer_diameter") + ": no coil fits between them");
  // The [spring] reader's own range of the index (EN 13906-1), so a sized spring reads back.
  s.min_index = number(r.OptionalNumber("min_index"), "min_index", 4.0, 20.0, false);
  s.max_index = number(r.OptionalNumber("max_index"), "max_index", 4.0, 20.0, false);
  if (s.min_index && s.max_index && *s.min_index > *s.max_index)
    r.Fail("min_index", "is above max_index: the range is empty");
  if (auto v = length("coil_step", 0.01)) s.coil_step_m = *v;
  s.min_active_coils =
      number(r.OptionalNumber("min_active_coils"), "min_active_coils", 2.0, 1000.0, false);
  s.max_active_coils =
      number(r.OptionalNumber("max_active_coils"), "max_active_coils", 2.0, 1000.0, false);
  if (s.min_active_coils && s.max_active_coils && *s.min_active_coils > *s.max_active_coils)
    r.Fail("min_active_coils", "is above max_active_coils: the range is empty");
  if (auto v = number(r.OptionalNumber("active_coil_step"), "active_coil_step", 0.01, 100.0, false))
    s.active_coil_step = *v;
  s.ends = r.OptionalString("ends");
  if (s.ends && *s.ends != "closed-ground" && *s.ends != "closed" && *s.ends != "open-ground" &&
      *s.ends != "open")
    r.Fail("ends", "expected \"closed-ground\", \"closed\", \"open-ground\" or \"open\", got \"" +
                       *s.ends + "\"");
  if (auto v = length("free_length_step", 0.01, /*zero=*/true)) s.free_length_step_m = *v;
  s.mass_without_spring_kg = r.OptionalQuantity("mass_without_spring", Dimension::kMass);
  if (s.mass_without_spring_kg && !(*s.mass_without_spring_kg > 0.0))
    r.Fail(r.last_key(), "must be positive, got " + Number(*s.mass_without_spring_kg));
  if (auto v = number(r.OptionalNumber("end_fixation"), "end_fixation", 0.1, 10.0, false))
    s.end_fixation = *v;
  if (auto v = number(r.OptionalNumber("candidates"), "candidates", 1, 100, true))
    s.candidates = static_cast<int>(*v);
  if (auto v = number(r.OptionalNumber("verify"), "verify", 0, 100, true))
    s.verify = static_cast<int>(*v);
  ReadDesignProblem(r, s);
  const bool one_wire = s.wire_m.size() == 1 && s.grades.size() <= 1;
  const bool one_index = s.min_index && s.max_index && *s.min_index == *s.max_index;
  const bool one_count =
      s.min_active_coils && s.max_active_coils && *s.min_active_coils == *s.max_active_coils;
  if (one_wire && one_index && one_count)
    r.Fail(key("wire"),
           "one wire, one index and one coil count leave nothing to choose; "
           "`needle check` judges a given spring");
  r.Finish();
  return s;
}

}  // namespace needle::case_internal
