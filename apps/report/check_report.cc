// The check's HTML report (check_writers.h).
#include <cmath>
#include <sstream>

#include "apps/case/case_profile.h"
#include "apps/report/check_report_parts.h"
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

using check_report::AddOverspeed;
using check_report::AddResonanceMap;
using check_report::AddSurgeFigure;
using check_report::LimitsTable;
using check_report::ProfileTable;
using check_report::Row;
using check_report::SceneTable;
using check_report::SpringTable;
using check_report::Verdict;

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
           r.liftoff() ? "<span class=\"fail\">yes</span>" + Escape(ShortJumpNote(r))
                       : "no" + Escape(BounceNote(r)))
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
  for (const SeriesPoint& p : r.series) {
    const bool in = p.crank_rad >= law.start_rad() && p.crank_rad <= law.end_rad();
    force.rows.push_back({p.crank_rad / kDeg, p.contact_force_N,
                          in ? QuasiStaticForce(law, rigid, omega, p.crank_rad) : NAN});
    motion.rows.push_back({p.crank_rad / kDeg, p.lift_m * 1e3, p.cam_m * 1e3});
  }
  // Drawn from a run of rows a pixel column each (LineEnvelope: every peak and drop of the
  // whole series kept, an impact's force spike too, where every n-th point could miss it).
  if (!r.series.empty()) {
    const double from_deg = r.series.front().crank_rad / kDeg;
    const double to_deg = r.series.back().crank_rad / kDeg;
    for (Series* s : {&force, &motion})
      s->rows = LineEnvelope(s->rows, from_deg, to_deg, kFigureWidthPx);
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

  const std::string scene = SceneTable(c, law, choice_, rpm, sum);
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
  top.push_back(scene);
  if (!skipped.empty()) {
    std::string s = "<h2>Skipped</h2><ul class=\"skip\">";
    for (const auto& k : skipped) s += "<li>" + Escape(k) + "</li>";
    top.push_back(s + "</ul>");
  }
  report.Fill(top_, top);
  if (spring) report.Fill(spring_, SpringTable(c, result));

  if (surge_ != kNone && result.surge && !result.surge->rated.series.empty())
    AddSurgeFigure(report, surge_, law, result, rpm);
  if (profile) report.AddHtml(ProfileTable(c, result));
  if (sweep) AddOverspeed(report, result);
  if (!result.limits.empty()) report.AddHtml(LimitsTable(result));
  if (result.harmonics && !result.surge_modes_hz.empty()) AddResonanceMap(report, c, result, rpm);
  return std::move(report_);
}

Report CheckReport(const BoundCase& c, const LiftLaw& law, const CheckResult& result,
                   Gnuplot* gnuplot) {
  CheckReportWriter writer(c, law, result.choice, result.speed_rpm, gnuplot);
  return writer.Finish(result);
}

}  // namespace needle
