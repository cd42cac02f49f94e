// Parts of the check's HTML report (check_report_parts.h).
#include "apps/report/check_report_parts.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "apps/case/case_profile.h"
#include "apps/report/result_writers.h"
#include "dynamics/overspeed.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/resonance.h"
#include "spring/spring_check.h"

namespace needle::check_report {
namespace {

// Whether the f_1/f_cam screen warns instead of failing (the coils' dynamics show no harm).
bool ScreenWarns(const CheckResult& r) {
  for (const LimitRow& x : r.limits)
    if (x.key == "surge_frequency_ratio") return x.verdict == "warning";
  return false;
}

}  // namespace

std::string Row(const std::string& name, const std::string& value) {
  return "<tr><th>" + Escape(name) + "</th><td>" + value + "</td></tr>";
}

std::string Verdict(bool ok) {
  return ok ? "<span class=\"pass\">pass</span>" : "<span class=\"fail\">FAIL</span>";
}

std::string SceneTable(const BoundCase& c, const LiftLaw& law, const LiftLawChoice& choice,
                       double rpm, const KinematicsSummary& sum) {
  std::ostringstream summary;
  summary << "<h2>Scene</h2><table>" << Row("case", Escape(c.path))
          << Row("rated speed", Fixed(rpm, 1) + " rpm")
          << Row("cycle", Escape(EngineCycleName(c.engine.cycle)))
          << Row("lift law", Escape(c.lift.source) + ", " +
                                 std::to_string(c.lift.table.crank_rad.size()) +
                                 " points, spline " + SplineKindName(law.kind()))
          << Row("spline chosen", Escape(choice.reason))
          << Row("open lift", Fixed(sum.open_rad / kDeg, 2) + "° to " +
                                  Fixed(sum.close_rad / kDeg, 2) + "°" +
                                  (law.closed_level_m() > 0
                                       ? " (where the lift exceeds " +
                                             Fixed(law.closed_level_m() * 1e3, 4) + " mm, 3σ)"
                                       : std::string(" (last zero before the rise to first zero "
                                                     "after the fall)")))
          << Row("injection period", Fixed(sum.injection_period_s * 1e3, 2) + " ms");
  if (Shows(FieldAt(LiftLawFields(law), "undershoot_mm")) && DipBeyondReadings(choice, law)) {
    summary << Row("WARNING", "the spline dips " + Fixed(law.undershoot_m() * 1e3, 4) +
                                  " mm below the seat at " + Fixed(law.undershoot_rad() / kDeg, 2) +
                                  "° inside the open lift; try another spline kind");
  }
  if (!choice.outliers.empty()) {  // left out: [lift] outliers = "drop"
    summary << Row("WARNING", std::to_string(choice.outliers.size()) +
                                  " outlier(s) of the lift table left out (outliers = \"drop\"; "
                                  "the spline's reason lists them)");
  }
  summary << Row("max lift", Fixed(sum.max_lift_m * 1e3, 3) + " mm at " +
                                 Fixed(sum.max_lift_rad / kDeg, 2) + "°")
          << Row("max velocity", Fixed(sum.max_velocity_m_s, 3) + " m/s at " +
                                     Fixed(sum.max_velocity_rad / kDeg, 2) + "°");
  if (sum.max_acceleration_m_s2) {
    const int d = AccelerationDecimals(sum);
    summary << Row("acceleration",
                   Fixed(*sum.max_acceleration_m_s2, d) +
                       PlusMinus(*sum.max_acceleration_m_s2, sum.max_acceleration_band_m_s2, d) +
                       " m/s² max at " + Fixed(*sum.max_acceleration_rad / kDeg, 2) + "°, " +
                       Fixed(*sum.min_acceleration_m_s2, d) +
                       PlusMinus(*sum.min_acceleration_m_s2, sum.min_acceleration_band_m_s2, d) +
                       " m/s² min at " + Fixed(*sum.min_acceleration_rad / kDeg, 2) + "°");
  }
  summary << "</table>";

  return summary.str();
}

std::string SpringTable(const BoundCase& c, const CheckResult& result) {
  const SpringCheckResult& s = *result.spring;
  std::ostringstream t;
  t << "<h2>Spring</h2><table>";
  if (s.basu_preload_N) {  // the row says what fails: the preload, against the formula
    t << Row("Basu's formula", "preload " + Fixed(s.train.preload_N / kKgf, 1) + " kgf vs " +
                                   Fixed(*s.basu_preload_N / kKgf, 1) + " kgf (" +
                                   Fixed(*s.basu_deviation_percent, 1) + " %), tolerance " +
                                   Fixed(s.basu_tolerance_percent, 1) +
                                   " % below: " + Verdict(s.basu_ok));
  }
  t << Row("inertia force m·max|a|",
           Fixed(s.inertia_force_N / kKgf, 2) + " kgf (" + Fixed(s.inertia_force_N, 1) + " N)")
    << Row("spring rate", Fixed(s.train.rate_N_m * 1e-3, 2) + " N/mm")
    << Row("min quasi-static contact force", Fixed(s.min_quasi_static.force_N, 1) + " N at " +
                                                 Fixed(s.min_quasi_static.crank_rad / kDeg, 2) +
                                                 "°")
    << Row("quasi-static lift-off n_qs", FixedOrNone(s.liftoff_rpm_quasi_static, 1) + " rpm")
    << Row("required preload (S " + Fixed(c.spring->safety_factor, 2) + " at " +
               Fixed(c.spring->overspeed_factor, 2) + " n)",
           Fixed(s.required_preload_N, 1) + " N; margin " +
               (std::isfinite(s.preload_margin_percent)
                    ? Fixed(s.preload_margin_percent, 1) + " %"
                    : std::string("unbounded (the rate alone suffices)")) +
               PreloadMarginNote(s) + " " + Verdict(s.preload_ok));
  if (s.helical) {
    const HelicalSpringCheck& h = *s.helical;
    t << Row("helical: shear stress at full lift",
             Fixed(h.stress_full_lift_Pa * 1e-6, 0) + " MPa of " +
                 Fixed(h.allowable_stress_Pa * 1e-6, 0) + " MPa " + Verdict(h.stress_ok))
      << Row("helical: coil gaps at full lift",
             Fixed(h.clearance_full_lift_m * 1e3, 2) + " mm, need " +
                 Fixed(h.min_clearance_m * 1e3, 2) + " mm " + Verdict(h.clearance_ok))
      << Row("helical: surge frequency",
             Fixed(h.surge_hz, 1) + " Hz, " +
                 Fixed(h.surge_ratio, DecimalsApart(h.surge_ratio, kMinSurgeRatio, 1)) +
                 "× the cam's " +
                 (ScreenWarns(result) ? std::string("warning (the coils' dynamics show no harm)")
                                      : Verdict(h.surge_ok)));
  }
  t << Row("combustion load F_g", Fixed(s.gas_force_N / kKgf, 1) + " kgf (" + Escape(s.gas_source) +
                                      "); preload against S·F_g " + Verdict(s.combustion_ok));
  t << Row("spring check", Verdict(s.pass)) << "</table>";
  return t.str();
}

std::string ProfileTable(const BoundCase& c, const CheckResult& result) {
  const auto at = [&](double cam_rad) {
    return CamAndCrank(c, result.cam_zero_crank_rad, cam_rad, 1, "°");
  };
  std::ostringstream t;
  t << "<h2>Cam profile</h2><table>"
    << Row("largest |pressure angle|",
           Fixed(std::abs(result.profile->max_pressure_angle_rad) / kDeg, 2) + "° at " +
               at(result.profile->max_pressure_angle_at_rad))
    << Row("least profile radius (convex)", Fixed(result.profile->min_profile_radius_m * 1e3, 2) +
                                                " mm at " +
                                                at(result.profile->min_profile_radius_at_rad))
    << Row("undercut", result.profile->undercut ? "<span class=\"fail\">UNDERCUT</span>"
                                                : "<span class=\"pass\">none</span>")
    << "</table>";
  return t.str();
}

std::string LimitsTable(const CheckResult& result) {
  std::ostringstream t;
  t << "<h2>Limits</h2><table class=\"grid\"><tr><th>limit</th><th>value</th><th>limit</th>"
       "<th>margin</th><th>verdict</th><th>where / why</th><th>source of the limit</th></tr>";
  for (const LimitRow& x : result.limits) {
    const std::string u = Escape(x.UnitSuffix());
    const bool judged = x.verdict != "not judged";
    const int d = DecimalsApart(x.value, x.limit, 2);
    t << "<tr><td>" << Escape(x.name) << "</td><td>"
      << (judged ? FixedOrNone(x.value, d) + u : std::string("—")) << "</td><td>"
      << (x.at_most ? "≤ " : "≥ ") << (std::isfinite(x.limit) ? FixedOrNone(x.limit, d) + u : "—")
      << "</td><td>" << (judged ? FixedOrNone(x.margin, d) + u : std::string("—")) << "</td><td>"
      << (!judged                  ? std::string("not judged")
          : x.verdict == "warning" ? std::string("warning")
                                   : Verdict(x.verdict == "pass"))
      << "</td><td>" << Escape(x.note) << "</td><td>" << Escape(x.source) << "</td></tr>";
  }
  return t.str() + "</table>";
}

void AddSurgeFigure(Report& report, size_t place, const LiftLaw& law, const CheckResult& result,
                    double rpm) {
  // Surge by its effect: the contact force with the spring as N coil masses against the
  // massless spring's, at the rated speed, over the lift of each run's last revolution
  // (folded onto the first: the steady one where the run has several).
  const SurgeStudy& sg = *result.surge;
  Series chain{"chain", {}}, massless{"massless", {}};
  const double from_rad = law.start_rad() - 5 * kDeg, to_rad = law.end_rad() + 20 * kDeg;
  for (const auto& [one, into] : {std::pair{&sg.rated, &chain}, {&sg.massless, &massless}}) {
    const double shift =
        one->cycles.empty() ? 0.0 : one->cycles.back().start_rad - one->cycles[0].start_rad;
    for (const SeriesPoint& p : one->series) {
      const double th = p.crank_rad - shift;
      if (th >= from_rad && th <= to_rad) into->rows.push_back({th / kDeg, p.contact_force_N});
    }
  }
  // Drawn from a run of rows a pixel column (LineEnvelope: the curves as the whole series draws
  // them; the chain's run has some 20 000 points in the window, and gnuplot's time grows with
  // them).
  for (Series* s : {&chain, &massless})
    s->rows = LineEnvelope(s->rows, from_rad / kDeg, to_rad / kDeg, kFigureWidthPx);
  // Runs stopped on a budget before the lift have nothing to draw (the check fails them as
  // undecided): the figure is left out, saying why.
  const bool drawn = !chain.rows.empty() || !massless.rows.empty();
  if (!drawn) {
    report.Fill(place,
                "<p>Surge figure not drawn: neither run reached the lift (the massless run is " +
                    RunStatusName(sg.massless.status) + ", the run with coil masses " +
                    RunStatusName(sg.rated.status) + ").</p>");
  }
  for (Series* s : {&chain, &massless})
    if (s->rows.empty()) s->rows.push_back({NAN, NAN});
  if (drawn)
    report.FigureAt(
        place,
        "Surge: the contact force with the spring as " + std::to_string(sg.masses) +
            " coil masses against the massless spring, at " + Fixed(rpm, 0) + " rpm",
        {chain, massless},
        "set xlabel 'crank angle (deg)'\nset ylabel 'contact force (N)'\nset key top right\n"
        "plot $massless using 1:2 with lines lw 2 title 'massless spring', $chain using 1:2 "
        "with lines lw 1 title '" +
            std::to_string(sg.masses) + " coil masses'");
}

void AddOverspeed(Report& report, const CheckResult& result) {
  const OverspeedResult& s = *result.sweep;
  const double n_qs = result.n_qs_rpm, overspeed_rpm = result.overspeed_rpm;
  Series rows{"rows", {}};
  for (const OverspeedRow& row : s.rows)
    rows.rows.push_back({row.speed_rpm, row.min_contact_force_N, row.jump_rad / kDeg});
  std::string marks;
  if (std::isfinite(n_qs))
    marks += "set arrow from " + Fixed(n_qs, 2) + ", graph 0 to " + Fixed(n_qs, 2) +
             ", graph 1 nohead dt 2 lc rgb '#555555'\nset label 'n_qs' at " + Fixed(n_qs, 2) +
             ", graph 0.95 offset 0.5,0\n";
  if (s.n_dyn_rpm)
    marks += "set arrow from " + Fixed(*s.n_dyn_rpm, 2) + ", graph 0 to " + Fixed(*s.n_dyn_rpm, 2) +
             ", graph 1 nohead lc rgb '#bb0000'\nset label 'n_dyn' at " + Fixed(*s.n_dyn_rpm, 2) +
             ", graph 0.85 offset 0.5,0 tc rgb '#bb0000'\n";
  report.AddFigure(
      "Overspeed: minimum contact force during the lift and total jump length against speed",
      {rows},
      marks +
          "set xlabel 'speed (rpm)'\nset ylabel 'min contact force (N)'\nset y2label 'jump "
          "(deg)'\n"
          "set y2tics\nset ytics nomirror\nset key top center\n"
          "plot $rows using 1:2 with linespoints lw 2 title 'min contact force', $rows using 1:3 "
          "axes x1y2 "
          "with linespoints title 'jump length'");
  std::ostringstream t;
  t << "<h2>Overspeed</h2><table>"
    << Row("quasi-static lift-off n_qs", FixedOrNone(n_qs, 1) + " rpm")
    << Row("dynamic lift-off n_dyn", s.n_dyn_rpm ? Fixed(*s.n_dyn_rpm, 1) + " rpm (bracket " +
                                                       Fixed(s.bracket_low_rpm, 2) + "–" +
                                                       Fixed(s.bracket_high_rpm, 2) + ")"
                                                 : OverspeedOutcome(s))
    << Row("overspeed to check",
           Fixed(overspeed_rpm, 1) + " rpm " +
               Verdict(Decided(s) && !(s.n_dyn_rpm && *s.n_dyn_rpm <= overspeed_rpm)))
    << "</table>";
  report.AddHtml(t.str());
}

void AddResonanceMap(Report& report, const BoundCase& c, const CheckResult& result, double rpm) {
  // The resonance map (a Campbell diagram): each significant cam harmonic's frequency
  // i·f_cam(n) against speed, the spring's modes as horizontal lines.
  const CamHarmonics& h = *result.harmonics;
  const double crank_turns = CrankTurnsPerCycle(c.engine.cycle);
  const double n_max =
      std::max(2.0 * rpm, result.sweep ? result.sweep_range.to_rpm : 0.0);  // the speeds shown
  Series lines{"orders", {}}, modes{"modes", {}}, hits{"hits", {}};
  std::ostringstream t;
  t << "<h2>Resonance map</h2><p>The cam's harmonics (orders whose acceleration reaches "
    << Fixed(100 * h.threshold, 1) << " % of the largest: 1 to " << h.highest_significant_order
    << ") against the spring's modes f_j = j·½√(k/m_s) = ";
  for (size_t j = 0; j < result.surge_modes_hz.size(); ++j)
    t << (j ? ", " : "") << Fixed(result.surge_modes_hz[j], 1) << " Hz";
  t << ". Order i meets mode j at n = " << Fixed(60.0 * crank_turns, 0)
    << "·f_j/i rpm.</p><table class=\"grid\"><tr><th>order i</th><th>acceleration harmonic "
       "(% of largest)</th>";
  for (size_t j = 0; j < result.surge_modes_hz.size(); ++j)
    t << "<th>meets mode " << j + 1 << " at (rpm)</th>";
  t << "</tr>";
  const double largest = h.largest_acceleration_m_rad2;
  const double per_rpm = result.spring->helical->cam_hz / rpm;  // f_cam per rpm
  for (int i = 1; i <= h.highest_significant_order; ++i) {
    t << "<tr><td>" << i << "</td><td>" << Fixed(100 * h.acceleration_m_rad2[i] / largest, 1)
      << "</td>";
    for (double f : result.surge_modes_hz) {
      const double n = f / (i * per_rpm);
      t << "<td>" << Fixed(n, 0) << "</td>";
      if (n <= n_max) hits.rows.push_back({n, f});
    }
    t << "</tr>";
    lines.rows.push_back({0.0, 0.0, double(i)});
    lines.rows.push_back({n_max, i * per_rpm * n_max, double(i)});
    lines.rows.push_back({NAN, NAN, NAN});
  }
  for (double f : result.surge_modes_hz) {
    modes.rows.push_back({0.0, f});
    modes.rows.push_back({n_max, f});
    modes.rows.push_back({NAN, NAN});
  }
  if (hits.rows.empty()) hits.rows.push_back({NAN, NAN});
  report.AddHtml(t.str() + "</table>");
  report.AddFigure(
      "Resonance map: cam harmonic frequencies i·f_cam against speed (lines, orders 1 to " +
          std::to_string(h.highest_significant_order) +
          "), the spring's first three modes (dashed) and where they meet (circles); the "
          "vertical line is the rated speed",
      {lines, modes, hits},
      "set xlabel 'speed (rpm)'\nset ylabel 'frequency (Hz)'\nunset key\nset xrange [0:" +
          Fixed(n_max, 1) + "]\nset yrange [0:" + Fixed(1.2 * result.surge_modes_hz.back(), 1) +
          "]\nset arrow from " + Fixed(rpm, 1) + ", graph 0 to " + Fixed(rpm, 1) +
          ", graph 1 nohead dt 2 lc rgb '#888888'\n"
          "plot $orders using 1:2 with lines lw 1 lc rgb '#4477aa', "
          "$modes using 1:2 with lines dt 2 lw 2 lc rgb '#cc3311', "
          "$hits using 1:2 with points pt 6 ps 1.2 lc rgb '#000000'",
      520);
}

}  // namespace needle::check_report
