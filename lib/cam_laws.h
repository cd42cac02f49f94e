#pragma once
/// @file
/// Closed-form rise laws s(θ) on 0 ≤ θ ≤ β rising from 0 to H at rest at both ends, with
/// u = θ/β (the classical test laws for spline differentiation and benchmarks):
///
///   cycloidal   s = H (u − sin(2πu)/(2π))
///   harmonic    s = H (1 − cos(πu))/2
///   poly345     s = H (10u³ − 15u⁴ + 6u⁵)
///
/// Outside [0, β] the law is held at its end value (0 before, H after).

#include <string>

namespace needle {

enum class CamLawKind { kCycloidal, kHarmonic, kPoly345 };

/// A closed-form rise of height `height` over angle `beta` (any consistent units, β > 0).
class CamLaw {
 public:
  CamLaw(CamLawKind kind, double height, double beta);

  /// d^order s/dθ^order at θ, order 0..3 (units of height per unit angle^order).
  double Derivative(double theta, int order) const;
  double Lift(double theta) const { return Derivative(theta, 0); }

  CamLawKind kind() const { return kind_; }
  double height() const { return height_; }
  double beta() const { return beta_; }
  std::string name() const;

 private:
  CamLawKind kind_;
  double height_;
  double beta_;
};

}  // namespace needle
