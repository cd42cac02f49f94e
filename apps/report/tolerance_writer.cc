// What tolerance prints: its JSON object, text and report (tolerance_writer.h).
#include "apps/report/tolerance_writer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/bound_case.h"
#include "apps/report/html_report.h"
#include "apps/report/output_paths.h"
#include "apps/report/result_writers.h"
#include "apps/study/tolerance_study.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {
namespace {

// The quantities the text and the report lead with (all are in the JSON).
const std::vector<std::pair<std::string, std::string>> kHeadline = {
    {"spring.liftoff_rpm_quasi_static", "n_qs (rpm)"},
    {"overspeed.liftoff_rpm_dynamic", "n_dyn (rpm)"},
    {"spring.preload_margin_percent", "preload margin against the sizing (%)"},
    {"spring.basu_deviation_percent", "preload against Basu's formula (%)"},
    {"dynamics.min_contact_force_during_lift_N", "least contact force in the lift (N)"},
    {"dynamics.max_impact_speed_m_s", "largest impact speed (m/s)"},
};

std::string Rho(double r) { return std::isfinite(r) ? Fixed(r, 3) : std::string("-"); }

// The inputs by |ρ|, largest first, as "name ρ" pairs.
std::vector<std::pair<std::string, double>> Ranked(const Drivers& d) {
  std::vector<std::pair<std::string, double>> v;
  for (const auto& [k, r] : d)
    if (std::isfinite(r)) v.emplace_back(k, r);
  std::sort(v.begin(), v.end(),
            [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  return v;
}

}  // namespace

nlohmann::json ToleranceJson(const BoundCase& c, const ToleranceResult& r) {
  const ToleranceSection& t = r.tolerance;
  const double n = static_cast<double>(r.samples.size());
  const double p_low = r.failure_probability_low, p_high = r.failure_probability_high;
  nlohmann::json j;
  j["case"] = c.path;
  j["samples"] = r.samples.size();
  j["seed"] = r.options.seed;
  j["first_sample"] = r.options.first_sample;
  j["threads"] = r.options.threads;
  j["seconds"] = r.seconds;
  j["seconds_per_sample"] = r.seconds * r.options.threads / n;
  PutFields(j["tolerance"], ToleranceSectionFields(t));
  j["tolerance"]["applied"] = ScatterSources(t);
  j["failure_probability"] = r.failure_probability;
  j["failure_probability_95"] = {p_low, p_high};
  j["failure_by_item"] = r.failure_by_item;
  nlohmann::json drivers;
  for (const auto& [k, v] : r.fail_drivers) drivers[k] = Finite(v);
  j["fail_drivers"] = drivers;
  nlohmann::json dist;
  for (const auto& [key, d] : r.distributions) {
    nlohmann::json od;
    if (const auto it = r.output_drivers.find(key); it != r.output_drivers.end())
      for (const auto& [k, v] : it->second) od[k] = Finite(v);
    PutFields(dist[key], DistributionFields(d));
    dist[key]["drivers"] = od;
  }
  j["distributions"] = dist;
  nlohmann::json samples = nlohmann::json::array();
  for (const ToleranceSample& s : r.samples) {
    nlohmann::json in, out;
    for (const auto& [k, v] : s.inputs) in[k] = Finite(v);
    for (const auto& [k, v] : s.outputs) out[k] = Finite(v);
    nlohmann::json one = {
        {"inputs", in}, {"outputs", out}, {"pass", s.pass}, {"failing", s.failing}};
    if (!s.refused.empty()) one["refused"] = s.refused;
    samples.push_back(one);
  }
  j["sample_results"] = samples;
  return j;
}

Report ToleranceReport(const BoundCase& c, const ToleranceResult& r, std::uint64_t seed) {
  const ToleranceSection& t = r.tolerance;
  const double p_low = r.failure_probability_low, p_high = r.failure_probability_high;
  Report report("needle tolerance: " + (c.title.empty() ? c.path : c.title));  // Html escapes
  std::ostringstream head;
  head << "<p>" << r.samples.size() << " samples, seed " << seed << ", " << r.options.threads
       << " threads, " << Fixed(r.seconds, 1) << " s.</p><h2>Scatter (one σ)</h2><table>"
       << "<tr><td>lift-table error</td><td>" << Fixed(t.lift_sigma_m * 1e3, 4)
       << " mm, correlation length " << Fixed(t.lift_correlation_rad / kDeg, 2)
       << "°</td></tr><tr><td>mass, preload, rate, stiffness, speed</td><td>"
       << Fixed(100 * t.mass_fraction, 2) << ", " << Fixed(100 * t.preload_fraction, 2) << ", "
       << Fixed(100 * t.rate_fraction, 2) << ", " << Fixed(100 * t.stiffness_fraction, 2) << ", "
       << Fixed(100 * t.speed_fraction, 2) << " %</td></tr><tr><td>roller play</td><td>"
       << Fixed(t.play_sigma_m * 1e3, 4) << " mm</td></tr><tr><td>applied</td><td>"
       << Escape(ScatterSources(t)) << "</td></tr></table>"
       << "<h2>Failure</h2><p>The check fails in " << Fixed(100 * r.failure_probability, 2)
       << " % of the samples (95 % interval " << Fixed(100 * p_low, 2) << "–"
       << Fixed(100 * p_high, 2) << " %).</p><table class=\"grid\"><tr><th>failing item</th>"
       << "<th>samples</th></tr>";
  for (const auto& [item, p] : r.failure_by_item)
    head << "<tr><td>" << Escape(item) << "</td><td>" << Fixed(100 * p, 2) << " %</td></tr>";
  head << "</table><h2>What drives it (Spearman ρ with failing)</h2><table class=\"grid\">";
  for (const auto& [input, rho] : Ranked(r.fail_drivers))
    head << "<tr><td>" << Escape(input) << "</td><td>" << Rho(rho) << "</td></tr>";
  head << "</table><h2>Distributions</h2><table class=\"grid\"><tr><th>quantity</th><th>mean"
       << "</th><th>σ</th><th>5 %</th><th>median</th><th>95 %</th><th>finite</th></tr>";
  for (const auto& [key, d] : r.distributions) {
    head << "<tr><td>" << Escape(key) << "</td><td>" << Fixed(d.mean, 4) << "</td><td>"
         << Fixed(d.std_dev, 4) << "</td><td>" << Fixed(d.p05, 4) << "</td><td>" << Fixed(d.p50, 4)
         << "</td><td>" << Fixed(d.p95, 4) << "</td><td>" << d.count << "</td></tr>";
  }
  report.AddHtml(head.str() + "</table>");
  for (const auto& [key, label] : kHeadline) {
    const auto it = r.distributions.find(key);
    if (it == r.distributions.end() || it->second.count < 2 || !(it->second.max > it->second.min))
      continue;
    Series values{"v", {}};
    for (const ToleranceSample& s : r.samples) {  // a refused sample has no outputs
      const auto v = s.outputs.find(key);
      if (v != s.outputs.end() && std::isfinite(v->second)) values.rows.push_back({v->second});
    }
    const double width = (it->second.max - it->second.min) / 30.0;
    // A spread within round-off, or bins below their printed resolution (12 decimals: a width
    // printed as 0 made gnuplot refuse the figure), is no histogram.
    const double scale = std::max(std::abs(it->second.max), std::abs(it->second.min));
    if (!(width >= 1e-11) || !(it->second.max - it->second.min > 1e-9 * scale)) continue;
    report.AddFigure(
        label + ": histogram of " + std::to_string(it->second.count) + " samples", {values},
        "set xlabel \"" + label +
            "\"\nset ylabel 'samples'\nunset key\nset style fill solid 0.6\n"
            "bin(x) = " +
            Fixed(width, 12) + " * floor((x - " + Fixed(it->second.min, 12) + ") / " +
            Fixed(width, 12) + ") + " + Fixed(it->second.min + width / 2, 12) +
            "\nplot $v using (bin($1)):(1.0) smooth frequency with boxes lc rgb '#1f77b4'",
        320);
  }
  return report;
}

std::string ToleranceText(const BoundCase& c, const ToleranceResult& r, std::uint64_t seed,
                          const std::optional<std::string>& report_path) {
  const ToleranceSection& t = r.tolerance;
  const double n = static_cast<double>(r.samples.size());
  const double p_low = r.failure_probability_low, p_high = r.failure_probability_high;
  std::ostringstream out;
  out << (c.title.empty() ? c.path : c.title) << '\n'
      << r.samples.size() << " samples, seed " << seed << ", " << r.options.threads
      << " threads: " << Fixed(r.seconds, 2) << " s, "
      << Fixed(1e3 * r.seconds * r.options.threads / n, 1) << " ms of one core per sample\n"
      << "scatter (one sigma): lift " << Fixed(t.lift_sigma_m * 1e3, 4) << " mm (correlation "
      << Fixed(t.lift_correlation_rad / kDeg, 2) << " deg), mass "
      << Fixed(100 * t.mass_fraction, 2) << " %, preload " << Fixed(100 * t.preload_fraction, 2)
      << " %, rate " << Fixed(100 * t.rate_fraction, 2) << " %, stiffness "
      << Fixed(100 * t.stiffness_fraction, 2) << " %, play " << Fixed(t.play_sigma_m * 1e3, 4)
      << " mm, speed " << Fixed(100 * t.speed_fraction, 2) << " %\n"
      << "scatter applied: " << ScatterSources(t) << "\n\n";
  char line[300];
  std::snprintf(line, sizeof line, "%-40s %11s %10s %11s %11s %11s\n", "", "mean", "sigma", "5 %",
                "median", "95 %");
  out << line;
  for (const auto& [key, label] : kHeadline) {
    const auto it = r.distributions.find(key);
    if (it == r.distributions.end()) continue;
    const Distribution& d = it->second;
    std::snprintf(line, sizeof line, "%-40s %11.4g %10.3g %11.4g %11.4g %11.4g%s\n", label.c_str(),
                  d.mean, d.std_dev, d.p05, d.p50, d.p95,
                  d.count < static_cast<int>(n)
                      ? (" (" + std::to_string(static_cast<int>(n) - d.count) + " without)").c_str()
                      : "");
    out << line;
  }
  out << "\nthe check fails in " << Fixed(100 * r.failure_probability, 2)
      << " % of the samples (95 % " << Fixed(100 * p_low, 2) << " .. " << Fixed(100 * p_high, 2)
      << " %)\n";
  for (const auto& [item, p] : r.failure_by_item) {
    out << "  " << item << ": " << Fixed(100 * p, 2) << " %";
    if (item == "case refused") {
      for (const ToleranceSample& s : r.samples) {
        if (s.refused.empty()) continue;
        out << " (the first: " << s.refused << ")";
        break;
      }
    }
    out << '\n';
  }
  if (r.failure_probability > 0.0 && r.failure_probability < 1.0) {
    out << "what drives failing (Spearman rho):";
    for (const auto& [input, rho] : Ranked(r.fail_drivers)) out << ' ' << input << ' ' << Rho(rho);
    out << '\n';
  }
  const auto dyn = r.output_drivers.find("overspeed.liftoff_rpm_dynamic");
  if (dyn != r.output_drivers.end()) {
    out << "what drives n_dyn (Spearman rho):";
    for (const auto& [input, rho] : Ranked(dyn->second)) out << ' ' << input << ' ' << Rho(rho);
    out << '\n';
  }
  if (report_path) out << "report: " << *report_path << '\n';
  return out.str();
}

}  // namespace needle
