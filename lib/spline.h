#pragma once
/// @file
/// Splines through (or, for `smoothing`, near) a table (x_i, y_i), i = 0..N, on
/// non-uniform, strictly increasing knots (docs/model.md §2):
///
///   natural      cubic, C², s''(x_0) = s''(x_N) = 0
///   not-a-knot   cubic, C², s''' continuous at x_1 and x_{N−1}
///   clamped      cubic, C², s'(x_0), s'(x_N) given (`at-rest`: both zero)
///   quintic      quintic, C⁴, s⁽⁵⁾ continuous at x_1, x_2, x_{N−2}, x_{N−1}
///                (the not-a-knot conditions of the quintic: reproduces any quintic)
///   pchip        Fritsch–Carlson monotone cubic Hermite, C¹ (no second derivative)
///   makima       modified Akima cubic Hermite, C¹ (no second derivative)
///   smoothing    cubic smoothing spline, C², minimising
///                Σ((y_i − f(x_i))/σ)² + λ∫f''², λ by the discrepancy principle
///                (weighted residual = N+1) or by generalised cross-validation.
///   local        local quintic regression, the window at each reading by Lepski's rule for
///                the readings' σ (lib/local_fit.h); C², ends from the data; the default
///                reading of an exported table (lib/lift_data.h)
///
/// Every kind returns a PiecewisePolynomial; its continuity() tells which derivatives
/// are meaningful (acceleration needs continuity ≥ 2).

#include <optional>
#include <string>
#include <vector>

#include "lib/piecewise_polynomial.h"

namespace needle {

enum class SplineKind {
  kNatural,
  kNotAKnot,
  kClamped,
  kQuintic,
  kPchip,
  kMakima,
  kSmoothing,
  kLocal
};

/// How the smoothing spline picks λ.
enum class SmoothingRule {
  kDiscrepancy,  ///< weighted residual Σ((y_i − f_i)/σ)² = N+1 (docs/model.md default)
  kGcv,          ///< minimise generalised cross-validation
};

/// Options of a spline build. Every field has a default; Validate() checks them in one place.
struct SplineOptions {
  /// Which spline. Default: not-a-knot (no end assumption, O(h⁴) values).
  SplineKind kind = SplineKind::kNotAKnot;
  /// `clamped` only: slope dy/dx at x_0, in y-units per x-unit. Default 0 (at rest).
  double start_slope = 0.0;
  /// `clamped` only: slope dy/dx at x_N. Default 0 (at rest).
  double end_slope = 0.0;
  /// `smoothing` and `local` only: standard deviation σ of each y_i, in y-units, > 0.
  /// Default: the paper's 0.01 mm rounding, σ = 1e-5 m / √12.
  double sigma = 1e-5 / 3.4641016151377544;
  /// `local` only: σ is the readings' rounding (q/√12), not white noise (lib/local_fit.h).
  bool quantized = false;
  /// The table is a sparse one (under kDenseTablePoints readings, lib/lift_data.h): an
  /// interpolating spline's band takes its truncation to fall slower than h² (lib/spline_band.h).
  bool sparse_table = false;
  /// `smoothing` only: how λ is chosen.
  SmoothingRule smoothing_rule = SmoothingRule::kDiscrepancy;

  /// Throws std::invalid_argument naming the field, its value and the rule it broke.
  void Validate() const;
};

/// The case-file name of a kind ("not-a-knot", …).
std::string SplineKindName(SplineKind kind);

/// Parses a case-file name; std::nullopt if unknown.
std::optional<SplineKind> ParseSplineKind(const std::string& name);

/// All kinds, in documentation order.
std::vector<SplineKind> AllSplineKinds();

/// Comma-separated list of all kind names, for messages.
std::string SplineKindList();

/// The least number of table points `kind` needs (2 for natural/clamped/pchip/makima,
/// 4 for not-a-knot, 6 for quintic, 3 for smoothing, 7 for local).
int MinimumPoints(SplineKind kind);

/// True when the kind's second derivative is continuous (acceleration is available).
bool HasAcceleration(SplineKind kind);

/// Throws std::invalid_argument as BuildSpline does on inputs it cannot take.
void CheckSplineInputs(const std::vector<double>& x, const std::vector<double>& y,
                       const SplineOptions& options);

/// Builds the spline of `options.kind` through (x, y). Throws std::invalid_argument when
/// x is not strictly increasing, sizes differ, values are not finite or there are fewer
/// than MinimumPoints(kind) points.
PiecewisePolynomial BuildSpline(const std::vector<double>& x, const std::vector<double>& y,
                                const SplineOptions& options);

// The builders behind BuildSpline (inputs already checked).
PiecewisePolynomial BuildCubicSpline(const std::vector<double>& x, const std::vector<double>& y,
                                     const SplineOptions& options);
PiecewisePolynomial BuildQuinticSpline(const std::vector<double>& x, const std::vector<double>& y);
PiecewisePolynomial BuildPchip(const std::vector<double>& x, const std::vector<double>& y);
PiecewisePolynomial BuildMakima(const std::vector<double>& x, const std::vector<double>& y);
PiecewisePolynomial BuildSmoothingSpline(const std::vector<double>& x, const std::vector<double>& y,
                                         const SplineOptions& options);

/// Cubic Hermite pieces from values y_i and slopes d_i: on [x_i, x_{i+1}], h = x_{i+1} − x_i,
/// δ = (y_{i+1} − y_i)/h: c0 = y_i, c1 = d_i, c2 = (3δ − 2d_i − d_{i+1})/h,
/// c3 = (d_i + d_{i+1} − 2δ)/h². `continuity` is stored as given.
PiecewisePolynomial CubicHermite(const std::vector<double>& x, const std::vector<double>& y,
                                 const std::vector<double>& slopes, int continuity);

}  // namespace needle
