// The design page's computations: design_api.h.
#include "apps/serve/design_api.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <stdexcept>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/case/case_writer.h"
#include "apps/report/check_writers.h"
#include "apps/report/html_report.h"
#include "apps/study/check_scene.h"
#include "dynamics/simulation.h"
#include "lib/case_error.h"
#include "lib/input_file.h"
#include "lib/kinematics.h"
#include "lib/units.h"

namespace needle {
namespace {

constexpr char kKeyChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_";

constexpr Dimension kDimensions[] = {
    Dimension::kAngle,       Dimension::kLength,  Dimension::kVelocity,  Dimension::kAcceleration,
    Dimension::kMass,        Dimension::kForce,   Dimension::kStiffness, Dimension::kTime,
    Dimension::kPressure,    Dimension::kDensity, Dimension::kSlope,     Dimension::kPercent,
    Dimension::kTemperature, Dimension::kArea,    Dimension::kVolume,    Dimension::kPower};

// The keys of `section` that state `key`'s quantity in another unit (preload_kgf beside
// preload_N): an override replaces them.
std::vector<std::string> SameQuantity(const toml::table& section, const std::string& key) {
  std::vector<std::string> out;
  for (Dimension d : kDimensions) {
    for (const std::string& unit : UnitSuffixes(d)) {
      const std::string tail = "_" + unit;
      if (key.size() <= tail.size() || key.compare(key.size() - tail.size(), tail.size(), tail))
        continue;
      const std::string stem = key.substr(0, key.size() - tail.size());
      for (const std::string& other : UnitSuffixes(d)) {
        if (other != unit && section.contains(stem + "_" + other))
          out.push_back(stem + "_" + other);
      }
    }
  }
  return out;
}

// A JSON scalar as TOML text; empty for what a case file cannot hold.
std::string ScalarText(const nlohmann::json& v) {
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX)) return "";
  if (v.is_number_integer()) return std::to_string(v.get<int64_t>());
  if (v.is_number()) {
    const double x = v.get<double>();
    return std::isfinite(x) ? ExactDecimal(x) : "";
  }
  if (v.is_string()) {
    std::ostringstream out;
    out << toml::value<std::string>(v.get<std::string>());
    return out.str();
  }
  return "";
}

nlohmann::json ParseBody(const std::string& body, const std::string& where) {
  if (body.find_first_not_of(" \t\r\n") == std::string::npos) return nlohmann::json::object();
  nlohmann::json j = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded())
    throw CaseError(where +
                    ": overrides: expected a JSON object such as "
                    "{\"spring\": {\"preload_N\": 1700}}, got text that is not JSON");
  return j;
}

ApiReply Error(const std::string& line) { return {400, nlohmann::json{{"error", line}}.dump()}; }

// One curve of a run as the page draws it: the rows a line plot of the series needs at twice
// the report's figure width (LineEnvelope, the report's own: every peak and drop kept, where
// every n-th point would lose an impact's spike), as {"crank_deg": […], "value": […]}.
template <typename Value>
nlohmann::json Curve(const std::vector<SeriesPoint>& series, Value value) {
  Rows rows;
  for (const SeriesPoint& p : series) rows.push_back({p.crank_rad / kDeg, value(p)});
  const Rows drawn = LineEnvelope(rows, series.front().crank_rad / kDeg,
                                  series.back().crank_rad / kDeg, 2 * kFigureWidthPx);
  std::vector<double> x, y;
  for (size_t i = 0; i < drawn.size(); ++i) {
    x.push_back(drawn.row(i)[0]);
    y.push_back(drawn.row(i)[1]);
  }
  return {{"crank_deg", x}, {"value", y}};
}

nlohmann::json PageSeries(const BoundCase& c, const CheckResult& r) {
  nlohmann::json s;
  const Kinematics kin(*c.lift.law, r.speed_rpm);
  const KinematicsSummary& sum = r.kinematics;
  std::vector<double> deg, lift, vel, acc;
  for (int i = 0; i <= 400; ++i) {
    const double th = sum.open_rad + (sum.close_rad - sum.open_rad) * i / 400.0;
    const KinematicsPoint p = kin.At(th);
    deg.push_back(th / kDeg);
    lift.push_back(p.lift_m * 1e3);
    vel.push_back(p.velocity_m_s);
    acc.push_back(p.acceleration_m_s2.value_or(NAN));
  }
  s["kinematics"] = {
      {"crank_deg", deg}, {"lift_mm", lift}, {"velocity_m_s", vel}, {"acceleration_m_s2", acc}};
  // The acceleration's 95 % band where the law is a local fit of measured readings (the lift
  // table's accuracy, docs/lift-data.md): at its nodes, at the rated speed.
  const double w2 = kin.omega() * kin.omega();
  std::vector<double> band_deg, low, high;
  for (const LocalNode& n : c.lift.law->nodes()) {
    if (n.x < sum.open_rad || n.x > sum.close_rad) continue;
    band_deg.push_back(n.x / kDeg);
    low.push_back((n.s[2] - n.band2) * w2);
    high.push_back((n.s[2] + n.band2) * w2);
  }
  if (!band_deg.empty())
    s["acceleration_band"] = {{"crank_deg", band_deg}, {"low_m_s2", low}, {"high_m_s2", high}};
  if (r.run && !r.run->series.empty()) {
    const std::vector<SeriesPoint>& run = r.run->series;
    const auto force = [](const SeriesPoint& p) { return p.contact_force_N; };
    s["run"] = {{"lift_mm", Curve(run, [](const SeriesPoint& p) { return p.lift_m * 1e3; })},
                {"cam_mm", Curve(run, [](const SeriesPoint& p) { return p.cam_m * 1e3; })},
                {"contact_force_N", Curve(run, force)}};
    // The impacts, at the needle's lift where they happen (the series' first point from there).
    std::vector<double> at, impact_lift;
    std::vector<std::string> kind;
    for (const Impact& i : r.run->impacts) {
      const auto near = std::lower_bound(
          run.begin(), run.end(), i.crank_rad,
          [](const SeriesPoint& p, double crank_rad) { return p.crank_rad < crank_rad; });
      at.push_back(i.crank_rad / kDeg);
      impact_lift.push_back((near == run.end() ? run.back() : *near).lift_m * 1e3);
      kind.push_back(i.kind);
    }
    s["impacts"] = {{"crank_deg", at}, {"lift_mm", impact_lift}, {"kind", kind}};
    // The contact force at f·n, the speed the verdict asks the needle to follow the cam at:
    // one more run of the check's scene with the rated run's options.
    if (c.scene && r.overspeed_rpm > 0.0) {
      SimulationOptions o = r.run_options;
      o.record_series = true;
      o.series_sink = nullptr;
      const SimulationResult at_fn = Simulate(*c.scene, r.overspeed_rpm, o);
      if (!at_fn.series.empty()) {
        s["run_overspeed"] = {{"speed_rpm", r.overspeed_rpm},
                              {"contact_force_N", Curve(at_fn.series, force)}};
      }
    }
  }
  if (r.sweep) {
    std::vector<double> n, f;
    for (const OverspeedRow& row : r.sweep->rows) {
      n.push_back(row.speed_rpm);
      f.push_back(row.min_contact_force_N);
    }
    s["overspeed"] = {{"speed_rpm", n}, {"min_contact_force_N", f}};
  }
  return s;
}

}  // namespace

std::string CaseWithOverrides(const std::string& case_text, const nlohmann::json& overrides,
                              const std::string& where, bool files) {
  if (!overrides.is_object())
    throw CaseError(where +
                    ": overrides: expected a JSON object of sections, such as "
                    "{\"spring\": {\"preload_N\": 1700}}");
  toml::table table;
  try {
    table = toml::parse(case_text, where);
  } catch (const toml::parse_error& e) {
    throw CaseError(where + ": " + std::string(e.description()));
  }
  // The file's own lines, kept: a key replaced is its lines dropped (a multi-line array too, by
  // its source region) and the new line put under its section's header; a new section at the end.
  std::vector<std::string> lines;
  std::istringstream in(case_text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::vector<bool> dropped(lines.size(), false);
  std::map<size_t, std::string> after;  // a header's line (0-based) → the lines put under it
  std::string appended;
  for (const auto& [section, keys] : overrides.items()) {
    if (!keys.is_object())
      throw CaseError(where + ": overrides: " + section +
                      ": expected an object of keys, such as {\"preload_N\": 1700}");
    const toml::table* t = table[section].as_table();
    std::string block;
    for (const auto& [key, value] : keys.items()) {
      const std::string text = ScalarText(value);
      if (text.empty())
        throw CaseError(where + ": overrides: [" + section + "] " + key +
                        ": expected a number, a string or true/false");
      if (key.empty() || section.empty() ||
          (key + section).find_first_not_of(kKeyChars) != std::string::npos)
        throw CaseError(where + ": overrides: " + nlohmann::json(section).dump() + " " +
                        nlohmann::json(key).dump() +
                        ": expected section and key names of letters, digits and _");
      if (key == "csv" && !files)  // a path: the page tunes numbers, it does not open files
        throw CaseError(where + ": overrides: [" + section + "] " + key +
                        ": names a file; the design page does not open files (edit the case)");
      std::vector<std::string> old;  // the key and its quantity in other units, replaced
      if (t) {
        old = SameQuantity(*t, key);
        if (t->contains(key)) old.push_back(key);
      }
      std::string comment;  // a replaced line's own comment, kept on the new line
      for (const std::string& k : old) {
        const toml::source_region& r = t->get(k)->source();
        for (size_t n = r.begin.line; n >= 1 && n <= r.end.line && n <= lines.size(); ++n)
          dropped[n - 1] = true;
        if (!comment.empty() || r.begin.line != r.end.line || r.end.line > lines.size()) continue;
        const std::string& l = lines[r.end.line - 1];
        const size_t hash = l.find('#', std::min<size_t>(r.end.column - 1, l.size()));
        if (hash != std::string::npos) comment = "  " + l.substr(hash);
      }
      block += key + " = " + text + comment + "\n";
    }
    const auto header = [&](const toml::table& written) {  // its own "[section]" line
      const size_t at = written.source().begin.line;
      if (written.is_inline() || at < 1 || at > lines.size()) return false;
      const std::string& l = lines[at - 1];
      const size_t first = l.find_first_not_of(" \t");
      return first != std::string::npos && l[first] == '[';
    };
    if (t && !header(*t))
      throw CaseError(where + ": overrides: [" + section +
                      "]: the case writes this section inline or as dotted keys; write it as a [" +
                      section + "] block to tune it here");
    if (t) {
      after[t->source().begin.line - 1] += block;
    } else {
      appended += "\n[" + section + "]\n" + block;
    }
  }
  std::string out;
  for (size_t n = 0; n < lines.size(); ++n) {
    if (!dropped[n]) out += lines[n] + "\n";
    if (after.count(n)) out += after[n];
  }
  return out + appended;
}

DesignSession::DesignSession(std::string case_path) : path_(std::move(case_path)) {
  text_ = ReadInputFile(path_, "case file");
  (void)ParseCase(text_, path_);  // refused now, with the CLI's line, not at the first request
}

template <typename Reply>
ApiReply DesignSession::Answer(const std::string& request_body, Reply reply) const {
  try {
    return reply(CaseWithOverrides(text_, ParseBody(request_body, path_), path_));
  } catch (const CaseError& e) {
    return Error(e.what());
  } catch (const std::invalid_argument& e) {  // bad input, as the CLI's exit 2 takes it
    return Error(e.what());
  }
}

ApiReply DesignSession::Check(const std::string& request_body) const {
  return Answer(request_body, [this](const std::string& text) -> ApiReply {
    const BoundCase c = Bind(ParseCase(text, path_));
    const CheckResult r = CheckScene(c);  // the CLI's options: its series recorded too
    return {200, CheckJson(c, *c.lift.law, r, "").dump(2)};
  });
}

ApiReply DesignSession::Design(const std::string& request_body) const {
  return Answer(request_body, [this](const std::string& text) -> ApiReply {
    const BoundCase c = Bind(ParseCase(text, path_));
    const CheckResult r = CheckScene(c);
    nlohmann::json j;
    j["check"] = CheckJson(c, *c.lift.law, r, "");
    j["series"] = PageSeries(c, r);
    return {200, j.dump()};
  });
}

ApiReply DesignSession::SaveCase(const std::string& request_body) const {
  return Answer(request_body, [this](const std::string& text) -> ApiReply {
    (void)ParseCase(text, path_);  // what is saved reads back
    return {200, nlohmann::json{{"toml", text}}.dump()};
  });
}

std::string DesignSession::CaseJson() const {
  const toml::table table = toml::parse(text_, path_);
  std::ostringstream out;
  out << toml::json_formatter{table};
  return out.str();
}

}  // namespace needle
