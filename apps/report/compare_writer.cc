#include "apps/report/compare_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

#include "apps/report/check_writers.h"
#include "apps/study/check_scene.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/quasi_static.h"

namespace needle {
namespace {

// A value as check --json writes it: null, a bool, a text, a whole number or a number.
nlohmann::json ValueJson(const CheckValue& v) {
  switch (v.kind) {
    case CheckValue::Kind::kNone:
      return nullptr;
    case CheckValue::Kind::kFlag:
      return v.flag;
    case CheckValue::Kind::kText:
      return v.text;
    case CheckValue::Kind::kCount:
      return static_cast<long long>(v.number);
    case CheckValue::Kind::kNumber:
      break;
  }
  return v.number;
}

std::string Shown(const CheckValue& v) {
  switch (v.kind) {
    case CheckValue::Kind::kNone:
      return "-";
    case CheckValue::Kind::kFlag:
      return v.flag ? "yes" : "no";
    case CheckValue::Kind::kText:
      return v.text;
    case CheckValue::Kind::kCount:
      return std::to_string(static_cast<long long>(v.number));
    case CheckValue::Kind::kNumber:
      break;
  }
  std::ostringstream s;
  s.precision(6);
  s << v.number;
  return s.str();
}

std::string Difference(const ComparedItem& item) {
  if (!item.a.is_number() || !item.b.is_number()) return "";
  const double a = item.a.number, b = item.b.number;
  std::ostringstream s;
  s.precision(4);
  s << (b - a >= 0 ? "+" : "") << b - a;
  if (a != 0.0 && b != a)
    s << " (" << (b - a >= 0 ? "+" : "") << Fixed(100.0 * (b - a) / a, 1) << " %)";
  return s.str();
}

std::string Joined(const std::vector<std::string>& list, const std::string& sep) {
  std::string s;
  for (const std::string& x : list) s += (s.empty() ? "" : sep) + x;
  return s;
}

}  // namespace

nlohmann::json CompareJson(const Comparison& cmp, const std::string& path) {
  nlohmann::json j;
  j["a"] = CheckJson(cmp.a.c, *cmp.a.law, cmp.a.result, path);
  j["b"] = CheckJson(cmp.b.c, *cmp.b.law, cmp.b.result, path);
  j["report"] = path;
  j["flipped"] = cmp.flipped;
  j["differing"] = cmp.differing;
  j["like_for_like"] = cmp.unlike.empty();
  j["not_like_for_like"] = cmp.unlike;
  nlohmann::json rows = nlohmann::json::array();
  for (const ComparedItem& i : cmp.items) {
    nlohmann::json r = {
        {"key", i.key}, {"a", ValueJson(i.a)}, {"b", ValueJson(i.b)}, {"verdict", i.verdict}};
    if (i.verdict) {
      r["flips"] = i.flips;
      r["differs"] = i.differs;
    } else if (i.a.is_number() && i.b.is_number()) {
      r["difference"] = i.b.number - i.a.number;
    } else {
      r["difference"] = nullptr;
    }
    rows.push_back(r);
  }
  j["items"] = rows;
  return j;
}

std::string CompareText(const Comparison& cmp, const std::string& path) {
  const CheckedDesign &a = cmp.a, &b = cmp.b;
  std::ostringstream out;
  out << "A: " << (a.c.title.empty() ? a.c.path : a.c.title) << " — overall "
      << (a.result.pass ? "pass" : "FAIL") << '\n'
      << "B: " << (b.c.title.empty() ? b.c.path : b.c.title) << " — overall "
      << (b.result.pass ? "pass" : "FAIL") << '\n';
  if (!cmp.unlike.empty()) out << "not like for like: " << Joined(cmp.unlike, "; ") << '\n';
  out << '\n';
  char line[400];
  std::snprintf(line, sizeof line, "%-44s %14s %14s\n", "verdict", "A", "B");
  out << line;
  for (const ComparedItem& i : cmp.items) {
    if (!i.verdict) continue;
    std::snprintf(line, sizeof line, "%-44s %14s %14s%s\n", i.key.c_str(), Shown(i.a).c_str(),
                  Shown(i.b).c_str(),
                  i.flips     ? "  FLIPS"
                  : i.differs ? "  differs"
                              : "");
    out << line;
  }
  std::snprintf(line, sizeof line, "\n%-44s %14s %14s  %s\n", "quantity", "A", "B", "B - A");
  out << line;
  for (const ComparedItem& i : cmp.items) {
    if (i.verdict) continue;
    std::snprintf(line, sizeof line, "%-44s %14s %14s  %s\n", i.key.c_str(), Shown(i.a).c_str(),
                  Shown(i.b).c_str(), Difference(i).c_str());
    out << line;
  }
  for (const CheckedDesign* d : {&a, &b})
    for (const std::string& f : d->result.failing)
      out << (d == &a ? "A" : "B") << " fails: " << f << '\n';
  out << (cmp.flipped.empty() ? "no verdict flips"
                              : std::to_string(cmp.flipped.size()) + " verdict(s) flip")
      << '\n';
  if (!cmp.differing.empty())
    out << cmp.differing.size()
        << " other difference(s), not flips: " << Joined(cmp.differing, ", ") << '\n';
  out << "report: " << path << '\n';
  return out.str();
}

namespace {

// The comparison's tables: the two designs, the flips and differences, the verdicts side by
// side, each one's failing lines and the quantities with B − A.
std::string CompareTables(const Comparison& cmp) {
  const CheckedDesign &a = cmp.a, &b = cmp.b;
  std::ostringstream t;
  t << "<p>A: " << Escape(a.c.title.empty() ? a.c.path : a.c.title) << " (" << Escape(a.c.path)
    << ")<br>B: " << Escape(b.c.title.empty() ? b.c.path : b.c.title) << " (" << Escape(b.c.path)
    << ")</p>";
  if (!cmp.unlike.empty()) {
    t << "<p><span class=\"fail\">Not like for like</span>: " << Escape(Joined(cmp.unlike, "; "))
      << ".</p>";
  }
  t << "<p>"
    << (cmp.flipped.empty() ? "No verdict flips."
                            : "<span class=\"fail\">" + std::to_string(cmp.flipped.size()) +
                                  " verdict(s) flip</span>: " + Escape(Joined(cmp.flipped, ", ")))
    << "</p>";
  if (!cmp.differing.empty()) {
    t << "<p>" << cmp.differing.size()
      << " other difference(s), not flips: " << Escape(Joined(cmp.differing, ", ")) << "</p>";
  }
  t << "<h2>Verdicts</h2><table class=\"grid\"><tr><th>item</th><th>A</th><th>B</th><th></th>"
       "</tr>";
  for (const ComparedItem& i : cmp.items) {
    if (!i.verdict) continue;
    t << "<tr><td>" << Escape(i.key) << "</td><td>" << Escape(Shown(i.a)) << "</td><td>"
      << Escape(Shown(i.b)) << "</td><td>"
      << (i.flips     ? "<span class=\"fail\">flips</span>"
          : i.differs ? "differs"
                      : "")
      << "</td></tr>";
  }
  t << "</table><h2>Failing</h2><table class=\"grid\"><tr><th>A</th><th>B</th></tr><tr><td>";
  for (const CheckedDesign* d : {&a, &b}) {
    for (const std::string& f : d->result.failing) t << Escape(f) << "<br>";
    if (d->result.failing.empty()) t << "nothing";
    t << (d == &a ? "</td><td>" : "</td></tr></table>");
  }
  t << "<h2>Quantities</h2><table class=\"grid\"><tr><th>quantity</th><th>A</th><th>B</th>"
       "<th>B − A</th></tr>";
  for (const ComparedItem& i : cmp.items) {
    if (i.verdict) continue;
    t << "<tr><td>" << Escape(i.key) << "</td><td>" << Shown(i.a) << "</td><td>" << Shown(i.b)
      << "</td><td>" << Escape(Difference(i)) << "</td></tr>";
  }
  return t.str() + "</table>";
}

// Lift, velocity and acceleration of both against crank angle, each at its rated speed.
void AddKinematicsFigure(Report& report, const CheckedDesign& a, const CheckedDesign& b) {
  std::vector<Series> svaj;
  for (const CheckedDesign* d : {&a, &b}) {
    Series s{d == &a ? "a" : "b", {}};
    const Kinematics kin(*d->law, d->result.speed_rpm);
    const double th0 = d->law->table_start_rad(), thn = d->law->table_end_rad();
    for (int i = 0; i <= 600; ++i) {
      const KinematicsPoint p = kin.At(th0 + (thn - th0) * i / 600.0);
      s.rows.push_back(
          {p.crank_rad / kDeg, p.lift_m * 1e3, p.velocity_m_s, p.acceleration_m_s2.value_or(NAN)});
    }
    svaj.push_back(s);
  }
  const auto plot = [](int column) {
    const std::string c = std::to_string(column);
    return "plot $a using 1:" + c + " with lines lw 2 title 'A', $b using 1:" + c +
           " with lines lw 2 dt 2 title 'B'\n";
  };
  report.AddFigure(
      "Lift, velocity and acceleration of A (solid) and B (dashed) against crank angle", svaj,
      "set multiplot layout 3,1\nset lmargin 12\nset key top right\nset ylabel 'lift "
      "(mm)'\nset format x ''\n" +
          plot(2) + "set ylabel 'velocity (m/s)'\n" + plot(3) +
          "set ylabel 'acceleration (m/s²)'\nset format x '%g'\nset xlabel 'crank "
          "angle (deg)'\n" +
          plot(4) + "unset multiplot",
      900);
}

// Contact forces: quasi-static F_qs of both, and the dynamic F_c where a run was made.
void AddForceFigure(Report& report, const CheckedDesign& a, const CheckedDesign& b) {
  std::vector<Series> forces;
  std::string script =
      "set xlabel 'crank angle (deg)'\nset ylabel 'contact force (N)'\n"
      "set key top right\nplot ";
  bool any = false;
  for (const CheckedDesign* d : {&a, &b}) {
    const std::string name = d == &a ? "A" : "B", dash = d == &a ? "1" : "2";
    if (d->result.spring) {
      Series s{d == &a ? "qa" : "qb", {}};
      const double omega = OmegaFromRpm(d->result.speed_rpm);
      const double th0 = d->law->start_rad(), thn = d->law->end_rad();
      for (int i = 0; i <= 600; ++i) {
        const double th = th0 + (thn - th0) * i / 600.0;
        s.rows.push_back(
            {th / kDeg, QuasiStaticForce(*d->law, d->result.spring->train, omega, th)});
      }
      script += std::string(any ? ", " : "") + "$" + s.name + " using 1:2 with lines lw 2 dt " +
                dash + " lc rgb '#1f77b4' title '" + name + " quasi-static'";
      forces.push_back(s);
      any = true;
    }
    if (d->result.run && !d->result.run->series.empty()) {
      Series s{d == &a ? "da" : "db", {}};
      const auto& series = d->result.run->series;
      for (size_t k = 0; k < series.size(); k += std::max<size_t>(1, series.size() / 3000))
        s.rows.push_back({series[k].crank_rad / kDeg, series[k].contact_force_N});
      script += std::string(any ? ", " : "") + "$" + s.name + " using 1:2 with lines lw 1 dt " +
                dash + " lc rgb '#d62728' title '" + name + " dynamic'";
      forces.push_back(s);
      any = true;
    }
  }
  if (any) {
    report.AddFigure(
        "Contact force of A (solid) and B (dashed): quasi-static F_qs at the rated "
        "speed and, where the design has a train, the dynamic F_c",
        forces, script);
  } else {
    report.AddHtml("<p>No contact forces: neither design has [needle] and [spring].</p>");
  }
}

}  // namespace

Report CompareReport(const Comparison& cmp) {
  // The report: verdicts, quantities, and both designs' curves overlaid.
  Report report("needle compare: " + cmp.a.c.path + " against " + cmp.b.c.path);  // Html escapes
  report.AddHtml(CompareTables(cmp));
  AddKinematicsFigure(report, cmp.a, cmp.b);
  AddForceFigure(report, cmp.a, cmp.b);
  return report;
}

}  // namespace needle
