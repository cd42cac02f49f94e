// Tests of one window's least-squares weights (lib/local_window.h).
#include "lib/local_window.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
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

// The weights as they were formed before the window's rows were factored in place: Q formed from
// the QR of a copy and multiplied by [R⁻ᵀ; 0] (a general product).
Eigen::MatrixXd FormedWeights(const Eigen::MatrixXd& v, int terms) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(v);
  const Eigen::MatrixXd r = qr.matrixQR().topRows(terms).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd z =
      r.transpose().triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(terms, terms));
  return qr.householderQ() * (Eigen::MatrixXd::Identity(v.rows(), terms) * z);
}

// QrWeights gives those weights bit for bit (the local fit's every output rests on them): on
// 600 windows of 7 to 40 readings, one-sided and about a point inside, of 5, 6 and JoinWindows'
// 10 columns, the readings' places drawn at random.
TEST(LocalWindowTest, QrWeightsAreTheFormedWeightsBitForBit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> place(-1.0, 1.0);
  for (int trial = 0; trial < 600; ++trial) {
    const int readings = 7 + trial % 34, terms = trial % 7 == 0 ? 10 : 5 + trial % 2;
    if (readings < terms + 1) continue;
    const double t = trial % 3 == 0 ? -1.0 : place(rng);  // one-sided, or about a point
    Eigen::MatrixXd v(readings, terms);
    for (int r = 0; r < readings; ++r) {
      const double u = (place(rng) - t) / 2.4, a = 1.0 - std::abs(u * u * u);
      double power = std::sqrt(a * a * a);
      for (int c = 0; c < terms; ++c, power *= u) v(r, c) = power;
    }
    Eigen::MatrixXd factors = v, g(readings, terms);
    local_window::QrWeights(factors, terms, g);
    const Eigen::MatrixXd formed = FormedWeights(v, terms);
    for (Eigen::Index i = 0; i < g.size(); ++i) {
      ASSERT_EQ(g.data()[i], formed.data()[i])
          << "trial " << trial << ", " << readings << " readings, " << terms << " terms";
    }
  }
}

}  // namespace
}  // namespace needle
