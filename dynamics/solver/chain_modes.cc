#include "dynamics/solver/chain_modes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/solver/tridiagonal_qep.h"
#include "lib/output.h"

namespace needle {
namespace {

// A complex tridiagonal matrix's LU factors with partial pivoting, as LAPACK's zgttrf and
// zgttrs make and use them (Eigen has no banded solver; the chain needs one O(N) solve a mode).
class TridiagonalLU {
 public:
  using Complex = std::complex<double>;
  // The matrix with diagonal `d`, subdiagonal `l` (l[i] = T(i+1, i)) and superdiagonal `u`
  // (u[i] = T(i, i+1)); a pivot of 0 is taken as `tiny` (inverse iteration's rule).
  TridiagonalLU(std::vector<Complex> d, std::vector<Complex> l, std::vector<Complex> u, double tiny)
      : d_(std::move(d)),
        l_(std::move(l)),
        u_(std::move(u)),
        u2_(d_.size(), 0.0),
        swap_(d_.size(), false) {
    const int n = static_cast<int>(d_.size());
    for (int i = 0; i + 1 < n; ++i) {
      if (std::norm(d_[i]) >= std::norm(l_[i])) {  // no interchange: eliminate l[i]
        if (d_[i] == 0.0) d_[i] = tiny;
        l_[i] /= d_[i];
        d_[i + 1] -= l_[i] * u_[i];
      } else {  // rows i and i + 1 interchanged
        const Complex fact = d_[i] / l_[i];
        d_[i] = l_[i];
        l_[i] = fact;
        const Complex temp = u_[i];
        u_[i] = d_[i + 1];
        d_[i + 1] = temp - fact * d_[i + 1];
        if (i + 2 < n) {
          u2_[i] = u_[i + 1];
          u_[i + 1] = -fact * u_[i + 1];
        }
        swap_[i] = true;
      }
    }
    if (n > 0 && d_[n - 1] == 0.0) d_[n - 1] = tiny;
  }
  // b ← T⁻¹ b.
  void Solve(Eigen::VectorXcd& b) const {
    const int n = static_cast<int>(d_.size());
    for (int i = 0; i + 1 < n; ++i) {
      if (!swap_[i]) {
        b[i + 1] -= l_[i] * b[i];
      } else {
        const Complex temp = b[i];
        b[i] = b[i + 1];
        b[i + 1] = temp - l_[i] * b[i];
      }
    }
    for (int i = n - 1; i >= 0; --i) {
      Complex s = b[i];
      if (i + 1 < n) s -= u_[i] * b[i + 1];
      if (i + 2 < n) s -= u2_[i] * b[i + 2];
      b[i] = s / d_[i];
    }
  }

 private:
  std::vector<Complex> d_, l_, u_, u2_;
  std::vector<bool> swap_;
};

}  // namespace

ChainModes::ChainModes(const NeedleTrain& train, const ContactMode& mode,
                       ChainEigenvalues eigenvalues)
    : dofs_(train.Coils() + 1), eigenvalues_(eigenvalues) {
  Assemble(train, mode);
  sparse_K_ = K_.sparseView();
  sparse_C_ = C_.sparseView();
  stiffness_.compute(sparse_K_);
  if (stiffness_.info() != Eigen::Success || !(train.SegmentRateNm() > 0.0)) {
    throw std::invalid_argument("method \"exact\": the coil chain needs a spring rate above 0");
  }
  damped_ = !C_.isZero(0.0);
  // The responses w_d to the needle's forcing τ^d/d! (Particular).
  responses_ = Eigen::MatrixXd::Zero(dofs_, kResponseDegree + 1);
  for (int d = 0; d <= kResponseDegree; ++d) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(dofs_);
    if (d == 0) r[0] = 1.0;
    if (d >= 1) r -= sparse_C_ * responses_.col(d - 1);
    if (d >= 2) r -= mass_.cwiseProduct(responses_.col(d - 2));
    responses_.col(d) = stiffness_.solve(r);
  }
  Decompose();
  // V as a real matrix and its entries' sizes; the segments' differences of V's lift rows (the last
  // segment ends at the fixed seat) and the first segment's force rate k + cλ on them
  // (ChainUpperBounds).
  const Eigen::Index m = lambda_.size();
  const double k = train.SegmentRateNm(), c = train.SegmentDampingNsm();
  vectors_real_.resize(2 * dofs_, 2 * m);
  vectors_real_ << vectors_.real(), -vectors_.imag();
  vector_sizes_ = vectors_.cwiseAbs();
  lambda_sizes_ = lambda_.cwiseAbs();
  differences_.resize(dofs_ + 1, 2 * m);
  difference_sizes_.resize(dofs_ + 1, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    for (int s = 0; s <= dofs_; ++s) {
      const auto lift = [&](int i) { return i < dofs_ ? vectors_(i, j) : std::complex<double>(); };
      // The force row from the velocity rows, as NeedleTrain::SpringForce reads a state (on the
      // dense path they are λ times the lift rows only to the eigensolver's residual).
      const std::complex<double> d =
          s < dofs_ ? lift(s) - lift(s + 1)
                    : k * (lift(0) - lift(1)) + c * (vectors_(dofs_, j) - vectors_(dofs_ + 1, j));
      differences_(s, j) = d.real();
      differences_(s, m + j) = -d.imag();
      difference_sizes_(s, j) = std::abs(d);
    }
  }
}

std::shared_ptr<const ChainModes> ChainModes::Shared(const NeedleTrain& train,
                                                     const ContactMode& mode) {
  // What Assemble reads, and the mode: equal keys make equal chains, bit for bit.
  struct Key {
    int coils;
    bool cam, seat;
    std::array<double, 8> numbers;
    bool operator==(const Key& o) const {
      return coils == o.coils && cam == o.cam && seat == o.seat && numbers == o.numbers;
    }
  };
  const Key key{
      train.Coils(),
      mode.cam,
      mode.seat,
      {train.SegmentRateNm(), train.SegmentDampingNsm(), train.CoilMassKg(), train.NeedleMassKg(),
       train.cam_law().ForceStiffness(), train.cam_law().ForceDamping(),
       train.seat_law().ForceStiffness(), train.seat_law().ForceDamping()}};
  // The thread's chains, the last asked at the back.
  thread_local std::vector<std::pair<Key, std::shared_ptr<const ChainModes>>> kept;
  const auto found =
      std::find_if(kept.begin(), kept.end(), [&](const auto& entry) { return entry.first == key; });
  if (found != kept.end()) {
    std::rotate(found, found + 1, kept.end());
    return kept.back().second;
  }
  auto made = std::make_shared<const ChainModes>(train, mode);
  if (kept.size() == kSharedKept) kept.erase(kept.begin());
  kept.emplace_back(key, made);
  return made;
}

std::array<std::shared_ptr<const ChainModes>, 4> ChainModes::SharedEveryMode(
    const NeedleTrain& train) {
  std::array<std::shared_ptr<const ChainModes>, 4> modes;
  for (int i = 0; i < 4; ++i) modes[i] = Shared(train, ContactMode{(i & 1) != 0, (i & 2) != 0});
  return modes;
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
  // against 1, some 1e8, costs the eigenvalues and vectors digits); then V = S⁻¹ Ṽ, V⁻¹ = Ṽ⁻¹ S.
  const Eigen::VectorXd root_mass = mass_.cwiseSqrt(), inv_root = root_mass.cwiseInverse();
  const Eigen::MatrixXd Kt = inv_root.asDiagonal() * K_ * inv_root.asDiagonal();
  const Eigen::MatrixXd Ct = inv_root.asDiagonal() * C_ * inv_root.asDiagonal();
  const double scale = std::sqrt(Kt.cwiseAbs().rowwise().sum().maxCoeff());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = scale * Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -Kt / scale;
  A.bottomRightCorner(n, n) = -Ct;
  const bool undamped = C_.isZero(0.0);
  // Eigenvalues only, certified by Aberth's iteration on det T(λ) in O(N²) (tridiagonal_qep.h),
  // else by the balanced A's Hessenberg QR, O(N³); each mode's vectors from the tridiagonal T(λ)
  // in O(N) (QuadraticMode)...
  {
    std::optional<Eigen::VectorXcd> values;
    if (eigenvalues_ == ChainEigenvalues::kAberth) {
      values = TridiagonalQepEigenvalues(
          {mass_, K_.diagonal(), K_.diagonal(1), C_.diagonal(), C_.diagonal(1)});
    }
    if (!values) {
      const Eigen::EigenSolver<Eigen::MatrixXd> eigen(A, /*computeEigenvectors=*/false);
      if (eigen.info() != Eigen::Success) {
        throw std::invalid_argument("method \"exact\": the coil chain's modes did not converge");
      }
      values = eigen.eigenvalues();
    }
    const std::vector<int> keep = KeepOnePerPair(*values, undamped);
    vectors_.resize(2 * n, static_cast<Eigen::Index>(keep.size()));
    inverse_.resize(static_cast<Eigen::Index>(keep.size()), 2 * n);
    bool all = true;
    for (int r = 0; all && r < static_cast<int>(keep.size()); ++r) all = QuadraticMode(r);
    if (all) return;
  }
  // ... unless a mode is near another (near critical damping, where V⁻¹'s rows made one by one
  // lose digits as 1/conditioning²): A's eigenvectors and their inverse, O(N³).
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
        Significant(lu.rcond(), 3) + " < 1e-8); take dopri5");
  }
  Eigen::VectorXd S(2 * n);
  S << root_mass, root_mass / scale;
  const Eigen::MatrixXcd V = S.cwiseInverse().cast<std::complex<double>>().asDiagonal() * Vt;
  const Eigen::MatrixXcd Vinv = lu.inverse() * S.cast<std::complex<double>>().asDiagonal();
  const std::vector<int> keep = KeepOnePerPair(eigen.eigenvalues(), undamped);
  vectors_.resize(2 * n, static_cast<Eigen::Index>(keep.size()));
  inverse_.resize(static_cast<Eigen::Index>(keep.size()), 2 * n);
  for (size_t r = 0; r < keep.size(); ++r) {
    vectors_.col(static_cast<Eigen::Index>(r)) = V.col(keep[r]);
    inverse_.row(static_cast<Eigen::Index>(r)) = Vinv.row(keep[r]);
  }
  // Near critical damping even these lose digits (as ε over the modes' distance): the kept
  // modes' sum Σ_k w_k Re(V_k V⁻¹_k) must be the identity, in balanced units, to kInverseError.
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  for (Eigen::Index k = 0; k < lambda_.size(); ++k)
    sum.noalias() += weight_[k] * (vectors_.col(k) * inverse_.row(k)).real();
  const double error = (S.asDiagonal() * sum * S.cwiseInverse().asDiagonal() -
                        Eigen::MatrixXd::Identity(2 * n, 2 * n))
                           .cwiseAbs()
                           .maxCoeff();
  if (!(error <= kInverseError)) {
    throw std::invalid_argument(
        "method \"exact\": a mode of the coil chain is at or near critical damping (its modal "
        "sum inverts to " +
        Significant(error, 3) + ", beyond 1e-10); take dopri5");
  }
}

std::vector<int> ChainModes::KeepOnePerPair(const Eigen::VectorXcd& all, bool undamped) {
  // One of each conjugate pair (EigenSolver gives them as exact conjugates, side by side).
  std::vector<int> keep;
  for (int i = 0; i < all.size(); ++i) {
    if (all[i].imag() >= 0.0) keep.push_back(i);
  }
  const int m = static_cast<int>(keep.size());
  lambda_.resize(m);
  weight_.resize(m);
  fastest_ = fastest_oscillation_ = 0.0;
  for (int r = 0; r < m; ++r) {
    const int i = keep[r];
    // Undamped (no dashpot pushes, ζ_s = 0): every λ is imaginary; round-off's real part, of
    // either sign, is dropped, so that no term of the modal sum grows (the bounds need it).
    lambda_[r] = undamped ? std::complex<double>(0.0, all[i].imag()) : all[i];
    weight_[r] = all[i].imag() > 0.0 ? 2.0 : 1.0;
    fastest_ = std::max(fastest_, std::abs(all[i]));
    fastest_oscillation_ = std::max(fastest_oscillation_, std::abs(all[i].imag()));
  }
  return keep;
}

bool ChainModes::QuadraticMode(int r) {
  using Complex = std::complex<double>;
  const Complex lambda = lambda_[r];
  double norm = 0.0;
  const Eigen::VectorXcd phi = NullVector(lambda, &norm);
  // A's right vector z = [φ, λφ]; its left one, T(λ) = λ²M + λC + K being symmetric, is
  // y = [(λM + C)φ, Mφ], with yᵀz = φᵀ(2λM + C)φ (no conjugates): V⁻¹'s row is yᵀ/(yᵀz).
  const Eigen::VectorXcd m_phi = mass_.cast<Complex>().cwiseProduct(phi);
  const Eigen::VectorXcd c_phi = sparse_C_.cast<Complex>() * phi;
  const Complex d = phi.cwiseProduct(2.0 * lambda * m_phi + c_phi).sum();
  // yᵀz against its terms' sizes: near 0 where λ is near another (near critical damping),
  // and there the rows made one by one are no inverse of V to the digits the bounds and the
  // audit need. And T(λ)φ = 0 to round-off, or inverse iteration did not converge.
  const Eigen::VectorXd size = phi.cwiseAbs();
  const double terms =
      size.dot(2.0 * std::abs(lambda) * mass_.cwiseProduct(size) + sparse_C_.cwiseAbs() * size);
  const Eigen::VectorXcd residual =
      (lambda * lambda) * m_phi + lambda * c_phi + sparse_K_.cast<Complex>() * phi;
  if (!(std::abs(d) >= kQuadraticConditioning * terms) ||
      !(std::sqrt(residual.cwiseAbs2().maxCoeff()) <= kNullResidual * norm)) {
    return false;
  }
  vectors_.col(r) << phi, lambda * phi;
  inverse_.row(r) << ((lambda * m_phi + c_phi) / d).transpose(), (m_phi / d).transpose();
  return true;
}

Eigen::VectorXcd ChainModes::NullVector(std::complex<double> lambda, double* norm) const {
  using Complex = std::complex<double>;
  const int n = dofs_;
  // T(λ) = λ²M + λC + K, tridiagonal and symmetric: its diagonal and off-diagonal, and ‖T‖∞.
  std::vector<Complex> diag(n), off(std::max(n - 1, 0));
  *norm = 0.0;
  for (int i = 0; i < n; ++i) {
    diag[i] = lambda * lambda * mass_[i] + lambda * C_(i, i) + K_(i, i);
    if (i + 1 < n) off[i] = lambda * C_(i, i + 1) + K_(i, i + 1);
  }
  for (int i = 0; i < n; ++i) {
    *norm = std::max(*norm, std::abs(diag[i]) + (i > 0 ? std::abs(off[i - 1]) : 0.0) +
                                (i + 1 < n ? std::abs(off[i]) : 0.0));
  }
  // Inverse iteration with λ, an eigenvalue to round-off: T(λ) is singular to round-off, and
  // two solves from a vector of ones give its null vector (a zero pivot taken as ε‖T‖).
  const TridiagonalLU lu(diag, off, off, std::numeric_limits<double>::epsilon() * *norm);
  Eigen::VectorXcd x = Eigen::VectorXcd::Ones(n);
  for (int iteration = 0; iteration < 2; ++iteration) {
    lu.Solve(x);
    Eigen::Index top = 0;
    x.cwiseAbs2().maxCoeff(&top);
    x /= x[top];
  }
  return x;
}

Eigen::MatrixXd ChainModes::Particular(const double* f, int degree) const {
  const int n = dofs_;
  if (degree <= kResponseDegree) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, degree + 1);
    for (int i = 0; i <= degree; ++i) {
      if (f[i] == 0.0) continue;
      double factor = f[i];  // f_i i!/j!, from j = i down
      for (int j = i; j >= 0; --j) {
        a.col(j) += factor * responses_.col(i - j);
        factor *= j;
      }
    }
    return a;
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, degree + 3);  // two zero columns above the top
  for (int j = degree; j >= 0; --j) {
    Eigen::VectorXd r = -(j + 1.0) * (sparse_C_ * a.col(j + 1)) -
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
