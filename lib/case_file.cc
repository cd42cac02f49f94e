#include "lib/case_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "lib/units.h"

namespace needle {
namespace {

std::string Number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// Reads the keys of one TOML table against a schema given by the calls made on it; every
// key must be consumed, and each dimensional key must carry a unit suffix of its dimension.
class SectionReader {
 public:
  SectionReader(const toml::table* table, std::string file, std::string section)
      : table_(table), file_(std::move(file)), section_(std::move(section)) {}

  bool present() const { return table_ != nullptr; }

  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    std::string where = file_ + ": ";
    if (!section_.empty()) where += "[" + section_ + "] ";
    throw CaseError(where + key + ": " + what);
  }

  // Finds the key `name_<unit>` for a quantity; returns the key and its SI factor's unit.
  std::optional<std::pair<std::string, std::string>> FindQuantity(const std::string& name,
                                                                  Dimension dimension) {
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
    if (found) used_.insert(found->first);
    return found;
  }

  std::optional<double> OptionalQuantity(const std::string& name, Dimension dimension) {
    const auto key = FindQuantity(name, dimension);
    if (!key) return std::nullopt;
    const double raw = ToNumber(key->first, *table_->get(key->first));
    return ToSi(dimension, key->second, raw);
  }

  double Quantity(const std::string& name, Dimension dimension) {
    const auto v = OptionalQuantity(name, dimension);
    if (!v) Fail(name, "missing; expected " + Suggestions(name, dimension));
    return *v;
  }

  std::optional<std::vector<double>> OptionalQuantityArray(const std::string& name,
                                                           Dimension dimension) {
    const auto key = FindQuantity(name, dimension);
    if (!key) return std::nullopt;
    const toml::node& node = *table_->get(key->first);
    const toml::array* array = node.as_array();
    if (!array) Fail(key->first, "expected an array of numbers");
    std::vector<double> out;
    for (size_t i = 0; i < array->size(); ++i) {
      const double raw = ToNumber(key->first + "[" + std::to_string(i) + "]", *array->get(i));
      out.push_back(ToSi(dimension, key->second, raw));
    }
    return out;
  }

  std::optional<double> OptionalNumber(const std::string& name) {
    if (!table_ || !table_->contains(name)) return std::nullopt;
    used_.insert(name);
    return ToNumber(name, *table_->get(name));
  }

  std::optional<std::string> OptionalString(const std::string& name) {
    if (!table_ || !table_->contains(name)) return std::nullopt;
    used_.insert(name);
    const auto* s = table_->get(name)->as_string();
    if (!s) Fail(name, "expected a string");
    return s->get();
  }

  // Declares a plain key (no unit) the section knows, so FindQuantity does not mistake it.
  void Known(const std::string& key) { known_plain_.insert(key); }

  // Every key must have been read.
  void Finish() const {
    if (!table_) return;
    for (const auto& [k, node] : *table_) {
      (void)node;
      const std::string key(k.str());
      if (!used_.count(key)) Fail(key, "unknown key in this section");
    }
  }

 private:
  bool IsOtherQuantity(const std::string& key) const { return known_plain_.count(key) > 0; }

  static std::string Suggestions(const std::string& name, Dimension dimension) {
    std::string out;
    for (const std::string& u : UnitSuffixes(dimension)) {
      out += (out.empty() ? "" : " or ") + name + "_" + u;
    }
    return out;
  }

  double ToNumber(const std::string& key, const toml::node& node) const {
    double v;
    if (const auto* i = node.as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* f = node.as_floating_point()) {
      v = f->get();
    } else {
      Fail(key, "expected a number");
    }
    if (std::isnan(v)) Fail(key, "is NaN; expected a finite number");
    if (!std::isfinite(v)) Fail(key, "is infinite; expected a finite number");
    return v;
  }

  const toml::table* table_;
  std::string file_;
  std::string section_;
  std::set<std::string> used_;
  std::set<std::string> known_plain_;
};

EngineSection ReadEngine(SectionReader r) {
  if (!r.present()) r.Fail("speed_rpm", "section [engine] is missing; it needs speed_rpm");
  EngineSection e;
  e.speed_rpm = r.Quantity("speed", Dimension::kRotationSpeed);
  if (!(e.speed_rpm > 0.0)) r.Fail("speed_rpm", "must be positive, got " + Number(e.speed_rpm));
  if (auto cycle = r.OptionalString("cycle")) {
    if (*cycle != "four-stroke" && *cycle != "two-stroke") {
      r.Fail("cycle", "expected \"four-stroke\" or \"two-stroke\", got \"" + *cycle + "\"");
    }
    e.cycle = *cycle;
  }
  r.Finish();
  return e;
}

LiftSection ReadLift(SectionReader r) {
  if (!r.present())
    r.Fail("crank_deg", "section [lift] is missing; it needs crank_deg and lift_mm");
  LiftSection lift;
  r.Known("end_slope");
  const auto normal = r.OptionalString("normal_curve");
  const auto crank = r.OptionalQuantityArray("crank", Dimension::kAngle);
  const auto values = r.OptionalQuantityArray("lift", Dimension::kLength);
  const auto max_lift = r.OptionalQuantity("max_lift", Dimension::kLength);
  if (normal) {
    if (*normal != "basu") r.Fail("normal_curve", "expected \"basu\", got \"" + *normal + "\"");
    if (crank || values)
      r.Fail("normal_curve", "give either normal_curve or crank_deg + lift_mm, not both");
    if (!max_lift) r.Fail("max_lift_mm", "missing; normal_curve = \"basu\" needs max_lift_mm");
    if (!(*max_lift > 0.0))
      r.Fail("max_lift_mm", "must be positive, got " + Number(*max_lift * 1e3));
    lift.table = BasuNormalCurve(*max_lift);
    lift.source = "basu normal curve";
  } else {
    if (max_lift) r.Fail("max_lift_mm", "only used with normal_curve = \"basu\"");
    if (!crank) r.Fail("crank_deg", "missing; expected an array of crank angles (or normal_curve)");
    if (!values) r.Fail("lift_mm", "missing; expected an array of lifts, one per crank angle");
    if (crank->size() != values->size()) {
      r.Fail("lift_mm", "has " + std::to_string(values->size()) + " values but crank_deg has " +
                            std::to_string(crank->size()));
    }
    if (crank->size() < 2) r.Fail("crank_deg", "needs at least 2 points");
    for (size_t i = 1; i < crank->size(); ++i) {
      if (!((*crank)[i] > (*crank)[i - 1])) {
        r.Fail("crank_deg", "angles must increase strictly, but entry " + std::to_string(i) + " (" +
                                Number((*crank)[i] / kDeg) + ") follows entry " +
                                std::to_string(i - 1) + " (" + Number((*crank)[i - 1] / kDeg) +
                                ")");
      }
    }
    for (size_t i = 0; i < values->size(); ++i) {
      if ((*values)[i] < 0.0) {
        r.Fail("lift_mm", "entry " + std::to_string(i) + " is negative (" +
                              Number((*values)[i] * 1e3) + "); lift is measured from the seat");
      }
    }
    lift.table = {*crank, *values};
    lift.source = "table";
  }
  if (auto spline = r.OptionalString("spline")) {
    const auto kind = ParseSplineKind(*spline);
    if (!kind)
      r.Fail("spline", "unknown kind \"" + *spline + "\"; expected one of " + SplineKindList());
    lift.spline.kind = *kind;
  }
  if (auto res = r.OptionalQuantity("resolution", Dimension::kLength)) {
    if (!(*res > 0.0)) r.Fail("resolution_mm", "must be positive, got " + Number(*res * 1e3));
    lift.resolution_m = *res;
  }
  lift.spline.sigma = lift.resolution_m / std::sqrt(12.0);  // σ of a uniform rounding error
  const auto end_slope_name = r.OptionalString("end_slope");
  const auto end_slopes = r.OptionalQuantityArray("end_slope", Dimension::kSlope);
  if (end_slope_name || end_slopes) {
    const std::string key = end_slope_name ? "end_slope" : "end_slope_mm_deg";
    if (lift.spline.kind != SplineKind::kClamped) {
      r.Fail(key, "applies to spline = \"clamped\" only");
    }
    if (end_slope_name && end_slopes) r.Fail(key, "give end_slope or end_slope_mm_deg, not both");
    if (end_slope_name && *end_slope_name != "at-rest") {
      r.Fail("end_slope", "expected \"at-rest\" or end_slope_mm_deg = [start, end]");
    }
    if (end_slopes) {
      if (end_slopes->size() != 2) r.Fail(key, "expected two slopes: [start, end]");
      lift.spline.start_slope = (*end_slopes)[0];
      lift.spline.end_slope = (*end_slopes)[1];
    }
  }
  if (auto rule = r.OptionalString("smoothing")) {
    if (lift.spline.kind != SplineKind::kSmoothing)
      r.Fail("smoothing", "applies to spline = \"smoothing\" only");
    if (*rule == "discrepancy") {
      lift.spline.smoothing_rule = SmoothingRule::kDiscrepancy;
    } else if (*rule == "gcv") {
      lift.spline.smoothing_rule = SmoothingRule::kGcv;
    } else {
      r.Fail("smoothing", "expected \"discrepancy\" or \"gcv\", got \"" + *rule + "\"");
    }
  }
  r.Finish();
  return lift;
}

PaperSection ReadPaper(SectionReader r) {
  PaperSection p;
  const auto crank = r.OptionalQuantityArray("crank", Dimension::kAngle);
  const auto velocity = r.OptionalQuantityArray("velocity", Dimension::kVelocity);
  if (crank.has_value() != velocity.has_value()) {
    r.Fail(crank ? "crank_deg" : "velocity",
           "published velocities need both crank_deg and velocity_<unit>");
  }
  if (crank) {
    if (crank->size() != velocity->size()) {
      r.Fail("velocity", "has " + std::to_string(velocity->size()) + " values but crank_deg has " +
                             std::to_string(crank->size()));
    }
    p.crank_rad = *crank;
    p.velocity_m_s = *velocity;
  }
  p.max_acceleration_m_s2 = r.OptionalQuantity("max_acceleration", Dimension::kAcceleration);
  p.inertia_force_N = r.OptionalQuantity("inertia_force", Dimension::kForce);
  p.mean_lift_m = r.OptionalQuantity("mean_lift", Dimension::kLength);
  r.Finish();
  return p;
}

const toml::table* Section(const toml::table& root, const std::string& file, const char* name) {
  const toml::node* node = root.get(name);
  if (!node) return nullptr;
  const toml::table* t = node->as_table();
  if (!t) throw CaseError(file + ": " + name + ": expected a section [" + name + "]");
  return t;
}

}  // namespace

Case ParseCase(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    std::string description(e.description());
    for (char& ch : description) {
      if (ch == '\n') ch = ' ';
    }
    throw CaseError(path + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                    ": malformed TOML: " + description);
  }
  static const std::set<std::string> kSections = {"engine", "lift", "paper"};
  for (const auto& [k, node] : root) {
    const std::string key(k.str());
    if (key == "title") {
      if (!node.is_string()) throw CaseError(path + ": title: expected a string");
      continue;
    }
    if (!kSections.count(key)) {
      throw CaseError(path + ": " + key + ": unknown " + (node.is_table() ? "section" : "key") +
                      " (known: title, [engine], [lift], [paper])");
    }
  }
  Case c;
  c.path = path;
  c.title = root["title"].value_or(std::string());
  c.engine = ReadEngine(SectionReader(Section(root, path, "engine"), path, "engine"));
  c.lift = ReadLift(SectionReader(Section(root, path, "lift"), path, "lift"));
  if (const toml::table* paper = Section(root, path, "paper")) {
    c.paper = ReadPaper(SectionReader(paper, path, "paper"));
  }
  CheckSplineFits(c, c.lift.spline.kind, "[lift] spline");
  return c;
}

Case LoadCase(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError(path + ": cannot open the case file for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw CaseError(path + ": read error");
  return ParseCase(buffer.str(), path);
}

void CheckSplineFits(const Case& c, SplineKind kind, const std::string& where) {
  const int need = MinimumPoints(kind);
  const int have = static_cast<int>(c.lift.table.crank_rad.size());
  if (have < need) {
    throw CaseError(c.path + ": " + where + ": \"" + SplineKindName(kind) + "\" needs at least " +
                    std::to_string(need) + " points, the lift table has " + std::to_string(have));
  }
}

LiftLaw MakeLiftLaw(const Case& c) {
  try {
    return LiftLaw(c.lift.table, c.lift.spline);
  } catch (const std::exception& e) {
    throw CaseError(c.path + ": [lift]: " + e.what());
  }
}

}  // namespace needle
