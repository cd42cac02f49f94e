#pragma once
/// @file
/// Internal to lib/'s break search (lift_breaks.cc, lift_junctions.cc): a polynomial fitted to
/// the readings on one side of a break, and the root finder that meets two of them.

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <vector>

namespace needle {

/// p(θ) = Σ_k a_k u^k, u = (θ − c)/h, k = 0 … Degree.
template <int Degree>
struct SidePolynomial {
  double c = 0.0, h = 1.0;
  Eigen::Matrix<double, Degree + 1, 1> a = Eigen::Matrix<double, Degree + 1, 1>::Zero();
  /// dᵒʳᵈᵉʳp/dθᵒʳᵈᵉʳ at t.
  double Value(double t, int order) const {
    const double u = (t - c) / h;
    double v = 0.0;
    for (int m = Degree; m >= order; --m) {
      double falling = 1.0;
      for (int j = 0; j < order; ++j) falling *= (m - j);
      v = v * u + falling * a(m);
    }
    return v / std::pow(h, order);
  }
};

/// The basis u^k, k = 0 … Degree, u = (θ − c)/h, at readings [from, to) of x: a row a reading.
template <int Degree>
Eigen::MatrixXd SideBasis(const std::vector<double>& x, size_t from, size_t to, double c,
                          double h) {
  Eigen::MatrixXd v(to - from, Degree + 1);
  for (size_t i = from; i < to; ++i) {
    const double u = (x[i] - c) / h;
    double power = 1.0;
    for (int k = 0; k <= Degree; ++k, power *= u) v(i - from, k) = power;
  }
  return v;
}

/// A root of f on [lo, hi] by sampling (64 steps) and bisection; nullopt when f keeps its sign.
template <class F>
std::optional<double> RootIn(F f, double lo, double hi) {
  constexpr int kSamples = 64;
  double a = lo, fa = f(lo);
  for (int k = 1; k <= kSamples; ++k) {
    double b = lo + (hi - lo) * k / kSamples;
    const double fb = f(b);
    if (fa == 0.0) return a;
    if (fa * fb < 0.0) {
      for (int it = 0; it < 100; ++it) {
        const double m = 0.5 * (a + b), fm = f(m);
        if (fm == 0.0) return m;
        if ((fm < 0.0) == (fa < 0.0)) {
          a = m;
          fa = fm;
        } else {
          b = m;
        }
      }
      return 0.5 * (a + b);
    }
    a = b;
    fa = fb;
  }
  if (fa == 0.0) return a;
  return std::nullopt;
}

}  // namespace needle
