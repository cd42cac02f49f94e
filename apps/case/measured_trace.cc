#include "apps/case/measured_trace.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "lib/case_error.h"
#include "lib/lift_data.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

namespace {

std::string Mm(double m) { return Significant(m * 1e3, 4) + " mm"; }
std::string Deg(double rad) { return Significant(rad / kDeg, 5) + " deg"; }

// The line of reading i, for messages ("PATH:LINE" or "PATH").
std::string Where(const MeasuredTrace& t, size_t i) {
  return i < t.lines.size() ? t.path + ":" + std::to_string(t.lines[i]) : t.path;
}

// The speed the clock gives, rpm: the least-squares slope of crank angle against time.
double ClockSpeedRpm(const MeasuredTrace& t) {
  const size_t n = t.time_s.size();
  double mt = 0.0, ma = 0.0;
  for (size_t i = 0; i < n; ++i) {
    mt += t.time_s[i] / n;
    ma += t.table.crank_rad[i] / n;
  }
  double sta = 0.0, stt = 0.0;
  for (size_t i = 0; i < n; ++i) {
    sta += (t.time_s[i] - mt) * (t.table.crank_rad[i] - ma);
    stt += (t.time_s[i] - mt) * (t.time_s[i] - mt);
  }
  return sta / stt * 60.0 / (2.0 * kPi);
}

// The width at half height of the samples (θ, y): from the last half-height crossing before the
// largest lift to the first after it, linearly located; nullopt when the samples do not fall
// below half height on both sides.
std::optional<double> HalfWidth(const std::vector<double>& th, const std::vector<double>& y) {
  const size_t top = static_cast<size_t>(std::max_element(y.begin(), y.end()) - y.begin());
  const double half = 0.5 * y[top];
  size_t a = top, b = top;
  while (a > 0 && y[a - 1] >= half) --a;
  while (b + 1 < y.size() && y[b + 1] >= half) ++b;
  if (a == 0 || b + 1 == y.size()) return std::nullopt;
  const auto cross = [&](size_t lo, size_t hi) {
    return th[lo] + (half - y[lo]) * (th[hi] - th[lo]) / (y[hi] - y[lo]);
  };
  return cross(b, b + 1) - cross(a - 1, a);
}

}  // namespace

void CheckMeasuredTrace(const MeasuredTrace& t, const BoundCase& b) {
  const std::vector<double>& th = t.table.crank_rad;
  const std::vector<double>& y = t.table.lift_m;
  if (th.size() != y.size() || (!t.time_s.empty() && t.time_s.size() != th.size())) {
    throw CaseError(t.path + ": the trace's columns differ in length");
  }
  for (size_t i = 0; i < th.size(); ++i) {
    if (!std::isfinite(th[i]) || !std::isfinite(y[i])) {
      throw CaseError(Where(t, i) + ": reading " + std::to_string(i) +
                      " is not a finite number; a trace needs finite angles and lifts");
    }
    if (i > 0 && !(th[i] > th[i - 1])) {
      const auto [now, before] = SignificantApart(th[i] / kDeg, th[i - 1] / kDeg);
      throw CaseError(Where(t, i) + ": crank_deg " + now + " does not increase after " + before +
                      "; angles must increase strictly");
    }
  }
  if (th.size() < static_cast<size_t>(kMinTraceLiftReadings)) {
    throw CaseError(t.path + ": the trace has " + std::to_string(th.size()) +
                    " reading(s); expected at least " + std::to_string(kMinTraceLiftReadings) +
                    " inside the cam's lift");
  }
  const LiftLaw& law = *b.lift.law;
  const double open = law.start_rad(), close = law.end_rad();
  const long inside =
      std::count_if(th.begin(), th.end(), [&](double a) { return a >= open && a <= close; });
  if (inside < kMinTraceLiftReadings) {
    std::ostringstream m;
    m << t.path << ": crank_deg: the trace runs " << Deg(th.front()) << " to " << Deg(th.back())
      << " with " << inside << " reading(s) inside the cam's lift (" << Deg(open) << " to "
      << Deg(close) << "); expected at least " << kMinTraceLiftReadings
      << " (a trace of another cam, or cam angles under crank_deg?)";
    throw CaseError(m.str());
  }
  const double cam_top = law.Max(0).value;
  const auto top = std::max_element(y.begin(), y.end());
  const size_t k = static_cast<size_t>(top - y.begin());
  if (*top > kTraceOverLiftFactor * cam_top) {
    throw CaseError(Where(t, k) + ": lift: the trace reaches " + Mm(*top) + ", " +
                    Significant(*top / cam_top, 3) + " times the cam's largest lift (" +
                    Mm(cam_top) + "); expected at most " + Significant(kTraceOverLiftFactor, 2) +
                    " times (a trace in um under lift_mm?)");
  }
  if (*top < kTraceUnderLiftFraction * cam_top) {
    throw CaseError(t.path + ": lift: the trace reaches only " + Mm(*top) + ", " +
                    Significant(*top / cam_top, 3) + " of the cam's largest lift (" + Mm(cam_top) +
                    "); expected at least " + Significant(kTraceUnderLiftFraction, 2) +
                    " of it (a trace in mm under lift_um, or of another cam?)");
  }
  // The width at half lift against the cam's (sampled every 0.05° of its lift).
  std::vector<double> cam_th, cam_y;
  for (double a = open; a <= close; a += 0.05 * kDeg) {
    cam_th.push_back(a);
    cam_y.push_back(law.Lift(a));
  }
  cam_th.push_back(close);
  cam_y.push_back(law.Lift(close));
  cam_th.insert(cam_th.begin(), open - kDeg);
  cam_y.insert(cam_y.begin(), 0.0);
  cam_th.push_back(close + kDeg);
  cam_y.push_back(0.0);
  const std::optional<double> width = HalfWidth(th, y), cam_width = HalfWidth(cam_th, cam_y);
  if (width && cam_width && *cam_width > 0.0 &&
      !(*width >= kTraceWidthLo * *cam_width && *width <= kTraceWidthHi * *cam_width)) {
    throw CaseError(t.path + ": crank_deg: the trace is above half its largest lift over " +
                    Deg(*width) + ", the cam over " + Deg(*cam_width) + ": " +
                    Significant(*width / *cam_width, 2) + " times; expected " +
                    Significant(kTraceWidthLo, 2) + " to " + Significant(kTraceWidthHi, 2) +
                    " times (" +
                    (*width < *cam_width ? "cam angles under crank_deg? name that column cam_deg"
                                         : "crank angles under cam_deg? name that column "
                                           "crank_deg; or a trace of another cam") +
                    ")");
  }
  if (t.time_s.empty()) return;
  for (size_t i = 1; i < t.time_s.size(); ++i) {
    if (!(t.time_s[i] > t.time_s[i - 1])) {
      const auto [now, before] = SignificantApart(t.time_s[i], t.time_s[i - 1], 8);
      throw CaseError(Where(t, i) + ": time: " + now + " s does not increase after " + before +
                      " s; a clock must increase strictly");
    }
  }
  const double clock_rpm = ClockSpeedRpm(t);
  if (!(std::abs(clock_rpm / t.speed_rpm - 1.0) <= kTraceSpeedTolerance)) {
    throw CaseError(t.path + ": time: the trace's clock gives " + Significant(clock_rpm, 5) +
                    " rpm (its crank angle against its time), the trace's speed is " +
                    Significant(t.speed_rpm, 5) + " rpm; expected within " +
                    Significant(kTraceSpeedTolerance * 100, 2) +
                    " % (the trace of another speed, or cam angles under crank_deg?)");
  }
}

MeasuredTrace ReadMeasuredTrace(const std::string& path, double speed_rpm, const BoundCase& b) {
  MeasuredTrace t;
  t.path = path;
  t.speed_rpm = speed_rpm;
  t.table = ReadLiftCsv(path, b.engine.cycle, &t.lines, &t.time_s);
  CheckMeasuredTrace(t, b);
  return t;
}

}  // namespace needle
