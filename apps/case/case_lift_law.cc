// A case's lift law: the spline and open-lift choice of its [lift] table, made once here.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

#include "apps/case/case_file.h"
#include "apps/case/plausible_ranges.h"
#include "apps/case/section_reader.h"
#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"
#include "lib/input_file.h"
#include "lib/output.h"
#include "lib/toml_text.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle {

using case_internal::Number;

LiftLawChoice CaseLiftChoice(const Case& c) {
  LiftDataOptions o;
  if (c.lift.spline_given) o.kind = c.lift.spline.kind;
  o.spline = c.lift.spline;
  o.noise_m = c.lift.noise_m;
  if (c.lift.resolution_given) o.resolution_m = c.lift.resolution_m;
  o.open_rad = c.lift.open_rad;
  o.close_rad = c.lift.close_rad;
  o.breaks_rad = c.lift.breaks_rad;
  o.drop_outliers = c.lift.drop_outliers;
  o.find_breaks = !c.lift.breaks_given;
  LiftLawChoice choice = ChooseLiftLaw(c.lift.table, o);
  if (choice.corner) {
    // A corner: the lift's velocity jumps, the law cannot be differentiated there.
    const LiftBreak& k = *choice.corner;
    std::string at = c.path + ": [lift] " + c.lift.lift_key + "[" + std::to_string(k.index) + "]";
    if (k.index < c.lift.lines.size()) {
      at = c.lift.csv_path + ":" + std::to_string(c.lift.lines[k.index]);
      if (c.lift.csv_path != c.path) at = c.path + ": [lift] csv: " + at;
    }
    throw CaseError(at + ": the lift has a corner at " + Fixed(k.crank_rad / kDeg, 3) +
                    " deg (its velocity jumps by " + Fixed(k.jump * 1e3 * kDeg, 4) +
                    " mm/deg): a needle's lift has no corners; correct the readings there, or "
                    "round the corner off in the law the table was made from");
  }
  if (choice.outliers.empty()) return choice;
  // Where a reading is: the CSV file's line, or the entry of the case's array.
  auto where = [&](size_t index) {
    if (index < c.lift.lines.size()) return "line " + std::to_string(c.lift.lines[index]);
    return "entry " + std::to_string(index);
  };
  auto reading = [&](const LiftOutlier& x) {
    return Number(x.lift_m * 1e3) + " mm at " + Number(c.lift.table.crank_rad[x.index] / kDeg) +
           " deg";
  };
  const LiftOutlier& first = choice.outliers.front();
  const size_t more = choice.outliers.size() - 1;
  if (!c.lift.drop_outliers) {
    std::string at;
    if (first.index < c.lift.lines.size()) {
      at = c.lift.csv_path + ":" + std::to_string(c.lift.lines[first.index]);
      if (c.lift.csv_path != c.path) at = c.path + ": [lift] csv: " + at;
    } else {
      at = c.path + ": [lift] " + c.lift.lift_key + "[" + std::to_string(first.index) + "]";
    }
    std::string others;
    for (size_t k = 1; k < choice.outliers.size() && k <= 5; ++k) {
      others += (k > 1 ? ", " : "") + where(choice.outliers[k].index);
    }
    if (more > 5) others += ", …";
    throw CaseError(
        at + ": the reading " + reading(first) + " stands out of its neighbourhood (" +
        Number(first.expected_m * 1e3) + " mm by the cubic through the four readings around it, " +
        Number(std::round(first.sigmas)) + " robust sigma of " +
        Number(choice.robust_noise_m * 1e3) + " mm off): an outlier" +
        (more ? " (" + std::to_string(more) + " more: " + others + ")" : std::string()) +
        "; correct it, or set [lift] outliers = \"drop\" to leave it out" +
        (c.lift.csv_path == c.path ? " (in a case file reading this table with csv = …)" : ""));
  }
  choice.reason += "; " + std::to_string(choice.outliers.size()) + " outlier" + (more ? "s" : "") +
                   " left out (";
  for (size_t k = 0; k < choice.outliers.size(); ++k) {
    const LiftOutlier& x = choice.outliers[k];
    choice.reason += (k ? "; " : "") + where(x.index) + ": " + reading(x) + ", neighbourhood " +
                     Number(x.expected_m * 1e3) + " mm";
  }
  choice.reason += ")";
  return choice;
}

CaseLift ResolveLift(const Case& c) {
  try {
    CaseLift lift{CaseLiftChoice(c), nullptr};
    lift.law = std::make_shared<const LiftLaw>(lift.choice.table, lift.choice.law);
    return lift;
  } catch (const CaseError&) {
    throw;
  } catch (const std::exception& e) {
    // A stated break the law refuses names its key (issue 51's trial: "[lift]: break 0 …").
    const std::string what = e.what();
    const bool breaks = c.lift.breaks_given && what.rfind("break ", 0) == 0;
    throw CaseError(c.path + ": [lift]" + (breaks ? " breaks" : "") + ": " + what);
  }
}

LiftLaw MakeLiftLaw(const Case& c) { return *ResolveLift(c).law; }

}  // namespace needle
