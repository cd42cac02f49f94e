// The coil chain's side of ClosedFormPiece (closed_form.h, chain_modes.h): the particular
// solution of every node, the modal coefficients of the start's homogeneous part, the needle's
// modal sum and its bounds, and the whole chain's state along the piece.
#include <cmath>
#include <complex>

#include "dynamics/solver/closed_form.h"
#include "lib/units.h"

namespace needle {

void ClosedFormPiece::StartChain() {
  // The needle's row of the chain: its mass, and K₀₀ and C₀₀ (for the accessors only).
  m_ = chain_->NeedleMass();
  K_ = chain_->NeedleStiffness();
  c_ = chain_->NeedleDamping();
  sigma_ = beta_ = root_ = 0.0;
  chain_p_ = chain_->Particular(f_.data(), kMaxDegree);
  for (int j = 0; j <= kMaxDegree; ++j) p_[j] = chain_p_(0, j);
  longest_step_ = kPi / chain_->Fastest();
  SetStart();
  // The start's homogeneous part z_h(0) = [q − P(0), q̇ − P′(0)], node 0 the needle, node i the
  // coil mass i (state entries 3 + i and 3 + (N − 1) + i).
  const int n = chain_->Dofs(), coils = n - 1;
  Eigen::VectorXd h0(2 * n);
  h0[0] = Y0_;
  h0[n] = V0_;
  for (int i = 1; i < n; ++i) {
    h0[i] = x0_[3 + i] - chain_p_(i, 0);
    h0[n + i] = x0_[3 + coils + i] - chain_p_(i, 1);
  }
  chain_rest_ = (h0.array() == 0.0).all();
  chain_c_ = (chain_->Inverse() * h0.cast<std::complex<double>>())
                 .cwiseProduct(chain_->Weight().cast<std::complex<double>>());
  alpha_ = chain_->Vectors().row(0).transpose().cwiseProduct(chain_c_);
  // Re(V diag(w c) g) = [Re(V diag(w c)), −Im(V diag(w c))] [Re g; Im g]: one real product.
  const Eigen::Index m = chain_c_.size();
  const Eigen::MatrixXcd vc = chain_->Vectors() * chain_c_.asDiagonal();
  chain_real_.resize(2 * n, 2 * m);
  chain_real_ << vc.real(), -vc.imag();
  grow_.resize(2 * m);
  dz_.resize(2 * n);
}

const ClosedFormPiece::ChainNeedle& ClosedFormPiece::ChainAt(double tau) const {
  if (tau == chain_at_.tau) return chain_at_;
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  const Eigen::Index m = lambda.size();
  double dh = 0.0, dhv = 0.0, ha = 0.0;
  for (Eigen::Index k = 0; k < m; ++k) {
    // e^{λτ} − 1 = (e^{aτ} − 1 − 2 e^{aτ} sin²(bτ/2)) + i e^{aτ} sin(bτ): no cancellation where
    // the mode is slow against τ.
    const double a = lambda[k].real(), b = lambda[k].imag();
    const double em1 = std::expm1(a * tau), e = 1.0 + em1;
    const double sin_half = std::sin(0.5 * b * tau), cos_half = std::cos(0.5 * b * tau);
    const std::complex<double> g(em1 - 2.0 * e * sin_half * sin_half,
                                 2.0 * e * sin_half * cos_half);
    grow_[k] = g.real();
    grow_[m + k] = g.imag();
    const std::complex<double> al = alpha_[k] * lambda[k];
    dh += (alpha_[k] * g).real();
    dhv += (al * g).real();
    ha += (al * lambda[k] * (1.0 + g)).real();
  }
  chain_at_ = {tau, dh, dhv, ha};
  return chain_at_;
}

TrainState ClosedFormPiece::ChainState(double tau) const {
  const std::array<double, 2> yv = PositionVelocity(tau);  // fills grow_ at τ
  const int n = chain_->Dofs(), coils = n - 1;
  Eigen::VectorXd& dz = dz_;
  dz.noalias() = chain_real_ * grow_;
  TrainState x(x0_.size(), 0.0);
  x[0] = yv[0];
  x[1] = yv[1];
  for (int i = 1; i < n; ++i) {
    // P_i(τ) − P_i(0) and P_i′(τ) − P_i′(0), by Horner.
    double p = 0.0, dp = 0.0;
    for (int j = degree_p_; j >= 1; --j) {  // every node's P has the needle's degree at most
      p = p * tau + chain_p_(i, j);
      dp = dp * tau + j * chain_p_(i, j);
    }
    p *= tau;
    x[3 + i] = x0_[3 + i] + p + dz[i];
    x[3 + coils + i] = x0_[3 + coils + i] + (dp - chain_p_(i, 1)) + dz[n + i];
  }
  return x;
}

bool ClosedFormPiece::HomogeneousZero() const {
  return chain_ ? chain_rest_ : Y0_ == 0.0 && V0_ == 0.0;
}

TrainState ClosedFormPiece::MotionState(double t) const {
  if (chain_) return ChainState(t - t0_);
  const std::array<double, 2> yv = PositionVelocity(t - t0_);
  return {yv[0], yv[1], 0.0, 0.0};
}

void ClosedFormPiece::ChainStart(double t) const {
  // The modal sum: each term's size |α_k| e^{Re λ_k τ} never grows after τ.
  const double tau = t - t0_;
  const ChainNeedle& h = ChainAt(tau);
  HomogeneousStart& s = start_;
  s = HomogeneousStart{t, Y0_ + h.dh, V0_ + h.dhv, h.ha, 0.0, 0.0, 0.0, 0.0};
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    const double size = std::abs(alpha_[k]) * std::exp(lambda[k].real() * tau);
    const double l = std::abs(lambda[k]);
    s.lift_amplitude += size;
    s.e1 += size * l;
    s.e2 += size * l * l;
    s.b3 += size * l * l * l;
  }
}

}  // namespace needle
