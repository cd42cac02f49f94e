#pragma once
/// @file
/// The rigid-train (quasi-static) contact force and what follows from it (docs/model.md §6):
///
///     F_qs(θ) = m·a(θ) + P₀ + k·s(θ) − F_g,      a = ω² d²s/dθ²,
///     n_qs = (60/2π) · √( min_{s''<0} (P₀ + k·s − F_g) / (m·|d²s/dθ²|) ),
///
/// and the least preload that keeps S·m·|a| below the spring's net force wherever the
/// needle decelerates, at the overspeed f·n:
///
///     P₀,req = max_{s''<0} ( S·m·(fω)²·|d²s/dθ²| − k·s + F_g ).

#include "lib/lift_law.h"
#include "lib/rigid_train.h"

namespace needle {

/// F_qs(θ) at crank speed ω (rad/s), N. Needs a C² lift law.
double QuasiStaticForce(const LiftLaw& law, const RigidTrain& train, double omega,
                        double crank_rad);

struct ForceMinimum {
  double force_N = 0.0;
  double crank_rad = 0.0;
};

/// The smallest F_qs over [θ_0, θ_N] and where it falls, to ~1e-10 rad.
ForceMinimum MinQuasiStaticForce(const LiftLaw& law, const RigidTrain& train, double omega);

/// n_qs in rpm: +∞ when s'' is never negative; 0 when the spring's net force P₀ + k·s − F_g
/// is not positive somewhere the needle decelerates.
double QuasiStaticLiftoffRpm(const LiftLaw& law, const RigidTrain& train);

/// The 95 % band of n_qs, rpm, from the law's acceleration band (LiftLaw::nodes(): s'' ± its
/// half-width at each node, at the largest deceleration and at the least spring reserve, those
/// two with the nearest node's; its unsafe end also at LiftLaw::ReachNodes(false)), always holding
/// QuasiStaticLiftoffRpm; none for a law without one.
std::optional<ExtremumBand> QuasiStaticLiftoffBand(const LiftLaw& law, const RigidTrain& train);

/// P₀,req (N, ≥ 0) at the acceleration band's unsafe end: RequiredPreloadN with |s''| raised by
/// its half-width at each node, at the largest deceleration and where the law needs the most
/// preload (those two with the nearest node's), and at LiftLaw::ReachNodes(false); none for a law
/// without a band.
std::optional<double> RequiredPreloadUnsafeN(const LiftLaw& law, const RigidTrain& train,
                                             double omega, double safety_factor,
                                             double overspeed_factor);

/// P₀,req in N (≥ 0) at crank speed ω·overspeed_factor with safety factor S.
double RequiredPreloadN(const LiftLaw& law, const RigidTrain& train, double omega,
                        double safety_factor, double overspeed_factor);

/// Throws std::invalid_argument when the law has no continuous second derivative (pchip,
/// makima): quasi-static forces need acceleration.
void RequireAcceleration(const LiftLaw& law);

}  // namespace needle
