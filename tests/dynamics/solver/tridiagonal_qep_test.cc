// The chain's eigenvalues by Aberth's iteration (dynamics/solver/tridiagonal_qep.h): closed forms
// for one mass, the dense first-order QR on chains of 2-41 masses in every kind of damping, and
// the clusters it must hand to the dense QR (nullopt) rather than certify.
#include "dynamics/solver/tridiagonal_qep.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

namespace needle {
namespace {

using Complex = std::complex<double>;

// N masses in a row, the last held to ground: segment rate k and dashpot c between neighbours,
// the first mass of `needle_kg` with `k0`, `c0` added on its own row (a contact).
TridiagonalQep Chain(int n, double needle_kg, double coil_kg, double k, double c, double k0,
                     double c0) {
  TridiagonalQep q;
  q.mass = Eigen::VectorXd::Constant(n, coil_kg);
  q.mass[0] = needle_kg;
  q.k_diag = Eigen::VectorXd::Constant(n, 2.0 * k);
  q.c_diag = Eigen::VectorXd::Constant(n, 2.0 * c);
  q.k_diag[0] = k + k0;
  q.c_diag[0] = c + c0;
  q.k_off = Eigen::VectorXd::Constant(n - 1, -k);
  q.c_off = Eigen::VectorXd::Constant(n - 1, -c);
  return q;
}

// The first-order matrix's eigenvalues by Eigen's dense QR, balanced as ChainModes balances it.
Eigen::VectorXcd Dense(const TridiagonalQep& q) {
  const Eigen::Index n = q.mass.size();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), C = Eigen::MatrixXd::Zero(n, n);
  K.diagonal() = q.k_diag;
  C.diagonal() = q.c_diag;
  if (n > 1) {
    K.diagonal(1) = K.diagonal(-1) = q.k_off;
    C.diagonal(1) = C.diagonal(-1) = q.c_off;
  }
  const Eigen::VectorXd inv = q.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd Kt = inv.asDiagonal() * K * inv.asDiagonal();
  const Eigen::MatrixXd Ct = inv.asDiagonal() * C * inv.asDiagonal();
  const double s = std::sqrt(Kt.cwiseAbs().rowwise().sum().maxCoeff());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = s * Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -Kt / s;
  A.bottomRightCorner(n, n) = -Ct;
  return Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
}

// The largest distance from each of `got` to the nearest unused one of `want`, over max |λ|.
double Mismatch(const Eigen::VectorXcd& got, const Eigen::VectorXcd& want) {
  std::vector<bool> used(want.size(), false);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < got.size(); ++i) {
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < want.size(); ++j) {
      if (!used[j] && (best < 0 || std::abs(got[i] - want[j]) < std::abs(got[i] - want[best])))
        best = j;
    }
    used[best] = true;
    worst = std::max(worst, std::abs(got[i] - want[best]));
  }
  return worst / want.cwiseAbs().maxCoeff();
}

// Pairs side by side as exact conjugates, Im > 0 first; real ones with Im exactly 0.
void ExpectPairsInPlace(const Eigen::VectorXcd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (v[i].imag() == 0.0) continue;
    ASSERT_GT(v[i].imag(), 0.0) << i;
    ASSERT_LT(i + 1, v.size());
    EXPECT_EQ(v[i + 1], std::conj(v[i])) << i;
    ++i;
  }
}

TEST(TridiagonalQepTest, OneMassIsItsOwnQuadratic) {
  // m λ² + c λ + k = 0: 2 kg, 8e4 N/m, ζ = 0.1 and ζ = 2 (two real roots).
  const double m = 2.0, k = 8e4, w = std::sqrt(k / m);
  for (double zeta : {0.1, 2.0}) {
    const std::optional<Eigen::VectorXcd> got =
        TridiagonalQepEigenvalues(Chain(1, m, m, k, 2.0 * zeta * std::sqrt(k * m), 0.0, 0.0));
    ASSERT_TRUE(got) << zeta;
    ASSERT_EQ(got->size(), 2);
    ExpectPairsInPlace(*got);
    if (zeta < 1.0) {
      EXPECT_NEAR((*got)[0].real(), -zeta * w, 1e-12 * w);
      EXPECT_NEAR((*got)[0].imag(), w * std::sqrt(1.0 - zeta * zeta), 1e-12 * w);
    } else {
      const double root = w * std::sqrt(zeta * zeta - 1.0);
      std::vector<double> re = {(*got)[0].real(), (*got)[1].real()};
      std::sort(re.begin(), re.end());
      EXPECT_NEAR(re[0], -zeta * w - root, 1e-12 * w);
      EXPECT_NEAR(re[1], -zeta * w + root, 1e-12 * w);
    }
  }
}

TEST(TridiagonalQepTest, ChainsAgreeWithTheDenseQr) {
  // A needle of 0.8-11.5 kg on coils of 0.01-0.3 kg, rates 1e4-1e6 N/m a segment, dashpots
  // none, light, proportional and heavy; with and without a stiff damped contact on the needle
  // (1e9 N/m, ζ 0.05-0.9), which makes the damping non-proportional.
  int cases = 0, with_real = 0;
  for (int n : {2, 3, 6, 11, 21, 41}) {
    for (double needle_kg : {0.8, 11.5}) {
      for (double coil_kg : {0.01, 0.3}) {
        for (double k : {1e4, 1e6}) {
          for (double zeta : {0.0, 0.01, 0.3, 0.8}) {
            for (double contact_zeta : {0.0, 0.05, 0.9, 3.0}) {
              const double c = 2.0 * zeta * std::sqrt(k * coil_kg);
              const double k0 = contact_zeta > 0.0 ? 1e9 : 0.0;
              const double c0 = 2.0 * contact_zeta * std::sqrt(k0 * needle_kg);
              const TridiagonalQep q = Chain(n, needle_kg, coil_kg, k, c, k0, c0);
              const std::optional<Eigen::VectorXcd> got = TridiagonalQepEigenvalues(q);
              SCOPED_TRACE(::testing::Message()
                           << "n " << n << " m " << needle_kg << " m_c " << coil_kg << " k " << k
                           << " zeta " << zeta << " contact " << contact_zeta);
              ASSERT_TRUE(got);
              ASSERT_EQ(got->size(), 2 * n);
              ExpectPairsInPlace(*got);
              EXPECT_LT(Mismatch(*got, Dense(q)), 1e-12);
              ++cases;
              with_real += (got->imag().array() == 0.0).any();
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(cases, 768);
  EXPECT_GT(with_real, 20);  // overdamped modes met, not only pairs
}

TEST(TridiagonalQepTest, UndampedRootsAreImaginary) {
  const TridiagonalQep q = Chain(21, 0.8, 0.03, 3e5, 0.0, 0.0, 0.0);
  const std::optional<Eigen::VectorXcd> got = TridiagonalQepEigenvalues(q);
  ASSERT_TRUE(got);
  EXPECT_LT(got->real().cwiseAbs().maxCoeff(), 1e-12 * got->cwiseAbs().maxCoeff());
  EXPECT_LT(Mismatch(*got, Dense(q)), 1e-12);
}

TEST(TridiagonalQepTest, ClustersAreLeftToTheDenseQr) {
  // One mass at critical damping: a double root, which no iteration certifies.
  const double m = 2.0, k = 8e4;
  EXPECT_FALSE(TridiagonalQepEigenvalues(Chain(1, m, m, k, 2.0 * std::sqrt(k * m), 0.0, 0.0)));
  // Malformed: sizes that disagree, a mass of 0.
  TridiagonalQep q = Chain(5, 0.8, 0.1, 1e5, 1.0, 0.0, 0.0);
  q.k_off.resize(3);
  EXPECT_FALSE(TridiagonalQepEigenvalues(q));
  q = Chain(5, 0.8, 0.1, 1e5, 1.0, 0.0, 0.0);
  q.mass[2] = 0.0;
  EXPECT_FALSE(TridiagonalQepEigenvalues(q));
}

}  // namespace
}  // namespace needle
