#pragma once
/// @file
/// Internal to the solver: the train's motion in closed form on one piece, one contact mode and
/// one segment of the cam input (method "exact", docs/model.md §9). There the equation of
/// motion of docs/model.md §4 is linear with constant coefficients and a polynomial forcing:
///
///     m ÿ + c ẏ + K y = f(τ),   τ = t − t₀,
///     c = c_c [cam pushes] + c_s [seat pushes],   K = k + k_c [cam] + k_s [seat],
///     f(τ) = k_c u(τ) + c_c u̇(τ) [cam] − P₀ + F_g,   u(τ) the cam segment's polynomial in time.
///
/// From (y₀, ẏ₀) the solution is y = P(τ) + Y₀ φ₀(τ) + V₀ φ₁(τ) with
///   P   the polynomial particular solution, P = Σ a_j τ^j by the recurrence
///       K a_j + c (j+1) a_{j+1} + m (j+2)(j+1) a_{j+2} = f_j from the top degree down
///       (K = c = 0: m ÿ = f, integrated twice);
///   Y₀ = y₀ − P(0), V₀ = ẏ₀ − P'(0);
///   φ₀, φ₁ the homogeneous solutions with φ₀(0) = 1, φ₀'(0) = 0, φ₁(0) = 0, φ₁'(0) = 1:
///       σ = c/(2m),  β = K/m − σ²,   φ₁ = e^{−στ} S,   φ₀ = e^{−στ} (C + σ S),
///       β > 0: C = cos(√β τ),  S = sin(√β τ)/√β        (under-damped; undamped when σ = 0)
///       β = 0: C = 1,          S = τ                    (critically damped; K = c = 0)
///       β < 0: C = cosh(μ τ),  S = sinh(μ τ)/μ, μ = √−β (over-damped)
///   one formula, continuous across β = 0. Where μτ ≥ ½ the over-damped pair is taken as
///   e^{−στ}C = (e^{r₁τ} + e^{r₂τ})/2, e^{−στ}S = (e^{r₁τ} − e^{r₂τ})/(2μ) with
///   r₁ = −(K/m)/(σ + μ), r₂ = −σ − μ: no overflow of cosh against e^{−στ}, no cancellation in r₁.
///
/// The audit integrals W and D (docs/model.md §6) are the integrals of the train's own Ẇ and Ḋ
/// along this solution in closed form (Audit): with y = P + h, the products of polynomials
/// exactly, ∫ c h'² = H(0) − H(τ) from the homogeneous part's energy H = ½mh'² + ½Kh², and
/// ∫ q h by parts through m h'' + c h' + K h = 0, which ends at q's degree. No quadrature, so a
/// piece may be as long as its events allow.
///
/// Root isolation needs bounds: for a witness that is a linear form of (y, ẏ, u, u̇) (see
/// LinearForm), Bounds() gives |w'| and |w''| over an interval, from the polynomial part's
/// coefficients and the homogeneous part's energy ½mh'² + ½Kh², which never grows (c ≥ 0).
///
/// The coil chain ([spring] masses > 1, without coil clash) takes the same form with y, P and h
/// the needle's entries of the chain's vectors (chain_modes.h): P from the chain's recurrence,
/// h(τ) = Re Σ_k α_k e^{λ_k τ} over its modes. Its bounds come from the modal sum, each term
/// decaying (Re λ_k ≤ 0): |h⁽ʲ⁾(τ)| ≤ Σ_k |α_k| |λ_k|ʲ e^{Re λ_k τ_a} for τ ≥ τ_a. Its audit
/// integrals close the same way with vectors (ChainAudit): ∫ h′ᵀC h′ = H(0) − H(τ) from the
/// whole chain's free energy H = ½h′ᵀM h′ + ½hᵀK h, and ∫ qᵀh by parts (ChainModes::FreeIntegral).

#include <Eigen/Dense>
#include <array>
#include <optional>
#include <vector>

#include "dynamics/model/needle_train.h"
#include "dynamics/solver/chain_modes.h"
#include "dynamics/solver/contact_events.h"

namespace needle {

/// Over [t_a, t_b]: the range of the form's values, lo ≤ w ≤ hi (valid for any t_b, from the
/// polynomial part's coefficients and the homogeneous part's energy, which never grows).
struct FormRange {
  double lo = 0.0, hi = 0.0;
};

/// Over [t_a, t_b]: bounds on |w'| and |w''|, and w'(t_a) exact.
struct FormBounds {
  double slope_bound = 0.0;      ///< ≥ max |w'|
  double curvature_bound = 0.0;  ///< ≥ max |w''|
  double slope_at_start = 0.0;   ///< w'(t_a)
};

/// A coil chain's motion near t_c as polynomials in s = t − t_c (ClosedFormPiece::ChainTaylorAt):
/// a search over a short bracket evaluates O(N·D) a point where the closed form costs
/// O(N·m) with m exponentials and sines.
struct ChainTaylor {
  static constexpr int kMaxDegree = 20;
  bool valid = false;  ///< false where the remainder may exceed the modal sum's round-off
  double t_c = 0.0;    ///< s
  /// Rows: the lifts of the nodes held (node 0 the needle), then the needle's speed; column j
  /// the coefficient of s^j (m/s^j, m/s^(j+1)).
  Eigen::MatrixXd coef;
  /// The train's state at t: the needle's lift and speed, the coils' lifts where held; the
  /// coils' velocities, W and D at 0 (what a force or a compression does not read).
  TrainState At(double t, size_t state_size) const;
  /// The needle's lift and speed at t alone.
  std::array<double, 2> LiftAndSpeed(double t) const;
  /// Row r's polynomial at t, by Horner.
  double Row(Eigen::Index r, double t) const;
};

class ClosedFormPiece {
 public:
  static constexpr int kMaxDegree = 8;  ///< of P (cam pieces up to quintic, integrated twice)
  using Poly = std::array<double, kMaxDegree + 1>;

  /// The piece of `train` in `mode` from (t₀, x₀) on the cam's segment holding angle
  /// `segment_angle_rad`, under linear contact laws (ExactRefusal is nullopt); `chain` is the
  /// chain's modes in `mode` when the train has coil masses (else nullptr). Throws
  /// std::invalid_argument when the cam piece's degree is above 6.
  ClosedFormPiece(const NeedleTrain& train, const ContactMode& mode, double segment_angle_rad,
                  double t0, const TrainState& x0, const ChainModes* chain = nullptr);

  /// A coil chain's samples at `count` equally spaced times ts[0] < … < ts[count − 1] (t₀ ≤
  /// ts[0]): their modes' e^{λ_k τ} − 1 made once, from one e^{λ_k Δ} per mode and the
  /// recurrence g_j = g_{j−1} + ρ + g_{j−1} ρ (ρ = e^{λ_k Δ} − 1), for MotionState, Motion and
  /// LiftAndSpeed at exactly those times. They are the values at τ₀ + jΔ, each some ulps of t
  /// from its sample's rounded time: the same as the closed form to 1e-13 of the homogeneous
  /// part's size near the start (test TheSamplesByRecurrenceAreTheClosedFormsStates), to
  /// |λ_k| ulp(t) of a mode's size late in a run (4e-12 at t = 4 s for |λ| = 1e4/s: an ulp's
  /// shift of the time). count < 2 forgets them. Nothing for one mass.
  void ChainSampleTimes(const double* ts, int count) const;
  /// The state [y, ẏ, W, D] at t, and the coils' lifts and velocities of a chain (any t ≥ t₀;
  /// exact for the lifts and velocities).
  TrainState State(double t) const;
  /// The same with W and D by 10-point Gauss–Legendre on `parts` equal parts of [t₀, t] (the
  /// rule for K = 0 and no chain; tests compare the closed form with it).
  TrainState StateByQuadrature(double t, int parts) const;
  /// y, ẏ, ÿ at t.
  std::array<double, 3> Motion(double t) const;
  /// The train's state at t with W and D at 0: y and ẏ (one mass), and the coils' lifts and
  /// velocities (the chain). Without `coil_speeds`, a chain's coils from the second on are
  /// given no velocity (NaN): what a record reads (the lifts, the spring's force), at about
  /// half the cost.
  TrainState MotionState(double t, bool coil_speeds = true) const;
  /// Whether the piece carries a coil chain.
  bool Chain() const { return chain_ != nullptr; }
  /// A chain's homogeneous part at its largest: max over the nodes of Σ_k |V_ik w_k c_k|, for
  /// the lifts (m) and the velocities (m/s), which bound |h_i(τ)| and |h_i′(τ)| at every τ ≥ 0
  /// (each mode decays). Made once a piece.
  std::array<double, 2> ChainStartRinging() const;
  /// A chain's needle: Σ_k |α_k| |λ_k|² and Σ_k |α_k| |λ_k|³, which bound the homogeneous part's
  /// |h₀″(τ)| (m/s²) and |h₀‴(τ)| (m/s³) at every τ ≥ 0 (each mode decays): under a constant
  /// forcing, the rates of the needle's speed and acceleration.
  std::array<double, 2> ChainNeedleRateBounds() const;
  /// y and ẏ at t (Motion's first two, without ÿ).
  std::array<double, 2> LiftAndSpeed(double t) const { return PositionVelocity(t - t0_); }
  /// The cam input u and its rate u̇ at t on the piece's own polynomials (the train's own
  /// evaluation on the cam's spline agrees with them up to round-off).
  std::array<double, 2> Input(double t) const;
  /// The form's value at t on the piece's own polynomials (no search of the cam's segments).
  double FormValue(const LinearForm& form, double t) const;
  /// The same with the needle's lift and speed at t given (y, ẏ: a chain's Taylor polynomials).
  double FormValue(const LinearForm& form, double t, const std::array<double, 2>& yv) const;
  /// The polynomial part of the form, q = form·(P, P′, u, u̇) + nothing of h, in s = t − t_a
  /// (Range and Bounds over an interval that starts at t_a share it).
  Poly FormPolynomial(const LinearForm& form, double t_a) const {
    return Shifted(FormPolynomial(form), t_a);
  }
  /// The same in τ = t − t₀ (a search over many intervals makes it once), and that polynomial
  /// moved to s = t − t_a.
  Poly FormPolynomial(const LinearForm& form) const;
  Poly Shifted(const Poly& q, double t_a) const;
  /// Bounds of the form over [t_a, t_b], t₀ ≤ t_a < t_b.
  FormBounds Bounds(const LinearForm& form, double t_a, double t_b) const {
    return Bounds(form, FormPolynomial(form, t_a), t_a, t_b);
  }
  /// The same with the form's polynomial in s = t − t_a (FormPolynomial) given.
  FormBounds Bounds(const LinearForm& form, const Poly& q, double t_a, double t_b) const;
  /// The range of the form over [t_a, t_b], t₀ ≤ t_a ≤ t_b (t_b may be +∞ when the
  /// polynomial part is constant).
  FormRange Range(const LinearForm& form, double t_a, double t_b) const {
    return Range(form, FormPolynomial(form, t_a), t_a, t_b);
  }
  /// The same with the form's polynomial in s = t − t_a (FormPolynomial) given.
  FormRange Range(const LinearForm& form, const Poly& q, double t_a, double t_b) const;
  /// A coil chain over [t_a, t_b], t₀ ≤ t_a ≤ t_b: upper bounds on its largest segment
  /// compression (m) and on the spring's force on the needle P₀ + k s₁ + c ṡ₁ (N), each from the
  /// particular solution's polynomials and the modal sum (terms that never grow): the lesser of
  /// the terms at their full size and, over a stretch short against some modes, their values at
  /// t_a with the slow modes' Taylor bounds (a sample interval's bound follows the chain).
  std::array<double, 2> ChainUpperBounds(double t_a, double t_b) const;
  /// A coil chain's Taylor polynomials about t_c ≥ t₀: the needle's lift and speed, and with
  /// `coils` the coils' lifts (a segment's compression), of the least degree D whose remainder over
  /// |s| ≤ reach, at most ρ^(D+1)/(D+1)! e^ρ of each mode's size with ρ = |λ_k| reach, is below
  /// 2⁻⁵³ (ρ ≤ π/16, a bracket of two of a stretch's 16 samples: D = 11; a witness's bracket in
  /// the certified search may reach ρ ≈ 1.4, D = 20); not valid above ChainTaylor::kMaxDegree.
  /// The value at t_c is the closed form's own.
  ChainTaylor ChainTaylorAt(double t_c, double reach, bool coils) const;
  /// The homogeneous part's energy ½ m h'² + ½ K h² at t ≥ t₀, J, which no later time exceeds
  /// (one mass only: a chain's needle trades energy with its coils; std::logic_error there).
  double HomogeneousEnergy(double t) const;
  /// Stiffness K (N/m), mass m (kg) and whether the cam input is constant on the piece.
  double stiffness() const { return K_; }
  double mass() const { return m_; }
  double damping() const { return c_; }
  bool InputConstant() const { return InputDegree() == 0; }
  /// The degree of the cam input's polynomial on the piece (0: constant, 1: a ramp).
  int InputDegree() const;
  /// At rest for good: no homogeneous part (y₀ and ẏ₀ are the particular solution's, exactly),
  /// a constant forcing and input, so that y and ẏ keep their starting bits at every t.
  bool Frozen() const { return HomogeneousZero() && ForcingConstant() && InputConstant(); }
  /// Whether the forcing f(τ) is constant on the piece (then ÿ = −(K h + c h′)/m: the net force
  /// on the needle is the homogeneous part's alone).
  bool ForcingConstant() const;
  /// The static (particular) lift where the input is constant, m.
  double RestLift() const { return p_[0]; }
  /// Half an oscillation (π over the largest of √(K/m) and the decay rates; a chain's fastest
  /// mode), s; +∞ for K = c = 0: the longest step in which the 10-point rule is exact to
  /// round-off (K = 0), and the stepper's cap on a piece (the record's 16 samples a stretch).
  double LongestStep() const { return longest_step_; }
  double start_time() const { return t0_; }

 private:
  struct AuditTerms {
    double work_J = 0.0, dissipated_J = 0.0;
  };
  // W and D over [t₀, t₀ + T] in closed form, given y and ẏ at its end (K > 0).
  AuditTerms Audit(double T, double y1, double v1) const;
  // The same for the coil chain, from the whole chain's homogeneous part z1 = [h, h′] at T.
  AuditTerms ChainAudit(double T, const Eigen::VectorXd& z1) const;
  // ∫₀ᵀ q(τ) h(τ) dτ for the homogeneous part h, which is h1, hv1 (h, h') at T.
  double HomogeneousIntegral(const Poly& q, double T, double h1, double hv1) const;
  // h, h' at t (one-entry cache: bounds and ranges ask at the same t_a).
  std::array<double, 2> HomogeneousAt(double t) const;
  // What Bounds and Range read of the homogeneous part at an interval's start t_a: h, h′, h″,
  // and from its energy H the bounds |h′| ≤ e1 = √(2H/m), |h″| ≤ e2, |h‴| ≤ b3, |h| ≤ √(2H/K)
  // (one entry: the witnesses of a piece are bounded from the same start).
  struct HomogeneousStart {
    double t = -1e300, h = 0.0, hv = 0.0, ha = 0.0, e1 = 0.0, e2 = 0.0, b3 = 0.0;
    double lift_amplitude = 0.0;
  };
  const HomogeneousStart& StartAt(double t_a) const;
  // The chain's particular solution, modal coefficients and step (the constructor's rest).
  void StartChain();
  // StartAt's homogeneous start for the chain, from the modal sum.
  void ChainStart(double t) const;
  // From p_ and u_: P′, the four polynomials' degrees, and the homogeneous start Y₀, V₀.
  void SetStart();
  // No homogeneous part at all: the start is the particular solution's, to the bit.
  bool HomogeneousZero() const;
  // The chain's needle entries at τ: h(τ) − h(0), h′(τ) − h′(0) and h″(τ) (cached by τ), and
  // the modes' e^{λ_k τ} − 1 in grow_.
  struct ChainNeedle {
    double tau = -1e300, dh = 0.0, dhv = 0.0, ha = 0.0;  // s, m, m/s, m/s²
  };
  const ChainNeedle& ChainAt(double tau) const;
  // The chain's whole state at τ, W and D at 0 (MotionState's `coil_speeds`).
  TrainState ChainState(double tau, bool coil_speeds = true) const;
  // e^{−στ}C − 1 and e^{−στ}S at τ ≥ 0.
  void Basis(double tau, double& ecm1, double& es) const;
  void BasisUncached(double tau, double& ecm1, double& es) const;
  /// (y, ẏ) at τ = t − t₀ after the piece's start: Motion's first two, FormValue's inputs.
  std::array<double, 2> PositionVelocity(double tau) const;

  const NeedleTrain& train_;
  ContactMode mode_;
  double t0_;
  TrainState x0_;
  double m_, c_, K_;
  double sigma_, beta_, root_;  // root_ = √|β|
  double r1_ = 0.0, r2_ = 0.0;  // over-damped exponents
  Poly f_{};                    // the forcing in τ
  Poly p_{}, dp_{};             // particular solution in τ, and its derivative
  Poly u_{}, du_{};             // the cam input in τ (cam mode or not), and its derivative
  int degree_p_ = 0, degree_dp_ = 0, degree_u_ = 0, degree_du_ = 0;  // Degree() of each
  double Y0_, V0_;
  double longest_step_;
  mutable double cached_t_ = -1e300;
  mutable std::array<double, 2> cached_h_{};
  // Basis's last τ and its two values (a bisection asks for the value at a midpoint, then for
  // the bounds of the half that starts there).
  mutable double basis_tau_ = -1e300, basis_ecm1_ = 0.0, basis_es_ = 0.0;
  mutable HomogeneousStart start_;
  // The coil chain: its modes in this contact mode (nullptr for one mass), the particular
  // solution of every node (N × (kMaxDegree + 1), row 0 is p_), the modal coefficients w_k c_k
  // of the start's homogeneous part, the needle's α_k = w_k V₀ₖ c_k, and the modes' e^{λτ} − 1.
  const ChainModes* chain_ = nullptr;
  Eigen::MatrixXd chain_p_;
  Eigen::VectorXcd chain_c_, alpha_;
  Eigen::MatrixXcd alpha_rates_;    // α_k λ_k and α_k λ_k², m × 2
  Eigen::VectorXd alpha_sizes_;     // |α_k| (ChainStart)
  Eigen::VectorXd chain_leftover_;  // h(0) − Re V w c, 2N (ChainUpperBounds)
  Eigen::VectorXd chain_h0_;        // the start's homogeneous part [h(0), h′(0)], 2N
  bool chain_rest_ = false;
  // [Re; Im] of e^{λτ} − 1 and of w c (e^{λτ} − 1), and the state's change.
  mutable Eigen::VectorXd grow_, terms_, dz_;
  mutable ChainNeedle chain_at_;
  // ChainSampleTimes': the samples' τ and their [Re; Im] of e^{λτ} − 1 (2m × count).
  mutable std::vector<double> sample_tau_;
  mutable double sample_step_ = 0.0;
  mutable Eigen::MatrixXd sample_grow_;
  mutable std::optional<std::array<double, 2>> ringing_;  // ChainStartRinging's, once made
};

}  // namespace needle
