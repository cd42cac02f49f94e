// The bands of an interpolating spline's s'' and of a local fit's shared bias (lib/spline_band.h).
#include "lib/spline_band.h"

#include <algorithm>
#include <cmath>

namespace needle {
namespace {

// Two-sided 95 % of a normal variable, in standard deviations.
constexpr double kBand95 = 1.96;

// A truncation error of s'' that falls as h² (a cubic's; a quintic's falls faster, and is then
// overstated): the spline at twice the spacing differs from it by (4 − 1) times its error.
constexpr double kRichardsonDivisor = 3.0;

// A sparse table (options.sparse_table: fewer than 30 readings) resolves a rise in a handful of
// readings, short of the h² regime: its error is taken to fall as h^1.32 only, so the spline at
// twice the spacing differs from it by (2.5 − 1) times its error. On bench/export_trial.py's
// 3000 random exports (seed 1; 757 sparse), the truth lay beyond a band's unsafe end at 5.2 %
// of the sparse extremes with the divisor 3, 3.4 % with 2, 2.1 % with 1.5 (a 95 % band's 2.5
// %), 1.1 % with 1; on seed 2, held out, 5.9 %, 3.2 %, 1.8 %, 1.0 %.
constexpr double kSparseRichardsonDivisor = 1.5;

// Readings between the ones of one probing comb: 24, where a quintic's response has fallen to
// 0.43^12 ≈ 4e-5 of its peak (and a cubic's to 0.27^12 ≈ 1e-7).
constexpr size_t kProbeSpacing = 24;

bool Interpolating(SplineKind kind) {
  return kind == SplineKind::kNatural || kind == SplineKind::kNotAKnot ||
         kind == SplineKind::kClamped || kind == SplineKind::kQuintic;
}

// Every other reading from `first` (0 or 1), the table's two ends always kept.
void Half(const std::vector<double>& x, const std::vector<double>& y, size_t first,
          std::vector<double>* hx, std::vector<double>* hy) {
  const size_t n = x.size();
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 || i + 1 == n || i % 2 == first) {
      hx->push_back(x[i]);
      hy->push_back(y[i]);
    }
  }
}

}  // namespace

void AddLocalFitBias(const std::vector<double>& x, const std::vector<double>& y,
                     const SplineOptions& options, LocalFit* fit, LocalTrim trim) {
  const size_t n = x.size();
  if (n > static_cast<size_t>(kLocalMaxNodes) || n < 2 * static_cast<size_t>(kLocalMinimumPoints))
    return;
  std::vector<double> hx, hy;
  Half(x, y, 0, &hx, &hy);
  const LocalFit half = FitLocal(hx, hy, options.sigma, options.quantized, trim);
  for (LocalNode& node : fit->nodes)
    node.band2 += std::abs(half.law.Evaluate(node.x, 2) - node.s[2]);
}

std::vector<LocalNode> InterpolationNodes(const std::vector<double>& x,
                                          const std::vector<double>& y,
                                          const SplineOptions& options,
                                          const PiecewisePolynomial& law) {
  const size_t n = x.size();
  if (!Interpolating(options.kind) || n > static_cast<size_t>(kInterpolationBandPoints) ||
      n < 2 * static_cast<size_t>(MinimumPoints(options.kind))) {
    return {};
  }
  // The rounding: Σ_i g_ji² from the splines of combs of unit readings, every kProbeSpacing-th
  // (a clamped spline's end slopes held). A spline's response to one reading decays as ~0.27
  // (a cubic's) to ~0.43 (a quintic's) per reading away from it, so at x_j a comb's s'' is the
  // response to its one reading nearest j, to 1e-4 of it (Curtis, Powell and Reid's probing).
  SplineOptions unit = options;
  unit.start_slope = unit.end_slope = 0.0;
  std::vector<double> sum_g2(n, 0.0), comb(n, 0.0);
  const size_t spacing = std::min(n, kProbeSpacing);
  for (size_t r = 0; r < spacing; ++r) {
    for (size_t i = 0; i < n; ++i) comb[i] = (i % spacing == r) ? 1.0 : 0.0;
    const PiecewisePolynomial g = BuildSpline(x, comb, unit);
    for (size_t j = 0; j < n; ++j) sum_g2[j] += std::pow(g.Evaluate(x[j], 2), 2);
  }
  // The truncation: the splines through each half of the readings.
  const double divisor = options.sparse_table ? kSparseRichardsonDivisor : kRichardsonDivisor;
  std::vector<double> truncation(n, 0.0);
  for (size_t first : {0u, 1u}) {
    std::vector<double> hx, hy;
    Half(x, y, first, &hx, &hy);
    const PiecewisePolynomial half = BuildSpline(hx, hy, options);
    for (size_t j = 0; j < n; ++j) {
      const double d = std::abs(half.Evaluate(x[j], 2) - law.Evaluate(x[j], 2));
      truncation[j] = std::max(truncation[j], d / divisor);
    }
  }
  std::vector<LocalNode> nodes(n);
  for (size_t j = 0; j < n; ++j) {
    LocalNode& node = nodes[j];
    node.x = x[j];
    for (int k = 0; k < 3; ++k) node.s[k] = law.Evaluate(x[j], k);
    node.band2 = kBand95 * options.sigma * std::sqrt(sum_g2[j]) + truncation[j];
    node.window = 1;
    node.width = 0.0;
  }
  return nodes;
}

}  // namespace needle
