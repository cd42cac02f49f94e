// The key reader's small checks, the follower keys and the TOML front (section_reader.h).
#include "apps/case/section_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "apps/case/plausible_ranges.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle::case_internal {

std::string Number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// A required or optional quantity that must be positive; the message names the key as written.
double Positive(SectionReader& r, const std::string& name, Dimension dimension, double si_to_shown,
                const std::string& shown_key) {
  const double v = r.Quantity(name, dimension);
  if (!(v > 0.0)) r.Fail(shown_key, "must be positive, got " + Number(v * si_to_shown));
  return v;
}

// An optional quantity that must be positive when given; the message names `shown_key` and,
// when `unit` is not empty, the unit of the value shown.
std::optional<double> OptionalPositive(SectionReader& r, const std::string& name,
                                       Dimension dimension, double si_to_shown,
                                       const std::string& shown_key, const std::string& unit) {
  const auto v = r.OptionalQuantity(name, dimension);
  if (v && !(*v > 0.0)) {
    r.Fail(shown_key,
           "must be positive, got " + Number(*v * si_to_shown) + (unit.empty() ? "" : " " + unit));
  }
  return v;
}

// An optional whole number in [1, hi], checked before any cast (a cast of 3e9 or 1e308 is
// undefined); the message shows the range as "[1, hi_text]".
std::optional<long> OptionalCount(SectionReader& r, const std::string& key, double hi,
                                  const std::string& hi_text) {
  const auto v = r.OptionalNumber(key);
  if (!v) return std::nullopt;
  if (!(*v >= 1.0 && *v <= hi) || *v != std::floor(*v))
    r.Fail(key, "must be a whole number in [1, " + hi_text + "], got " + Number(*v));
  return static_cast<long>(*v);
}

// A length key, positive (or ≥ 0), checked as it is read so that a failure names the key as
// written; its plausible range is the table's (Finish).
std::optional<double> SignedLength(SectionReader& r, const std::string& name, bool positive,
                                   bool required) {
  auto v = required ? std::optional<double>(r.Quantity(name, Dimension::kLength))
                    : r.OptionalQuantity(name, Dimension::kLength);
  if (v && !(positive ? *v > 0.0 : *v >= 0.0))
    r.Fail(r.last_key(), std::string("must be ") + (positive ? "positive" : "≥ 0") + ", got " +
                             Number(*v * 1e3) + " mm");
  return v;
}

FollowerGeometry ReadFollowerKeys(SectionReader& r) {
  FollowerGeometry k;
  if (auto name = r.OptionalString("follower")) {
    const std::optional<FollowerKind> kind = ParseFollowerKind(*name);
    if (!kind)
      r.Fail("follower", "expected \"roller\", \"flat\" or \"curved\", got \"" + *name + "\"");
    k.kind = *kind;
  }
  const std::string kind = FollowerKindName(k.kind);
  // Each checked as it is read, so that a failure names the key as written (last_key).
  auto length = [&](const std::string& name, bool positive) {
    return SignedLength(r, name, positive);
  };
  const auto roller = length("roller_radius", false);
  if (roller && k.kind != FollowerKind::kRoller)
    r.Fail(r.last_key(), "a " + kind + " follower has no roller" +
                             (k.kind == FollowerKind::kCurved ? "; give face_radius_mm" : ""));
  const auto face = length("face_radius", true);
  if (face && k.kind != FollowerKind::kCurved)
    r.Fail(r.last_key(), "only a curved follower has a face radius (follower = \"curved\")");
  if (k.kind == FollowerKind::kCurved && !face)
    r.Fail("face_radius_mm", "a curved follower needs the radius of its face");
  const auto half_width = length("face_half_width", true);
  if (half_width && k.kind == FollowerKind::kRoller)
    r.Fail(r.last_key(), "a roller has no face; set follower = \"flat\" or \"curved\"");
  k.roller_radius_m = roller.value_or(0.0);
  k.face_radius_m = face.value_or(0.0);
  k.face_half_width_m = half_width.value_or(0.0);
  return k;
}

std::optional<EngineCycle> OptionalCycle(SectionReader& r) {
  const auto name = r.OptionalString("cycle");
  if (!name) return std::nullopt;
  const std::optional<EngineCycle> cycle = ParseEngineCycle(*name);
  if (!cycle) r.Fail("cycle", "expected " + EngineCycleList() + ", got \"" + *name + "\"");
  return cycle;
}

const toml::table* Section(const toml::table& root, const std::string& file, const char* name) {
  const toml::node* node = root.get(name);
  if (!node) return nullptr;
  const toml::table* t = node->as_table();
  if (!t) throw CaseError(file + ": " + name + ": expected a section [" + name + "]");
  return t;
}

// Parses TOML text; a malformed document is one CaseError line with its position.
toml::table ParseToml(const std::string& text, const std::string& path) {
  // toml++ sees ASCII only (lib/toml_text.h: its non-ASCII paths have undefined behaviour).
  const std::string ascii = AsciiTomlText(text, path);
  try {
    return toml::parse(ascii, path);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    std::string description(e.description());
    for (char& ch : description) {
      if (ch == '\n') ch = ' ';
    }
    throw CaseError(path + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                    ": malformed TOML: " + description);
  }
}

int EditDistance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace needle::case_internal
