#pragma once
/// @file
/// Internal to the case-file layer (not installed): the unit-aware key reader every section
/// reader is written with, its small checks, and the section readers that `ParseCase` lists
/// in its one section table (case_file.cc). One file per group of sections:
/// spring_sections.cc ([needle], [spring], [limits]), run_sections.cc ([engine], [train],
/// [solver], [overspeed], [tolerance], [profile], [paper]), lift_section.cc ([lift]).
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/case/case_keys.h"
#include "apps/case/plausible_ranges.h"
#include "lib/case_error.h"
#include "lib/field_error.h"
#include "lib/follower.h"
#include "lib/units.h"

namespace needle::case_internal {

/// Levenshtein's distance between a and b (insertions, deletions, substitutions).
int EditDistance(const std::string& a, const std::string& b);

// The largest magnitude any number in an input file may have.
constexpr double kLargestInput = 1e15;

/// A number as `operator<<` prints it, for messages.
std::string Number(double v);

// Reads the keys of one TOML table against a schema given by the calls made on it; every
// key must be consumed, and each dimensional key must carry a unit suffix of its dimension.
class SectionReader {
 public:
  /// `keys`: the file's declared keys (apps/case/case_keys.h), the only ones the reader may
  /// ask for, and their ranges; {} for a section not declared there (the engine file's
  /// [design], the synthesis file's [rise], [limits] and [output]: no list, no range).
  SectionReader(const toml::table* table, std::string file, std::string section,
                CaseKeyList keys = {})
      : table_(table), file_(std::move(file)), section_(std::move(section)), keys_(keys) {}

  bool present() const { return table_ != nullptr; }

  // Whether the section has the plain key `name` (read or not).
  bool Has(const std::string& name) const { return table_ && table_->contains(name); }

  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    std::string where = file_ + ": ";
    if (!section_.empty()) where += "[" + section_ + "] ";
    throw CaseError(where + key + ": " + what);
  }

  // Finds the key `name_<unit>` for a quantity; returns the key and its SI factor's unit.
  std::optional<std::pair<std::string, std::string>> FindQuantity(const std::string& name,
                                                                  Dimension dimension) {
    const CaseKey* declared = Declared(name, dimension);
    if (!table_) return std::nullopt;
    std::optional<std::pair<std::string, std::string>> found;
    for (const auto& [k, node] : *table_) {
      const std::string key(k.str());
      (void)node;
      if (key == name) {
        if (IsOtherQuantity(key)) continue;  // a plain key of the same name (`end_slope`)
        Fail(key, "needs a unit suffix: " + Suggestions(name, dimension));
      }
      if (key.size() <= name.size() + 1 || key.compare(0, name.size() + 1, name + "_") != 0) {
        continue;
      }
      if (BelongsToLongerName(key, name)) continue;  // `fuel_density_g_cm3` is not `fuel_…`
      const std::string unit = key.substr(name.size() + 1);
      const auto units = UnitSuffixes(dimension);
      if (std::find(units.begin(), units.end(), unit) == units.end()) {
        if (IsOtherQuantity(key)) continue;  // e.g. `end_slope` next to `end_slope_mm_deg`
        Fail(key, "unit suffix '" + unit + "' is not a unit of " + DimensionName(dimension) +
                      " (expected " + Suggestions(name, dimension) + ")");
      }
      if (found) Fail(key, "given twice, also as " + found->first + "; keep one");
      found = std::make_pair(key, unit);
    }
    if (found) {
      used_.insert(found->first);
      last_key_ = found->first;
      last_declared_ = declared;
    }
    return found;
  }

  std::optional<double> OptionalQuantity(const std::string& name, Dimension dimension) {
    const auto key = FindQuantity(name, dimension);
    if (!key) return std::nullopt;
    const double raw = ToNumber(key->first, *table_->get(key->first));
    const double si = ToSi(dimension, key->second, raw);
    if (!std::isfinite(si) || std::abs(si) > 1e18) Fail(key->first, "is out of range in SI units");
    read_.push_back({key->first, last_declared_, si, false});
    return si;
  }

  double Quantity(const std::string& name, Dimension dimension) {
    const auto v = OptionalQuantity(name, dimension);
    if (!v) Fail(name, "missing; expected " + Suggestions(name, dimension) + Typo(name, dimension));
    return *v;
  }

  std::optional<std::vector<double>> OptionalQuantityArray(const std::string& name,
                                                           Dimension dimension) {
    const auto key = FindQuantity(name, dimension);
    if (!key) return std::nullopt;
    const toml::node& node = *table_->get(key->first);
    const toml::array* array = node.as_array();
    if (!array) Fail(key->first, "expected an array of numbers");
    const SiConversion to_si = SiConversionOf(dimension, key->second);
    std::vector<double> out;
    out.reserve(array->size());
    for (size_t i = 0; i < array->size(); ++i) {
      // The entry's key ("lift_mm[3]") is built only for a message.
      const double v =
          ToNumber(*array->get(i), [&] { return key->first + "[" + std::to_string(i) + "]"; });
      out.push_back(to_si(v));
    }
    read_.push_back({key->first, last_declared_, 0.0, true, out});
    return out;
  }

  std::optional<double> OptionalNumber(const std::string& name) {
    const toml::node* node = PlainNode(name);
    if (!node) return std::nullopt;
    const double v = ToNumber(name, *node);
    read_.push_back({name, last_declared_, v, false});
    return v;
  }

  std::optional<std::string> OptionalString(const std::string& name) {
    const toml::node* node = PlainNode(name);
    if (!node) return std::nullopt;
    const auto* s = node->as_string();
    if (!s) Fail(name, "expected a string");
    return s->get();
  }

  std::optional<std::vector<std::string>> OptionalStringArray(const std::string& name) {
    const toml::node* node = PlainNode(name);
    if (!node) return std::nullopt;
    const toml::array* a = node->as_array();
    std::vector<std::string> out;
    for (size_t i = 0; a && i < a->size(); ++i) {
      const auto* s = a->get(i)->as_string();
      if (!s) break;
      out.push_back(s->get());
    }
    if (!a || a->empty() || out.size() != a->size())
      Fail(name, "expected a non-empty array of strings");
    return out;
  }

  std::optional<bool> OptionalBool(const std::string& name) {
    const toml::node* node = PlainNode(name);
    if (!node) return std::nullopt;
    const auto* b = node->as_boolean();
    if (!b) Fail(name, "expected true or false");
    return b->get();
  }

  // Declares a plain key (no unit) the section knows, so FindQuantity does not mistake it.
  void Known(const std::string& key) {
    Declared(key, Dimension::kNone);
    known_plain_.insert(key);
  }

  // Declares a quantity name that extends a shorter one (`fuel_density` beside `fuel`).
  void Declare(const std::string& name) { declared_.insert(name); }

  // Runs `validate`, a module struct's Validate() (the one place its rules are stated, for the
  // struct the section is read straight into), and turns its FieldError into this file's one
  // line: the key declared for that member, as written, the rule and the value in the unit the
  // key was written in ("t.toml: [train] contact_stiffness_N_mm: must be positive, got -5 N/mm").
  template <typename Validate>
  void Validated(const Validate& validate) const {
    try {
      validate();
    } catch (const FieldError& e) {
      const auto [key, value] = AsWritten(e.field, e.value);
      Fail(key, e.rule + ", got " + value);
    }
  }

  // The key (with its unit) of the quantity found last, for messages.
  const std::string& last_key() const { return last_key_; }

  // Every key must have been read, and every value read must lie in the plausible range its
  // declaration names (apps/case/case_keys.cc, from plausible_ranges.h). The section's own
  // checks (a sign, a missing partner, a module's Validate) ran before, so their messages come
  // first.
  void Finish() const {
    if (!table_) return;
    for (const auto& [k, node] : *table_) {
      (void)node;
      const std::string key(k.str());
      if (!used_.count(key)) Fail(key, "unknown key in this section");
    }
    for (const ReadValue& v : read_) {
      if (!v.declared || !v.declared->range) continue;
      const PlausibleRange& range = *v.declared->range;
      if (v.table_entry) {  // an array's entries, each held to the upper end only
        for (size_t i = 0; i < v.entries.size(); ++i) {
          if (v.entries[i] > range.hi)
            Fail(v.key + "[" + std::to_string(i) + "]", AboveRangeEnd(range, v.entries[i]));
        }
      } else if (v.declared->upper_only) {
        if (v.si > range.hi) Fail(v.key, AboveRangeEnd(range, v.si));
      } else if (!(v.si >= range.lo && v.si <= range.hi)) {
        Fail(v.key, ShownValue(range, v.si) + " is outside the plausible range " +
                        RangeText(range) + " (docs/ranges.md)");
      }
    }
  }

 private:
  // The declaration of member `member` of the struct the section is read into: the plain key of
  // that name, or the quantity whose name it starts with and a unit suffix of whose dimension it
  // ends in ("contact_stiffness_N_m", "atol_m", "settle_limit_deg"; not "atol_m_s"); nullptr
  // when none.
  const CaseKey* MemberKey(const std::string& member) const {
    if (!keys_.first) return nullptr;
    for (const CaseKey& k : keys_) {
      if (section_ != k.section) continue;
      const std::string name = k.name;
      if (k.dimension == Dimension::kNone) {
        if (member == name) return &k;
      } else if (member.compare(0, name.size() + 1, name + "_") == 0 &&
                 MemberUnitIn(member, k.dimension)) {
        return &k;
      }
    }
    return nullptr;
  }
  // The unit suffix of `dimension` member `member` ends in ("N_m" of contact_stiffness_N_m), or
  // nullopt.
  static std::optional<std::string> MemberUnitIn(const std::string& member, Dimension dimension) {
    for (const std::string& u : UnitSuffixes(dimension)) {
      if (member.size() > u.size() &&
          member.compare(member.size() - u.size() - 1, u.size() + 1, "_" + u) == 0)
        return u;
    }
    return std::nullopt;
  }
  // Member `member`'s key as the file wrote it and `value` (in the member's unit, the suffix its
  // name ends in) in that key's unit: ("contact_stiffness_N_mm", "-5 N/mm") for
  // contact_stiffness_N_m = -5000; a plain key and number as they are; the member's own name when
  // it has no key here.
  std::pair<std::string, std::string> AsWritten(const std::string& member, double value) const {
    const CaseKey* k = MemberKey(member);
    if (!k) return {member, Number(value)};
    const auto read = std::find_if(read_.begin(), read_.end(),
                                   [k](const ReadValue& v) { return v.declared == k; });
    if (k->dimension == Dimension::kNone || read == read_.end()) return {k->name, Number(value)};
    std::string unit = read->key.substr(std::string(k->name).size() + 1);
    const double si = ToSi(k->dimension, *MemberUnitIn(member, k->dimension), value);
    const std::string shown = Number(FromSi(k->dimension, unit, si));
    std::replace(unit.begin(), unit.end(), '_', '/');
    return {read->key, shown + " " + unit};
  }
  // The node of plain key `name` (declared with no unit), marked read, or nullptr when the
  // section does not have it.
  const toml::node* PlainNode(const std::string& name) {
    last_declared_ = Declared(name, Dimension::kNone);
    if (!table_ || !table_->contains(name)) return nullptr;
    used_.insert(name);
    return table_->get(name);
  }
  // The declaration of key `name` of `dimension` (kNone: a plain key) in the file's list, or
  // nullptr when the reader has none; a key the list does not declare is the reader's bug.
  const CaseKey* Declared(const std::string& name, Dimension dimension) const {
    if (!keys_.first) return nullptr;
    const CaseKey* k = FindCaseKey(keys_, section_, name, dimension);
    if (!k) {
      throw std::logic_error("[" + section_ + "] " + name + " (" + DimensionName(dimension) +
                             ") is read but not declared in apps/case/case_keys.cc");
    }
    return k;
  }
  bool IsOtherQuantity(const std::string& key) const { return known_plain_.count(key) > 0; }

  bool BelongsToLongerName(const std::string& key, const std::string& name) const {
    for (const std::string& other : declared_) {
      if (other.size() > name.size() && key.compare(0, other.size() + 1, other + "_") == 0) {
        return true;
      }
    }
    return false;
  }

  // " (is mas_kg a typo of mass_kg?)": a key of the section within two edits of one of the
  // suggestions (a typo that made the key unknown and the quantity missing), or "".
  std::string Typo(const std::string& name, Dimension dimension) const {
    if (!table_) return "";
    for (const auto& [k, node] : *table_) {
      (void)node;
      const std::string key(k.str());
      for (const std::string& u : UnitSuffixes(dimension)) {
        if (EditDistance(key, name + "_" + u) <= 2)
          return " (is " + key + " a typo of " + name + "_" + u + "?)";
      }
    }
    return "";
  }

  static std::string Suggestions(const std::string& name, Dimension dimension) {
    std::string out;
    for (const std::string& u : UnitSuffixes(dimension)) {
      out += (out.empty() ? "" : " or ") + name + "_" + u;
    }
    return out;
  }

  double ToNumber(const std::string& key, const toml::node& node) const {
    return ToNumber(node, [&] { return key; });
  }

  // The number `node` holds; `key()` names it in a message (built only then).
  template <typename Key>
  double ToNumber(const toml::node& node, const Key& key) const {
    double v;
    if (const auto* i = node.as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* f = node.as_floating_point()) {
      v = f->get();
    } else {
      Fail(key(), "expected a number");
    }
    if (std::isnan(v)) Fail(key(), "is NaN; expected a finite number");
    if (!std::isfinite(v)) Fail(key(), "is infinite; expected a finite number");
    // No input of a needle valve is this large; beyond it unit conversions and products
    // overflow (rate_N_mm = 1e308 became an "inf N/m" rate).
    if (std::abs(v) > kLargestInput) {
      std::ostringstream m;
      m << "is " << v << "; expected a magnitude of at most 1e15";
      Fail(key(), m.str());
    }
    return v;
  }

  // A value as read, in SI, for the range check in Finish.
  struct ReadValue {
    std::string key;          ///< as written ("mass_kg", "lift_mm")
    const CaseKey* declared;  ///< its declaration (nullptr: none)
    double si = 0.0;
    bool table_entry = false;       ///< an array: its entries, in SI, in `entries`
    std::vector<double> entries{};  ///< an array's entries, in SI
  };

  const toml::table* table_;
  std::string file_;
  std::string section_;
  std::vector<ReadValue> read_;
  std::set<std::string> used_;
  std::set<std::string> known_plain_;
  std::set<std::string> declared_;
  std::string last_key_;
  const CaseKey* last_declared_ = nullptr;
  CaseKeyList keys_;
};

// A required or optional quantity that must be positive; the message names the key as written.
double Positive(SectionReader& r, const std::string& name, Dimension dimension, double si_to_shown,
                const std::string& shown_key);

// An optional quantity that must be positive when given; the message names `shown_key` and,
// when `unit` is not empty, the unit of the value shown.
std::optional<double> OptionalPositive(SectionReader& r, const std::string& name,
                                       Dimension dimension, double si_to_shown,
                                       const std::string& shown_key, const std::string& unit = "");

// An optional whole number in [1, hi], checked before any cast (a cast of 3e9 or 1e308 is
// undefined); the message shows the range as "[1, hi_text]".
std::optional<long> OptionalCount(SectionReader& r, const std::string& key, double hi,
                                  const std::string& hi_text);

// A length key (optional unless `required`), positive (or ≥ 0), checked as it is read so that a
// failure names the key as written; its plausible range is the table's (SectionReader::Finish).
std::optional<double> SignedLength(SectionReader& r, const std::string& name, bool positive,
                                   bool required = false);

/// The follower's kind and shape keys (`follower`, roller_radius, face_radius, face_half_width;
/// 0 where not given), read straight into its geometry, shared by [profile] and the synthesis
/// file's [checks]: each key belongs to the kinds that have it. base_radius and offset are the
/// section's own.
FollowerGeometry ReadFollowerKeys(SectionReader& r);

/// The table `name` of `root`, or null when absent; a non-table there is a CaseError.
const toml::table* Section(const toml::table& root, const std::string& file, const char* name);

/// Parses TOML text; a malformed document is one CaseError line with its position.
toml::table ParseToml(const std::string& text, const std::string& path);

// The section readers, one per section of a case file.
NeedleSection ReadNeedle(SectionReader r);
HelicalGeometry ReadHelical(SectionReader& r);
SpringSection ReadSpring(SectionReader r);
LimitsSection ReadLimits(SectionReader r);
SizingSection ReadSizing(SectionReader r);  ///< sizing_section.cc
EngineSection ReadEngine(SectionReader r);
TrainSection ReadTrain(SectionReader r);
SolverSection ReadSolver(SectionReader r);
OverspeedSection ReadOverspeed(SectionReader r);
ToleranceSection ReadTolerance(SectionReader r);
ProfileSection ReadProfile(SectionReader r);
PaperSection ReadPaper(SectionReader r);
LiftSection ReadLift(SectionReader r, const std::string& case_path, EngineCycle cycle);

/// The optional `cycle` key of [engine] (case and engine file) and [output] (synthesis file).
std::optional<EngineCycle> OptionalCycle(SectionReader& r);

}  // namespace needle::case_internal
