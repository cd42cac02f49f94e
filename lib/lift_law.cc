#include "lib/lift_law.h"

#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/units.h"

namespace needle {

LiftTable BasuNormalCurve(double max_lift_m) {
  if (!(max_lift_m > 0.0) || !std::isfinite(max_lift_m)) {
    throw std::invalid_argument("BasuNormalCurve: max_lift must be positive, got " +
                                std::to_string(max_lift_m));
  }
  // NACA TM 477, table "% of maximum lift" against crank angle.
  static const double kPercent[] = {0, 2, 8, 21, 42, 68, 92, 100, 88, 58, 26, 0};
  LiftTable table;
  for (int i = 0; i < 12; ++i) {
    table.crank_rad.push_back((-15.0 + 5.0 * i) * kDeg);
    table.lift_m.push_back(max_lift_m * kPercent[i] / 100.0);
  }
  return table;
}

namespace {

PiecewisePolynomial Build(const LiftTable& table, const SplineOptions& options) {
  for (size_t i = 0; i < table.lift_m.size(); ++i) {
    if (table.lift_m[i] < 0.0) {
      throw std::invalid_argument("lift " + std::to_string(i) + " is negative (" +
                                  std::to_string(table.lift_m[i] * 1e3) +
                                  " mm): lift is measured from the seat and cannot be below it");
    }
  }
  return BuildSpline(table.crank_rad, table.lift_m, options);
}

}  // namespace

LiftLaw::LiftLaw(LiftTable table, const SplineOptions& options)
    : table_(std::move(table)), kind_(options.kind), spline_(Build(table_, options)) {}

double LiftLaw::Lift(double crank_rad) const { return Derivative(crank_rad, 0); }

double LiftLaw::Derivative(double crank_rad, int order) const {
  if (crank_rad < start_rad() || crank_rad > end_rad()) return 0.0;  // closed outside
  return spline_.Evaluate(crank_rad, order);
}

double LiftLaw::MeanLift() const { return spline_.Integral() / (end_rad() - start_rad()); }

Extremum LiftLaw::Max(int order) const { return Extrema(order).second; }
Extremum LiftLaw::Min(int order) const { return Extrema(order).first; }

std::pair<Extremum, Extremum> LiftLaw::Extrema(int order) const {
  // Candidates: both sides of every break, and the interior roots of the next derivative
  // on each piece (found by sampling, then TOMS 748 to machine precision).
  const auto& x = spline_.breaks();
  Extremum lo{x.front(), spline_.Evaluate(x.front(), order)};
  Extremum hi = lo;
  auto consider = [&](double at, double value) {
    if (value < lo.value) lo = {at, value};
    if (value > hi.value) hi = {at, value};
  };
  const int samples = 16;
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    const double a = x[i], b = x[i + 1];
    // Evaluate inside the piece: the polynomial of piece i, also at its right end.
    auto piece_value = [&](double t, int k) {
      const auto& c = spline_.coefficients();
      const double dt = t - a;
      double v = 0.0;
      for (int m = spline_.degree(); m >= k; --m) {
        double falling = 1.0;
        for (int j = 0; j < k; ++j) falling *= (m - j);
        v = v * dt + falling * c(static_cast<Eigen::Index>(i), m);
      }
      return v;
    };
    consider(a, piece_value(a, order));
    consider(b, piece_value(b, order));
    auto slope = [&](double t) { return piece_value(t, order + 1); };
    double t0 = a, s0 = slope(a);
    for (int k = 1; k <= samples; ++k) {
      const double t1 = a + (b - a) * k / samples;
      const double s1 = slope(t1);
      if (s0 == 0.0) consider(t0, piece_value(t0, order));
      if (s0 * s1 < 0.0) {
        std::uintmax_t it = 60;
        const auto r = boost::math::tools::toms748_solve(
            slope, t0, t1, s0, s1, boost::math::tools::eps_tolerance<double>(50), it);
        const double root = 0.5 * (r.first + r.second);
        consider(root, piece_value(root, order));
      }
      t0 = t1;
      s0 = s1;
    }
  }
  return {lo, hi};
}

}  // namespace needle
