// The kinematics table's JSON, text and CSV: WriteKinematics (kinematics_writer.h).
#include "apps/report/kinematics_writer.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/report/result_writers.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

namespace {

std::string Pad(const std::string& s, size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

}  // namespace

namespace {

// The kinematics as JSON: the choice, the summary and the law's fields, and the table.
nlohmann::json KinematicsJson(const KinematicsTable& table, const std::vector<Column>& columns,
                              const std::vector<std::vector<double>>& rows_si) {
  const BoundCase& c = table.c;
  const std::vector<KinematicsPoint>& rows = table.rows;
  nlohmann::json j;
  j["case"] = c.path;
  j["speed_rpm"] = table.speed_rpm;
  PutFields(j, LiftChoiceFields(table.choice));
  j["points"] = c.lift.table.crank_rad.size();
  PutFields(j, KinematicsFields(table.summary));
  PutFields(j, LiftLawFields(table.law));
  PutLiftTableWarnings(j, table.choice, table.law);
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < rows.size(); ++i) {
    nlohmann::json row = RowObject(columns, rows_si[i]);
    if (auto p = PaperVelocityAt(c, rows[i].crank_rad)) row["paper_velocity_m_s"] = *p;
    list.push_back(row);
  }
  j["table"] = list;
  return j;
}

// The text's head: the spline and its reason, the open lift, warnings and the extremes.
void KinematicsHead(std::ostream& out, const KinematicsTable& table) {
  const BoundCase& c = table.c;
  const LiftLawChoice& choice = table.choice;
  const LiftLaw& law = table.law;
  const KinematicsSummary& sum = table.summary;
  const double speed = table.speed_rpm;
  out << (c.title.empty() ? c.path : c.title) << '\n';
  out << "spline " << SplineKindName(law.kind()) << ": " << choice.reason << '\n';
  if (!choice.breaks_found.empty() && !choice.law.breaks_rad.empty()) {
    out << "breaks found (s'' jumps, the spline built apart at them): "
        << FieldText(FieldAt(LiftChoiceFields(choice), "breaks_deg")) << " deg\n";
  }
  const std::vector<Field> fields = KinematicsFields(sum), law_fields = LiftLawFields(law);
  const auto t = [&](const char* key) { return FieldText(FieldAt(fields, key)); };
  const auto lt = [&](const char* key) { return FieldText(FieldAt(law_fields, key)); };
  out << "open lift " << ValueText(FieldAt(fields, "open_deg")) << " to " << t("close_deg");
  if (law.closed_level_m() > 0)
    out << " (where the lift exceeds " << lt("closed_level_mm") << ", 3 sigma)";
  out << ", " << Fixed(speed, 1) << " rpm, injection period "
      << FieldText({"injection_period", display::kMs, sum.injection_period_s, 2}) << '\n';
  if (Shows(FieldAt(law_fields, "undershoot_mm")) && DipBeyondReadings(choice, law)) {
    out << "WARNING: the spline dips " << lt("undershoot_mm") << " below the seat at "
        << lt("undershoot_deg") << " inside the open lift; try another spline kind\n";
  }
  out << LiftTableWarnings(choice, law);
  if (!choice.outliers.empty()) {  // left out: [lift] outliers = "drop"
    out << "WARNING: " << choice.outliers.size()
        << " outlier(s) of the lift table left out (outliers = \"drop\"; the spline's reason "
           "lists them)\n";
  }
  out << "max lift " << t("max_lift_mm") << " at " << t("max_lift_deg") << ", mean lift "
      << t("mean_lift_mm") << ", rho " << t("rho") << '\n';
  out << "velocity " << t("max_velocity_m_s") << " max at " << t("max_velocity_deg") << ", "
      << t("min_velocity_m_s") << " min at " << t("min_velocity_deg") << '\n';
  if (sum.max_acceleration_m_s2) {
    const int d = AccelerationDecimals(sum);
    out << "acceleration " << Fixed(*sum.max_acceleration_m_s2, d)
        << PlusMinus(*sum.max_acceleration_m_s2, sum.max_acceleration_band_m_s2, d)
        << " m/s^2 max at " << t("max_acceleration_deg") << ", "
        << Fixed(*sum.min_acceleration_m_s2, d)
        << PlusMinus(*sum.min_acceleration_m_s2, sum.min_acceleration_band_m_s2, d)
        << " m/s^2 min at " << t("min_acceleration_deg") << '\n';
  } else {
    out << "acceleration unavailable: " << SplineKindName(law.kind())
        << " is C1 only (its second derivative jumps at the knots)\n";
  }
  if (c.paper && c.paper->max_acceleration_m_s2) {
    const double a_abs = sum.max_acceleration_m_s2 ? std::max(std::abs(*sum.max_acceleration_m_s2),
                                                              std::abs(*sum.min_acceleration_m_s2))
                                                   : NAN;
    out << "paper: max acceleration " << Fixed(*c.paper->max_acceleration_m_s2, 1)
        << " m/s^2; computed max |a| " << Fixed(a_abs, DecimalsFor(a_abs, 2, 2)) << " m/s^2\n";
  }
  if (table.paper) {
    const PaperVelocityDeviation& d = *table.paper;
    out << "paper velocity (" << d.points << " points): mean |deviation| "
        << Fixed(10.0 * d.mean_abs_m_s, 2) << " dcm/s, largest " << Fixed(10.0 * d.largest_m_s, 2)
        << " dcm/s at " << Fixed(d.largest_at_rad / kDeg, 1) << " deg\n";
  }
}

// The text's table, in paper units (mm, dcm/s) or SI, with the paper's velocities beside.
void KinematicsRows(std::ostream& out, const KinematicsTable& table, bool paper) {
  const BoundCase& c = table.c;
  const std::vector<KinematicsPoint>& rows = table.rows;
  out << '\n'
      << Pad("crank deg", 9) << Pad(paper ? "lift mm" : "lift m", 12)
      << Pad(paper ? "v dcm/s" : "v m/s", 12) << Pad("a m/s^2", 12);
  if (!paper) out << Pad("j m/s^3", 14);
  if (table.paper) out << Pad("paper |v|", 11) << Pad("|v|-paper", 11);
  out << '\n';
  for (const auto& r : rows) {
    out << Pad(Fixed(r.crank_rad / kDeg, 2), 9);
    if (paper) {
      out << Pad(Fixed(r.lift_m * 1e3, 4), 12) << Pad(Fixed(r.velocity_m_s * 10.0, 3), 12);
    } else {
      out << Pad(Fixed(r.lift_m, 7), 12) << Pad(Fixed(r.velocity_m_s, 5), 12);
    }
    out << Pad(r.acceleration_m_s2 ? Fixed(*r.acceleration_m_s2, 2) : "n/a", 12);
    if (!paper) out << Pad(r.jerk_m_s3 ? Fixed(*r.jerk_m_s3, 1) : "n/a", 14);
    if (table.paper) {
      if (auto p = PaperVelocityAt(c, r.crank_rad)) {
        const double scale = paper ? 10.0 : 1.0;  // dcm/s or m/s
        out << Pad(Fixed(*p * scale, paper ? 2 : 4), 11)
            << Pad(Fixed((std::abs(r.velocity_m_s) - *p) * scale, paper ? 2 : 4), 11);
      }
    }
    out << '\n';
  }
}

}  // namespace

CommandOutput WriteKinematics(const KinematicsTable& table, const KinematicsWriting& w) {
  const std::vector<Column>& columns = KinematicsColumns();
  std::vector<std::vector<double>> rows_si;
  rows_si.reserve(table.rows.size());
  for (const auto& r : table.rows) rows_si.push_back(KinematicsRowSi(r));
  CommandOutput result;
  result.columns = SiColumns(columns, rows_si);
  if (w.csv) result.csv = CsvTable(columns, rows_si, 10);
  std::ostringstream out;
  if (w.json) {
    result.json = KinematicsJson(table, columns, rows_si);
  } else {
    KinematicsHead(out, table);
    KinematicsRows(out, table, w.paper_units);
  }
  result.text = out.str();
  return result;
}

}  // namespace needle
