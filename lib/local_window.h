#pragma once
/// @file
/// Internal to lib/'s local fit (local_fit.cc, local_join.cc; defined in local_window.cc): one
/// window's weighted least-squares fit and its misfit test (lib/local_fit.h has the model).

#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <vector>

#include "lib/local_fit.h"

namespace needle {
namespace local_window {

/// A window polynomial's coefficients: degree kLocalDegree and one.
inline constexpr int kTerms = kLocalDegree + 1;

/// Readings as fitted: a reading, or the mean of a bin of `count` consecutive readings.
using Points = BinMeans;

/// The estimates of s, s', s'' at t from the points [lo, hi), and the standard deviation of s''
/// per unit σ.
struct Estimate {
  double s[3] = {};
  double sd2 = 0.0;
  double width = 0.0;  ///< the window's span, rad
  /// The fit's residuals: the largest |s_i − fit(θ_i)| (m) and Σ c_i (s_i − fit(θ_i))² (m²).
  double largest_residual = 0.0, residual_square_sum = 0.0;
  double fifth = 0.0;  ///< |s⁽⁵⁾| of the fitted polynomial, m/rad⁵ (its roughness)
};

/// Readings [from, to) as fitted: themselves, or above kLocalMaxNodes the means of bins.
Points FittedPoints(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                    size_t to);

/// The polynomial of `terms` coefficients (the local degree's by default) fitted at t to the
/// points [lo, hi) with tricube weights; `quantized`: the noise of s'' as the rounding's bound.
Estimate FitAt(const Points& p, double t, size_t lo, size_t hi, bool quantized, int terms = kTerms);

/// The weights G = V (VᵀV)⁻¹ = Q₁ R⁻ᵀ of a least-squares fit's coefficients on its weighted rows V
/// (rows × terms, at most kQrMaxTerms), into g (rows × terms), by QR: VᵀV is ill-conditioned for a
/// one-sided window of a few readings. V is overwritten by its factors (callers' storage: a
/// window's on the stack).
void QrWeights(Eigen::Ref<Eigen::MatrixXd> v, int terms, Eigen::Ref<Eigen::MatrixXd> g);
inline constexpr int kQrMaxTerms = 2 * kLocalDegree;  // JoinWindows' 2 + 2 × 4

/// An estimate's noise per unit σ from its weights on the readings, Σ|w| and Σ w²/count:
/// rounding is no white noise, each reading's error at most q/2 = √3 σ and the estimate's at most
/// √3 σ Σ|w|, which stands for 1.96 standard deviations (`quantized`); else √(Σ w²/count).
inline double NoisePerSigma(double sum_abs, double sum_squares, bool quantized) {
  return quantized ? std::sqrt(3.0) * sum_abs / 1.96 : std::sqrt(sum_squares);
}

/// Whether the window's polynomial misses its `readings` readings by more than their noise can
/// (σ per reading; `quantized`: the rounding's bound, else white noise's χ² range).
bool Misfits(const Estimate& e, size_t readings, double sigma, bool quantized);

}  // namespace local_window
}  // namespace needle
