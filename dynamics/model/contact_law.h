#pragma once
/// @file
/// One unilateral contact of the needle (with the cam, or with its seat), as the train and the
/// event driver see it (docs/model.md §4). For a penetration g (m, > 0 = overlap) and its rate
/// ġ (m/s) a law gives:
///
///   witnesses   two signed functions whose signs decide whether the contact pushes; the
///               upward crossing of the first (the gap) is an impact
///   force       F(g, ġ) on its pushing branch, N, and ∂F/∂g, ∂F/∂ġ (Jacobians)
///   potential   V(g) of the energy audit, J, with V' and V'' (the conservative part of F)
///   reset       the gap rate after an impact from the one before (a restitution law); none
///               for a compliant law, whose velocities are continuous
///
/// The compliant law of the model (the default for both contacts):
///
///     F = k g + c ġ while g > 0 and k g + c ġ > 0, else 0;   c = 2ζ√(k m)
///     witnesses: g and k g + c ġ;   V = ½ k (g⁺)²;   no reset
///
/// The rigid law (Newton's restitution, docs/model.md §4):
///
///     g ≤ 0 always; at an impact ġ⁺ = −e ġ⁻ (0 ≤ e ≤ 1); while stuck (g = 0, ġ = 0) the contact
///     force is the constraint force λ the needle's motion on the surface needs, and the
///     contact lets go where λ reaches 0
///     witnesses: g (free; +1 while stuck) and λ (the train computes it);   V = 0
///
/// A new law is one class deriving from ContactLaw (see docs/architecture.md, "How to add").

#include <array>
#include <optional>
#include <string>

namespace needle {

/// The two witness functions of one contact at (g, ġ): [0] the gap, [1] the force branch.
using ContactWitnesses = std::array<double, 2>;

/// A law linear in (g, ġ): its pushing force is F = ForceStiffness()·g + ForceDamping()·ġ and
/// its witnesses are w₀ = gap_g·g + gap_rate·ġ and w₁ = branch_g·g + branch_rate·ġ. Method
/// "exact" (docs/model.md §9) solves the train in closed form only under such laws.
struct LinearWitnesses {
  double gap_g = 1.0, gap_rate = 0.0;        ///< w₀'s coefficients (1, 0: the gap itself)
  double branch_g = 0.0, branch_rate = 0.0;  ///< w₁'s coefficients (compliant: k, c)
};

class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  /// The law's name in messages and JSON ("compliant").
  virtual std::string name() const = 0;
  /// Witness functions at (g, ġ); signs > 0 mean "touching" and "would push".
  virtual ContactWitnesses Witnesses(double g, double g_rate) const = 0;
  /// Whether the contact pushes, from the signs (±1) of its two witnesses.
  virtual bool Pushes(int gap_sign, int branch_sign) const = 0;
  /// F on the pushing branch, N (the train applies 0 when the contact does not push).
  virtual double Force(double g, double g_rate) const = 0;
  /// ∂F/∂g on the pushing branch, N/m.
  virtual double ForceStiffness() const = 0;
  /// ∂F/∂ġ on the pushing branch, N·s/m.
  virtual double ForceDamping() const = 0;
  /// The gated force of the no-event baseline: F where the contact would push, else 0.
  double GatedForce(double g, double g_rate) const;
  /// The audit's potential V(g), J; V(g) = 0 for g ≤ 0.
  virtual double Potential(double g) const = 0;
  /// V'(g), N: the conservative part of F (F − V' is dissipated).
  virtual double ConservativeForce(double g) const = 0;
  /// V''(g), N/m.
  virtual double ConservativeStiffness(double g) const = 0;
  /// The reset map at an impact (an upward crossing of the gap witness): the gap rate after
  /// the impact from the approach rate ġ⁻ > 0; nullopt: no reset, velocities continuous.
  virtual std::optional<double> ImpactRate(double /*g_rate_before*/) const { return std::nullopt; }
  /// The law's linear form when it is linear in (g, ġ) (see LinearWitnesses); nullopt: not
  /// linear, and method "exact" refuses the train.
  virtual std::optional<LinearWitnesses> Linear() const { return std::nullopt; }
  /// True for a rigid law: the contact is a constraint while it pushes, its force the
  /// constraint force the train computes (NeedleTrain::Evaluate), not Force().
  virtual bool Constraint() const { return false; }
};

/// The compliant law: a spring k and a dashpot c = 2ζ√(k m) that push and never pull.
class CompliantContact final : public ContactLaw {
 public:
  /// stiffness_N_m > 0, damping_ratio ζ ≥ 0, mass_kg > 0 (the mass c is reckoned against).
  CompliantContact(double stiffness_N_m, double damping_ratio, double mass_kg);
  std::string name() const override { return "compliant"; }
  ContactWitnesses Witnesses(double g, double g_rate) const override {
    return {g, Force(g, g_rate)};
  }
  bool Pushes(int gap_sign, int branch_sign) const override {
    return gap_sign > 0 && branch_sign > 0;
  }
  double Force(double g, double g_rate) const override { return k_ * g + c_ * g_rate; }
  double ForceStiffness() const override { return k_; }
  double ForceDamping() const override { return c_; }
  double Potential(double g) const override;
  double ConservativeForce(double g) const override { return g > 0.0 ? k_ * g : 0.0; }
  double ConservativeStiffness(double g) const override { return g > 0.0 ? k_ : 0.0; }
  std::optional<LinearWitnesses> Linear() const override {
    return LinearWitnesses{1.0, 0.0, k_, c_};
  }

 private:
  double k_, c_;
};

/// The rigid law: an impenetrable surface with Newton's restitution coefficient e.
class RigidContact final : public ContactLaw {
 public:
  /// restitution e in [0, 1].
  explicit RigidContact(double restitution);
  std::string name() const override { return "rigid"; }
  /// The gap alone; the train replaces the branch witness by the constraint force.
  ContactWitnesses Witnesses(double g, double /*g_rate*/) const override { return {g, 0.0}; }
  bool Pushes(int gap_sign, int branch_sign) const override {
    return gap_sign > 0 && branch_sign > 0;
  }
  double Force(double /*g*/, double /*g_rate*/) const override { return 0.0; }
  double ForceStiffness() const override { return 0.0; }
  double ForceDamping() const override { return 0.0; }
  double Potential(double /*g*/) const override { return 0.0; }
  double ConservativeForce(double /*g*/) const override { return 0.0; }
  double ConservativeStiffness(double /*g*/) const override { return 0.0; }
  /// ġ⁺ = −e ġ⁻.
  std::optional<double> ImpactRate(double g_rate_before) const override {
    return -e_ * g_rate_before;
  }
  bool Constraint() const override { return true; }

 private:
  double e_;
};

}  // namespace needle
