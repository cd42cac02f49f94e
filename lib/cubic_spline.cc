// Interpolating cubic splines (natural, not-a-knot, clamped) in the second-derivative
// form. With h_i = x_{i+1} − x_i, δ_i = (y_{i+1} − y_i)/h_i and M_i = s''(x_i), continuity
// of s' at the interior knots gives
//
//     h_{i−1} M_{i−1} + 2(h_{i−1} + h_i) M_i + h_i M_{i+1} = 6(δ_i − δ_{i−1}),  i = 1..N−1,
//
// closed by one end condition at each end; then on [x_i, x_{i+1}], t = x − x_i:
//     s = y_i + b t + M_i/2 t² + (M_{i+1} − M_i)/(6h) t³,  b = δ_i − h(2M_i + M_{i+1})/6.
#include <Eigen/SparseCore>

#include "lib/linear_solve.h"
#include "lib/spline.h"

namespace needle {

PiecewisePolynomial BuildCubicSpline(const std::vector<double>& x, const std::vector<double>& y,
                                     const SplineOptions& options) {
  const int n = static_cast<int>(x.size()) - 1;  // intervals
  std::vector<double> h(n), delta(n);
  for (int i = 0; i < n; ++i) {
    h[i] = x[i + 1] - x[i];
    delta[i] = (y[i + 1] - y[i]) / h[i];  // δ_i
  }
  std::vector<Eigen::Triplet<double>> a;
  a.reserve(3 * (n + 1) + 2);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  for (int i = 1; i < n; ++i) {
    a.emplace_back(i, i - 1, h[i - 1]);
    a.emplace_back(i, i, 2.0 * (h[i - 1] + h[i]));
    a.emplace_back(i, i + 1, h[i]);
    rhs(i) = 6.0 * (delta[i] - delta[i - 1]);
  }
  switch (options.kind) {
    case SplineKind::kNatural:  // M_0 = M_N = 0
      a.emplace_back(0, 0, 1.0);
      a.emplace_back(n, n, 1.0);
      break;
    case SplineKind::kClamped:
      // s'(x_0) = δ_0 − h_0(2M_0 + M_1)/6 = d_0  →  2h_0 M_0 + h_0 M_1 = 6(δ_0 − d_0)
      a.emplace_back(0, 0, 2.0 * h[0]);
      a.emplace_back(0, 1, h[0]);
      rhs(0) = 6.0 * (delta[0] - options.start_slope);
      // s'(x_N) = δ_{N−1} + h(M_{N−1} + 2M_N)/6 = d_N
      a.emplace_back(n, n - 1, h[n - 1]);
      a.emplace_back(n, n, 2.0 * h[n - 1]);
      rhs(n) = 6.0 * (options.end_slope - delta[n - 1]);
      break;
    case SplineKind::kNotAKnot:
      // (M_1 − M_0)/h_0 = (M_2 − M_1)/h_1  →  h_1 M_0 − (h_0 + h_1) M_1 + h_0 M_2 = 0
      a.emplace_back(0, 0, h[1]);
      a.emplace_back(0, 1, -(h[0] + h[1]));
      a.emplace_back(0, 2, h[0]);
      a.emplace_back(n, n - 2, h[n - 1]);
      a.emplace_back(n, n - 1, -(h[n - 2] + h[n - 1]));
      a.emplace_back(n, n, h[n - 2]);
      break;
    default:
      throw std::logic_error("BuildCubicSpline: not a cubic kind");
  }
  const Eigen::VectorXd m = SolveSparse(n + 1, a, rhs, SplineKindName(options.kind) + " spline");
  Eigen::MatrixXd c(n, 4);
  for (int i = 0; i < n; ++i) {
    c(i, 0) = y[i];
    c(i, 1) = delta[i] - h[i] * (2.0 * m(i) + m(i + 1)) / 6.0;  // b = δ − h(2M_i + M_{i+1})/6
    c(i, 2) = 0.5 * m(i);                                       // M_i/2
    c(i, 3) = (m(i + 1) - m(i)) / (6.0 * h[i]);                 // (M_{i+1} − M_i)/(6h)
  }
  return PiecewisePolynomial(x, std::move(c), 2);
}

}  // namespace needle
