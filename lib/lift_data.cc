#include "lib/lift_data.h"

#include <cmath>
#include <sstream>

namespace needle {
namespace {

std::string Mm(double m) {
  std::ostringstream out;
  out.precision(3);
  out << m * 1e3;
  return out.str();
}

}  // namespace

double EstimateNoise(const std::vector<double>& x, const std::vector<double>& y) {
  constexpr int kOrder = 4;  // fourth divided differences: blind to cubics
  double sum = 0.0;
  long count = 0;
  for (size_t i = 0; i + kOrder < x.size(); ++i) {
    double d = 0.0, w2 = 0.0;
    bool flat = true;
    for (int j = 0; j <= kOrder; ++j) {
      double p = 1.0;
      for (int l = 0; l <= kOrder; ++l) {
        if (l != j) p *= x[i + j] - x[i + l];
      }
      const double w = 1.0 / p;
      d += w * y[i + j];
      w2 += w * w;
      if (y[i + j] != y[i]) flat = false;
    }
    if (flat) continue;
    sum += d * d / w2;  // e² with e = D/√Σw²
    ++count;
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

LiftLawChoice ChooseLiftLaw(const LiftTable& table, const LiftDataOptions& o) {
  LiftLawChoice c;
  c.law.spline = o.spline;
  c.law.open_rad = o.open_rad;
  c.law.close_rad = o.close_rad;
  c.law.breaks_rad = o.breaks_rad;
  const int n = static_cast<int>(table.crank_rad.size());
  const bool dense = n >= kDenseTablePoints;
  c.measured = (dense || o.noise_m.has_value()) && o.breaks_rad.empty();
  const std::string points = std::to_string(n) + " points";
  if (o.noise_m) {
    c.noise_m = *o.noise_m;
    c.noise_source = "stated";
  } else if (dense) {
    c.estimated_noise_m = EstimateNoise(table.crank_rad, table.lift_m);
    c.noise_m = *c.estimated_noise_m;
    c.noise_source = "estimated";
    if (o.resolution_m && c.noise_m < *o.resolution_m / std::sqrt(12.0)) {
      c.noise_m = *o.resolution_m / std::sqrt(12.0);  // rounding is noise the data cannot hide
      c.noise_source = "rounding";
    }
    // Exact data: keep a floor far below any measurement so the smoothing stays well posed.
    c.noise_m = std::max(c.noise_m, 1e-10);
  } else {
    c.noise_m = o.resolution_m.value_or(1e-5) / std::sqrt(12.0);  // the paper's 0.01 mm
    c.noise_source = "rounding";
  }
  c.law.spline.sigma = c.noise_m;
  if (c.measured) {
    c.law.closed_level_m = kClosedLevelSigmas * c.noise_m;
    c.law.negative_allowance_m = kNegativeSigmas * c.noise_m;
  }
  const std::string noise = "noise " + Mm(c.noise_m) + " mm (" + c.noise_source + ")";
  if (o.kind) {
    c.law.spline.kind = *o.kind;
    c.reason = std::string("stated in the case; ") +
               (c.measured ? "measured data, " : "exact table, ") + points + ", " + noise;
    return c;
  }
  if (c.measured) {
    c.law.spline.kind = SplineKind::kSmoothing;
    c.reason = (o.noise_m ? "noise stated" : "dense table (" + points + ")") +
               std::string(": measured data, ") + noise + "; smoothing spline";
    return c;
  }
  if (!o.breaks_rad.empty()) {
    c.law.spline.kind = SplineKind::kNotAKnot;
    c.reason = "exact table with " + std::to_string(o.breaks_rad.size()) + " breaks (" + points +
               "): not-a-knot cubic on each piece between them";
    return c;
  }
  const bool at_rest =
      !table.lift_m.empty() && table.lift_m.front() == 0.0 && table.lift_m.back() == 0.0;
  if (at_rest) {
    c.law.spline.kind = SplineKind::kClamped;
    c.law.spline.start_slope = c.law.spline.end_slope = 0.0;
    c.reason = "sparse exact table (" + points +
               ") closed at both ends: clamped cubic at rest at the seat";
  } else {
    c.law.spline.kind = SplineKind::kNotAKnot;
    c.reason = "sparse exact table (" + points + ") open at an end: not-a-knot cubic";
  }
  return c;
}

}  // namespace needle
