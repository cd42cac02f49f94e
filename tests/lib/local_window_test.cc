// Tests of one window's least-squares weights (lib/local_window.h).
#include "lib/local_window.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <utility>

namespace needle {
namespace {

// A one-sided window's weighted rows: readings every 0.01 rad at and after t = 0, the basis
// (θ/b)^c times the square root of the tricube weight (local_window::FitAt's rows).
Eigen::MatrixXd OneSidedRows(int readings, int terms) {
  const double b = 1.2 * 0.01 * (readings - 1);
  Eigen::MatrixXd v(readings, terms);
  for (int r = 0; r < readings; ++r) {
    const double u = 0.01 * r / b, a = 1.0 - u * u * u;
    double power = std::sqrt(a * a * a);
    for (int c = 0; c < terms; ++c, power *= u) v(r, c) = power;
  }
  return v;
}

// G = V (VᵀV)⁻¹: VᵀG is the identity, and G lies in V's column space (G = V M), here checked
// against the normal equations solved in long double, for the narrowest one-sided window (7
// readings of a quintic, VᵀV's condition some 1e9), a wider one, and JoinWindows' 10 columns.
TEST(LocalWindowTest, QrWeightsAreTheLeastSquaresWeights) {
  const std::pair<int, int> kWindows[] = {{7, 6}, {40, 6}, {23, 5}, {30, 10}};
  for (const auto& [readings, terms] : kWindows) {
    const Eigen::MatrixXd v = OneSidedRows(readings, terms);
    Eigen::MatrixXd factors = v, g(readings, terms);
    local_window::QrWeights(factors, terms, g);
    const Eigen::MatrixXd vtg = v.transpose() * g;
    EXPECT_LT((vtg - Eigen::MatrixXd::Identity(terms, terms)).cwiseAbs().maxCoeff(), 1e-9)
        << readings << " readings, " << terms << " terms";
    using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
    const LongMatrix vl = v.cast<long double>();
    const LongMatrix m = (vl.transpose() * vl).inverse();
    const Eigen::MatrixXd expected = (vl * m).cast<double>();
    EXPECT_LT((g - expected).cwiseAbs().maxCoeff(), 1e-8 * expected.cwiseAbs().maxCoeff())
        << readings << " readings, " << terms << " terms";
  }
}

}  // namespace
}  // namespace needle
