#pragma once
/// @file
/// The cam as the needle sees it, u(θ), with roller play δ ≥ 0 (docs/model.md §3):
///
///   inside [θ_0, θ_N]:  u = s(θ)
///   δ = 0:              u = s(θ_0) before, s(θ_N) after
///   δ > 0, tangent:     u = max(−δ, s(θ_0) + s'(θ_0)(θ − θ_0)) before θ_0, likewise after θ_N
///   δ > 0, ramp_deg X:  u linear from −δ at θ_0 − X to s(θ_0) at θ_0, and from s(θ_N) at θ_N
///                       to −δ at θ_N + X; −δ (the base circle) beyond.
///
/// u is C¹ inside the table and has slope jumps at the ramp joins; Breaks() lists every angle
/// where a derivative of u jumps, so integrators can step to them exactly.

#include <array>
#include <vector>

#include "lib/lift_law.h"

namespace needle {

/// One segment of u between two breaks as a polynomial: u(θ) = Σ_k coefficients[k]·(θ − origin)^k.
struct CamPiece {
  double origin_rad = 0.0;
  std::vector<double> coefficients;  ///< m/radᵏ, at least one
};

enum class RampKind {
  kTangent,  ///< Basu: the curve prolonged by its end tangents down to the base circle
  kLinear,   ///< ramps of a given angular length (`ramp_deg`)
};

class CamInput {
 public:
  /// `law` must outlive this object. play_m ≥ 0; ramp_rad > 0 for kLinear. Throws
  /// std::invalid_argument when a tangent ramp cannot reach the base circle (end slope zero
  /// or pointing the wrong way), naming the way out.
  CamInput(const LiftLaw& law, double play_m, RampKind ramp, double ramp_rad);

  /// u(θ), m.
  double U(double crank_rad) const;
  /// du/dθ, m/rad.
  double Slope(double crank_rad) const;
  /// d²u/dθ², m/rad² (0 on ramps and the base circle).
  double Curvature(double crank_rad) const;
  /// d³u/dθ³, m/rad³ (0 on ramps and the base circle).
  double Jerk(double crank_rad) const;
  /// {U, Slope} at once (one search for the spline's piece), the same numbers bit for bit.
  std::array<double, 2> USlope(double crank_rad) const;

  /// The polynomial u is on the segment that holds θ (segments are [a, b) between breaks).
  CamPiece Piece(double crank_rad) const;

  /// Start of u's rise (ramp foot, or θ_0 without play) and end of its fall, rad.
  double rise_start_rad() const { return rise_start_; }
  double fall_end_rad() const { return fall_end_; }
  /// Every angle where a derivative of u jumps (ramp feet, θ_0, θ_N, spline knots), sorted.
  const std::vector<double>& Breaks() const { return breaks_; }
  /// Whether u's slope may jump at the break `crank_rad` (one of Breaks()): at θ_0, θ_N and the
  /// ramp feet. Elsewhere (spline knots, a table's breaks) u is C¹ by the model, and a slope
  /// difference between pieces is only the spline's error.
  bool SlopeMayJump(double crank_rad) const {
    return crank_rad == rise_start_ || crank_rad == fall_end_ || crank_rad == law_.start_rad() ||
           crank_rad == law_.end_rad();
  }
  double play_m() const { return play_; }
  const LiftLaw& law() const { return law_; }
  /// The lift law's largest lift and its angle (LiftLaw::Max(0)), found once with the cam: every
  /// run reads it (the recorder's slope scale, the not-following rule).
  const Extremum& top() const { return top_; }

 private:
  const LiftLaw& law_;
  Extremum top_;
  double play_;
  double s0_, sn_, slope0_, slopen_;  // s and s' at θ_0, θ_N
  double rise_start_, fall_end_;
  std::vector<double> breaks_;
};

}  // namespace needle
