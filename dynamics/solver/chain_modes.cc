#include "dynamics/solver/chain_modes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

namespace needle {

ChainModes::ChainModes(const NeedleTrain& train, const ContactMode& mode)
    : dofs_(train.Coils() + 1) {
  Assemble(train, mode);
  sparse_K_ = K_.sparseView();
  sparse_C_ = C_.sparseView();
  stiffness_.compute(sparse_K_);
  if (stiffness_.info() != Eigen::Success || !(train.SegmentRateNm() > 0.0)) {
    throw std::invalid_argument("method \"exact\": the coil chain needs a spring rate above 0");
  }
  damped_ = !C_.isZero(0.0);
  Decompose();
}

void ChainModes::Assemble(const NeedleTrain& train, const ContactMode& mode) {
  const int n = dofs_;
  const double k = train.SegmentRateNm(), c = train.SegmentDampingNsm();
  K_ = Eigen::MatrixXd::Zero(n, n);
  C_ = Eigen::MatrixXd::Zero(n, n);
  mass_ = Eigen::VectorXd::Constant(n, train.CoilMassKg());
  mass_[0] = train.NeedleMassKg();
  // Segment j (1 … N) joins nodes j − 1 and j; node N is the fixed end.
  for (int j = 1; j <= n; ++j) {
    const int a = j - 1, b = j;
    K_(a, a) += k;
    C_(a, a) += c;
    if (b < n) {
      K_(b, b) += k;
      C_(b, b) += c;
      K_(a, b) -= k;
      K_(b, a) -= k;
      C_(a, b) -= c;
      C_(b, a) -= c;
    }
  }
  if (mode.cam) {
    K_(0, 0) += train.cam_law().ForceStiffness();
    C_(0, 0) += train.cam_law().ForceDamping();
  }
  if (mode.seat) {
    K_(0, 0) += train.seat_law().ForceStiffness();
    C_(0, 0) += train.seat_law().ForceDamping();
  }
}

void ChainModes::Decompose() {
  const int n = dofs_;
  // A in balanced coordinates: z̃ = S z with S = diag(M^½, M^½/s), s = √‖M^-½ K M^-½‖∞, so
  // that Ã = S A S⁻¹ = [[0, s I], [−K̃/s, −C̃]] holds entries of one size (A's own span k_c/m
  // against 1, some 1e8, costs the eigenvectors digits); then V = S⁻¹ Ṽ, V⁻¹ = Ṽ⁻¹ S.
  const Eigen::VectorXd root_mass = mass_.cwiseSqrt(), inv_root = root_mass.cwiseInverse();
  const Eigen::MatrixXd Kt = inv_root.asDiagonal() * K_ * inv_root.asDiagonal();
  const Eigen::MatrixXd Ct = inv_root.asDiagonal() * C_ * inv_root.asDiagonal();
  const double scale = std::sqrt(Kt.cwiseAbs().rowwise().sum().maxCoeff());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = scale * Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -Kt / scale;
  A.bottomRightCorner(n, n) = -Ct;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(A);
  if (eigen.info() != Eigen::Success) {
    throw std::invalid_argument("method \"exact\": the coil chain's modes did not converge");
  }
  const Eigen::MatrixXcd Vt = eigen.eigenvectors();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(Vt);
  // A mode at or near critical damping makes Ṽ (nearly) singular: its modal sum would lose the
  // digits the bounds and the audit need.
  if (!(lu.rcond() >= kLeastConditioning)) {
    throw std::invalid_argument(
        "method \"exact\": a mode of the coil chain is at or near critical damping (its "
        "eigenvectors' reciprocal condition " +
        std::to_string(lu.rcond()) + " < 1e-8); take dopri5");
  }
  Eigen::VectorXd S(2 * n);
  S << root_mass, root_mass / scale;
  KeepOnePerPair(eigen.eigenvalues(),
                 S.cwiseInverse().cast<std::complex<double>>().asDiagonal() * Vt,
                 lu.inverse() * S.cast<std::complex<double>>().asDiagonal(), C_.isZero(0.0));
}

void ChainModes::KeepOnePerPair(const Eigen::VectorXcd& all, const Eigen::MatrixXcd& V,
                                const Eigen::MatrixXcd& Vinv, bool undamped) {
  // One of each conjugate pair (EigenSolver gives them as exact conjugates, side by side).
  std::vector<int> keep;
  for (int i = 0; i < all.size(); ++i) {
    if (all[i].imag() >= 0.0) keep.push_back(i);
  }
  const int m = static_cast<int>(keep.size());
  lambda_.resize(m);
  weight_.resize(m);
  vectors_.resize(V.rows(), m);
  inverse_.resize(m, V.cols());
  for (int r = 0; r < m; ++r) {
    const int i = keep[r];
    // Undamped (no dashpot pushes, ζ_s = 0): every λ is imaginary; round-off's real part, of
    // either sign, is dropped, so that no term of the modal sum grows (the bounds need it).
    lambda_[r] = undamped ? std::complex<double>(0.0, all[i].imag()) : all[i];
    weight_[r] = all[i].imag() > 0.0 ? 2.0 : 1.0;
    vectors_.col(r) = V.col(i);
    inverse_.row(r) = Vinv.row(i);
    fastest_ = std::max(fastest_, std::abs(all[i]));
  }
}

Eigen::MatrixXd ChainModes::Particular(const double* f, int degree) const {
  const int n = dofs_;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, degree + 3);  // two zero columns above the top
  for (int j = degree; j >= 0; --j) {
    Eigen::VectorXd r = -(j + 1.0) * (C_ * a.col(j + 1)) -
                        ((j + 2.0) * (j + 1.0)) * mass_.cwiseProduct(a.col(j + 2));
    r[0] += f[j];
    a.col(j) = stiffness_.solve(r);
  }
  return a.leftCols(degree + 1);
}

double ChainModes::FreeIntegral(Eigen::MatrixXd q, double T, const Eigen::VectorXd& z0,
                                const Eigen::VectorXd& z1) const {
  const int n = dofs_;
  // The ends' M h′, M h and C h, which every level's boundary terms read.
  const Eigen::VectorXd Mv0 = mass_.cwiseProduct(z0.tail(n)), Mv1 = mass_.cwiseProduct(z1.tail(n));
  const Eigen::VectorXd Mh0 = mass_.cwiseProduct(z0.head(n)), Mh1 = mass_.cwiseProduct(z1.head(n));
  const Eigen::VectorXd Ch0 = sparse_C_ * z0.head(n), Ch1 = sparse_C_ * z1.head(n);
  int degree = static_cast<int>(q.cols()) - 1;
  while (degree >= 0 && q.col(degree).isZero(0.0)) --degree;
  double total = 0.0;
  Eigen::VectorXd rT(n), r1T(n);
  for (; degree >= 0; --degree) {
    const Eigen::MatrixXd r = stiffness_.solve(q.leftCols(degree + 1));
    // r(T) and r′(T) by Horner; r(0) = r₀, r′(0) = r₁.
    rT = r.col(degree);
    r1T.setZero();
    for (int j = degree; j >= 1; --j) {
      r1T = r1T * T + j * r.col(j);
      rT = rT * T + r.col(j - 1);
    }
    total -= rT.dot(Mv1) - r.col(0).dot(Mv0);
    total -= rT.dot(Ch1) - r.col(0).dot(Ch0);
    if (degree == 0) break;
    total += r1T.dot(Mh1) - r.col(1).dot(Mh0);
    // q ← C r′ − M r″, one degree lower.
    Eigen::MatrixXd next(n, degree);
    for (int j = 0; j < degree; ++j) {
      next.col(j) = (j + 1.0) * (sparse_C_ * r.col(j + 1));
      if (j + 2 <= degree)
        next.col(j) -= ((j + 2.0) * (j + 1.0)) * mass_.cwiseProduct(r.col(j + 2));
    }
    q = std::move(next);
  }
  return total;
}

double ChainModes::FreeEnergy(const Eigen::VectorXd& z) const {
  const int n = dofs_;
  return 0.5 * z.tail(n).dot(mass_.cwiseProduct(z.tail(n))) +
         0.5 * z.head(n).dot(sparse_K_ * z.head(n));
}

}  // namespace needle
