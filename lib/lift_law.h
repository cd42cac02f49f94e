#pragma once
/// @file
/// The lift law s(θ) of the needle (model.md §2): a spline through a table of crank angle
/// θ_i (rad, strictly increasing) and lift s_i (m), closed (s = 0) outside [θ_0, θ_N]:
///
///     s(θ) = spline(θ) on [θ_0, θ_N],  0 elsewhere;   dᵏs/dθᵏ from the spline, exact.

#include <vector>

#include "lib/piecewise_polynomial.h"
#include "lib/spline.h"

namespace needle {

/// A lift table in SI: crank angle θ_i in rad (negative before dead center), lift s_i in m.
struct LiftTable {
  std::vector<double> crank_rad;
  std::vector<double> lift_m;
};

/// Basu's normal curve (NACA TM 477), lift in percent of maximum at −15…40° in 5° steps.
/// Returns it scaled to `max_lift_m` (> 0).
LiftTable BasuNormalCurve(double max_lift_m);

/// Where a derivative of s takes its largest or smallest value.
struct Extremum {
  double crank_rad = 0.0;  ///< angle of the extremum, rad
  double value = 0.0;      ///< dᵏs/dθᵏ there, m/radᵏ
};

/// A lift law: table plus spline. Immutable after construction.
class LiftLaw {
 public:
  /// Builds the spline of `options.kind` through the table. Throws std::invalid_argument
  /// when the table is invalid for that kind (see BuildSpline) or a lift is negative.
  LiftLaw(LiftTable table, const SplineOptions& options);

  /// Lift s(θ), m; 0 outside [θ_0, θ_N].
  double Lift(double crank_rad) const;
  /// dᵏs/dθᵏ in m/radᵏ, k = 0..3; 0 outside [θ_0, θ_N]. For k = 2, 3 only meaningful when
  /// HasAcceleration() (C¹ kinds have a second derivative that jumps at the knots).
  double Derivative(double crank_rad, int order) const;
  /// True when s'' is continuous (all kinds but pchip and makima).
  bool HasAcceleration() const { return spline_.continuity() >= 2; }

  /// θ_0 and θ_N, rad.
  double start_rad() const { return table_.crank_rad.front(); }
  double end_rad() const { return table_.crank_rad.back(); }
  /// Mean lift over [θ_0, θ_N]: (1/(θ_N − θ_0)) ∫ s dθ, m.
  double MeanLift() const;
  /// Largest and smallest dᵏs/dθᵏ on [θ_0, θ_N], k = 0..2, located to ~1e-12 rad.
  Extremum Max(int order) const;
  Extremum Min(int order) const;

  const LiftTable& table() const { return table_; }
  const PiecewisePolynomial& spline() const { return spline_; }
  SplineKind kind() const { return kind_; }

 private:
  std::pair<Extremum, Extremum> Extrema(int order) const;

  LiftTable table_;
  SplineKind kind_;
  PiecewisePolynomial spline_;
};

}  // namespace needle
