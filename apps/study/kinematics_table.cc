#include "apps/study/kinematics_table.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "apps/case/plausible_ranges.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

namespace {

// The table's first and last angle, the open lift's ends, every multiple of the step between,
// and the paper's angles.
std::vector<double> RowAngles(const LiftLaw& law, double step_rad, const BoundCase& c) {
  const double lo = law.table_start_rad(), hi = law.table_end_rad();
  std::vector<double> rows = {lo, hi, law.start_rad(), law.end_rad()};
  const double first = std::ceil(lo / step_rad - 1e-9);
  for (double k = first; k * step_rad <= hi + 1e-12; k += 1.0) {
    rows.push_back(k * step_rad);
  }
  if (c.paper) rows.insert(rows.end(), c.paper->crank_rad.begin(), c.paper->crank_rad.end());
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end(),
                         [](double a, double b) { return std::abs(a - b) < 1e-9; }),
             rows.end());
  return rows;
}

}  // namespace

KinematicsTable MakeKinematicsTable(const BoundCase& c, const KinematicsTableOptions& o) {
  RequireSpeed(o.speed_rpm);
  RequireIn("--step", o.step_deg, kTableStepRange.lo, kTableStepRange.hi,
            "a spacing in crank degrees");
  const double speed = o.speed_rpm.value_or(c.engine.speed_rpm);
  LiftLawChoice choice = c.lift.choice;
  LiftLaw law = *c.lift.law;
  const Kinematics kin(law, speed);
  // A row budget: a table wider than 100 000 rows is no table (--step 1e-9 asked for 4 GB).
  const double span_deg = (law.table_end_rad() - law.table_start_rad()) / kDeg;
  if (span_deg / o.step_deg > 1e5) {
    throw CaseError("--step: " + Fixed(o.step_deg, 6) + " deg gives " +
                    std::to_string(static_cast<long long>(span_deg / o.step_deg)) +
                    " rows over the table's " + Fixed(span_deg, 1) +
                    " deg; at most 100000 (a step of at least " + Fixed(span_deg / 1e5, 6) +
                    " deg)");
  }
  const std::vector<double> angles = RowAngles(law, o.step_deg * kDeg, c);
  std::vector<KinematicsPoint> rows;
  rows.reserve(angles.size());
  for (double a : angles) rows.push_back(kin.At(a));
  std::optional<PaperVelocityDeviation> paper;
  if (c.paper && !c.paper->velocity_m_s.empty()) {
    PaperVelocityDeviation d;
    d.points = static_cast<int>(c.paper->crank_rad.size());
    double total = 0, worst = -1;
    for (size_t i = 0; i < c.paper->crank_rad.size(); ++i) {
      const double dev = std::abs(std::abs(kin.At(c.paper->crank_rad[i]).velocity_m_s) -
                                  c.paper->velocity_m_s[i]);  // | |v| − v_paper |
      total += dev;
      if (dev > worst) {
        worst = dev;
        d.largest_at_rad = c.paper->crank_rad[i];
      }
    }
    d.mean_abs_m_s = total / c.paper->crank_rad.size();
    d.largest_m_s = worst;
    paper = d;
  }
  KinematicsSummary summary = kin.Summarize();
  return KinematicsTable{
      c, speed, std::move(choice), std::move(law), std::move(summary), std::move(rows), paper};
}

}  // namespace needle
