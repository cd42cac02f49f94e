#pragma once
/// @file
/// Internal to the solver: the coil chain's free motion in one contact mode, by its modes
/// (method "exact" with [spring] masses > 1, docs/model.md §9). In a contact mode, without coil
/// clash, the chain of docs/model.md §4a is linear with constant coefficients:
///
///     M q̈ + C q̇ + K q = f(τ) e₀,   q = [y, x₁ … x_{N−1}],   M = diag(m, m_c, …, m_c),
///     K, C tridiagonal from the N segments (rate N k, dashpot c; the last one ends at the fixed
///     seat of the spring), with k_c + k_s and c_c + c_s added on the needle where the cam and
///     the seat push; f(τ) = k_c u + c_c u̇ [cam] − P₀ + F_g, the forcing of the one-mass form.
///
/// In first-order form z = [q, q̇], ż = A z + f(τ) [0, e₀/m], A = [[0, I], [−M⁻¹K, −M⁻¹C]]. Its
/// free motion is z_h(τ) = V e^{Λτ} V⁻¹ z_h(0) from A's eigen decomposition (complex: the exact
/// first-order propagator, for any damping, proportional to the segments' rates or not, as the
/// contacts' dashpots make it). A's eigenvalues come from Aberth's iteration on det T(λ), O(N²)
/// (tridiagonal_qep.h), or where it does not certify them from Hessenberg QR alone; its vectors
/// from the tridiagonal T(λ) = λ²M + λC + K: z = [φ, λφ] with T(λ)φ = 0 (inverse iteration, O(N)),
/// and, T being symmetric, V⁻¹'s row [((λM + C)φ)ᵀ, (Mφ)ᵀ] / φᵀ(2λM + C)φ, O(N) too (no O(N³)
/// vectors or inverse). Where a λ is near another (near critical damping) those rows lose digits
/// as the square of its conditioning: there A's dense eigenvectors and their inverse are taken.
/// K is positive definite (the chain is held at its fixed end), so
/// the polynomial particular solution comes from K⁻¹ by the recurrence
///
///     K a_j + C (j+1) a_{j+1} + M (j+2)(j+1) a_{j+2} = f_j e₀,   from the top degree down.
///
/// The audit's integrals of a free motion h (M h″ + C h′ + K h = 0, no forcing) against a
/// polynomial vector q close by parts, as the one-mass form's do (closed_form.h): with r = K⁻¹q,
///
///     ∫₀ᵀ qᵀh dτ = −[rᵀM h′]₀ᵀ + [r′ᵀM h]₀ᵀ − [rᵀC h]₀ᵀ + ∫₀ᵀ (C r′ − M r″)ᵀ h dτ,
///
/// whose last integral is of a polynomial one degree lower: it ends at q's degree. K and C are
/// tridiagonal, so each level costs O(N) a coefficient.
///
/// A train holds at most four such modes (cam, seat, both, none): Shared keeps them for the
/// thread's runs of such a chain.

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <array>
#include <memory>
#include <vector>

#include "dynamics/model/needle_train.h"

namespace needle {

/// How ChainModes finds A's eigenvalues: Aberth's O(N²) iteration on det T(λ), the dense QR
/// where it does not certify them (kAberth); or the dense QR alone (kDense: the benchmark's
/// before).
enum class ChainEigenvalues { kAberth, kDense };

class ChainModes {
 public:
  /// The least reciprocal condition of the eigenvectors taken: below it a mode is at or near
  /// critical damping (a defective A), and its modal sum loses the digits the run needs.
  static constexpr double kLeastConditioning = 1e-8;
  /// A mode's |φᵀ(2λM + C)φ| over its terms' sizes below this (a λ near another: V⁻¹'s rows made
  /// one by one would lose digits as its square) takes the dense O(N³) vectors and inverse.
  static constexpr double kQuadraticConditioning = 1e-3;
  /// ‖T(λ)φ‖∞ over ‖T(λ)‖∞ (φ's largest entry 1) above this: inverse iteration did not converge
  /// (the dense path then).
  static constexpr double kNullResidual = 1e-10;
  /// The dense path's Σ_k w_k Re(V_k V⁻¹_k) off the identity, in balanced units, above this: the
  /// chain is refused as near critical damping (its modal sum would lose the audit's digits).
  static constexpr double kInverseError = 1e-10;

  /// The chain of `train` (Coils() > 0, linear contact laws, no coil clash) in `mode`. Throws
  /// std::invalid_argument, with the reason, when K is not positive definite (a spring without
  /// rate) or a mode is at or near critical damping (kLeastConditioning).
  ChainModes(const NeedleTrain& train, const ContactMode& mode,
             ChainEigenvalues eigenvalues = ChainEigenvalues::kAberth);
  /// The same, made once per thread for each set of the numbers it is made of (the coils, their
  /// mass, rate and damping, the needle's mass, the contact laws' stiffness and damping, the
  /// mode) and shared by the thread's later runs of such a chain: a run's passes, a sweep's
  /// speeds, a study's samples whose spring and needle are not scattered. The kSharedKept
  /// chains last asked are kept. Throws as the constructor (a refused chain is not kept).
  static std::shared_ptr<const ChainModes> Shared(const NeedleTrain& train,
                                                  const ContactMode& mode);
  static constexpr int kSharedKept = 8;  // two trains' four contact modes
  /// Shared in each of the four contact modes (the cam and the seat pushing or not), at
  /// ModeIndex(mode). Throws as Shared.
  static std::array<std::shared_ptr<const ChainModes>, 4> SharedEveryMode(const NeedleTrain& train);
  static int ModeIndex(const ContactMode& mode) { return (mode.cam ? 1 : 0) + (mode.seat ? 2 : 0); }

  /// N: the needle and the N − 1 coil masses.
  int Dofs() const { return dofs_; }
  /// Stiffness, damping and mass of the needle's own row: K₀₀ (N/m), C₀₀ (N·s/m), m (kg).
  double NeedleStiffness() const { return K_(0, 0); }
  double NeedleDamping() const { return C_(0, 0); }
  double NeedleMass() const { return mass_[0]; }
  /// The mode's first-order eigenvalues λ_k (1/s, Re λ_k ≤ 0; exactly 0 for an undamped chain),
  /// one of each conjugate pair (Im λ ≥ 0) with its weight w_k (2 for a pair, 1 for a real one):
  /// z_h = Σ_k w_k Re(V_k c_k e^{λ_k τ}).
  const Eigen::VectorXcd& Lambda() const { return lambda_; }
  /// |λ_k|, rad/s.
  const Eigen::VectorXd& LambdaSizes() const { return lambda_sizes_; }
  const Eigen::VectorXd& Weight() const { return weight_; }
  /// V's columns for those λ_k (2N × count; rows: lifts in m, then velocities in m/s, of the
  /// needle and coils 1 … N − 1) and V⁻¹'s rows (count × 2N).
  const Eigen::MatrixXcd& Vectors() const { return vectors_; }
  const Eigen::MatrixXcd& Inverse() const { return inverse_; }
  /// V as the real 2N × 2·count [Re V, −Im V]: Re(V u) = [Re V, −Im V] [Re u; Im u].
  const Eigen::MatrixXd& VectorsReal() const { return vectors_real_; }
  /// |V_ik|, 2N × count.
  const Eigen::MatrixXd& VectorSizes() const { return vector_sizes_; }
  /// Each mode's vector differenced along the segments, row s − 1 = V_{s−1} − V_s over the lift
  /// rows (segment s's compression; V_N = 0, the fixed seat), and row N = k (V_0 − V_1) +
  /// c (V̇_0 − V̇_1) from the lift and velocity rows (the first segment's force k s₁ + c ṡ₁), as
  /// the real (N + 1) × 2·count [Re D, −Im D]: a free motion Re Σ_k V_k w_k c_k e^{λ_k τ} has
  /// segment s's compression Re Σ_k D_{s−1,k} w_k c_k e^{λ_k τ}.
  const Eigen::MatrixXd& Differences() const { return differences_; }
  /// |D_sk|, (N + 1) × count.
  const Eigen::MatrixXd& DifferenceSizes() const { return difference_sizes_; }
  /// max |λ_k|, rad/s: the fastest mode.
  double Fastest() const { return fastest_; }
  /// max |Im λ_k|, rad/s: the fastest oscillation (0 where every mode is overdamped). Far below
  /// Fastest() an overdamped mode is the fastest, and it caps exact's pieces (auto leaves such a
  /// chain to a time stepper: AutoMethod).
  double FastestOscillation() const { return fastest_oscillation_; }
  /// The particular solution's coefficients, N × (degree + 1), for the needle's forcing
  /// coefficients f_j (N/s^j, j = 0 … degree): column j is a_j (m/s^j), node 0 the needle.
  /// a_j = Σ_{i ≥ j} f_i (i!/j!) w_{i−j} from the chain's own responses w_d (K w₀ = e₀,
  /// K w_d + C w_{d−1} + M w_{d−2} = 0), made once: O(N·degree²), no solve.
  Eigen::MatrixXd Particular(const double* f, int degree) const;
  /// The degree up to which Particular reads the responses w_d (above it, it solves).
  static constexpr int kResponseDegree = 8;
  /// ∫₀ᵀ q(τ)ᵀ h(τ) dτ for a free motion h of the chain in this mode, from its states
  /// z = [h, h′] at τ = 0 and T (2N entries each, m and m/s); q is N × (degree + 1), column j
  /// the coefficient of τ^j (N/s^(j+1): a force rate, the integral in J; or any unit, the
  /// integral that unit times m·s).
  double FreeIntegral(Eigen::MatrixXd q, double T, const Eigen::VectorXd& z0,
                      const Eigen::VectorXd& z1) const;
  /// The free motion's energy ½ h′ᵀM h′ + ½ hᵀK h at z = [h, h′], J: its fall over a piece is
  /// the work of every dashpot of the mode on it, ∫ h′ᵀC h′ dτ.
  double FreeEnergy(const Eigen::VectorXd& z) const;
  /// Whether any dashpot acts in this mode (C ≠ 0).
  bool Damped() const { return damped_; }

 private:
  // M, K and C of the chain in `mode` (the constructor's first part).
  void Assemble(const NeedleTrain& train, const ContactMode& mode);
  // The balanced first-order matrix's eigenvalues, then each mode's vectors (QuadraticMode), or
  // where a mode is near another the dense eigenvectors and inverse, checked for conditioning.
  void Decompose();
  // λ and weight of one member of each conjugate pair, and fastest_; the members kept.
  std::vector<int> KeepOnePerPair(const Eigen::VectorXcd& all, bool undamped);
  // Mode r's column of V and row of V⁻¹ from λ_r and T(λ_r)'s null vector; false where the
  // mode is too near another (kQuadraticConditioning) or the null vector is not one.
  bool QuadraticMode(int r);
  // The null vector φ of T(λ) = λ²M + λC + K (λ an eigenvalue), its largest entry 1; ‖T‖∞.
  Eigen::VectorXcd NullVector(std::complex<double> lambda, double* norm) const;

  int dofs_;
  ChainEigenvalues eigenvalues_;
  Eigen::MatrixXd K_, C_;
  Eigen::VectorXd mass_;
  // K and C as sparse (tridiagonal) matrices, and K's Cholesky factor (Particular and
  // FreeIntegral solve with it: O(N) a column).
  Eigen::SparseMatrix<double> sparse_K_, sparse_C_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>
      stiffness_;
  bool damped_ = false;
  Eigen::MatrixXd responses_;  // w_0 … w_kResponseDegree, N × (kResponseDegree + 1)
  Eigen::VectorXcd lambda_;
  Eigen::VectorXd lambda_sizes_;
  Eigen::VectorXd weight_;
  Eigen::MatrixXcd vectors_, inverse_;
  Eigen::MatrixXd vectors_real_, vector_sizes_, differences_, difference_sizes_;
  double fastest_ = 0.0, fastest_oscillation_ = 0.0;
};

}  // namespace needle
