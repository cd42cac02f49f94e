#pragma once
/// @file
/// Internal to lib/'s break search (lift_breaks.cc, lift_junctions.cc) and kink search
/// (reading_kinks.cc): a polynomial fitted to the readings on one side of a break, the root
/// finder that meets two of them, and the residuals of polynomials kinked at given angles.

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cassert>
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

/// The basis u^k, k = 0 … `degree`, u = (θ − c)/h, at readings [from, to) of x: a row a reading.
inline Eigen::MatrixXd PowerBasis(const std::vector<double>& x, size_t from, size_t to, double c,
                                  double h, int degree) {
  Eigen::MatrixXd v(to - from, degree + 1);
  for (size_t i = from; i < to; ++i) {
    const double u = (x[i] - c) / h;
    double power = 1.0;
    for (int k = 0; k <= degree; ++k, power *= u) v(i - from, k) = power;
  }
  return v;
}

/// The same of a degree known at compile time.
template <int Degree>
Eigen::MatrixXd SideBasis(const std::vector<double>& x, size_t from, size_t to, double c,
                          double h) {
  return PowerBasis(x, from, to, c, h, Degree);
}

/// The sum of squared residuals of readings [from, to) of (x, y), m², fitted by a polynomial of
/// `degree` in u = (θ − c)/h (c, h: the readings' middle and half-span) and, at each ξ of
/// `kinks_rad`, the truncated powers (θ − ξ)ᵏ₊, k = 3 … `kink_degree`: polynomials of degree
/// `degree` that meet at each ξ with equal s, s' and s'' (a kink of s'', s''' and above jumping).
/// `kink_degree` ≤ `degree`.
inline double KinkedSquares(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                            size_t to, int degree, const std::vector<double>& kinks_rad,
                            int kink_degree = 3) {
  const int per_kink = kink_degree - 2;
  const int columns = degree + 1 + per_kink * static_cast<int>(kinks_rad.size());
  assert(to >= from + 2 && per_kink >= 1 && to - from >= static_cast<size_t>(columns));
  const double c = 0.5 * (x[from] + x[to - 1]), h = 0.5 * (x[to - 1] - x[from]);
  const Eigen::Index n = static_cast<Eigen::Index>(to - from);
  Eigen::MatrixXd v(n, columns);
  v.leftCols(degree + 1) = PowerBasis(x, from, to, c, h, degree);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u = (x[from + static_cast<size_t>(i)] - c) / h;
    int col = degree + 1;
    for (const double kink : kinks_rad) {
      const double past = std::max(0.0, u - (kink - c) / h);
      for (int k = 0; k < per_kink; ++k) v(i, col++) = std::pow(past, 3 + k);
    }
  }
  const Eigen::Map<const Eigen::VectorXd> r(y.data() + from, n);
  return (v * v.colPivHouseholderQr().solve(r) - r).squaredNorm();
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
