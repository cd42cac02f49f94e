#include "dynamics/solver/chain_modes.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

namespace needle {

ChainModes::ChainModes(const NeedleTrain& train, const ContactMode& mode)
    : dofs_(train.Coils() + 1) {
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
  stiffness_.compute(K_);
  if (stiffness_.info() != Eigen::Success || !(k > 0.0)) {
    throw std::invalid_argument("method \"exact\": the coil chain needs a spring rate above 0");
  }

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
  const Eigen::VectorXcd all = eigen.eigenvalues();
  const Eigen::MatrixXcd Vt = eigen.eigenvectors();
  const Eigen::MatrixXcd Vtinv = Eigen::PartialPivLU<Eigen::MatrixXcd>(Vt).inverse();
  // The decomposition must give Ã back: a defective Ã (repeated λ, critical damping) does not.
  const double misfit = (Vt * all.asDiagonal() * Vtinv - A.cast<std::complex<double>>()).norm();
  if (!(misfit <= 1e-9 * A.norm())) {
    throw std::invalid_argument(
        "method \"exact\": the coil chain's modes are defective (critically damped)");
  }
  Eigen::VectorXd S(2 * n);
  S << root_mass, root_mass / scale;
  const Eigen::MatrixXcd V = S.cwiseInverse().cast<std::complex<double>>().asDiagonal() * Vt;
  const Eigen::MatrixXcd Vinv = Vtinv * S.cast<std::complex<double>>().asDiagonal();
  // One of each conjugate pair (EigenSolver gives them as exact conjugates, side by side).
  std::vector<int> keep;
  for (int i = 0; i < 2 * n; ++i) {
    if (all[i].imag() >= 0.0) keep.push_back(i);
  }
  const int m = static_cast<int>(keep.size());
  lambda_.resize(m);
  weight_.resize(m);
  vectors_.resize(2 * n, m);
  inverse_.resize(m, 2 * n);
  for (int r = 0; r < m; ++r) {
    const int i = keep[r];
    lambda_[r] = all[i];
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

}  // namespace needle
