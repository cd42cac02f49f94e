#pragma once
/// @file
/// Case files: one scene per TOML file, every dimensional key carrying its unit as a
/// suffix (`speed_rpm`, `lift_mm`, `crank_deg`, `preload_kgf` or `preload_N`, …).
/// Values are converted to SI on reading (lib/units.h); nothing downstream sees units.
///
///     title = "…"                      optional
///     [engine]  speed_rpm, cycle = "four-stroke" | "two-stroke"
///     [lift]    crank_deg + lift_mm   |   normal_curve = "basu" + max_lift_mm
///               spline = "not-a-knot" (default) | natural | clamped | quintic | pchip |
///                        makima | smoothing
///               resolution_mm = 0.01 (table rounding; σ = resolution/√12 for smoothing)
///               end_slope = "at-rest" | end_slope_mm_deg = [start, end]   (clamped only)
///               smoothing = "discrepancy" (default) | "gcv"              (smoothing only)
///     [paper]   published values to compare with: crank_deg + velocity_dcm_s (magnitudes),
///               max_acceleration_m_s2, inertia_force_kgf, mean_lift_mm
///
/// Every problem is reported as one CaseError line: "FILE: [section] key: what was expected".

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lib/lift_law.h"
#include "lib/spline.h"

namespace needle {

/// A case-file problem; what() is one line naming the file, the key and what was expected.
class CaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct EngineSection {
  double speed_rpm = 0.0;             ///< rated crank speed, rpm, > 0
  std::string cycle = "four-stroke";  ///< "four-stroke" (cam at half crank speed) or "two-stroke"
};

struct LiftSection {
  LiftTable table;       ///< the lift table in SI (from crank_deg/lift_mm or the normal curve)
  SplineOptions spline;  ///< spline kind and its options
  double resolution_m = 1e-5;  ///< rounding of the table's lifts, m (paper: 0.01 mm)
  std::string source;          ///< "table" or "basu normal curve"
};

struct PaperSection {
  std::vector<double> crank_rad;     ///< angles of the published velocities, rad
  std::vector<double> velocity_m_s;  ///< published velocity magnitudes, m/s
  std::optional<double> max_acceleration_m_s2;
  std::optional<double> inertia_force_N;
  std::optional<double> mean_lift_m;
};

struct Case {
  std::string path;   ///< the file it came from, for messages
  std::string title;  ///< optional one-line description
  EngineSection engine;
  LiftSection lift;
  std::optional<PaperSection> paper;
};

/// Reads and validates a case file. Throws CaseError (one line) on any problem: unreadable
/// file, malformed TOML, missing or unknown keys, unknown unit suffixes, wrong types,
/// non-increasing angles, NaN, negative lift, too few points for the spline kind.
Case LoadCase(const std::string& path);

/// As LoadCase, from text already in memory; `path` is used in messages only.
Case ParseCase(const std::string& text, const std::string& path);

/// Builds the lift law of a case, turning spline-construction failures into CaseError.
LiftLaw MakeLiftLaw(const Case& c);

/// Checks that `kind` can be built on the case's table (enough points); throws CaseError
/// naming `where` (e.g. "--spline" or "[lift] spline") otherwise.
void CheckSplineFits(const Case& c, SplineKind kind, const std::string& where);

}  // namespace needle
