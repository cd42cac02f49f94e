#pragma once
/// @file
/// Spring surge against the cam's harmonics (docs/model.md §7).
///
/// The spring as N equal segments of rate N·k and mass m_s/N (a lumped wave equation): the
/// interior nodes carry m_s/N each, the ends are held (seat below, the needle on its cam above),
///
///     M ẍ + K x = 0,   K = N k · tridiag(−1, 2, −1),   M = (m_s/N) I   (N − 1 nodes),
///
/// whose natural frequencies f_i = (N/π) √(k/m_s) sin(iπ/(2N)) tend to the wave equation's
/// f_i = (i/2) √(k/m_s) of a spring fixed at both ends as N grows (error ≈ (iπ/N)²/24).
/// m_s = ρ π² d² D n / 4, the active coils' mass.
///
/// The cam's harmonics: the lift over one cam revolution as a Fourier series,
/// u(ψ) = c₀ + Σ c_i cos(iψ + φ_i), and the acceleration's, u''(ψ) = Σ a_i cos(iψ + χ_i),
/// taken inside the open lift (where the lift's slope jumps, at the ends of a table that starts
/// on a ramp, u'' holds a Dirac impulse whose harmonics never decay: that is an impact, judged
/// by the seating velocity, and is left out). Where u is smooth a_i = i² c_i. The harmonic of
/// order i (a_i Ω² at cam speed Ω) meets spring mode j at the speed where i·f_cam = f_j.

#include <vector>

#include "lib/lift_law.h"
#include "spring/spring_parameters.h"

namespace needle {

/// m_s of the active coils, kg.
double ActiveSpringMassKg(const HelicalGeometry& g);

/// The first `count` natural frequencies (Hz, ascending) of the spring of rate `rate_N_m` and
/// mass `spring_mass_kg` as `segments` ≥ 2 lumped segments held at both ends (Eigen's
/// self-adjoint eigensolver on M⁻¹K); count ≤ segments − 1. Throws std::invalid_argument on
/// a non-positive rate or mass or a count out of range.
std::vector<double> ChainNaturalFrequenciesHz(double rate_N_m, double spring_mass_kg, int segments,
                                              int count);

/// The wave equation's f_i = (i/2)·√(k/m_s), Hz.
double SurgeFrequencyHz(double rate_N_m, double spring_mass_kg, int mode);

/// The lift's harmonics over one cam revolution.
struct CamHarmonics {
  /// c_i, the amplitude of order i = 0 … orders of the lift (m); order i makes i oscillations
  /// per cam revolution.
  std::vector<double> lift_m;
  /// a_i, the acceleration's harmonic per (cam rad/s)², m/rad² (multiply by Ω²); a₀ = 0.
  std::vector<double> acceleration_m_rad2;
  double largest_acceleration_m_rad2 = 0.0;  ///< the largest a_i (i ≥ 1)
  /// The highest order whose acceleration harmonic reaches `threshold` of the largest.
  int highest_significant_order = 0;
  double threshold = 0.05;
};

/// The harmonics of `law`'s lift (zero outside its open lift) over one cam revolution of
/// `revolution_crank_rad` of crank (4π four-stroke, 2π two-stroke), orders 0 … `orders`, by
/// the FFT of 8192 samples (Eigen's FFT). `threshold` in (0, 1). Needs a C² law (throws
/// std::invalid_argument otherwise).
CamHarmonics LiftHarmonics(const LiftLaw& law, double revolution_crank_rad, int orders,
                           double threshold);

}  // namespace needle
