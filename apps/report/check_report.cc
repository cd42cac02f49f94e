// The check's HTML report (check_writers.h).
#include <cmath>
#include <sstream>

#include "apps/case/case_profile.h"
#include "apps/report/check_writers.h"
#include "apps/report/html_report.h"
#include "apps/report/result_writers.h"
#include "apps/study/check_scene.h"
#include "dynamics/overspeed.h"
#include "dynamics/simulation.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/spring_check.h"

namespace needle {
namespace {

// Whether the f_1/f_cam screen warns instead of failing (the coils' dynamics show no harm).
bool ScreenWarns(const CheckResult& r) {
  for (const LimitRow& x : r.limits)
    if (x.key == "surge_frequency_ratio") return x.verdict == "warning";
  return false;
}

std::string Row(const std::string& name, const std::string& value) {
  return "<tr><th>" + Escape(name) + "</th><td>" + value + "</td></tr>";
}

std::string Verdict(bool ok) {
  return ok ? "<span class=\"pass\">pass</span>" : "<span class=\"fail\">FAIL</span>";
}

std::string Sci(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

}  // namespace

CheckReportWriter::CheckReportWriter(const BoundCase& c, const LiftLaw& law,
                                     const LiftLawChoice& choice, double rpm, Gnuplot* gnuplot)
    : c_(c),
      law_(law),
      choice_(choice),
      rpm_(rpm),
      kin_(law, rpm),
      report_("needle check: " + (c.title.empty() ? c.path : c.title), gnuplot) {
  const Kinematics& kin = kin_;
  Report& report = report_;
  // Figure 1: lift, velocity, acceleration over the spline, with the table's points (or the
  // measured readings) and the paper's velocities as markers.
  Series kinematic{"kin", {}}, paper{"paper", {}}, points{"points", {}};
  const double th0 = law.table_start_rad(), thn = law.table_end_rad();
  for (int i = 0; i <= 600; ++i) {
    const KinematicsPoint p = kin.At(th0 + (thn - th0) * i / 600.0);
    kinematic.rows.push_back(
        {p.crank_rad / kDeg, p.lift_m * 1e3, p.velocity_m_s, p.acceleration_m_s2.value_or(NAN)});
  }
  for (size_t i = 0; i < c.lift.table.crank_rad.size(); ++i) {
    points.rows.push_back({c.lift.table.crank_rad[i] / kDeg, c.lift.table.lift_m[i] * 1e3});
  }
  if (c.paper) {
    for (size_t i = 0; i < c.paper->crank_rad.size(); ++i) {
      const double v = kin.At(c.paper->crank_rad[i]).velocity_m_s;
      paper.rows.push_back(
          {c.paper->crank_rad[i] / kDeg, (v < 0 ? -1.0 : 1.0) * c.paper->velocity_m_s[i]});
    }
  }
  if (paper.rows.empty()) paper.rows.push_back({NAN, NAN});
  top_ = report.Reserve();  // the verdict, the scene and what was skipped (Finish)
  report.AddHtml("<h2>Kinematics</h2>");
  const bool accel = law.HasAcceleration();
  const std::string points_label = choice.measured ? "readings" : "table";
  report.AddFigure(
      "Lift, velocity" + std::string(accel ? " and acceleration" : "") +
          " against crank angle at " + Fixed(rpm, 0) + " rpm; points: the lift " + points_label +
          (c.paper && !c.paper->crank_rad.empty() ? " and the paper's velocities" : "") +
          "; dashed: the open lift",
      {kinematic, paper, points},
      std::string(accel ? "set multiplot layout 3,1\n" : "set multiplot layout 2,1\n") +
          "set lmargin 12\nunset key\nset arrow from " + Fixed(law.start_rad() / kDeg, 3) +
          ", graph 0 to " + Fixed(law.start_rad() / kDeg, 3) +
          ", graph 1 nohead dt 2 lc rgb '#888888'\nset arrow from " +
          Fixed(law.end_rad() / kDeg, 3) + ", graph 0 to " + Fixed(law.end_rad() / kDeg, 3) +
          ", graph 1 nohead dt 2 lc rgb '#888888'\nset ylabel 'lift (mm)'\nset format x ''\n"
          "plot $kin using 1:2 with lines lw 2, $points using 1:2 with points pt 6 ps 0.6\n"
          "set ylabel 'velocity (m/s)'\n" +
          (accel ? "" : "set format x '%g'\nset xlabel 'crank angle (deg)'\n") +
          "plot $kin using 1:3 with lines lw 2, $paper using 1:2 with points pt 7 ps 0.8\n" +
          (accel ? "set ylabel 'acceleration (m/s²)'\nset format x '%g'\nset xlabel 'crank angle "
                   "(deg)'\nplot $kin using 1:4 with lines lw 2\n"
                 : "") +
          "unset multiplot",
      accel ? 900 : 620);

  // The velocity and acceleration table, like the paper's.
  {
    std::ostringstream t;
    t << "<h2>Kinematics table at " << Fixed(rpm, 0)
      << " rpm</h2><table class=\"grid\"><tr><th>crank angle (deg)</th><th>lift (mm)</th>"
         "<th>velocity (dcm/s)</th><th>acceleration (m/s²)</th>"
      << (c.paper && !c.paper->crank_rad.empty() ? "<th>paper |v| (dcm/s)</th>" : "") << "</tr>";
    for (double d = std::ceil(th0 / kDeg / 5.0) * 5.0; d <= thn / kDeg + 1e-9; d += 5.0) {
      const double a = d * kDeg;
      const KinematicsPoint p = kin.At(a);
      t << "<tr><td>" << Fixed(a / kDeg, 1) << "</td><td>" << Fixed(p.lift_m * 1e3, 3)
        << "</td><td>" << Fixed(p.velocity_m_s * 10.0, 2) << "</td><td>"
        << (p.acceleration_m_s2 ? Fixed(*p.acceleration_m_s2, 2) : std::string("n/a")) << "</td>";
      if (c.paper && !c.paper->crank_rad.empty()) {
        const auto pv = PaperVelocityAt(c, a);
        t << "<td>" << (pv ? Fixed(*pv * 10, 2) : std::string()) << "</td>";
      }
      t << "</tr>";
    }
    report.AddHtml(t.str() + "</table>");
  }

  spring_ = report.Reserve();
}

void CheckReportWriter::RatedRun(const SpringCheckResult& spring, const SimulationResult& r,
                                 const SimulationOptions& options) {
  if (rated_) throw std::logic_error("CheckReportWriter: the rated run given twice");
  rated_ = true;
  const LiftLaw& law = law_;
  const double rpm = rpm_;
  const Kinematics& kin = kin_;
  Report& report = report_;
  std::ostringstream d;
  d << "<h2>Dynamics at " << Fixed(rpm, 0) << " rpm</h2><table>"
    << Row("solver", Escape(r.method) + " (" + Escape(r.method_reason) + "), rtol " +
                         Sci(options.integrator.rtol))
    << Row("steps, right-hand sides, events", std::to_string(r.stats.steps) + ", " +
                                                  std::to_string(r.stats.rhs_evaluations) + ", " +
                                                  std::to_string(r.stats.events))
    << Row("energy residual", Sci(r.energy_residual))
    << Row("run", "to " + Fixed(r.run_end_rad / kDeg, 2) + "° (window end " +
                      Fixed(r.window_end_rad / kDeg, 2) + "°): " + RunStatusName(r.status) +
                      (r.status_reason.empty() ? std::string(", the needle at rest")
                                               : ", " + Escape(r.status_reason)))

    << Row("lift-off at the rated speed",
           r.liftoff() ? "<span class=\"fail\">yes</span>" + Escape(ShortJumpNote(r)) : "no")
    << Row("max contact force", Fixed(r.max_contact_force_N, 1) + " N; min during the lift " +
                                    Fixed(r.min_contact_force_during_lift_N, 1) + " N");
  for (const Impact& i : r.impacts) {
    d << Row("impact: " + i.kind,
             Fixed(i.crank_rad / kDeg, 3) + "°, " + Fixed(i.speed_m_s, 4) + " m/s");
  }
  for (const Episode& e : r.episodes) {
    d << Row("episode: " + e.kind, Fixed(e.start_rad / kDeg, 3) + "° to " +
                                       Fixed(e.end_rad / kDeg, 3) + "°, largest gap " +
                                       Fixed(e.max_gap_m * 1e3, 4) + " mm");
  }
  d << "</table>";
  report.AddHtml(d.str());
  const RigidTrain& rigid = spring.train;
  Series force{"force", {}}, motion{"motion", {}}, impacts{"impacts", {}}, shade{"shade", {}};
  const double omega = OmegaFromRpm(rpm);
  for (size_t k = 0; k < r.series.size(); k += std::max<size_t>(1, r.series.size() / 3000)) {
    const SeriesPoint& p = r.series[k];
    const bool in = p.crank_rad >= law.start_rad() && p.crank_rad <= law.end_rad();
    force.rows.push_back({p.crank_rad / kDeg, p.contact_force_N,
                          in ? QuasiStaticForce(law, rigid, omega, p.crank_rad) : NAN});
    motion.rows.push_back({p.crank_rad / kDeg, p.lift_m * 1e3, p.cam_m * 1e3});
  }
  for (const Impact& i : r.impacts) {
    impacts.rows.push_back(
        {i.crank_rad / kDeg,
         (i.kind.rfind("seat", 0) == 0 ? 0.0 : kin.At(i.crank_rad).lift_m * 1e3)});
  }
  if (impacts.rows.empty()) impacts.rows.push_back({NAN, NAN});
  std::string rects;
  for (const Episode& e : r.episodes) {
    rects += "set object rect from " + Fixed(e.start_rad / kDeg, 4) + ", graph 0 to " +
             Fixed(e.end_rad / kDeg, 4) + ", graph 1 fc rgb '#ffcccc' fs solid 0.6 behind\n";
  }
  report.AddFigure(
      "Contact force: quasi-static F_qs (rigid train) and dynamic F_c; lift-off episodes shaded",
      {force},
      rects +
          "set xlabel 'crank angle (deg)'\nset ylabel 'contact force (N)'\nset key top right\n"
          "plot $force using 1:3 with lines lw 2 title 'quasi-static', $force using 1:2 with "
          "lines lw 1 title 'dynamic'");
  surge_ = report.Reserve();  // the surge figure, known with the result (Finish)
  report.AddFigure("Needle lift against the cam input u(θ); impacts marked", {motion, impacts},
                   "set xlabel 'crank angle (deg)'\nset ylabel 'lift (mm)'\nset key top right\n"
                   "plot $motion using 1:3 with lines lw 2 title 'cam u', $motion using 1:2 with "
                   "lines lw 1 title 'needle y', "
                   "$impacts using 1:2 with points pt 7 ps 1.2 title 'impacts'");
}

Report CheckReportWriter::Finish(const CheckResult& result) {
  if (result.run && result.spring && !rated_)
    RatedRun(*result.spring, *result.run, result.run_options);
  const BoundCase& c = c_;
  const LiftLaw& law = law_;
  const double rpm = rpm_;
  Report& report = report_;
  const KinematicsSummary& sum = result.kinematics;
  const std::vector<std::string>& skipped = result.skipped;
  const std::vector<std::string>& failing = result.failing;
  const std::optional<SpringCheckResult>& spring = result.spring;
  const std::optional<OverspeedResult>& sweep = result.sweep;
  const std::optional<CamProfile>& profile = result.profile;
  const double n_qs = result.n_qs_rpm, overspeed_rpm = result.overspeed_rpm;

  std::ostringstream summary;
  summary << "<h2>Scene</h2><table>" << Row("case", Escape(c.path))
          << Row("rated speed", Fixed(rpm, 1) + " rpm")
          << Row("cycle", Escape(EngineCycleName(c.engine.cycle)))
          << Row("lift law", Escape(c.lift.source) + ", " +
                                 std::to_string(c.lift.table.crank_rad.size()) +
                                 " points, spline " + SplineKindName(law.kind()))
          << Row("spline chosen", Escape(choice_.reason))
          << Row("open lift", Fixed(sum.open_rad / kDeg, 2) + "° to " +
                                  Fixed(sum.close_rad / kDeg, 2) + "°" +
                                  (law.closed_level_m() > 0
                                       ? " (where the lift exceeds " +
                                             Fixed(law.closed_level_m() * 1e3, 4) + " mm, 3σ)"
                                       : std::string(" (last zero before the rise to first zero "
                                                     "after the fall)")))
          << Row("injection period", Fixed(sum.injection_period_s * 1e3, 2) + " ms");
  if (Shows(FieldAt(LiftLawFields(law), "undershoot_mm"))) {
    summary << Row("WARNING", "the spline dips " + Fixed(law.undershoot_m() * 1e3, 4) +
                                  " mm below the seat at " + Fixed(law.undershoot_rad() / kDeg, 2) +
                                  "° inside the open lift; try another spline kind");
  }
  if (!choice_.outliers.empty()) {  // left out: [lift] outliers = "drop"
    summary << Row("WARNING", std::to_string(choice_.outliers.size()) +
                                  " outlier(s) of the lift table left out (outliers = \"drop\"; "
                                  "the spline's reason lists them)");
  }
  summary << Row("max lift", Fixed(sum.max_lift_m * 1e3, 3) + " mm at " +
                                 Fixed(sum.max_lift_rad / kDeg, 2) + "°")
          << Row("max velocity", Fixed(sum.max_velocity_m_s, 3) + " m/s at " +
                                     Fixed(sum.max_velocity_rad / kDeg, 2) + "°");
  if (sum.max_acceleration_m_s2) {
    summary << Row("acceleration",
                   Fixed(*sum.max_acceleration_m_s2, 2) +
                       PlusMinus(*sum.max_acceleration_m_s2, sum.max_acceleration_band_m_s2, 2) +
                       " m/s² max at " + Fixed(*sum.max_acceleration_rad / kDeg, 2) + "°, " +
                       Fixed(*sum.min_acceleration_m_s2, 2) +
                       PlusMinus(*sum.min_acceleration_m_s2, sum.min_acceleration_band_m_s2, 2) +
                       " m/s² min at " + Fixed(*sum.min_acceleration_rad / kDeg, 2) + "°");
  }
  summary << "</table>";

  std::vector<std::string> top;
  top.push_back(std::string("<p>Overall: ") + Verdict(result.pass) +
                (result.not_judged.empty() ? "" : "; not judged: ") + Escape(result.not_judged) +
                "</p>");
  if (!failing.empty()) {
    std::string s = "<h2>Failing</h2><ul class=\"fail-list\">";
    for (const auto& f : failing) s += "<li>" + Escape(f) + "</li>";
    top.push_back(s + "</ul>");
  }
  if (!result.warnings.empty()) {
    std::string s = "<h2>Warnings</h2><ul>";
    for (const auto& w : result.warnings) s += "<li>" + Escape(w) + "</li>";
    top.push_back(s + "</ul>");
  }
  top.push_back(summary.str());
  if (!skipped.empty()) {
    std::string s = "<h2>Skipped</h2><ul class=\"skip\">";
    for (const auto& k : skipped) s += "<li>" + Escape(k) + "</li>";
    top.push_back(s + "</ul>");
  }
  report.Fill(top_, top);
  if (spring) {
    const SpringCheckResult& s = *spring;
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
                 " " + Verdict(s.preload_ok));
    if (s.helical) {
      const HelicalSpringCheck& h = *s.helical;
      t << Row("helical: shear stress at full lift",
               Fixed(h.stress_full_lift_Pa * 1e-6, 0) + " MPa of " +
                   Fixed(h.allowable_stress_Pa * 1e-6, 0) + " MPa " + Verdict(h.stress_ok))
        << Row("helical: coil gaps at full lift",
               Fixed(h.clearance_full_lift_m * 1e3, 2) + " mm, need " +
                   Fixed(h.min_clearance_m * 1e3, 2) + " mm " + Verdict(h.clearance_ok))
        << Row("helical: surge frequency",
               Fixed(h.surge_hz, 1) + " Hz, " + Fixed(h.surge_ratio, 1) + "× the cam's " +
                   (ScreenWarns(result) ? std::string("warning (the coils' dynamics show no harm)")
                                        : Verdict(h.surge_ok)));
    }
    t << Row("combustion load F_g", Fixed(s.gas_force_N / kKgf, 1) + " kgf (" +
                                        Escape(s.gas_source) + "); preload against S·F_g " +
                                        Verdict(s.combustion_ok));
    t << Row("spring check", Verdict(s.pass)) << "</table>";
    report.Fill(spring_, t.str());
  }

  if (surge_ != kNone && result.surge && !result.surge->rated.series.empty()) {
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
    // Drawn from two runs of rows a pixel column (LineEnvelope: the curves as the whole
    // series draws them; the chain's run has some 20 000 points in the window, and gnuplot's
    // time grows with them).
    for (Series* s : {&chain, &massless})
      s->rows = LineEnvelope(s->rows, from_rad / kDeg, to_rad / kDeg, 2 * kFigureWidthPx);
    // Runs stopped on a budget before the lift have nothing to draw (the check fails them as
    // undecided): the figure is left out, saying why.
    const bool drawn = !chain.rows.empty() || !massless.rows.empty();
    if (!drawn) {
      report.Fill(surge_,
                  "<p>Surge figure not drawn: neither run reached the lift (the massless run is " +
                      RunStatusName(sg.massless.status) + ", the run with coil masses " +
                      RunStatusName(sg.rated.status) + ").</p>");
    }
    for (Series* s : {&chain, &massless})
      if (s->rows.empty()) s->rows.push_back({NAN, NAN});
    if (drawn)
      report.FigureAt(
          surge_,
          "Surge: the contact force with the spring as " + std::to_string(sg.masses) +
              " coil masses against the massless spring, at " + Fixed(rpm, 0) + " rpm",
          {chain, massless},
          "set xlabel 'crank angle (deg)'\nset ylabel 'contact force (N)'\nset key top right\n"
          "plot $massless using 1:2 with lines lw 2 title 'massless spring', $chain using 1:2 "
          "with lines lw 1 title '" +
              std::to_string(sg.masses) + " coil masses'");
  }
  if (profile) {
    const auto at = [&](double cam_rad) {
      return CamAndCrank(c, result.cam_zero_crank_rad, cam_rad, 1, "°");
    };
    std::ostringstream t;
    t << "<h2>Cam profile</h2><table>"
      << Row("largest |pressure angle|",
             Fixed(std::abs(profile->max_pressure_angle_rad) / kDeg, 2) + "° at " +
                 at(profile->max_pressure_angle_at_rad))
      << Row("least profile radius (convex)", Fixed(profile->min_profile_radius_m * 1e3, 2) +
                                                  " mm at " +
                                                  at(profile->min_profile_radius_at_rad))
      << Row("undercut", profile->undercut ? "<span class=\"fail\">UNDERCUT</span>"
                                           : "<span class=\"pass\">none</span>")
      << "</table>";
    report.AddHtml(t.str());
  }
  if (sweep) {
    const OverspeedResult& s = *sweep;
    Series rows{"rows", {}};
    for (const OverspeedRow& row : s.rows)
      rows.rows.push_back({row.speed_rpm, row.min_contact_force_N, row.jump_rad / kDeg});
    std::string marks;
    if (std::isfinite(n_qs))
      marks += "set arrow from " + Fixed(n_qs, 2) + ", graph 0 to " + Fixed(n_qs, 2) +
               ", graph 1 nohead dt 2 lc rgb '#555555'\nset label 'n_qs' at " + Fixed(n_qs, 2) +
               ", graph 0.95 offset 0.5,0\n";
    if (s.n_dyn_rpm)
      marks += "set arrow from " + Fixed(*s.n_dyn_rpm, 2) + ", graph 0 to " +
               Fixed(*s.n_dyn_rpm, 2) + ", graph 1 nohead lc rgb '#bb0000'\nset label 'n_dyn' at " +
               Fixed(*s.n_dyn_rpm, 2) + ", graph 0.85 offset 0.5,0 tc rgb '#bb0000'\n";
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

  if (!result.limits.empty()) {
    std::ostringstream t;
    t << "<h2>Limits</h2><table class=\"grid\"><tr><th>limit</th><th>value</th><th>limit</th>"
         "<th>margin</th><th>verdict</th><th>where / why</th><th>source of the limit</th></tr>";
    for (const LimitRow& x : result.limits) {
      const std::string u = Escape(x.UnitSuffix());
      const bool judged = x.verdict != "not judged";
      t << "<tr><td>" << Escape(x.name) << "</td><td>"
        << (judged ? FixedOrNone(x.value, 2) + u : std::string("—")) << "</td><td>"
        << (x.at_most ? "≤ " : "≥ ") << (std::isfinite(x.limit) ? FixedOrNone(x.limit, 2) + u : "—")
        << "</td><td>" << (judged ? FixedOrNone(x.margin, 2) + u : std::string("—")) << "</td><td>"
        << (!judged                  ? std::string("not judged")
            : x.verdict == "warning" ? std::string("warning")
                                     : Verdict(x.verdict == "pass"))
        << "</td><td>" << Escape(x.note) << "</td><td>" << Escape(x.source) << "</td></tr>";
    }
    report.AddHtml(t.str() + "</table>");
  }
  if (result.harmonics && !result.surge_modes_hz.empty()) {
    // The resonance map (a Campbell diagram): each significant cam harmonic's frequency
    // i·f_cam(n) against speed, the spring's modes as horizontal lines.
    const CamHarmonics& h = *result.harmonics;
    const double crank_turns = CrankTurnsPerCycle(c.engine.cycle);
    const double n_max =
        std::max(2.0 * rpm, sweep ? result.sweep_range.to_rpm : 0.0);  // the speeds shown
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
    const double per_rpm = spring->helical->cam_hz / rpm;  // f_cam per rpm
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
  return std::move(report_);
}

Report CheckReport(const BoundCase& c, const LiftLaw& law, const CheckResult& result,
                   Gnuplot* gnuplot) {
  CheckReportWriter writer(c, law, result.choice, result.speed_rpm, gnuplot);
  return writer.Finish(result);
}

}  // namespace needle
