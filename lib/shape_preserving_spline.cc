// Shape-preserving C¹ cubic Hermite interpolants: the slopes d_i at the knots are chosen
// from the secants δ_i = (y_{i+1} − y_i)/h_i alone, then each piece is the cubic Hermite
// interpolant (CubicHermite). Their second derivative jumps at the knots, so needle
// reports no acceleration for them.
#include <cmath>

#include "lib/spline.h"

namespace needle {
namespace {

double Sign(double v) { return (v > 0.0) - (v < 0.0); }

// Fritsch–Carlson end slope (the three-point formula, limited to keep the shape):
// d = ((2h_0 + h_1)δ_0 − h_0 δ_1)/(h_0 + h_1); 0 if its sign differs from δ_0; 3δ_0 if the
// secants change sign and |d| > 3|δ_0|.
double PchipEndSlope(double h0, double h1, double delta0, double delta1) {
  double d = ((2.0 * h0 + h1) * delta0 - h0 * delta1) / (h0 + h1);
  if (Sign(d) != Sign(delta0)) {
    d = 0.0;
  } else if (Sign(delta0) != Sign(delta1) && std::abs(d) > 3.0 * std::abs(delta0)) {
    d = 3.0 * delta0;
  }
  return d;
}

}  // namespace

PiecewisePolynomial BuildPchip(const std::vector<double>& x, const std::vector<double>& y) {
  const int n = static_cast<int>(x.size()) - 1;
  std::vector<double> h(n), delta(n), d(n + 1, 0.0);
  for (int i = 0; i < n; ++i) {
    h[i] = x[i + 1] - x[i];
    delta[i] = (y[i + 1] - y[i]) / h[i];
  }
  if (n == 1) {
    d[0] = d[1] = delta[0];  // two points: the straight line
    return CubicHermite(x, y, d, 1);
  }
  for (int k = 1; k < n; ++k) {
    if (delta[k - 1] * delta[k] <= 0.0) {
      d[k] = 0.0;  // local extremum or flat: zero slope keeps the shape
    } else {
      // Weighted harmonic mean: d = (w1 + w2)/(w1/δ_{k−1} + w2/δ_k),
      // w1 = 2h_k + h_{k−1}, w2 = h_k + 2h_{k−1}.
      const double w1 = 2.0 * h[k] + h[k - 1];
      const double w2 = h[k] + 2.0 * h[k - 1];
      d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k]);
    }
  }
  d[0] = PchipEndSlope(h[0], h[1], delta[0], delta[1]);
  d[n] = PchipEndSlope(h[n - 1], h[n - 2], delta[n - 1], delta[n - 2]);
  return CubicHermite(x, y, d, 1);
}

PiecewisePolynomial BuildMakima(const std::vector<double>& x, const std::vector<double>& y) {
  const int n = static_cast<int>(x.size()) - 1;
  // Secants extended by two on each side: δ_{−1} = 2δ_0 − δ_1, δ_{−2} = 2δ_{−1} − δ_0, and
  // likewise past the end. Stored with an offset of 2.
  std::vector<double> delta(n + 4, 0.0);
  for (int i = 0; i < n; ++i) delta[i + 2] = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
  if (n == 1) {
    std::vector<double> d(2, delta[2]);
    return CubicHermite(x, y, d, 1);
  }
  delta[1] = 2.0 * delta[2] - delta[3];
  delta[0] = 2.0 * delta[1] - delta[2];
  delta[n + 2] = 2.0 * delta[n + 1] - delta[n];
  delta[n + 3] = 2.0 * delta[n + 2] - delta[n + 1];
  std::vector<double> d(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double dm2 = delta[i], dm1 = delta[i + 1], d0 = delta[i + 2], dp1 = delta[i + 3];
    // Modified Akima weights: w1 = |δ_{i+1} − δ_i| + |δ_{i+1} + δ_i|/2,
    //                         w2 = |δ_{i−1} − δ_{i−2}| + |δ_{i−1} + δ_{i−2}|/2.
    const double w1 = std::abs(dp1 - d0) + 0.5 * std::abs(dp1 + d0);
    const double w2 = std::abs(dm1 - dm2) + 0.5 * std::abs(dm1 + dm2);
    d[i] = (w1 + w2 > 0.0) ? (w1 * dm1 + w2 * d0) / (w1 + w2) : 0.5 * (dm1 + d0);
  }
  return CubicHermite(x, y, d, 1);
}

}  // namespace needle
