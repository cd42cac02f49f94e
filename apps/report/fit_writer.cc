#include "apps/report/fit_writer.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "lib/output.h"
#include "lib/units.h"

namespace needle {

namespace {

nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

std::string Unit(const FitKey& k) { return k.unit.empty() ? "" : " " + k.unit; }

// "a and b": the names of an unseparated pair.
std::string PairNames(const FitResult& r, const UnseparatedPair& p) {
  return r.parameters[p.a].key.name + " and " + r.parameters[p.b].key.name;
}

std::string PairAdvice(const FitResult& r, const UnseparatedPair& p) {
  std::ostringstream m;
  m << PairNames(r, p) << " are not separated by these traces (correlation "
    << Significant(p.correlation, 3) << "): the traces fix mainly a combination of the two";
  if (p.separating_rpm) {
    m << "; a trace at " << Significant(*p.separating_rpm, 4)
      << " rpm would narrow their intervals " << Significant(p.narrowing_a, 3) << " and "
      << Significant(p.narrowing_b, 3) << " times (correlation "
      << Significant(p.correlation_with, 3) << ")";
  } else {
    m << "; no second speed tried (0.5 to 2 times the traces' and the rated) would narrow their "
         "two intervals by a product of 4 (each about 2 times)";
  }
  return m.str();
}

}  // namespace

nlohmann::json FitJson(const BoundCase& c, const FitResult& r) {
  nlohmann::json j;
  j["case"] = c.path;
  nlohmann::json params = nlohmann::json::object();
  for (const FittedValue& v : r.parameters) {
    params[v.key.name] = {{"value", v.value},
                          {"low", v.low},
                          {"high", v.high},
                          {"start", v.start},
                          {"lower_bound", v.lower_bound},
                          {"upper_bound", v.upper_bound},
                          {"at_bound", v.at_bound},
                          {"identified", v.identified},
                          {"widened_by_scan", v.widened},
                          {"note", v.note}};
  }
  j["parameters"] = params;
  nlohmann::json corr = nlohmann::json::object();
  for (size_t a = 0; a < r.parameters.size(); ++a) {
    for (size_t b = 0; b < r.parameters.size(); ++b) {
      corr[r.parameters[a].key.name][r.parameters[b].key.name] = Number(r.correlation[a][b]);
    }
  }
  j["correlations"] = corr;
  j["unseparated"] = nlohmann::json::array();
  for (const UnseparatedPair& p : r.unseparated) {
    nlohmann::json u = {{"a", r.parameters[p.a].key.name},
                        {"b", r.parameters[p.b].key.name},
                        {"correlation", p.correlation},
                        {"advice", PairAdvice(r, p)}};
    u["separating_rpm"] = p.separating_rpm ? nlohmann::json(*p.separating_rpm) : nlohmann::json();
    if (p.separating_rpm) {
      u["correlation_with"] = p.correlation_with;
      u["narrowing"] = {p.narrowing_a, p.narrowing_b};
    }
    j["unseparated"].push_back(u);
  }
  j["traces"] = nlohmann::json::array();
  for (const TraceFit& t : r.traces) {
    j["traces"].push_back({{"path", t.path},
                           {"speed_rpm", t.speed_rpm},
                           {"readings", t.readings},
                           {"used", t.used},
                           {"noise_mm", t.noise_m * 1e3},
                           {"residual_rms_mm", t.rms_m * 1e3},
                           {"residual_over_noise", t.rms_m / t.noise_m},
                           {"runs_z", t.runs_z},
                           {"worst_from_deg", t.worst_from_rad / kDeg},
                           {"worst_to_deg", t.worst_to_rad / kDeg},
                           {"worst_rms_mm", t.worst_rms_m * 1e3}});
  }
  j["notes"] = r.notes;
  j["model"] = {{"chi2_reduced", r.chi2_reduced},
                {"scale_squared", r.scale2},
                {"misses_something", r.model_misses},
                {"note", r.model_note},
                {"residual_note", r.residual_note}};
  if (r.liftoff) {
    const LiftoffPrediction& p = *r.liftoff;
    nlohmann::json l = {{"status", p.status},
                        {"draws", p.draws},
                        {"draws_without_liftoff", p.draws_without},
                        {"draws_refused", p.draws_refused},
                        {"to_rpm", p.to_rpm}};
    const bool drawn = p.draws > p.draws_refused;
    l["value"] = p.value ? nlohmann::json(*p.value) : nlohmann::json();
    // null: no draw ran; high null with high_above_sweep: above the sweep's end
    l["low"] = drawn && std::isfinite(p.low) ? nlohmann::json(p.low) : nlohmann::json();
    l["high"] = drawn && std::isfinite(p.high) ? nlohmann::json(p.high) : nlohmann::json();
    l["high_above_sweep"] = drawn && !std::isfinite(p.high);
    j["liftoff_rpm_dynamic"] = l;
  }
  j["solver"] = {{"cost", r.cost},
                 {"iterations", r.iterations},
                 {"restarts", r.restarts},
                 {"starts", r.start_costs.size()},
                 {"model_runs", r.model_runs},
                 {"termination", r.termination},
                 {"seconds", r.seconds}};
  nlohmann::json costs = nlohmann::json::array();
  for (double s : r.start_costs) costs.push_back(Number(s));
  j["solver"]["start_costs"] = costs;
  return j;
}

std::string FitText(const BoundCase& c, const FitResult& r,
                    const std::optional<std::string>& report_path,
                    const std::optional<std::string>& case_path) {
  std::ostringstream o;
  o << "fit of " << c.path << " to " << r.traces.size() << " trace(s)\n";
  for (const TraceFit& t : r.traces) {
    o << "  " << t.path << " at " << Significant(t.speed_rpm, 6) << " rpm: " << t.used << " of "
      << t.readings << " readings in the run window, noise " << Significant(t.noise_m * 1e3, 3)
      << " mm, residual RMS " << Significant(t.rms_m * 1e3, 3) << " mm ("
      << Significant(t.rms_m / t.noise_m, 3) << " x noise)\n";
  }
  o << "fitted values (95 % intervals):\n";
  for (const FittedValue& v : r.parameters) {
    o << "  " << std::left << std::setw(32) << v.key.name << Significant(v.value, 6) << Unit(v.key)
      << "  [" << Significant(v.low, 5) << ", " << Significant(v.high, 5)
      << "]  (case: " << Significant(v.start, 6) << ")";
    if (!v.identified) {
      o << "  " << v.note;
    } else if (v.widened) {
      o << "  widened: the cost is as low farther out";
    }
    if (v.at_bound) o << "  at a bound";
    o << "\n";
  }
  for (const UnseparatedPair& p : r.unseparated) o << "  " << PairAdvice(r, p) << "\n";
  o << "residual: reduced chi-square " << Significant(r.chi2_reduced, 4)
    << ", robust scale squared " << Significant(r.scale2, 4)
    << (r.scale2 > 1.0 ? " (the intervals are widened by it)" : "") << "\n";
  for (const std::string& n : r.notes) o << "note: " << n << "\n";
  if (r.model_misses) o << "model: " << r.model_note << "\n";
  if (!r.residual_note.empty()) o << "residual: " << r.residual_note << "\n";
  if (r.liftoff) {
    const LiftoffPrediction& p = *r.liftoff;
    o << "n_dyn of the fitted case: ";
    if (p.value) {
      o << Significant(*p.value, 5) << " rpm";
    } else {
      o << "none up to " << Significant(p.to_rpm, 5) << " rpm (" << p.status << ")";
    }
    if (p.draws > p.draws_without) {
      o << ", 95 % range " << Significant(p.low, 5) << " to " << Significant(p.high, 5)
        << " rpm over " << p.draws << " draws";
      if (p.draws_without)
        o << " (" << p.draws_without << " without lift-off up to the sweep's end)";
    }
    o << "\n";
  }
  o << "solver: " << r.start_costs.size() << " start(s), " << r.model_runs << " model runs, "
    << Significant(r.seconds, 3) << " s; " << r.termination << "\n";
  if (case_path) o << "calibrated case: " << *case_path << "\n";
  if (report_path) o << "report: " << *report_path << "\n";
  return o.str();
}

Report FitReport(const BoundCase& c, const FitResult& r) {
  Report report("needle fit: " + (c.title.empty() ? c.path : c.title));
  std::ostringstream head;
  head << "<h1>Fit of " << Escape(c.path) << "</h1>\n<table><tr><th>key</th><th>case</th>"
       << "<th>fitted</th><th>95 % interval</th><th></th></tr>\n";
  for (const FittedValue& v : r.parameters) {
    head << "<tr><td>" << Escape(v.key.name) << "</td><td>" << Significant(v.start, 6)
         << "</td><td>" << Significant(v.value, 6) << "</td><td>" << Significant(v.low, 5) << " to "
         << Significant(v.high, 5) << "</td><td>"
         << Escape(v.identified ? (v.widened ? "widened by the scan" : "") : v.note)
         << (v.at_bound ? " at a bound" : "") << "</td></tr>\n";
  }
  head << "</table>\n";
  for (const UnseparatedPair& p : r.unseparated)
    head << "<p>" << Escape(PairAdvice(r, p)) << "</p>\n";
  head << "<p>Reduced chi-square " << Significant(r.chi2_reduced, 4) << ", robust scale squared "
       << Significant(r.scale2, 4) << ".</p>\n";
  for (const std::string& n : r.notes) head << "<p>" << Escape(n) << "</p>\n";
  if (r.model_misses) head << "<p><b>Model:</b> " << Escape(r.model_note) << "</p>\n";
  if (!r.residual_note.empty()) head << "<p>" << Escape(r.residual_note) << "</p>\n";
  report.AddHtml(head.str());
  for (const TraceFit& t : r.traces) {
    Series s{"trace", {}};
    for (size_t i = 0; i < t.crank_rad.size(); ++i) {
      s.rows.push_back({t.crank_rad[i] / kDeg, t.measured_m[i] * 1e3, t.fitted_m[i] * 1e3,
                        (t.measured_m[i] - t.fitted_m[i]) * 1e3});
    }
    const std::string name = t.path + " at " + Significant(t.speed_rpm, 6) + " rpm";
    report.AddFigure(
        "Measured and fitted lift: " + name, {s},
        "set xlabel 'crank angle (deg)'\nset ylabel 'lift (mm)'\nset key top right\n"
        "plot $trace using 1:2 with points pt 7 ps 0.3 lc rgb '#888888' title "
        "'measured', $trace using 1:3 with lines lw 2 lc rgb '#d62728' title 'fitted'");
    const std::string band = Fixed(2.0 * t.noise_m * 1e3, 9);
    report.AddFigure("Residual, measured − fitted, against ±2σ of the trace's noise: " + name, {s},
                     "set xlabel 'crank angle (deg)'\nset ylabel 'residual (mm)'\nunset key\n"
                     "plot $trace using 1:4 with points pt 7 ps 0.3 lc rgb '#1f77b4', " +
                         band + " with lines lc rgb '#888888', -" + band +
                         " with lines lc rgb '#888888'",
                     300);
  }
  return report;
}

}  // namespace needle
