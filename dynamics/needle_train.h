#pragma once
/// @file
/// The one-mass needle train (model.md §4), as an Odeint-style system holding its
/// parameters. State x = [y, ẏ, W, D]: lift (m, 0 = seated), velocity, and the two energy-audit
/// integrals (§6) carried as extra states so the residual is a by-product:
///
///     m ÿ = F_c + F_s − (P₀ + k y) + F_g
///     g_c = u(θ) − y,   ġ_c = ω u'(θ) − ẏ,   F_c = k_c g_c + c_c ġ_c  while the cam pushes
///     g_s = −y,         ġ_s = −ẏ,            F_s = k_s g_s + c_s ġ_s  while the seat pushes
///     Ẇ = F_c ω u'(θ),  Ḋ = (F_c − k_c g_c⁺) ġ_c + (F_s − k_s g_s⁺) ġ_s
///     E = ½mẏ² + P₀y + ½ky² − F_g y + ½k_c(g_c⁺)² + ½k_s(g_s⁺)²,   E − E₀ − W + D = 0
///
/// with θ = θ_a + ω t and c = 2ζ√(k m). Which contacts push is the contact mode, switched by
/// the event logic (dynamics/contact_events.h) where F = max(0, k g + c ġ) changes branch, so
/// that the right-hand side is smooth inside every step.

#include <array>
#include <limits>

#include "dynamics/cam_input.h"

namespace needle {

/// Parameters of the train, SI. Every field has a default; Validate() checks them.
struct TrainParameters {
  double mass_kg = 1.0;                 ///< m, > 0
  double preload_N = 0.0;               ///< P₀, ≥ 0
  double rate_N_m = 0.0;                ///< k, ≥ 0
  double gas_force_N = 0.0;             ///< F_g, opening positive
  double contact_stiffness_N_m = 1e8;   ///< k_c, > 0
  double contact_damping_ratio = 0.05;  ///< ζ_c, ≥ 0
  double seat_stiffness_N_m = 1e8;      ///< k_s, > 0
  double seat_damping_ratio = 0.05;     ///< ζ_s, ≥ 0

  /// Throws std::invalid_argument naming the field, its value and the rule it broke.
  void Validate() const;
  double contact_damping() const;  ///< c_c = 2ζ_c√(k_c m), N·s/m
  double seat_damping() const;     ///< c_s = 2ζ_s√(k_s m), N·s/m
};

/// Which contacts push (their force branch is k g + c ġ, else 0).
struct ContactMode {
  bool cam = false;
  bool seat = false;
};

using TrainState = std::array<double, 4>;  ///< y, ẏ, W, D

/// Gaps, rates and raw contact forces at one instant.
struct Contacts {
  double crank_rad = 0.0;
  double u = 0.0, u_slope = 0.0;                    ///< u(θ) m, du/dθ m/rad
  double g_c = 0.0, g_c_rate = 0.0, f_c_raw = 0.0;  ///< penetration, rate, k_c g + c_c ġ
  double g_s = 0.0, g_s_rate = 0.0, f_s_raw = 0.0;
};

class NeedleTrain {
 public:
  /// `cam` must outlive this object; ω > 0 rad/s; θ_a the angle at t = 0.
  NeedleTrain(const CamInput& cam, const TrainParameters& p, double omega, double theta_a_rad);

  /// dx/dt in the current mode.
  void operator()(const TrainState& x, TrainState& dxdt, double t) const;

  Contacts Evaluate(const TrainState& x, double t) const;
  /// Contact forces in `mode` (0 for a contact that does not push).
  double CamForce(const Contacts& c, ContactMode mode) const { return mode.cam ? c.f_c_raw : 0.0; }
  double SeatForce(const Contacts& c, ContactMode mode) const {
    return mode.seat ? c.f_s_raw : 0.0;
  }
  /// E of the audit (J).
  double Energy(const TrainState& x, double t) const;
  /// The audit's residual |E(t) − E(0) − W + D| / max(|W|, |E(0)|) between the start x0 (t = 0)
  /// and the state xt at time t, whose W and D are the integrated work and dissipation.
  double EnergyResidual(const TrainState& x0, const TrainState& xt, double t) const;

  /// The static-equilibrium start (model.md §5): y₀ and the mode it rests in.
  TrainState EquilibriumStart() const;

  double Angle(double t) const { return theta_a_ + omega_ * t; }
  double Time(double crank_rad) const { return (crank_rad - theta_a_) / omega_; }
  double omega() const { return omega_; }
  const TrainParameters& parameters() const { return p_; }
  const CamInput& cam() const { return cam_; }

  /// The integrators step to every break of the cam input. Inside a segment [a, b) the cam is
  /// evaluated on its own side of b: a stage that lands exactly on b sees the limit from the
  /// left, not the piece after the break. +∞ (the default) disables the clamp.
  void set_segment_end(double crank_rad) { segment_end_ = crank_rad; }
  void set_mode(ContactMode m) { mode_ = m; }
  ContactMode mode() const { return mode_; }
  /// Gated: the forces take F = max(0, k g + c ġ) for g > 0 inside the right-hand side,
  /// ignoring the mode (the no-event baseline of the benchmarks).
  void set_gated(bool gated) { gated_ = gated; }
  /// The forces the right-hand side uses at `c` (mode or gate).
  double AppliedCamForce(const Contacts& c) const;
  double AppliedSeatForce(const Contacts& c) const;
  /// m ÿ = F_c + F_s − (P₀ + k y) + F_g at `c` and state `x`, N (the equation of motion above).
  double NetForce(const Contacts& c, const TrainState& x) const;
  /// ∂f/∂x (row-major 4×4) and ∂f/∂t of the right-hand side in the current mode.
  void Jacobian(const TrainState& x, double t, std::array<double, 16>& dfdx,
                TrainState& dfdt) const;
  /// Right-hand-side evaluations so far.
  long evaluations() const { return evaluations_; }

 private:
  double CamAngle(double crank_rad) const;

  const CamInput& cam_;

  TrainParameters p_;
  double omega_, theta_a_;
  double c_c_, c_s_;
  ContactMode mode_;
  bool gated_ = false;
  double segment_end_ = std::numeric_limits<double>::infinity();

  mutable long evaluations_ = 0;
};

}  // namespace needle
