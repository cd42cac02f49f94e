#include "apps/scene/case_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "apps/scene/plausible_ranges.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle {
namespace {

// The largest magnitude any number in an input file may have.
constexpr double kLargestInput = 1e15;

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
    }
    return found;
  }

  std::optional<double> OptionalQuantity(const std::string& name, Dimension dimension) {
    const auto key = FindQuantity(name, dimension);
    if (!key) return std::nullopt;
    const double raw = ToNumber(key->first, *table_->get(key->first));
    const double si = ToSi(dimension, key->second, raw);
    if (!std::isfinite(si) || std::abs(si) > 1e18) Fail(key->first, "is out of range in SI units");
    read_.push_back({key->first, name, si, false});
    return si;
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
      const std::string entry = key->first + "[" + std::to_string(i) + "]";
      out.push_back(ToSi(dimension, key->second, ToNumber(entry, *array->get(i))));
      read_.push_back({entry, name, out.back(), true});
    }
    return out;
  }

  std::optional<double> OptionalNumber(const std::string& name) {
    if (!table_ || !table_->contains(name)) return std::nullopt;
    used_.insert(name);
    const double v = ToNumber(name, *table_->get(name));
    read_.push_back({name, name, v, false});
    return v;
  }

  std::optional<std::string> OptionalString(const std::string& name) {
    if (!table_ || !table_->contains(name)) return std::nullopt;
    used_.insert(name);
    const auto* s = table_->get(name)->as_string();
    if (!s) Fail(name, "expected a string");
    return s->get();
  }

  std::optional<bool> OptionalBool(const std::string& name) {
    if (!table_ || !table_->contains(name)) return std::nullopt;
    used_.insert(name);
    const auto* b = table_->get(name)->as_boolean();
    if (!b) Fail(name, "expected true or false");
    return b->get();
  }

  // Declares a plain key (no unit) the section knows, so FindQuantity does not mistake it.
  void Known(const std::string& key) { known_plain_.insert(key); }

  // Declares a quantity name that extends a shorter one (`fuel_density` beside `fuel`).
  void Declare(const std::string& name) { declared_.insert(name); }

  // The key (with its unit) of the quantity found last, for messages.
  const std::string& last_key() const { return last_key_; }

  // Every key must have been read, and every value read must lie in its plausible range
  // (apps/scene/plausible_ranges.h, the one table of them). The section's own checks (a sign,
  // a missing partner) ran as each key was read, so their messages come first.
  void Finish() const {
    if (!table_) return;
    for (const auto& [k, node] : *table_) {
      (void)node;
      const std::string key(k.str());
      if (!used_.count(key)) Fail(key, "unknown key in this section");
    }
    for (const ReadValue& v : read_) {
      const RangedKey* ranged = FindRangedKey(section_, v.name);
      if (!ranged) continue;
      const PlausibleRange& range = *ranged->range;
      if (v.table_entry || ranged->upper_only) {
        if (v.si > range.hi)
          Fail(v.key, ShownValue(range, v.si) + " is above the plausible range's end " +
                          ShownValue(range, range.hi) + " (docs/ranges.md)");
      } else if (!(v.si >= range.lo && v.si <= range.hi)) {
        Fail(v.key, ShownValue(range, v.si) + " is outside the plausible range " +
                        RangeText(range) + " (docs/ranges.md)");
      }
    }
  }

 private:
  bool IsOtherQuantity(const std::string& key) const { return known_plain_.count(key) > 0; }

  bool BelongsToLongerName(const std::string& key, const std::string& name) const {
    for (const std::string& other : declared_) {
      if (other.size() > name.size() && key.compare(0, other.size() + 1, other + "_") == 0) {
        return true;
      }
    }
    return false;
  }

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
    // No input of a needle valve is this large; beyond it unit conversions and products
    // overflow (rate_N_mm = 1e308 became an "inf N/m" rate).
    if (std::abs(v) > kLargestInput) {
      std::ostringstream m;
      m << "is " << v << "; expected a magnitude of at most 1e15";
      Fail(key, m.str());
    }
    return v;
  }

  // A value as read, in SI, for the range check in Finish.
  struct ReadValue {
    std::string key;   ///< as written ("mass_kg", "lift_mm[3]")
    std::string name;  ///< without the unit suffix ("mass")
    double si = 0.0;
    bool table_entry = false;  ///< an entry of an array
  };

  const toml::table* table_;
  std::string file_;
  std::string section_;
  std::vector<ReadValue> read_;
  std::set<std::string> used_;
  std::set<std::string> known_plain_;
  std::set<std::string> declared_;
  std::string last_key_;
};

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
                                       const std::string& shown_key, const std::string& unit = "") {
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

NeedleSection ReadNeedle(SectionReader r) {
  NeedleSection n;
  n.mass_kg = r.Quantity("mass", Dimension::kMass);
  if (!(n.mass_kg > 0.0)) r.Fail("mass_kg", "must be positive, got " + Number(n.mass_kg));
  n.diameter_m = r.OptionalQuantity("diameter", Dimension::kLength);
  if (n.diameter_m && !(*n.diameter_m > 0.0)) {
    r.Fail("diameter_mm", "must be positive, got " + Number(*n.diameter_m * 1e3));
  }
  // The gas load (docs/model.md §4): stated, or a combustion pressure on the needle's area, by
  // default Basu's 35 kg/cm² ("the spring must be strong enough to withstand the combustion
  // pressure"); 0 without a diameter.
  const auto gas = r.OptionalQuantity("gas_force", Dimension::kForce);
  const std::string gas_key = gas ? r.last_key() : "";
  const auto pressure = r.OptionalQuantity("combustion_pressure", Dimension::kPressure);
  if (gas && pressure) {
    r.Fail(gas_key, "give gas_force or combustion_pressure, not both");
  }
  if (pressure && !(*pressure >= 0.0)) {
    r.Fail(r.last_key(), "must not be negative, got " + Number(*pressure) + " Pa");
  }
  if (pressure && !n.diameter_m) {
    r.Fail(r.last_key(), "needs diameter_mm (the load is the pressure on the needle's area)");
  }
  const double area = n.diameter_m ? kPi * *n.diameter_m * *n.diameter_m / 4.0 : 0.0;
  if (gas) {
    n.gas_force_N = *gas;
    n.gas_source = "stated";
  } else if (pressure) {
    n.gas_force_N = *pressure * area;
    n.gas_source = "combustion pressure " + Number(*pressure * 1e-5) + " bar on the needle";
  } else if (n.diameter_m) {
    n.gas_force_N = 35.0 * kKgf * 1e4 * area;  // 35 kg/cm² on π d²/4
    n.gas_source = "Basu's 35 kg/cm2 on the needle";
  } else {
    n.gas_force_N = 0.0;
    n.gas_source = "none (no needle diameter)";
  }
  r.Finish();
  return n;
}

HelicalGeometry ReadHelical(SectionReader& r) {
  HelicalGeometry g;
  g.wire_m = Positive(r, "wire", Dimension::kLength, 1e3, "wire_mm");
  g.coil_m = Positive(r, "coil", Dimension::kLength, 1e3, "coil_mm");
  const auto coils = r.OptionalNumber("active_coils");
  if (!coils) r.Fail("active_coils", "missing; the helical check needs the number of active coils");
  if (!(*coils >= 2.0))
    r.Fail("active_coils", "must be at least 2 (EN 13906-1), got " + Number(*coils));
  g.active_coils = *coils;
  g.free_length_m = Positive(r, "free_length", Dimension::kLength, 1e3, "free_length_mm");
  if (auto grade = r.OptionalString("grade")) {
    g.grade = ParseWireGrade(*grade);
    if (!g.grade)
      r.Fail("grade", "expected one of " + WireGradeList() + ", got \"" + *grade + "\"");
  }
  if (auto peened = r.OptionalBool("shot_peened")) g.shot_peened = *peened;
  if (g.grade && !r.FindQuantity("shear_modulus", Dimension::kPressure)) {
    g.shear_modulus_Pa = GradeData(*g.grade).shear_modulus_Pa;  // EN 13906-1's G of the grade
  } else {
    g.shear_modulus_Pa =
        Positive(r, "shear_modulus", Dimension::kPressure, 1e-9, "shear_modulus_GPa");
  }
  if (auto rho = r.OptionalQuantity("density", Dimension::kDensity)) {
    if (!(*rho > 0.0)) r.Fail("density_kg_m3", "must be positive, got " + Number(*rho));
    g.density_kg_m3 = *rho;
  }
  if (g.grade && !r.FindQuantity("tensile", Dimension::kPressure)) {
    try {
      g.tensile_Pa = TensileStrengthPa(*g.grade, g.wire_m);  // R_m(d) of the grade
    } catch (const std::invalid_argument& e) {
      r.Fail("grade", e.what());
    }
  } else {
    g.tensile_Pa = Positive(r, "tensile", Dimension::kPressure, 1e-6, "tensile_MPa");
  }
  const double index = g.coil_m / g.wire_m;
  if (index < 4.0 || index > 20.0) {
    r.Fail("coil_mm", "spring index D/d = " + Number(index) +
                          " is outside 4…20 (EN 13906-1); change the wire or the coil diameter");
  }
  if (auto ends = r.OptionalString("ends")) {
    if (*ends == "closed-ground") {
      g.ends = SpringEnds::kClosedGround;
    } else if (*ends == "closed") {
      g.ends = SpringEnds::kClosed;
    } else if (*ends == "open-ground") {
      g.ends = SpringEnds::kOpenGround;
    } else if (*ends == "open") {
      g.ends = SpringEnds::kOpen;
    } else {
      r.Fail("ends", "expected \"closed-ground\", \"closed\", \"open-ground\" or \"open\", got \"" +
                         *ends + "\"");
    }
  }
  if (auto corr = r.OptionalString("stress_correction")) {
    if (*corr != "bergstrasser" && *corr != "wahl") {
      r.Fail("stress_correction", "expected \"bergstrasser\" or \"wahl\", got \"" + *corr + "\"");
    }
    g.wahl = *corr == "wahl";
  }
  if (auto f = r.OptionalNumber("allowable_stress_fraction")) {
    if (!(*f > 0.0 && *f <= 1.0)) {
      r.Fail("allowable_stress_fraction", "must be in (0, 1], got " + Number(*f));
    }
    g.allowable_fraction = *f;
  }
  return g;
}

SpringSection ReadSpring(SectionReader r) {
  SpringSection sp;
  sp.preload_N = r.Quantity("preload", Dimension::kForce);
  if (sp.preload_N < 0.0)
    r.Fail(r.last_key(), "must not be negative, got " + Number(sp.preload_N) + " N");
  sp.rate_N_m = r.OptionalQuantity("rate", Dimension::kStiffness);
  if (sp.rate_N_m && *sp.rate_N_m < 0.0) {
    r.Fail(r.last_key(), "must not be negative, got " + Number(*sp.rate_N_m) + " N/m");
  }
  if (auto s = r.OptionalNumber("safety_factor")) {
    if (!(*s >= 1.0)) r.Fail("safety_factor", "must be at least 1, got " + Number(*s));
    sp.safety_factor = *s;
  }
  if (auto f = r.OptionalNumber("overspeed_factor")) {
    if (!(*f >= 1.0)) r.Fail("overspeed_factor", "must be at least 1, got " + Number(*f));
    sp.overspeed_factor = *f;
  }
  if (auto t = r.OptionalNumber("basu_tolerance_percent")) {
    if (!(*t >= 0.0 && *t <= 100.0))
      r.Fail("basu_tolerance_percent", "must be in 0…100, got " + Number(*t));
    sp.basu_tolerance_percent = *t;
  }
  if (r.FindQuantity("wire", Dimension::kLength)) {
    sp.helical = ReadHelical(r);
  }
  if (!sp.rate_N_m && !sp.helical) {
    r.Fail("rate", "missing; give rate_N_mm (or rate_N_m, rate_kgf_mm …) or the helical geometry");
  }
  if (auto n = OptionalCount(r, "masses", kMaxCoilMasses, std::to_string(kMaxCoilMasses))) {
    if (*n > 1 && !sp.helical)
      r.Fail("masses",
             "needs the helical geometry (wire_mm, coil_mm, active_coils …): the coil "
             "masses are the active coils' mass");
    sp.masses = static_cast<int>(*n);
  }
  if (auto z = r.OptionalNumber("surge_damping_ratio")) {
    if (!(*z >= 0.0 && *z <= 1.0))
      r.Fail("surge_damping_ratio", "must be in [0, 1], got " + Number(*z));
    if (sp.masses == 1)
      r.Fail("surge_damping_ratio", "needs masses of at least 2 (a massless spring has no surge)");
    sp.surge_damping_ratio = *z;
  }
  if (auto clash = r.OptionalBool("clash")) {
    if (*clash && sp.masses == 1)
      r.Fail("clash", "needs masses of at least 2 (the coils that meet)");
    sp.coil_clash = *clash;
  }
  if (auto k = r.OptionalQuantity("clash_stiffness", Dimension::kStiffness)) {
    if (!sp.coil_clash) r.Fail(r.last_key(), "needs clash = true");
    if (!(*k > 0.0)) r.Fail(r.last_key(), "must be positive, got " + Number(*k) + " N/m");
    sp.clash_stiffness_N_m = *k;
  }
  if (auto z = r.OptionalNumber("clash_damping_ratio")) {
    if (!sp.coil_clash) r.Fail("clash_damping_ratio", "needs clash = true");
    if (!(*z >= 0.0 && *z <= 1.0))
      r.Fail("clash_damping_ratio", "must be in [0, 1], got " + Number(*z));
    sp.clash_damping_ratio = *z;
  }
  r.Finish();
  return sp;
}

TrainSection ReadTrain(SectionReader r) {
  TrainSection t;
  if (auto contact = r.OptionalString("contact")) {
    if (*contact != "compliant" && *contact != "rigid")
      r.Fail("contact", "expected \"compliant\" or \"rigid\", got \"" + *contact + "\"");
    t.rigid = *contact == "rigid";
  }
  if (t.rigid) {
    // Newton's restitution; the compliant law's keys do not apply.
    for (auto [key, into] : {std::pair<const char*, double*>{"restitution", &t.restitution},
                             {"seat_restitution", &t.seat_restitution}}) {
      if (auto e = r.OptionalNumber(key)) {
        if (!(*e >= 0.0 && *e <= 1.0)) r.Fail(key, "must be in [0, 1], got " + Number(*e));
        *into = *e;
      }
    }
    for (const char* key : {"contact_stiffness", "seat_stiffness"}) {
      if (r.OptionalQuantity(key, Dimension::kStiffness))
        r.Fail(r.last_key(), "applies to contact = \"compliant\"; a rigid contact has none");
    }
    for (const char* key : {"contact_damping_ratio", "seat_damping_ratio"}) {
      if (r.OptionalNumber(key))
        r.Fail(key, "applies to contact = \"compliant\"; a rigid contact has restitution");
    }
  } else {
    for (const char* key : {"restitution", "seat_restitution"}) {
      if (r.OptionalNumber(key))
        r.Fail(key, "applies to contact = \"rigid\"; a compliant contact has a damping ratio");
    }
    t.contact_stiffness_N_m = r.Quantity("contact_stiffness", Dimension::kStiffness);
    if (!(t.contact_stiffness_N_m > 0.0)) {
      r.Fail(r.last_key(), "must be positive, got " + Number(t.contact_stiffness_N_m) + " N/m");
    }
    if (auto ks = r.OptionalQuantity("seat_stiffness", Dimension::kStiffness)) {
      if (!(*ks > 0.0)) r.Fail(r.last_key(), "must be positive, got " + Number(*ks) + " N/m");
      t.seat_stiffness_N_m = *ks;
    } else {
      t.seat_stiffness_N_m = t.contact_stiffness_N_m;
    }
    for (auto [key, into] :
         {std::pair<const char*, double*>{"contact_damping_ratio", &t.contact_damping_ratio},
          {"seat_damping_ratio", &t.seat_damping_ratio}}) {
      if (auto z = r.OptionalNumber(key)) {
        if (!(*z >= 0.0)) r.Fail(key, "must not be negative, got " + Number(*z));
        *into = *z;
      }
    }
  }
  if (auto play = r.OptionalQuantity("play", Dimension::kLength)) {
    if (!(*play >= 0.0)) r.Fail("play_mm", "must not be negative, got " + Number(*play * 1e3));
    t.play_m = *play;
  }
  r.Known("ramp");
  const auto ramp = r.OptionalString("ramp");
  const auto ramp_angle = r.OptionalQuantity("ramp", Dimension::kAngle);
  if (ramp && *ramp != "tangent")
    r.Fail("ramp", "expected \"tangent\" or ramp_deg = <angle>, got \"" + *ramp + "\"");
  if (ramp && ramp_angle) r.Fail("ramp", "give ramp = \"tangent\" or ramp_deg, not both");
  if (ramp_angle) {
    if (!(*ramp_angle > 0.0))
      r.Fail("ramp_deg", "must be positive, got " + Number(*ramp_angle / kDeg));
    t.linear_ramp = true;
    t.ramp_rad = *ramp_angle;
  }
  r.Finish();
  return t;
}

SolverSection ReadSolver(SectionReader r) {
  SolverSection s;
  if (auto m = r.OptionalString("method")) {
    if (*m != "auto" && !ParseMethod(*m)) {  // the names from the method table
      std::string list = "auto";
      for (Method known : AllMethods()) list += ", " + MethodName(known);
      r.Fail("method", "expected one of " + list + "; got \"" + *m + "\"");
    }
    s.method = *m;
  }
  if (auto rtol = r.OptionalNumber("rtol")) {
    if (!(*rtol >= kMinRtol && *rtol <= kMaxRtol))
      r.Fail("rtol", "must be in " + RtolRangeText() + ", got " + Number(*rtol));
    s.rtol = *rtol;
  }
  if (auto atol = r.OptionalQuantity("atol", Dimension::kLength)) {
    if (!(*atol > 0.0)) r.Fail("atol", "must be positive");
    s.atol_m = *atol;
  }
  // Budgets: whole numbers in a range a long holds.
  for (auto [key, into] :
       {std::pair<const char*, long*>{"max_steps", &s.max_steps}, {"max_events", &s.max_events}}) {
    if (auto v = OptionalCount(r, key, 1e12, "1e12")) *into = *v;
  }
  if (auto v = r.OptionalNumber("max_seconds")) {
    if (!(*v >= 0.0 && *v <= 86400.0))
      r.Fail("max_seconds", "must be in [0, 86400] s (0: no wall-time budget), got " + Number(*v));
    s.max_seconds = *v;
  }
  if (auto settle = r.OptionalQuantity("settle", Dimension::kAngle)) {
    if (!(*settle > 0.0 && *settle <= 36000.0 * kDeg))
      r.Fail("settle_deg", "must be in (0, 36000] deg, got " + Number(*settle / kDeg));
    s.settle_limit_deg = *settle / kDeg;
  }
  if (auto v = OptionalCount(r, "cycles", kMaxCycles, std::to_string(kMaxCycles)))
    s.cycles = static_cast<int>(*v);
  if (auto v = r.OptionalNumber("period_tolerance")) {
    if (!(*v > 0.0 && *v <= 1e-2))
      r.Fail("period_tolerance", "must be in (0, 1e-2], got " + Number(*v));
    s.period_tolerance = *v;
  }
  s.start_rad = r.OptionalQuantity("start", Dimension::kAngle);
  s.end_rad = r.OptionalQuantity("end", Dimension::kAngle);
  if (s.start_rad && s.end_rad && !(*s.end_rad > *s.start_rad)) {
    r.Fail("end_deg", "must be after start_deg");
  }
  r.Finish();
  return s;
}

OverspeedSection ReadOverspeed(SectionReader r) {
  OverspeedSection o;
  o.from_rpm = r.OptionalQuantity("from", Dimension::kRotationSpeed);
  o.to_rpm = r.OptionalQuantity("to", Dimension::kRotationSpeed);
  if (o.from_rpm && !(*o.from_rpm > 0.0))
    r.Fail("from_rpm", "must be positive, got " + Number(*o.from_rpm));
  if (o.from_rpm && o.to_rpm && !(*o.to_rpm > *o.from_rpm)) {
    r.Fail("to_rpm", "the sweep range is empty: to_rpm (" + Number(*o.to_rpm) +
                         ") must exceed from_rpm (" + Number(*o.from_rpm) + ")");
  }
  o.steady_state = r.OptionalBool("steady_state").value_or(false);
  r.Finish();
  return o;
}

ToleranceSection ReadTolerance(SectionReader r) {
  ToleranceSection t;
  // A σ ≥ 0 and at most `most` (SI), named as written.
  const auto sigma = [&r](const std::string& name, Dimension d, double most, double shown,
                          const std::string& unit, double& into) {
    if (auto v = r.OptionalQuantity(name, d)) {
      if (!(*v >= 0.0 && *v <= most))
        r.Fail(r.last_key(), "must be ≥ 0 and at most " + Number(most * shown) + " " + unit +
                                 ", got " + Number(*v * shown) + " " + unit);
      into = *v;
    }
  };
  r.Declare("lift_correlation");  // not a unit of `lift`
  sigma("lift", Dimension::kLength, 1e-3, 1e3, "mm", t.lift_sigma_m);
  sigma("lift_correlation", Dimension::kAngle, 2.0 * kPi, 1.0 / kDeg, "deg",
        t.lift_correlation_rad);
  sigma("mass", Dimension::kPercent, 0.5, 100.0, "%", t.mass_fraction);
  sigma("preload", Dimension::kPercent, 0.5, 100.0, "%", t.preload_fraction);
  sigma("rate", Dimension::kPercent, 0.5, 100.0, "%", t.rate_fraction);
  sigma("stiffness", Dimension::kPercent, 0.5, 100.0, "%", t.stiffness_fraction);
  sigma("play", Dimension::kLength, 1e-2, 1e3, "mm", t.play_sigma_m);
  sigma("speed", Dimension::kPercent, 0.5, 100.0, "%", t.speed_fraction);
  r.Finish();
  return t;
}

// An optional length key, positive (or ≥ 0) and at most 10 m, checked as it is read so that a
// failure names the key as written.
std::optional<double> BoundedLength(SectionReader& r, const std::string& name, bool positive) {
  auto v = r.OptionalQuantity(name, Dimension::kLength);
  if (v && !((positive ? *v > 0.0 : *v >= 0.0) && *v <= 10.0))
    r.Fail(r.last_key(), std::string("must be ") + (positive ? "positive" : "≥ 0") +
                             " and at most 10000 mm, got " + Number(*v * 1e3) + " mm");
  return v;
}

// The follower's kind and its radius and face keys, the same in [profile] and [checks]: each
// key belongs to the kinds that have it.
struct FollowerKeys {
  FollowerKind kind = FollowerKind::kRoller;
  std::optional<double> roller_radius_m, face_radius_m, face_half_width_m;
};

FollowerKeys ReadFollowerKeys(SectionReader& r) {
  FollowerKeys k;
  auto length = [&](const std::string& name, bool positive) {
    return BoundedLength(r, name, positive);
  };
  if (auto name = r.OptionalString("follower")) {
    const std::optional<FollowerKind> kind = ParseFollowerKind(*name);
    if (!kind)
      r.Fail("follower", "expected \"roller\", \"flat\" or \"curved\", got \"" + *name + "\"");
    k.kind = *kind;
  }
  const std::string kind = FollowerKindName(k.kind);
  k.roller_radius_m = length("roller_radius", false);
  if (k.roller_radius_m && k.kind != FollowerKind::kRoller)
    r.Fail(r.last_key(), "a " + kind + " follower has no roller" +
                             (k.kind == FollowerKind::kCurved ? "; give face_radius_mm" : ""));
  k.face_radius_m = length("face_radius", true);
  if (k.face_radius_m && k.kind != FollowerKind::kCurved)
    r.Fail(r.last_key(), "only a curved follower has a face radius (follower = \"curved\")");
  if (k.kind == FollowerKind::kCurved && !k.face_radius_m)
    r.Fail("face_radius_mm", "a curved follower needs the radius of its face");
  k.face_half_width_m = length("face_half_width", true);
  if (k.face_half_width_m && k.kind == FollowerKind::kRoller)
    r.Fail(r.last_key(), "a roller has no face; set follower = \"flat\" or \"curved\"");
  return k;
}

LimitsSection ReadLimits(SectionReader r) {
  LimitsSection l;
  const auto optional_fraction = [&r](const std::string& name, double low) {
    const std::optional<double> v = r.OptionalQuantity(name, Dimension::kPercent);
    if (v && !(*v >= low && *v <= 1.0))
      r.Fail(r.last_key(), "must be in " + Number(low * 100) + "…100 %, got " + Number(*v * 100));
    return v;
  };
  const auto fraction = [&](const std::string& name, double low, double& into) {
    if (auto v = optional_fraction(name, low)) into = *v;
  };
  if (auto v = OptionalPositive(r, "seating_velocity", Dimension::kVelocity, 1.0,
                                "seating_velocity_m_s", "m/s"))
    l.seating_velocity_m_s = *v;
  if (auto v = OptionalPositive(r, "lash_impact_velocity", Dimension::kVelocity, 1.0,
                                "lash_impact_velocity_m_s", "m/s"))
    l.lash_impact_velocity_m_s = *v;
  l.min_contact_force_fraction = optional_fraction("min_contact_force", 0.0);
  fraction("separation_margin", -1.0, l.separation_margin_fraction);
  if (auto v = OptionalPositive(r, "hertz_stress", Dimension::kPressure, 1e-6, "hertz_stress_MPa",
                                "MPa"))
    l.hertz_stress_Pa = *v;
  l.contact_length_m =
      OptionalPositive(r, "contact_length", Dimension::kLength, 1e3, "contact_length_mm", "mm");
  if (auto v = OptionalPositive(r, "elastic_modulus", Dimension::kPressure, 1e-9,
                                "elastic_modulus_GPa", "GPa"))
    l.elastic_modulus_Pa = *v;
  if (auto nu = r.OptionalNumber("poisson")) {
    if (!(*nu >= 0.0 && *nu < 0.5)) r.Fail("poisson", "must be in [0, 0.5), got " + Number(*nu));
    l.poisson = *nu;
  }
  if (auto f = r.OptionalNumber("fatigue_safety_factor")) {
    if (!(*f >= 1.0 && *f <= 10.0))
      r.Fail("fatigue_safety_factor", "must be in 1…10, got " + Number(*f));
    l.fatigue_safety_factor = *f;
  }
  l.coil_gap_m = OptionalPositive(r, "coil_gap", Dimension::kLength, 1e3, "coil_gap_mm", "mm");
  fraction("harmonic_threshold", 0.001, l.harmonic_threshold);
  if (!(l.harmonic_threshold < 1.0)) r.Fail("harmonic_threshold_percent", "must be below 100 %");
  r.Finish();
  return l;
}

ProfileSection ReadProfile(SectionReader r) {
  ProfileSection p;
  FollowerGeometry& g = p.follower;
  const FollowerKeys k = ReadFollowerKeys(r);
  g.kind = k.kind;
  g.base_radius_m = Positive(r, "base_radius", Dimension::kLength, 1e3, "base_radius_mm");
  g.roller_radius_m = k.roller_radius_m.value_or(0.0);
  g.face_radius_m = k.face_radius_m.value_or(0.0);
  g.face_half_width_m = k.face_half_width_m.value_or(0.0);
  g.offset_m = r.OptionalQuantity("offset", Dimension::kLength).value_or(0.0);
  if (!(std::abs(g.offset_m) <= 10.0))
    r.Fail("offset", "must be within ±10000 mm, got " + Number(g.offset_m * 1e3) + " mm");
  if (g.kind != FollowerKind::kFlat &&
      !(std::abs(g.offset_m) < g.base_radius_m + g.ContactRadius())) {
    r.Fail("offset", "must be smaller than base radius plus " +
                         std::string(g.kind == FollowerKind::kCurved ? "face" : "roller") +
                         " radius");
  }
  if (auto l = r.OptionalNumber("lever_ratio")) {
    if (!(*l > 0.0)) r.Fail("lever_ratio", "must be positive, got " + Number(*l));
    g.lever_ratio = *l;
  }
  if (auto n = r.OptionalNumber("points")) {
    if (!(*n >= 8 && *n <= 1e6) || *n != std::floor(*n))
      r.Fail("points", "must be a whole number in 8…1e6");
    p.points = static_cast<int>(*n);
  }
  r.Finish();
  return p;
}

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

LiftSection ReadLift(SectionReader r, const std::string& case_path, bool four_stroke) {
  if (!r.present())
    r.Fail("crank_deg", "section [lift] is missing; it needs crank_deg and lift_mm");
  LiftSection lift;
  r.Known("end_slope");
  const auto normal = r.OptionalString("normal_curve");
  const auto csv = r.OptionalString("csv");
  const auto crank = r.OptionalQuantityArray("crank", Dimension::kAngle);
  const std::string crank_key = crank ? r.last_key() : "crank_deg";
  const auto values = r.OptionalQuantityArray("lift", Dimension::kLength);
  const std::string lift_key = values ? r.last_key() : "lift_mm";
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
  } else if (csv) {
    if (crank || values) r.Fail("csv", "give either csv or crank_deg + lift_mm, not both");
    if (max_lift) r.Fail("max_lift_mm", "only used with normal_curve = \"basu\"");
    if (csv->empty()) r.Fail("csv", "expected the path of a CSV file");
    const std::filesystem::path p(*csv);
    const std::string full = p.is_absolute()
                                 ? p.string()
                                 : (std::filesystem::path(case_path).parent_path() / p).string();
    try {
      lift.table = ReadLiftCsv(full, four_stroke, &lift.lines);
    } catch (const CaseError& e) {
      r.Fail("csv", e.what());  // "CASE: [lift] csv: TABLE:LINE:COLUMN: what"
    }
    lift.source = "csv " + full;
    lift.csv_path = full;
  } else {
    if (max_lift) r.Fail("max_lift_mm", "only used with normal_curve = \"basu\"");
    if (!crank) r.Fail("crank_deg", "missing; expected an array of crank angles (or normal_curve)");
    if (!values) r.Fail("lift_mm", "missing; expected an array of lifts, one per crank angle");
    if (crank->size() != values->size()) {
      r.Fail("lift_mm", "has " + std::to_string(values->size()) + " values but crank_deg has " +
                            std::to_string(crank->size()));
    }
    if (crank->size() < 2) r.Fail("crank_deg", "needs at least 2 points");
    // Plausible readings (lib/lift_data.h), shown in the key's own unit.
    auto plausible = [&](const std::vector<double>& array, const std::string& key,
                         Dimension dimension, double limit, const std::string& range) {
      const std::string unit = key.substr(key.find('_') + 1);
      const double per_unit = ToSi(dimension, unit, 1.0);
      for (size_t i = 0; i < array.size(); ++i) {
        if (!(std::abs(array[i]) <= limit)) {
          r.Fail(key + "[" + std::to_string(i) + "]",
                 "is " + Number(array[i] / per_unit) + " " + unit +
                     ", outside the plausible range ±" + Number(limit / per_unit) + " " + unit +
                     " (" + range + "); a typo or a unit mix-up?");
        }
      }
    };
    plausible(*crank, crank_key, Dimension::kAngle, kMaxCrankRad,
              "a crank angle within ±720°, a four-stroke cycle either side of dead centre");
    plausible(*values, lift_key, Dimension::kLength, kMaxLiftM, "a lift within ±1 m");
    for (size_t i = 1; i < crank->size(); ++i) {
      if (!((*crank)[i] > (*crank)[i - 1])) {
        r.Fail("crank_deg", "angles must increase strictly, but entry " + std::to_string(i) + " (" +
                                Number((*crank)[i] / kDeg) + ") follows entry " +
                                std::to_string(i - 1) + " (" + Number((*crank)[i - 1] / kDeg) +
                                ")");
      }
    }
    lift.table = {*crank, *values};
    lift.source = "table";
    lift.lift_key = lift_key;
  }
  if (auto spline = r.OptionalString("spline")) {
    const auto kind = ParseSplineKind(*spline);
    if (!kind)
      r.Fail("spline", "unknown kind \"" + *spline + "\"; expected one of " + SplineKindList());
    lift.spline.kind = *kind;
    lift.spline_given = true;
  }
  if (auto res = r.OptionalQuantity("resolution", Dimension::kLength)) {
    if (!(*res > 0.0)) r.Fail("resolution_mm", "must be positive, got " + Number(*res * 1e3));
    lift.resolution_m = *res;
    lift.resolution_given = true;
  }
  if (auto noise = r.OptionalQuantity("noise", Dimension::kLength)) {
    if (!(*noise > 0.0))
      r.Fail(r.last_key(), "must be positive, got " + Number(*noise * 1e3) + " mm");
    lift.noise_m = *noise;
  }
  if (auto outliers = r.OptionalString("outliers")) {
    if (*outliers != "refuse" && *outliers != "drop") {
      r.Fail("outliers", "expected \"refuse\" or \"drop\", got \"" + *outliers + "\"");
    }
    lift.drop_outliers = *outliers == "drop";
  }
  lift.open_rad = r.OptionalQuantity("open", Dimension::kAngle);
  lift.close_rad = r.OptionalQuantity("close", Dimension::kAngle);
  const double first = lift.table.crank_rad.front(), last = lift.table.crank_rad.back();
  if (lift.open_rad && !(*lift.open_rad >= first && *lift.open_rad < last)) {
    r.Fail("open_deg", "must lie inside the table (" + Number(first / kDeg) + " to " +
                           Number(last / kDeg) + " deg), got " + Number(*lift.open_rad / kDeg));
  }
  if (lift.close_rad && !(*lift.close_rad > first && *lift.close_rad <= last)) {
    r.Fail("close_deg", "must lie inside the table (" + Number(first / kDeg) + " to " +
                            Number(last / kDeg) + " deg), got " + Number(*lift.close_rad / kDeg));
  }
  if (lift.open_rad && lift.close_rad && !(*lift.close_rad > *lift.open_rad)) {
    r.Fail("close_deg", "must be after open_deg");
  }
  if (auto breaks = r.OptionalQuantityArray("breaks", Dimension::kAngle)) {
    if (normal) r.Fail(r.last_key(), "applies to a table (crank_deg + lift_mm, or csv)");
    if (lift.noise_m) r.Fail(r.last_key(), "marks an exact table; it cannot go with noise_mm");
    lift.breaks_given = true;  // `breaks_deg = []`: none, and none sought in the table
    for (size_t i = 1; i < breaks->size(); ++i) {
      if (!((*breaks)[i] > (*breaks)[i - 1]))
        r.Fail(r.last_key(), "angles must increase strictly (entry " + std::to_string(i) + ")");
    }
    if (lift.spline_given && lift.spline.kind != SplineKind::kNotAKnot &&
        lift.spline.kind != SplineKind::kNatural && lift.spline.kind != SplineKind::kQuintic) {
      r.Fail(r.last_key(),
             "needs spline = \"not-a-knot\", \"natural\" or \"quintic\" (a "
             "spline built apart on each piece), got \"" +
                 SplineKindName(lift.spline.kind) + "\"");
    }
    lift.breaks_rad = *breaks;
  }
  lift.spline.sigma = lift.resolution_m / std::sqrt(12.0);  // σ of a uniform rounding error
  const auto end_slope_name = r.OptionalString("end_slope");
  const auto end_slopes = r.OptionalQuantityArray("end_slope", Dimension::kSlope);
  if (end_slope_name || end_slopes) {
    const std::string key = end_slope_name ? "end_slope" : "end_slope_mm_deg";
    if (lift.spline.kind != SplineKind::kClamped || !lift.spline_given) {
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
  p.spring_preload_N = r.OptionalQuantity("spring_preload", Dimension::kForce);
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

}  // namespace

Case ParseCase(const std::string& text, const std::string& path) {
  const toml::table root = ParseToml(text, path);
  static const std::set<std::string> kSections = {"engine",    "lift",   "needle",    "spring",
                                                  "train",     "solver", "overspeed", "profile",
                                                  "tolerance", "paper",  "limits"};
  for (const auto& [k, node] : root) {
    const std::string key(k.str());
    if (key == "title") {
      if (!node.is_string()) throw CaseError(path + ": title: expected a string");
      continue;
    }
    if (!kSections.count(key)) {
      throw CaseError(path + ": " + key + ": unknown " + (node.is_table() ? "section" : "key") +
                      " (known: title, [engine], [lift], [needle], [spring], [train], [solver], "
                      "[overspeed], [profile], [tolerance], [paper], [limits])");
    }
  }
  Case c;
  c.path = path;
  c.title = root["title"].value_or(std::string());
  c.engine = ReadEngine(SectionReader(Section(root, path, "engine"), path, "engine"));
  c.lift = ReadLift(SectionReader(Section(root, path, "lift"), path, "lift"), path,
                    c.engine.cycle == "four-stroke");
  if (const toml::table* needle = Section(root, path, "needle")) {
    c.needle = ReadNeedle(SectionReader(needle, path, "needle"));
  }
  if (const toml::table* spring = Section(root, path, "spring")) {
    c.spring = ReadSpring(SectionReader(spring, path, "spring"));
  }
  if (const toml::table* t = Section(root, path, "train"))
    c.train = ReadTrain(SectionReader(t, path, "train"));
  if (const toml::table* t = Section(root, path, "solver"))
    c.solver = ReadSolver(SectionReader(t, path, "solver"));
  if (const toml::table* t = Section(root, path, "overspeed")) {
    c.overspeed = ReadOverspeed(SectionReader(t, path, "overspeed"));
  }
  if (const toml::table* t = Section(root, path, "profile"))
    c.profile = ReadProfile(SectionReader(t, path, "profile"));
  if (const toml::table* t = Section(root, path, "tolerance"))
    c.tolerance = ReadTolerance(SectionReader(t, path, "tolerance"));
  if (const toml::table* paper = Section(root, path, "paper")) {
    c.paper = ReadPaper(SectionReader(paper, path, "paper"));
  }
  if (const toml::table* t = Section(root, path, "limits"))
    c.limits = ReadLimits(SectionReader(t, path, "limits"));
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
  if (c.spring && c.spring->coil_clash && !c.spring->clash_stiffness_N_m && c.train &&
      c.train->rigid) {
    throw CaseError(path +
                    ": [spring] clash: a rigid [train] has no contact stiffness for the coils "
                    "to take; give clash_stiffness_N_m");
  }
  if (c.overspeed && c.overspeed->steady_state && !(c.solver && c.solver->cycles >= 2)) {
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

DesignInputs ParseDesignInputs(const std::string& text, const std::string& path) {
  const toml::table root = ParseToml(text, path);
  for (const auto& [k, node] : root) {
    const std::string key(k.str());
    if (key == "title" || key == "engine" || key == "design") continue;
    throw CaseError(path + ": " + key + ": unknown " + (node.is_table() ? "section" : "key") +
                    " (known: title, [engine], [design])");
  }
  DesignInputs d;
  d.path = path;
  d.title = root["title"].value_or(std::string());
  SectionReader e(Section(root, path, "engine"), path, "engine");
  if (!e.present())
    e.Fail("power_hp", "section [engine] is missing; it needs power_hp and speed_rpm");
  d.power_W = Positive(e, "power", Dimension::kPower, 1.0, "power_hp");
  d.speed_rpm = Positive(e, "speed", Dimension::kRotationSpeed, 1.0, "speed_rpm");
  if (auto cycle = e.OptionalString("cycle")) {
    if (*cycle != "four-stroke" && *cycle != "two-stroke") {
      e.Fail("cycle", "expected \"four-stroke\" or \"two-stroke\", got \"" + *cycle + "\"");
    }
    d.cycle = *cycle;
  }
  e.Finish();
  SectionReader r(Section(root, path, "design"), path, "design");
  r.Declare("fuel_density");
  auto positive = [&](const std::string& name, Dimension dim, double shown, const std::string& key,
                      double& into) {
    if (auto v = OptionalPositive(r, name, dim, shown, key)) into = *v;
  };
  auto number = [&](const std::string& key, double lo, double& into) {
    if (auto v = r.OptionalNumber(key)) {
      if (!(*v > lo)) r.Fail(key, "must be above " + Number(lo) + ", got " + Number(*v));
      into = *v;
    }
  };
  if (auto v = r.OptionalQuantity("fuel", Dimension::kSpecificFuel)) {
    if (!(*v > 0.0)) r.Fail("fuel_g_hp_h", "must be positive, got " + Number(*v));
    d.fuel_g_hp_h = *v;
  }
  positive("fuel_density", Dimension::kDensity, 1e-3, "fuel_density_g_cm3", d.fuel_density_kg_m3);
  positive("injection_crank", Dimension::kAngle, 180.0 / kPi, "injection_crank_deg",
           d.injection_crank_rad);
  positive("injection_air_pressure", Dimension::kPressure, 1.0 / 101325.0,
           "injection_air_pressure_atm", d.injection_air_pressure_Pa);
  positive("cylinder_pressure", Dimension::kPressure, 1.0 / 101325.0, "cylinder_pressure_atm",
           d.cylinder_pressure_Pa);
  if (auto t = r.OptionalQuantity("air_temperature", Dimension::kTemperature)) {
    if (!(*t > 0.0)) r.Fail("air_temperature", "must be above absolute zero");
    d.air_temperature_K = *t;
  }
  number("velocity_coefficient", 0.0, d.velocity_coefficient);
  if (d.velocity_coefficient > 1.0) {
    r.Fail("velocity_coefficient", "must be at most 1, got " + Number(d.velocity_coefficient));
  }
  if (auto a = r.OptionalString("atomizer")) {
    if (*a != "disk" && *a != "sleeve")
      r.Fail("atomizer", "expected \"disk\" or \"sleeve\", got \"" + *a + "\"");
    d.atomizer = *a;
  }
  if (auto ratio = r.OptionalString("pressure_ratio")) {
    if (*ratio != "absolute" && *ratio != "gauge") {
      r.Fail("pressure_ratio", "expected \"absolute\" or \"gauge\", got \"" + *ratio + "\"");
    }
    d.gauge_ratio = *ratio == "gauge";
  }
  if (auto m = r.OptionalNumber("mixing_ratio")) {
    if (!(*m > 0.0)) r.Fail("mixing_ratio", "must be positive, got " + Number(*m));
    d.mixing_ratio = *m;
  }
  positive("cam_peripheral_velocity", Dimension::kVelocity, 1.0, "cam_peripheral_velocity_m_s",
           d.cam_peripheral_velocity_m_s);
  number("disk_to_roller", 1.0, d.disk_to_roller);
  // Checked as an integer in range before the cast (3e9 printed "−2147483648 holes").
  if (auto holes = OptionalCount(r, "nozzle_holes", 1000.0, "1000"))
    d.nozzle_holes = static_cast<int>(*holes);
  if (auto v = r.OptionalQuantity("discharge_passage", Dimension::kLength)) {
    if (!(*v > 0.0)) r.Fail("discharge_passage_mm", "must be positive, got " + Number(*v * 1e3));
    d.discharge_passage_m = *v;
  }
  positive("max_lift_limit", Dimension::kLength, 1e3, "max_lift_limit_mm", d.max_lift_limit_m);
  if (auto list = r.OptionalQuantityArray("passage_candidates", Dimension::kLength)) {
    if (list->empty()) r.Fail("passage_candidates_mm", "must not be empty");
    for (double v : *list) {
      if (!(v > 0.0)) r.Fail("passage_candidates_mm", "every diameter must be positive");
    }
    d.passage_candidates_m = *list;
  }
  if (auto v = r.OptionalQuantity("needle_diameter", Dimension::kLength)) {
    if (!(*v > 0.0)) r.Fail("needle_diameter_mm", "must be positive, got " + Number(*v * 1e3));
    d.needle_diameter_m = *v;
  }
  if (auto v = r.OptionalQuantity("cam_disk", Dimension::kLength)) {
    if (!(*v > 0.0)) r.Fail("cam_disk_mm", "must be positive, got " + Number(*v * 1e3));
    d.cam_disk_m = *v;
  }
  if (auto m = r.OptionalQuantity("moving_mass", Dimension::kMass)) {
    if (!(*m > 0.0 && *m <= 1e4))
      r.Fail("moving_mass_kg", "must be in (0, 1e4] kg, got " + Number(*m));
    d.moving_mass_kg = *m;
  }
  number("rho", 1.0, d.rho);
  number("nozzle_ratio", 0.0, d.nozzle_ratio);
  r.Finish();
  return d;
}

SynthesisFile LoadSynthesisFile(const std::string& path) {
  return ParseSynthesisFile(ReadInputFile(path, "synthesis file"), path);
}

SynthesisFile ParseSynthesisFile(const std::string& text, const std::string& path) {
  const toml::table root = ParseToml(text, path);
  for (const auto& [k, node] : root) {
    const std::string key(k.str());
    if (key == "title" || key == "rise" || key == "limits" || key == "checks" || key == "output")
      continue;
    throw CaseError(path + ": " + key + ": unknown " + (node.is_table() ? "section" : "key") +
                    " (known: title, [rise], [limits], [checks], [output])");
  }
  SynthesisFile f;
  f.path = path;
  f.title = root["title"].value_or(std::string());
  SectionReader rise(Section(root, path, "rise"), path, "rise");
  if (!rise.present())
    rise.Fail("angle_deg", "section [rise] is missing; it needs angle_deg and lift_mm");
  // Ranges that keep the synthesis finite and its memory bounded (a lift of 3e305 mm made the
  // speed search loop forever; a step of 1e-7° asked for 5.7 GB).
  f.rise_rad = Positive(rise, "angle", Dimension::kAngle, 180.0 / kPi, "angle_deg");
  if (!(f.rise_rad <= 2 * kPi))
    rise.Fail(rise.last_key(), "must be at most 360 deg of cam, got " + Number(f.rise_rad / kDeg));
  f.height_m = Positive(rise, "lift", Dimension::kLength, 1e3, "lift_mm");
  if (!(f.height_m <= 1.0))
    rise.Fail(rise.last_key(), "must be at most 1000 mm, got " + Number(f.height_m * 1e3) + " mm");
  if (auto st = rise.OptionalQuantity("step", Dimension::kAngle)) {
    if (!(*st > 0.0 && *st < f.rise_rad / 10))
      rise.Fail(rise.last_key(), "must be positive and below a tenth of the rise");
    if (!(*st >= f.rise_rad / 1e6))
      rise.Fail(rise.last_key(), "must be at least a millionth of the rise (" +
                                     Number(f.rise_rad / kDeg / 1e6) + " deg): at most 1e6 steps");
    f.step_rad = *st;
  }
  rise.Finish();
  SectionReader lim(Section(root, path, "limits"), path, "limits");
  if (!lim.present())
    lim.Fail("acceleration", "section [limits] is missing; it needs acceleration and deceleration");
  if (auto v = lim.OptionalQuantity("speed", Dimension::kSlope)) {
    if (!(*v > 0.0 && *v < 1e6)) lim.Fail(lim.last_key(), "must be positive and finite");
    f.speed_limit = *v;
  }
  f.accel_limit = Positive(lim, "acceleration", Dimension::kSlope2, 1e3, "acceleration_mm_rad2");
  f.decel_limit = Positive(lim, "deceleration", Dimension::kSlope2, 1e3, "deceleration_mm_rad2");
  if (!(f.accel_limit < 1e12)) lim.Fail("acceleration", "must be finite (below 1e15 mm/rad2)");
  if (!(f.decel_limit < 1e12)) lim.Fail("deceleration", "must be finite (below 1e15 mm/rad2)");
  if (auto v = lim.OptionalQuantity("jerk", Dimension::kSlope3)) {
    if (!(*v > 0.0 && *v < 1e15)) lim.Fail(lim.last_key(), "must be positive and finite");
    f.jerk_limit = *v;
  }
  lim.Finish();
  if (const toml::table* t = Section(root, path, "checks")) {
    SectionReader ch(t, path, "checks");
    // Each value is checked as it is read, so a failure names the key as written.
    auto length = [&](const std::string& name, bool positive) {
      return BoundedLength(ch, name, positive);
    };
    const FollowerKeys k = ReadFollowerKeys(ch);
    f.follower = k.kind;
    f.base_radius_m = length("base_radius", true);
    f.roller_radius_m = k.roller_radius_m;
    f.face_radius_m = k.face_radius_m;
    f.face_half_width_m = k.face_half_width_m;
    if ((k.kind != FollowerKind::kRoller || f.face_half_width_m) && !f.base_radius_m)
      ch.Fail("base_radius",
              "a " + std::string(FollowerKindName(k.kind)) + " follower needs base_radius_mm");
    if (auto u = ch.OptionalQuantity("min_entrainment_speed", Dimension::kVelocity)) {
      if (!(*u > 0.0 && *u <= 1e3))
        ch.Fail(ch.last_key(), "must be in (0, 1000] m/s, got " + Number(*u) + " m/s");
      if (!f.base_radius_m) ch.Fail("base_radius", "the lubrication limit needs base_radius_mm");
      f.min_entrainment_m_s = *u;
    }
    f.offset_m = ch.OptionalQuantity("offset", Dimension::kLength).value_or(0.0);
    if (!(std::abs(f.offset_m) <= 10.0))
      ch.Fail(ch.last_key(), "must be within ±10000 mm, got " + Number(f.offset_m * 1e3) + " mm");
    f.max_pressure_angle_rad = ch.OptionalQuantity("max_pressure_angle", Dimension::kAngle);
    if (f.max_pressure_angle_rad &&
        !(*f.max_pressure_angle_rad > 0.0 && *f.max_pressure_angle_rad < kPi / 2))
      ch.Fail(ch.last_key(),
              "must be in (0, 90) deg, got " + Number(*f.max_pressure_angle_rad / kDeg) + " deg");
    f.min_profile_radius_m = length("min_profile_radius", false);
    if (f.min_profile_radius_m && !f.base_radius_m) {
      ch.Fail("base_radius", "the curvature limit needs base_radius_mm");
    }
    f.spring_preload_N = ch.OptionalQuantity("spring_preload", Dimension::kForce);
    if (f.spring_preload_N && !(*f.spring_preload_N >= 0.0 && *f.spring_preload_N <= 1e7))
      ch.Fail(ch.last_key(), "must be in [0, 1e7] N, got " + Number(*f.spring_preload_N) + " N");
    f.spring_rate_N_m = ch.OptionalQuantity("spring_rate", Dimension::kStiffness);
    if (f.spring_rate_N_m && !(*f.spring_rate_N_m >= 0.0 && *f.spring_rate_N_m <= 1e12))
      ch.Fail(ch.last_key(),
              "must be in [0, 1e9] N/mm, got " + Number(*f.spring_rate_N_m * 1e-3) + " N/mm");
    f.moving_mass_kg = ch.OptionalQuantity("moving_mass", Dimension::kMass);
    if (f.moving_mass_kg && !(*f.moving_mass_kg > 0.0 && *f.moving_mass_kg <= 1e4))
      ch.Fail(ch.last_key(), "must be in (0, 1e4] kg, got " + Number(*f.moving_mass_kg) + " kg");
    f.min_spring_reserve = ch.OptionalNumber("min_spring_reserve");
    if (f.min_spring_reserve && !(f.spring_preload_N && f.moving_mass_kg)) {
      ch.Fail("min_spring_reserve",
              "needs spring_preload_N (or _kgf), moving_mass_kg and [output] speed_rpm");
    }
    if (f.min_spring_reserve && !(*f.min_spring_reserve > 0.0 && *f.min_spring_reserve <= 1e6))
      ch.Fail("min_spring_reserve", "must be in (0, 1e6]");
    f.contact_length_m = length("contact_length", true);
    if (auto e = ch.OptionalQuantity("elastic_modulus", Dimension::kPressure)) {
      if (!(*e > 0.0 && *e <= 1e13))
        ch.Fail(ch.last_key(), "must be in (0, 1e4] GPa, got " + Number(*e * 1e-9) + " GPa");
      f.elastic_modulus_Pa = *e;
    }
    if (auto nu = ch.OptionalNumber("poisson")) {
      if (!(*nu >= 0.0 && *nu < 0.5)) ch.Fail("poisson", "must be in [0, 0.5), got " + Number(*nu));
      f.poisson = *nu;
    }
    f.max_contact_stress_Pa = ch.OptionalQuantity("max_contact_stress", Dimension::kPressure);
    if (f.max_contact_stress_Pa &&
        !(*f.max_contact_stress_Pa > 0.0 && *f.max_contact_stress_Pa <= 1e13))
      ch.Fail(ch.last_key(),
              "must be in (0, 1e7] MPa, got " + Number(*f.max_contact_stress_Pa * 1e-6) + " MPa");
    if (f.max_contact_stress_Pa &&
        !(f.contact_length_m && f.spring_preload_N && f.moving_mass_kg && f.base_radius_m)) {
      ch.Fail("max_contact_stress",
              "needs contact_length_mm, spring_preload, moving_mass_kg and base_radius_mm");
    }

    if (f.max_pressure_angle_rad && !f.base_radius_m)
      ch.Fail("base_radius", "the pressure-angle check needs base_radius_mm");
    ch.Finish();
  }
  if (const toml::table* t = Section(root, path, "output")) {
    SectionReader o(t, path, "output");
    if (auto fall = o.OptionalString("fall")) {
      if (*fall != "mirror" && *fall != "none") o.Fail("fall", "expected \"mirror\" or \"none\"");
      f.mirror_fall = *fall == "mirror";
    }
    f.crank_start_rad = o.OptionalQuantity("crank_start", Dimension::kAngle).value_or(0.0);
    if (auto n = o.OptionalQuantity("speed", Dimension::kRotationSpeed)) {
      if (!(*n > 0.0 && *n <= 1e6))
        o.Fail("speed_rpm", "must be in (0, 1e6] rpm, got " + Number(*n));
      f.speed_rpm = *n;
    }
    if (auto cyc = o.OptionalString("cycle")) {
      if (*cyc != "four-stroke" && *cyc != "two-stroke")
        o.Fail("cycle", "expected \"four-stroke\" or \"two-stroke\"");
      f.cycle = *cyc;
    }
    o.Finish();
  }
  return f;
}

DesignInputs LoadDesignInputs(const std::string& path) {
  return ParseDesignInputs(ReadInputFile(path, "engine file"), path);
}

std::optional<double> PaperVelocityAt(const Case& c, double crank_rad) {
  if (!c.paper) return std::nullopt;
  for (size_t i = 0; i < c.paper->crank_rad.size(); ++i) {
    if (std::abs(c.paper->crank_rad[i] - crank_rad) < 1e-9) return c.paper->velocity_m_s[i];
  }
  return std::nullopt;
}

bool IsCsvPath(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == ".csv";
}

Case CaseFromLiftCsv(const std::string& path, const std::string& cycle) {
  Case c;
  c.path = path;
  c.engine.cycle = cycle;
  c.lift.table = ReadLiftCsv(path, cycle == "four-stroke", &c.lift.lines);
  c.lift.source = "csv " + path;
  c.lift.csv_path = path;
  return c;
}

LiftLawChoice CaseLiftChoice(const Case& c) {
  LiftDataOptions o;
  if (c.lift.spline_given) o.kind = c.lift.spline.kind;
  o.spline = c.lift.spline;
  o.noise_m = c.lift.noise_m;
  if (c.lift.resolution_given) o.resolution_m = c.lift.resolution_m;
  o.open_rad = c.lift.open_rad;
  o.close_rad = c.lift.close_rad;
  o.breaks_rad = c.lift.breaks_rad;
  o.drop_outliers = c.lift.drop_outliers;
  o.find_breaks = !c.lift.breaks_given;
  LiftLawChoice choice = ChooseLiftLaw(c.lift.table, o);
  if (choice.corner) {
    // A corner: the lift's velocity jumps, the law cannot be differentiated there.
    const LiftBreak& k = *choice.corner;
    std::string at = c.path + ": [lift] " + c.lift.lift_key + "[" + std::to_string(k.index) + "]";
    if (k.index < c.lift.lines.size()) {
      at = c.lift.csv_path + ":" + std::to_string(c.lift.lines[k.index]);
      if (c.lift.csv_path != c.path) at = c.path + ": [lift] csv: " + at;
    }
    throw CaseError(at + ": the lift has a corner at " + Fixed(k.crank_rad / kDeg, 3) +
                    " deg (its velocity jumps by " + Fixed(k.jump * 1e3 * kDeg, 4) +
                    " mm/deg): a needle's lift has no corners; correct the readings there, or "
                    "round the corner off in the law the table was made from");
  }
  if (choice.outliers.empty()) return choice;
  // Where a reading is: the CSV file's line, or the entry of the case's array.
  auto where = [&](size_t index) {
    if (index < c.lift.lines.size()) return "line " + std::to_string(c.lift.lines[index]);
    return "entry " + std::to_string(index);
  };
  auto reading = [&](const LiftOutlier& x) {
    return Number(x.lift_m * 1e3) + " mm at " + Number(c.lift.table.crank_rad[x.index] / kDeg) +
           " deg";
  };
  const LiftOutlier& first = choice.outliers.front();
  const size_t more = choice.outliers.size() - 1;
  if (!c.lift.drop_outliers) {
    std::string at;
    if (first.index < c.lift.lines.size()) {
      at = c.lift.csv_path + ":" + std::to_string(c.lift.lines[first.index]);
      if (c.lift.csv_path != c.path) at = c.path + ": [lift] csv: " + at;
    } else {
      at = c.path + ": [lift] " + c.lift.lift_key + "[" + std::to_string(first.index) + "]";
    }
    std::string others;
    for (size_t k = 1; k < choice.outliers.size() && k <= 5; ++k) {
      others += (k > 1 ? ", " : "") + where(choice.outliers[k].index);
    }
    if (more > 5) others += ", …";
    throw CaseError(
        at + ": the reading " + reading(first) + " stands out of its neighbourhood (" +
        Number(first.expected_m * 1e3) + " mm by the cubic through the four readings around it, " +
        Number(std::round(first.sigmas)) + " robust sigma of " +
        Number(choice.robust_noise_m * 1e3) + " mm off): an outlier" +
        (more ? " (" + std::to_string(more) + " more: " + others + ")" : std::string()) +
        "; correct it, or set [lift] outliers = \"drop\" to leave it out" +
        (c.lift.csv_path == c.path ? " (in a case file reading this table with csv = …)" : ""));
  }
  choice.reason += "; " + std::to_string(choice.outliers.size()) + " outlier" + (more ? "s" : "") +
                   " left out (";
  for (size_t k = 0; k < choice.outliers.size(); ++k) {
    const LiftOutlier& x = choice.outliers[k];
    choice.reason += (k ? "; " : "") + where(x.index) + ": " + reading(x) + ", neighbourhood " +
                     Number(x.expected_m * 1e3) + " mm";
  }
  choice.reason += ")";
  return choice;
}

LiftLaw MakeLiftLaw(const Case& c) {
  try {
    const LiftLawChoice choice = CaseLiftChoice(c);
    return LiftLaw(choice.table, choice.law);
  } catch (const CaseError&) {
    throw;
  } catch (const std::exception& e) {
    throw CaseError(c.path + ": [lift]: " + e.what());
  }
}

}  // namespace needle
