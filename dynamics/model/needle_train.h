#pragma once
/// @file
/// The needle train (docs/model.md §4 and §4a), as an Odeint-style system holding its
/// parameters. State x = [y, ẏ, W, D, …coils]: lift (m, 0 = seated), velocity, the two energy-audit
/// integrals (§6) carried as extra states so the residual is a by-product:
///
///     m ÿ = F_c + F_s − (P₀ + k y) + F_g
///     g_c = u(θ) − y,   ġ_c = ω u'(θ) − ẏ,   F_c = k_c g_c + c_c ġ_c  while the cam pushes
///     g_s = −y,         ġ_s = −ẏ,            F_s = k_s g_s + c_s ġ_s  while the seat pushes
///     Ẇ = F_c ω u'(θ),  Ḋ = (F_c − k_c g_c⁺) ġ_c + (F_s − k_s g_s⁺) ġ_s
///     E = ½mẏ² + P₀y + ½ky² − F_g y + ½k_c(g_c⁺)² + ½k_s(g_s⁺)²,   E − E₀ − W + D = 0
///
/// with θ = θ_a + ω t. With `coil_masses` N > 1 (docs/model.md §4a) the spring is a chain of N
/// segments of rate N k between the fixed seat of the spring and the needle, with N − 1 coil
/// masses m_s/N (positions x_i, velocities v_i, i = 1…N−1 from the needle) appended to the
/// state; the needle carries the top half-segment (m = mass_kg − m_s/3 + m_s/(2N)) and the
/// spring force P₀ + k y becomes the first segment's S₁ = P₀ + N k (y − x₁) + c (ẏ − v₁):
///
///     m_c ẍ_i = S_i − S_{i+1},   S_j = P₀ + N k (x_{j−1} − x_j) + c (v_{j−1} − v_j),  x_0 = y, x_N
///     = 0
///
/// with c = 2 ζ_s N k / ω₁ (ζ_s the first surge mode's damping ratio, ω₁ = π√(k/m_s)); E gains
/// ½ Σ m_c v_i² and replaces ½ k y² by ½ N k Σ (x_{j−1} − x_j)², and Ḋ gains Σ c (v_{j−1} − v_j)².
/// With `coil_clash` a segment whose compression s_j = x_{j−1} − x_j passes its travel to solid
/// δ = travel/N meets the next coils: a third contact law (compliant, k_cl and ζ_cl against m_c)
/// on the penetration g_j = s_j − δ adds its force to S_j, its potential to E and its loss to Ḋ,
/// and its witnesses join the event driver's (docs/model.md §4a).
/// F_c and F_s come from the two contact laws (dynamics/model/contact_law.h; the compliant law by
/// default: k g + c ġ with c = 2ζ√(k m)). A rigid contact that sticks is a constraint: the needle
/// moves with its surface (ÿ = ω² u'' on the cam, 0 on the seat) and F_c (F_s) is the constraint
/// force λ = m ÿ + P₀ + k y − F_g − (the other contact's force). Which contacts push is the contact
/// mode, switched by the event driver (dynamics/solver/event_driver.h) where a law's witness
/// changes sign, so that the right-hand side is smooth inside every step. The train holds no
/// integration state: the mode and the segment being integrated come in a Phase.

#include <array>
#include <boost/container/static_vector.hpp>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "dynamics/model/cam_input.h"
#include "dynamics/model/contact_law.h"

namespace needle {

/// Which law both contacts follow (docs/model.md §4).
enum class ContactKind {
  kCompliant,  ///< spring and dashpot (k_c, ζ_c; k_s, ζ_s)
  kRigid,      ///< impenetrable, Newton's restitution (e, e_s), sticking while pushed
};

/// The contact laws' parameters, SI (docs/model.md §3–4): a case's [train] is read straight
/// into them (apps/case/run_sections.cc). Every field has a default.
struct ContactParameters {
  double contact_stiffness_N_m = 1e8;             ///< k_c of the compliant cam contact, > 0
  double contact_damping_ratio = 0.05;            ///< ζ_c, ≥ 0
  double seat_stiffness_N_m = 1e8;                ///< k_s of the compliant seat contact, > 0
  double seat_damping_ratio = 0.05;               ///< ζ_s, ≥ 0
  ContactKind contact = ContactKind::kCompliant;  ///< the law of both contacts
  double restitution = 0.0;                       ///< e of the rigid cam contact, in [0, 1]
  double seat_restitution = 0.0;                  ///< e_s of the rigid seat, in [0, 1]
  bool rigid() const { return contact == ContactKind::kRigid; }

  /// The contact laws' rules, in one place: k_c, ζ_c, k_s and ζ_s (compliant only: a rigid law
  /// has none), e and e_s in [0, 1]. Throws FieldError (lib/field_error.h) naming the field, its
  /// value and the rule.
  void Validate() const;

 protected:
  void ValidateContacts(const char* owner) const;  ///< Validate, naming `owner` in what()
};

/// Parameters of the train, SI: its contacts' and the rest. Every field has a default;
/// Validate() checks them.
struct TrainParameters : ContactParameters {
  double mass_kg = 1.0;         ///< m, > 0
  double preload_N = 0.0;       ///< P₀, ≥ 0
  double rate_N_m = 0.0;        ///< k, ≥ 0
  double gas_force_N = 0.0;     ///< F_g, opening positive
  int coil_masses = 1;          ///< N of the spring's chain, in [1, kMaxCoilMasses]; 1: massless k
  double spring_mass_kg = 0.0;  ///< m_s of the active coils, > 0 and < 3 mass_kg when N > 1
  double surge_damping_ratio = 0.0;  ///< ζ_s of the first surge mode, in [0, 1] (N > 1)
  /// The spring's travel from its installed length to solid, L₁ − L_c, m; ≥ 0 (0: unknown).
  /// With N > 1 the run records the least coil gap; each segment goes solid at travel/N.
  double coil_travel_m = 0.0;
  bool coil_clash = false;  ///< segments meet when solid (needs N > 1 and coil_travel_m > 0)
  double clash_stiffness_N_m = 1e8;   ///< k_cl of the coils in contact, > 0 (with coil_clash)
  double clash_damping_ratio = 0.05;  ///< ζ_cl against the coil mass m_c, ≥ 0 (with coil_clash)

  /// Throws FieldError (a std::invalid_argument) naming the field, its value and the rule it
  /// broke; the contacts' rules are ContactParameters::Validate's.
  void Validate() const;
};

/// Which contacts push (their force is the law's pushing branch, else 0).
struct ContactMode {
  bool cam = false;
  bool seat = false;
  std::uint64_t clash = 0;  ///< bit j − 1: segment j of the chain is solid (coil clash)
  /// Whether segment j (1…N) is solid, and making it so.
  bool Solid(int j) const { return (clash >> (j - 1)) & 1u; }
  void SetSolid(int j) { clash |= std::uint64_t{1} << (j - 1); }
  bool operator==(const ContactMode& o) const {
    return cam == o.cam && seat == o.seat && clash == o.clash;
  }
  bool operator!=(const ContactMode& o) const { return !(*this == o); }
};

/// Whether two numbers are the same to the bit (−0 is not 0; a NaN is itself).
inline bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

/// What the event driver integrates in: the contact mode, and the end of the cam input's
/// segment (inside [a, b) the cam is evaluated on its own side of b: a stage that lands
/// exactly on b sees the limit from the left; +∞: no clamp). `gated` replaces the mode by
/// F = max(0, F) for g > 0 inside the right-hand side (the no-event baseline of the benchmarks).
struct Phase {
  ContactMode mode;
  double segment_end_rad = std::numeric_limits<double>::infinity();
  bool gated = false;
  /// Every field the same, the angle to the bit (what a memo of the right-hand side keys on).
  bool Identical(const Phase& o) const {
    return mode == o.mode && gated == o.gated && SameBits(segment_end_rad, o.segment_end_rad);
  }
};
static_assert(sizeof(Phase) == 32, "Phase has a new field: compare it in Phase::Identical");

/// The largest N of the spring's chain.
inline constexpr int kMaxCoilMasses = 40;
/// y, ẏ, W, D, then x_1…x_{N−1} and v_1…v_{N−1} of the coil masses: 4 + 2(N − 1) entries,
/// stored inline (no allocation when copied).
using TrainState = boost::container::static_vector<double, 4 + 2 * (kMaxCoilMasses - 1)>;
/// ∂f/∂x of the right-hand side, row-major n×n (n: the state's size).
using TrainJacobian = std::vector<double>;

/// Gaps, rates and raw contact forces at one instant.
struct Contacts {
  double crank_rad = 0.0;
  /// The needle's lift and velocity as the contacts see them: the state's, or the surface's
  /// while a rigid contact sticks (so integration drift never reads as a gap).
  double y = 0.0, v = 0.0;
  double u = 0.0, u_slope = 0.0;                    ///< u(θ) m, du/dθ m/rad
  double g_c = 0.0, g_c_rate = 0.0, f_c_raw = 0.0;  ///< penetration, rate, pushing-branch force
  double g_s = 0.0, g_s_rate = 0.0, f_s_raw = 0.0;
  /// The spring's force on the needle, closing positive: P₀ + k y, or S₁ of the chain, N.
  double spring_N = 0.0;
};

class NeedleTrain {
 public:
  /// `cam` must outlive this object; ω > 0 rad/s; θ_a the angle at t = 0. The contact laws
  /// default to the compliant law of `p` (k_c, ζ_c and k_s, ζ_s).
  NeedleTrain(const CamInput& cam, const TrainParameters& p, double omega, double theta_a_rad,
              std::shared_ptr<const ContactLaw> cam_law = nullptr,
              std::shared_ptr<const ContactLaw> seat_law = nullptr);

  /// dx/dt in `phase` (the equation of motion and the audit integrals above); into `at`, when
  /// given, Evaluate(x, t, phase), which it computes on the way.
  void Derivative(const TrainState& x, double t, const Phase& phase, TrainState& dxdt,
                  Contacts* at = nullptr) const;
  /// ∂f/∂x and ∂f/∂t of the right-hand side in `phase` (not gated).
  void Jacobian(const TrainState& x, double t, const Phase& phase, TrainJacobian& dfdx,
                TrainState& dfdt) const;

  /// Gaps and pushing-branch forces at (x, t), the cam evaluated inside `phase`'s segment.
  Contacts Evaluate(const TrainState& x, double t, const Phase& phase = Phase{}) const;
  /// The forces the right-hand side uses at `c` in `phase` (mode or gate), N.
  double AppliedCamForce(const Contacts& c, const Phase& phase) const;
  double AppliedSeatForce(const Contacts& c, const Phase& phase) const;
  /// m ÿ = F_c + F_s − (P₀ + k y) + F_g at `c` (its y: the state's, or the surface's while a
  /// rigid contact sticks) in `phase`, N.
  double NetForce(const Contacts& c, const Phase& phase) const;
  /// E of the audit (J).
  double Energy(const TrainState& x, double t) const;
  /// The audit's residual |E(t) − E(0) − W + D| / max(|W|, |E(0)|, P₀L + ½kL²) (L: the
  /// table's largest lift) between the start x0 (t = 0) and the state xt at time t, whose W and
  /// D are the integrated work and dissipation.
  double EnergyResidual(const TrainState& x0, const TrainState& xt, double t) const;
  /// The reset map of an impact: after the gap witness of the cam (`cam` true) or the seat
  /// crossed upward at (x, t), the state with the law's gap rate after the impact, the
  /// impulse's work on W and the kinetic energy lost on D (so the audit still closes);
  /// nullopt when the law has no reset.
  std::optional<TrainState> Reset(bool cam, const TrainState& x, double t,
                                  const Phase& phase) const;

  /// Rigid contacts (ContactLaw::Constraint) at a state reached without integration (the
  /// start, an impact, a contact letting go): `phase`'s mode with each rigid contact sticking
  /// where the needle is on its surface (|g| ≤ GapTolerance()), moves with it (|ġ| ≤
  /// RateTolerance()) and the constraint force would push (λ > 0); compliant contacts as given.
  ContactMode StickingMode(const TrainState& x, double t, const Phase& phase) const;
  /// x with the needle put on the surface of every sticking rigid contact of `phase` (y = u,
  /// ẏ = ω u' on the cam; y = 0, ẏ = 0 on the seat); the kinetic energy this changes is booked
  /// on D (dissipated), so the audit closes.
  TrainState Project(const TrainState& x, double t, const Phase& phase) const;
  /// A rigid contact touches within this gap, m: 1e-14 of the cam input's largest lift and play.
  double GapTolerance() const { return gap_tolerance_; }
  /// … and moves with its surface within this rate, m/s (1e-10 of ω times that lift).
  double RateTolerance() const { return 1e4 * omega_ * gap_tolerance_; }
  /// Any contact rigid (ContactLaw::Constraint).
  bool HasConstraint() const { return cam_rigid_ || seat_rigid_; }

  /// The static-equilibrium start (docs/model.md §5): y₀ and the mode it rests in (the coils
  /// of a chain evenly compressed, at rest).
  TrainState EquilibriumStart() const;
  /// √((k_c + k_s + N k)/m), or the chain's 2√(N k/m_c) if higher, rad/s: the fastest
  /// oscillation, for a first step.
  double FastestAngularFrequency() const;
  /// The state's size, 4 + 2(N − 1).
  int StateSize() const { return 4 + 2 * (coils_ > 0 ? coils_ : 0); }
  /// N − 1: the coil masses in the state (0 for the massless spring).
  int Coils() const { return coils_; }
  /// The needle's entry that state entry i is measured like: 0 for a lift (y, x_i), 1 for a
  /// velocity (ẏ, v_i), 2 and 3 for W and D.
  int MeasuredLike(int i) const { return i < 4 ? i : (i < 4 + coils_ ? 0 : 1); }
  /// The needle's mass m in the equation of motion, kg: mass_kg, or mass_kg − m_s/3 + m_s/(2N).
  double NeedleMassKg() const { return needle_mass_kg_; }
  /// A coil mass m_c = m_s/N, kg, a segment's rate N k, N/m, and its dashpot c, N·s/m (0
  /// without coil masses).
  double CoilMassKg() const { return coil_mass_kg_; }
  double SegmentRateNm() const { return segment_rate_N_m_; }
  double SegmentDampingNsm() const { return segment_damping_N_s_m_; }
  /// The largest |v_i| of the coil masses, m/s (0 without them).
  double LargestCoilSpeed(const TrainState& x) const;
  /// The largest compression of one segment beyond its installed length, max_j x_{j−1} − x_j,
  /// m (y for the massless spring).
  double LargestSegmentCompression(const TrainState& x) const;
  /// The chain's segments that can clash: N with coil_clash, else 0.
  int ClashSegments() const { return clash_law_ ? coils_ + 1 : 0; }
  /// Segment j's (1…N) clash penetration g_j = s_j − travel/N, m, and its rate ṡ_j, m/s, with
  /// the needle's lift and velocity as the contacts see them in `c`.
  std::array<double, 2> SegmentPenetration(const TrainState& x, const Contacts& c, int j) const;
  /// The law of the coils in contact (only with ClashSegments() > 0).
  const ContactLaw& clash_law() const { return *clash_law_; }

  double Angle(double t) const { return theta_a_ + omega_ * t; }
  double Time(double crank_rad) const { return (crank_rad - theta_a_) / omega_; }
  double omega() const { return omega_; }
  const TrainParameters& parameters() const { return p_; }
  const CamInput& cam() const { return cam_; }
  const ContactLaw& cam_law() const { return *cam_law_; }
  const ContactLaw& seat_law() const { return *seat_law_; }

 private:
  double CamAngle(double crank_rad, const Phase& phase) const;
  // Segment j's (1…N) ∂S_j/∂s_j and ∂S_j/∂ṡ_j in `phase`: the rate and dashpot, and the clash
  // law's while the mode has the segment solid.
  double SegmentStiffness(int j, const Phase& phase) const;
  double SegmentDamping(int j, const Phase& phase) const;
  // Jacobian()'s rows and columns of the chain's coils (N > 1), u'' = `upp` at c's angle.
  void ChainJacobian(const TrainState& x, const Contacts& c, const Phase& phase, double upp,
                     TrainJacobian& J, TrainState& dfdt) const;

  const CamInput& cam_;
  TrainParameters p_;
  double omega_, theta_a_;
  std::shared_ptr<const ContactLaw> cam_law_, seat_law_;
  bool cam_rigid_ = false, seat_rigid_ = false;  // their Constraint(), asked once
  // The spring's force on the needle at needle lift y and velocity v in `phase` (its clashing
  // segments); into `coil_rates` (when given) the coils' v̇_i, into `dissipation_W` the
  // dashpots' and clash contacts' power.
  double SpringForce(const TrainState& x, double y, double v, const Phase& phase,
                     double* coil_rates, double* dissipation_W) const;
  // Evaluate(), its spring walking the whole chain into `coil_rates` and `dissipation_W` when
  // they are given (Derivative: one walk for the contacts and the coils).
  Contacts EvaluateWith(const TrainState& x, double t, const Phase& phase, double* coil_rates,
                        double* dissipation_W) const;
  // Node i's lift and velocity (0: the needle at y, v; N: the fixed end).
  double NodeLift(const TrainState& x, double y, int i) const {
    return i == 0 ? y : (i == coils_ + 1 ? 0.0 : x[3 + i]);
  }
  double NodeVelocity(const TrainState& x, double v, int i) const {
    return i == 0 ? v : (i == coils_ + 1 ? 0.0 : x[3 + coils_ + i]);
  }
  // Segment j's compression beyond installed s_j = x_{j−1} − x_j and its rate ṡ_j, the needle
  // at y, v.
  std::array<double, 2> SegmentMotion(const TrainState& x, double y, double v, int j) const {
    return {NodeLift(x, y, j - 1) - NodeLift(x, y, j),
            NodeVelocity(x, v, j - 1) - NodeVelocity(x, v, j)};
  }
  std::shared_ptr<const ContactLaw> clash_law_;  // null without coil_clash
  double segment_travel_m_ = 0.0;                // δ = travel/N

  double gap_tolerance_ = 0.0;
  double lift_energy_J_ = 0.0;  // P₀L + ½kL²: the residual's least scale
  int coils_ = 0;               // N − 1
  double needle_mass_kg_ = 0.0;
  double coil_mass_kg_ = 0.0, segment_rate_N_m_ = 0.0, segment_damping_N_s_m_ = 0.0;
};

}  // namespace needle
