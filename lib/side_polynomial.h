#pragma once
/// @file
/// Internal to lib/'s break search (lift_breaks.cc, lift_junctions.cc, lift_dwells.cc) and kink
/// search (reading_kinks.cc): a polynomial fitted to the readings on one side of a break, the
/// root finder that meets two of them, and the residuals of polynomials kinked at given angles.
/// Their dense decompositions (QR, LDLT, the Gram product) are made in side_polynomial.cc, once:
/// each of the four files instantiated them itself, 28–45 s of clang's time apiece in the fuzz
/// build (scripts/fuzz.sh), 9 s each without.

#include <Eigen/Core>
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

/// The least-squares coefficients a of v a ≈ r (column-pivoting Householder QR). The dense
/// decompositions of the break search live in side_polynomial.cc, made once for its four users.
Eigen::VectorXd QrSolve(const Eigen::MatrixXd& v, const Eigen::Ref<const Eigen::VectorXd>& r);
/// vᵀv.
Eigen::MatrixXd Gram(const Eigen::MatrixXd& v);
/// x of a x = b, a symmetric and positive semi-definite (LDLT).
Eigen::VectorXd LdltSolve(const Eigen::MatrixXd& a, const Eigen::Ref<const Eigen::VectorXd>& b);

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
double KinkedSquares(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                     size_t to, int degree, const std::vector<double>& kinks_rad,
                     int kink_degree = 3);

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
