#include "lib/side_polynomial.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>

namespace needle {

Eigen::VectorXd QrSolve(const Eigen::MatrixXd& v, const Eigen::Ref<const Eigen::VectorXd>& r) {
  return v.colPivHouseholderQr().solve(r);
}

Eigen::MatrixXd Gram(const Eigen::MatrixXd& v) { return v.transpose() * v; }

Eigen::VectorXd LdltSolve(const Eigen::MatrixXd& a, const Eigen::Ref<const Eigen::VectorXd>& b) {
  return a.ldlt().solve(b);
}

double KinkedSquares(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                     size_t to, int degree, const std::vector<double>& kinks_rad, int kink_degree) {
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

}  // namespace needle
