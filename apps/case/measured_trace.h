#pragma once
/// @file
/// A measured lift trace (`needle fit`, docs/fit.md): the needle's lift at one speed, as a test
/// bench records it (an inductive or eddy-current lift sensor sampled against a crank-angle
/// encoder), read from a CSV of `crank_deg` (or `cam_deg`) and `lift_mm` (or `lift_um`, …), with
/// an optional clock column `time_s` (or `time_ms`). Read as lift tables are (lib/lift_data.h
/// ReadLiftCsv) and then checked against the case it is a trace of: every refusal one CaseError
/// line naming the file, the column and what was expected.

#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "lib/lift_law.h"

namespace needle {

/// Fewest readings of a trace inside the cam's lift: fewer do not show the needle's motion.
constexpr int kMinTraceLiftReadings = 10;
/// A trace's largest lift may exceed the cam's largest lift by at most this factor (the needle
/// overshoots the cam where it flies, by far less): a larger one is a unit slip (µm as mm).
constexpr double kTraceOverLiftFactor = 2.0;
/// … and must reach at least this fraction of it (a needle the cam lifts follows it most of the
/// way): a smaller one is the other slip (mm as µm), or a trace of another cam.
constexpr double kTraceUnderLiftFraction = 0.2;
/// The trace's width at half its largest lift may be this many times the cam's at most, and
/// at least kTraceWidthLo of it: a four-stroke trace in cam angles under crank_deg is half as
/// wide (crank angles under cam_deg twice), while play, ramps and a needle that flies move the
/// width by far less.
constexpr double kTraceWidthLo = 0.6, kTraceWidthHi = 1.7;
/// The speed a trace's clock gives (its crank angle against its time) may differ from the speed
/// stated for it by at most this fraction.
constexpr double kTraceSpeedTolerance = 0.01;

/// One measured trace.
struct MeasuredTrace {
  std::string path;            ///< the CSV, for messages
  double speed_rpm = 0.0;      ///< the speed it was recorded at
  LiftTable table;             ///< crank angle (rad) and lift (m) of each reading
  std::vector<int> lines;      ///< the CSV line of each reading
  std::vector<double> time_s;  ///< the clock of each reading, s; empty: the trace has none
};

/// Reads `path` as a trace of case `b` recorded at `speed_rpm` and checks it against the case:
/// angles that increase and finite numbers (ReadLiftCsv), at least kMinTraceLiftReadings readings
/// inside the cam's lift, a largest lift within [kTraceUnderLiftFraction, kTraceOverLiftFactor]
/// of the cam's, a width at half its largest lift within [kTraceWidthLo, kTraceWidthHi] of the
/// cam's (where the trace covers both its half-lift crossings), and, with a clock column, a clock
/// that increases and gives `speed_rpm` within kTraceSpeedTolerance. Throws CaseError
/// ("PATH:LINE:COLUMN: what" or "PATH: column: what").
MeasuredTrace ReadMeasuredTrace(const std::string& path, double speed_rpm, const BoundCase& b);

/// The same checks on a trace already in memory (`needle.fit` from Python's arrays).
void CheckMeasuredTrace(const MeasuredTrace& trace, const BoundCase& b);

}  // namespace needle
