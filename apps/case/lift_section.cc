// [lift] (section_reader.h).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "apps/case/plausible_ranges.h"
#include "apps/case/section_reader.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle::case_internal {

namespace {

// normal_curve = "basu": the table of Basu's normal curve scaled to max_lift_mm.
void ReadNormalCurve(SectionReader& r, const std::string& normal, bool table_given,
                     const std::optional<double>& max_lift, LiftSection& lift) {
  if (normal != "basu") r.Fail("normal_curve", "expected \"basu\", got \"" + normal + "\"");
  if (table_given)
    r.Fail("normal_curve", "give either normal_curve or crank_deg + lift_mm, not both");
  if (!max_lift) r.Fail("max_lift_mm", "missing; normal_curve = \"basu\" needs max_lift_mm");
  if (!(*max_lift > 0.0)) r.Fail("max_lift_mm", "must be positive, got " + Number(*max_lift * 1e3));
  lift.table = BasuNormalCurve(*max_lift);
  lift.source = "basu normal curve";
}

// csv = "PATH": the table of a CSV file beside the case (relative paths from its folder).
void ReadCsvTable(SectionReader& r, const std::string& csv, bool table_given,
                  const std::optional<double>& max_lift, const std::string& case_path,
                  EngineCycle cycle, LiftSection& lift) {
  if (table_given) r.Fail("csv", "give either csv or crank_deg + lift_mm, not both");
  if (max_lift) r.Fail("max_lift_mm", "only used with normal_curve = \"basu\"");
  if (csv.empty()) r.Fail("csv", "expected the path of a CSV file");
  const std::filesystem::path p(csv);
  const std::string full =
      p.is_absolute() ? p.string() : (std::filesystem::path(case_path).parent_path() / p).string();
  try {
    lift.table = ReadLiftCsv(full, cycle, &lift.lines);
  } catch (const CaseError& e) {
    r.Fail("csv", e.what());  // "CASE: [lift] csv: TABLE:LINE:COLUMN: what"
  }
  // The plausible lift of a table's entry, as lift_mm's entries are judged (docs/ranges.md).
  const std::vector<double>& lifts = lift.table.lift_m;
  for (size_t i = 0; i < lifts.size(); ++i) {
    if (lifts[i] > kLiftRange.hi) {
      r.Fail("csv", full + ":" + std::to_string(i < lift.lines.size() ? lift.lines[i] : 0) + ": " +
                        AboveRangeEnd(kLiftRange, lifts[i]));
    }
  }
  lift.source = "csv " + full;
  lift.csv_path = full;
}

// crank_deg + lift_mm: the arrays, as long as each other, plausible and increasing in angle.
void ReadArrayTable(SectionReader& r, const std::optional<std::vector<double>>& crank,
                    const std::string& crank_key, const std::optional<std::vector<double>>& values,
                    const std::string& lift_key, const std::optional<double>& max_lift,
                    LiftSection& lift) {
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
      const auto [now, before] = SignificantApart((*crank)[i] / kDeg, (*crank)[i - 1] / kDeg);
      r.Fail("crank_deg", "angles must increase strictly, but entry " + std::to_string(i) + " (" +
                              now + ") follows entry " + std::to_string(i - 1) + " (" + before +
                              ")");
    }
  }
  lift.table = {*crank, *values};
  lift.source = "table";
  lift.lift_key = lift_key;
}

// The table's rule: spline, resolution, noise, outliers, and the open lift stated.
void ReadLiftRule(SectionReader& r, LiftSection& lift) {
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
}

// breaks_deg: angles where s'' jumps (an exact table's pieces built apart).
void ReadBreaks(SectionReader& r, bool normal, LiftSection& lift) {
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
}

// end_slope (clamped) and smoothing (the smoothing spline's rule).
void ReadSplineEnds(SectionReader& r, LiftSection& lift) {
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
}

}  // namespace

LiftSection ReadLift(SectionReader r, const std::string& case_path, EngineCycle cycle) {
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
    ReadNormalCurve(r, *normal, crank || values, max_lift, lift);
  } else if (csv) {
    ReadCsvTable(r, *csv, crank || values, max_lift, case_path, cycle, lift);
  } else {
    ReadArrayTable(r, crank, crank_key, values, lift_key, max_lift, lift);
  }
  ReadLiftRule(r, lift);
  ReadBreaks(r, normal.has_value(), lift);
  lift.spline.sigma = lift.resolution_m / std::sqrt(12.0);  // σ of a uniform rounding error
  ReadSplineEnds(r, lift);
  r.Finish();
  return lift;
}

}  // namespace needle::case_internal
