// The case file: its one section table and the checks across sections; the key reader and
// the section readers are section_reader.h's.
#include "apps/case/case_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "apps/case/plausible_ranges.h"
#include "apps/case/section_reader.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle {

using case_internal::Number;
using case_internal::ParseToml;
using case_internal::Section;
using case_internal::SectionReader;

namespace {

// The sections of a case file, listed once: the order they are read in (a later section may use
// an earlier one: [lift] the engine's cycle) and the order the "known" message names them.
struct SectionEntry {
  const char* name;
  bool always_read;  // read when absent too (its reader says what is missing)
  void (*read)(SectionReader r, Case& c);
};

const SectionEntry kSectionTable[] = {
    {"engine", true, [](SectionReader r, Case& c) { c.engine = case_internal::ReadEngine(r); }},
    {"lift", true,
     [](SectionReader r, Case& c) { c.lift = case_internal::ReadLift(r, c.path, c.engine.cycle); }},
    {"needle", false, [](SectionReader r, Case& c) { c.needle = case_internal::ReadNeedle(r); }},
    {"spring", false, [](SectionReader r, Case& c) { c.spring = case_internal::ReadSpring(r); }},
    {"train", false, [](SectionReader r, Case& c) { c.train = case_internal::ReadTrain(r); }},
    {"solver", false, [](SectionReader r, Case& c) { c.solver = case_internal::ReadSolver(r); }},
    {"overspeed", false,
     [](SectionReader r, Case& c) { c.overspeed = case_internal::ReadOverspeed(r); }},
    {"profile", false, [](SectionReader r, Case& c) { c.profile = case_internal::ReadProfile(r); }},
    {"tolerance", false,
     [](SectionReader r, Case& c) { c.tolerance = case_internal::ReadTolerance(r); }},
    {"paper", false, [](SectionReader r, Case& c) { c.paper = case_internal::ReadPaper(r); }},
    {"limits", false, [](SectionReader r, Case& c) { c.limits = case_internal::ReadLimits(r); }},
    {"sizing", false, [](SectionReader r, Case& c) { c.sizing = case_internal::ReadSizing(r); }},
};

const SectionEntry* FindSection(const std::string& name) {
  for (const SectionEntry& s : kSectionTable) {
    if (name == s.name) return &s;
  }
  return nullptr;
}

// The preload per needle area in its plausible range (kPreloadPressureRange): a preload typed in
// kgf for N, or a diameter in cm for mm, holds the needle with thousands of bar, and passes every
// rule that asks the preload to be large enough.
void CheckPreloadPressure(const Case& c, const toml::table& root) {
  if (!c.needle || !c.needle->diameter_m || !c.spring) return;
  const double d = *c.needle->diameter_m, area = kPi / 4.0 * d * d;
  const double p = c.spring->preload_N / area;
  const PlausibleRange& r = kPreloadPressureRange;
  if (p <= r.hi) return;
  std::string key = "preload";  // as written
  if (const toml::table* spring = root["spring"].as_table()) {
    for (const auto& [k, node] : *spring) {
      (void)node;
      if (std::string(k.str()).rfind("preload_", 0) == 0) key = std::string(k.str());
    }
  }
  throw CaseError(c.path + ": [spring] " + key + ": " + Number(c.spring->preload_N) + " N on the " +
                  Number(d * 1e3) + " mm needle ([needle] diameter) is " + ShownValue(r, p) +
                  " on its area, above the plausible range's end " + ShownValue(r, r.hi) +
                  " (docs/ranges.md): a preload in kgf typed for N, or a diameter in cm typed "
                  "for mm?");
}

}  // namespace

Case ParseCase(const std::string& text, const std::string& path) {
  const toml::table root = ParseToml(text, path);
  for (const auto& [k, node] : root) {
    const std::string key(k.str());
    if (key == "title") {
      if (!node.is_string()) throw CaseError(path + ": title: expected a string");
      continue;
    }
    if (!FindSection(key)) {
      std::string known = "title";
      for (const SectionEntry& s : kSectionTable) known += std::string(", [") + s.name + "]";
      throw CaseError(path + ": " + key + ": unknown " + (node.is_table() ? "section" : "key") +
                      " (known: " + known + ")");
    }
  }
  Case c;
  c.path = path;
  c.title = root["title"].value_or(std::string());
  for (const SectionEntry& s : kSectionTable) {
    const toml::table* t = Section(root, path, s.name);
    if (t || s.always_read) s.read(SectionReader(t, path, s.name, CaseFileKeys()), c);
  }
  if (c.lift.spline_given) CheckSplineFits(c, c.lift.spline.kind, "[lift] spline");
  // The moving mass includes a third of the spring (docs/model.md §4): with the spring's
  // geometry known, a lighter one is impossible (and the coil-mass model of check's surge
  // verdict has no needle left).
  if (c.spring && c.spring->helical && c.needle) {
    const double third = ActiveSpringMassKg(*c.spring->helical) / 3.0;
    if (!(c.needle->mass_kg > third)) {
      throw CaseError(path + (c.spring->masses > 1 ? ": [spring] masses" : ": [needle] mass_kg") +
                      ": the moving mass [needle] mass_kg = " + Number(c.needle->mass_kg) +
                      " kg includes a third of the spring, but a third of the active coils is " +
                      Number(third) + " kg");
    }
  }
  CheckPreloadPressure(c, root);
  if (c.spring && c.spring->coil_clash && !c.spring->clash_stiffness_N_m && c.train &&
      c.train->rigid()) {
    throw CaseError(path +
                    ": [spring] clash: a rigid [train] has no contact stiffness for the coils "
                    "to take; give clash_stiffness_N_m");
  }
  if (c.overspeed && c.overspeed->steady_state && !(c.solver && c.solver->run.cycles >= 2)) {
    throw CaseError(path +
                    ": [overspeed] steady_state: needs [solver] cycles of at least 2 (the steady "
                    "state is judged on the revolutions after the first)");
  }
  return c;
}

Case LoadCase(const std::string& path) { return ParseCase(ReadInputFile(path, "case file"), path); }

void CheckSplineFits(const Case& c, SplineKind kind, const std::string& where) {
  const int need = MinimumPoints(kind);
  const int have = static_cast<int>(c.lift.table.crank_rad.size());
  if (have < need) {
    throw CaseError(c.path + ": " + where + ": \"" + SplineKindName(kind) + "\" needs at least " +
                    std::to_string(need) + " points, the lift table has " + std::to_string(have));
  }
}

bool IsCsvPath(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == ".csv";
}

Case CaseFromLiftCsv(const std::string& path, EngineCycle cycle) {
  Case c;
  c.path = path;
  c.engine.cycle = cycle;
  c.lift.table = ReadLiftCsv(path, cycle, &c.lift.lines);
  c.lift.source = "csv " + path;
  c.lift.csv_path = path;
  return c;
}

}  // namespace needle
