// A measured trace (apps/case/measured_trace.h) checked against its case: every bad trace the
// fit can be given is refused with one line naming the file, the column and what was expected.
#include "apps/case/measured_trace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "apps/case/case_file.h"
#include "lib/case_error.h"

namespace needle {
namespace {

const std::string kExample1 = std::string(NEEDLE_SOURCE_DIR) + "/cases/basu-example1.toml";

// A trace file: the cam's own lift (Basu Example 1's law) at 0.5° steps over −20…50°, each row
// written by `row` (angle in deg, lift in mm, row index).
std::string WriteTrace(const std::string& name, const std::string& header,
                       const std::function<std::string(double, double, int)>& row) {
  const BoundCase b = Bind(LoadCase(kExample1));
  const std::string path =
      (std::filesystem::temp_directory_path() / ("needle-trace-" + name + ".csv")).string();
  std::ofstream out(path);
  out << header << "\n";
  int i = 0;
  for (double deg = -20.0; deg <= 50.0 + 1e-9; deg += 0.5, ++i) {
    out << row(deg, b.lift.law->Lift(deg * kDeg) * 1e3, i) << "\n";
  }
  return path;
}

std::string Refusal(const std::string& path, double rpm = 125.0) {
  try {
    ReadMeasuredTrace(path, rpm, Bind(LoadCase(kExample1)));
  } catch (const CaseError& e) {
    return e.what();
  }
  return "accepted";
}

std::string Row(double deg, double mm) { return std::to_string(deg) + "," + std::to_string(mm); }

TEST(MeasuredTrace, ReadsAGoodTraceWithItsClock) {
  const double rpm = 125.0;
  const std::string path =
      WriteTrace("good", "crank_deg,lift_mm,time_ms", [&](double d, double y, int) {
        return Row(d, y) + "," + std::to_string((d + 20.0) / (6.0 * rpm) * 1e3);
      });
  const MeasuredTrace t = ReadMeasuredTrace(path, rpm, Bind(LoadCase(kExample1)));
  EXPECT_EQ(t.table.crank_rad.size(), 141u);
  EXPECT_EQ(t.time_s.size(), 141u);
  EXPECT_NEAR(t.time_s[2], 1.0 / (6.0 * rpm), 1e-9);
  EXPECT_EQ(Refusal(path, rpm), "accepted");
}

TEST(MeasuredTrace, RefusesAnglesThatDoNotIncrease) {
  const std::string path = WriteTrace("back", "crank_deg,lift_mm", [](double d, double y, int i) {
    return Row(i == 5 ? d - 2.0 : d, y);
  });
  EXPECT_EQ(Refusal(path), path +
                               ":7:1: crank_deg -19.5 does not increase after -18 (line 6); "
                               "angles must increase strictly");
}

TEST(MeasuredTrace, RefusesANaN) {
  const std::string path = WriteTrace("nan", "crank_deg,lift_mm", [](double d, double y, int i) {
    return i == 3 ? std::to_string(d) + ",nan" : Row(d, y);
  });
  EXPECT_EQ(Refusal(path), path + ":5:2: 'nan' is not a finite number (column lift_mm)");
}

TEST(MeasuredTrace, RefusesATraceOutsideTheLift) {
  const std::string path = WriteTrace("outside", "crank_deg,lift_mm",
                                      [](double d, double y, int) { return Row(d + 200.0, y); });
  EXPECT_EQ(Refusal(path),
            path +
                ": crank_deg: the trace runs 180 deg to 250 deg with 0 reading(s) inside the "
                "cam's lift (-15 deg to 40 deg); expected at least 10 (a trace of another cam, "
                "or cam angles under crank_deg?)");
}

TEST(MeasuredTrace, RefusesCamAnglesUnderCrankDeg) {
  // Issue 51's trial: a four-stroke trace written in cam angles (half the crank's) under
  // crank_deg kept enough readings inside the lift and was fitted, to a 25 tkgf preload.
  const std::string path = WriteTrace("cam-angles", "crank_deg,lift_mm",
                                      [](double d, double y, int) { return Row(d / 2.0, y); });
  EXPECT_EQ(Refusal(path), path +
                               ": crank_deg: the trace is above half its largest lift over 12.269 "
                               "deg, the cam over 24.537 deg: 0.5 times; expected 0.6 to 1.7 "
                               "times (cam angles under crank_deg? name that column cam_deg)");
  const std::string crank = WriteTrace("crank-as-cam", "crank_deg,lift_mm",
                                       [](double d, double y, int) { return Row(d * 2.0, y); });
  EXPECT_EQ(Refusal(crank), crank +
                                ": crank_deg: the trace is above half its largest lift over "
                                "49.077 deg, the cam over 24.537 deg: 2 times; expected 0.6 to 1.7 "
                                "times (crank angles under cam_deg? name that column crank_deg; or "
                                "a trace of another cam)");
}

TEST(MeasuredTrace, RefusesAWrongUnit) {
  const std::string um_as_mm =
      WriteTrace("um-as-mm", "crank_deg,lift_mm", [](double d, double y, int) {
        return Row(d, y * 1000.0 / 12.2);  // a 300 mm lift
      });
  EXPECT_EQ(Refusal(um_as_mm),
            um_as_mm +
                ":81: lift: the trace reaches 301.1 mm, 82 times the cam's largest lift "
                "(3.674 mm); expected at most 2 times (a trace in um under lift_mm?)");
  const std::string mm_as_um = WriteTrace("mm-as-um", "crank_deg,lift_um",
                                          [](double d, double y, int) { return Row(d, y); });
  EXPECT_EQ(Refusal(mm_as_um),
            mm_as_um +
                ": lift: the trace reaches only 0.003674 mm, 0.001 of the cam's largest "
                "lift (3.674 mm); expected at least 0.2 of it (a trace in mm under "
                "lift_um, or of another cam?)");
}

TEST(MeasuredTrace, RefusesASpeedItsClockContradicts) {
  const std::string path =
      WriteTrace("clock", "crank_deg,lift_mm,time_s", [](double d, double y, int) {
        return Row(d, y) + "," + std::to_string((d + 20.0) / (6.0 * 125.0));
      });
  EXPECT_EQ(Refusal(path, 150.0),
            path +
                ": time: the trace's clock gives 125 rpm (its crank angle against its time), "
                "the trace's speed is 150 rpm; expected within 1 % (the trace of another "
                "speed, or cam angles under crank_deg?)");
  EXPECT_EQ(Refusal(path, 125.0), "accepted");
}

TEST(MeasuredTrace, RefusesATimeColumnInALiftTable) {
  // A case's lift table has no clock: the third column stays refused there.
  const std::string path = WriteTrace("table-with-time", "crank_deg,lift_mm,time_s",
                                      [](double d, double y, int) { return Row(d, y) + ",0"; });
  EXPECT_THROW(ReadLiftCsv(path, EngineCycle::kFourStroke), CaseError);
}

}  // namespace
}  // namespace needle
