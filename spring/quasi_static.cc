#include "spring/quasi_static.h"

#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "lib/spline.h"
#include "lib/units.h"

namespace needle {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Smallest f(θ) on [θ_0, θ_N]: 64 samples per spline piece, then Brent's method on the
// bracket around the best sample. f may be +∞ where it is undefined.
ForceMinimum Minimize(const LiftLaw& law, const std::function<double(double)>& f) {
  const auto& x = law.spline().breaks();
  const int per_piece = 64;
  double best_x = x.front(), best = f(x.front());
  double best_lo = x.front(), best_hi = x.front();
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    for (int k = 0; k <= per_piece; ++k) {
      const double t = x[i] + (x[i + 1] - x[i]) * k / per_piece;
      const double v = f(t);
      if (v < best) {
        best = v;
        best_x = t;
        best_lo = x[i] + (x[i + 1] - x[i]) * std::max(0, k - 1) / per_piece;
        best_hi = x[i] + (x[i + 1] - x[i]) * std::min(per_piece, k + 1) / per_piece;
      }
    }
  }
  if (std::isfinite(best) && best_hi > best_lo) {
    const auto r = boost::math::tools::brent_find_minima(f, best_lo, best_hi, 50);
    if (r.second < best) {
      best = r.second;
      best_x = r.first;
    }
  }
  return {best, best_x};
}

// The law's nodes, its largest deceleration, its deceleration peaks on kinks and the law where
// the quantity banded is most unsafe (`worst`, when the law decelerates): all but the nodes may
// lie between nodes. Each with its band.
std::vector<LocalNode> BandNodes(const LiftLaw& law, const ForceMinimum& worst) {
  std::vector<LocalNode> nodes = law.nodes();
  nodes.push_back(law.ExtremeNode(false));
  for (const LocalNode& kink : law.KinkNodes(false)) nodes.push_back(kink);
  if (std::isfinite(worst.force_N)) nodes.push_back(law.NodeAt(worst.crank_rad));
  return nodes;
}

// The least spring reserve at ω = 1 rad/s, g(θ) = (P₀ + k s − F_g)/(m |s''|) where s'' < 0
// (n_qs = (60/2π)·√(min g)), and where.
ForceMinimum MinSpringReserve(const LiftLaw& law, const RigidTrain& train) {
  return Minimize(
      law, [&](double th) { return train.SpringReserve(law.Lift(th), law.Derivative(th, 2)); });
}

// n_qs of the least spring reserve g: +∞ where none decelerates, 0 where g ≤ 0.
double RpmOfReserve(double g) {
  if (!std::isfinite(g)) return kInf;
  if (g <= 0.0) return 0.0;
  return 60.0 / (2.0 * kPi) * std::sqrt(g);  // ω → rpm
}

// −h(θ) minimised ⇔ h(θ) = S m (fω)² |s''| − k s + F_g maximised where s'' < 0: minus the
// preload required, and where.
ForceMinimum MinMinusRequired(const LiftLaw& law, const RigidTrain& train, double w,
                              double safety_factor) {
  return Minimize(law, [&](double th) {
    const double s2 = law.Derivative(th, 2);
    if (!(s2 < 0.0)) return kInf;
    return -(safety_factor * train.mass_kg * w * w * -s2 - train.rate_N_m * law.Lift(th) +
             train.gas_force_N);
  });
}

// The preload required from MinMinusRequired's result: F_g alone where the law never
// decelerates; never below 0.
double RequiredOf(const ForceMinimum& m, const RigidTrain& train) {
  if (!std::isfinite(m.force_N)) return std::max(0.0, train.gas_force_N);
  return std::max(0.0, -m.force_N);
}

}  // namespace

void RequireAcceleration(const LiftLaw& law) {
  if (!law.HasAcceleration()) {
    throw std::invalid_argument(
        "the " + SplineKindName(law.kind()) +
        " spline is C1 only and has no acceleration; quasi-static forces "
        "need a C2 spline (not-a-knot, natural, clamped, quintic, smoothing)");
  }
}

double QuasiStaticForce(const LiftLaw& law, const RigidTrain& train, double omega,
                        double crank_rad) {
  const double a = omega * omega * law.Derivative(crank_rad, 2);  // a = ω² s''
  return train.ContactForceN(law.Lift(crank_rad), a);
}

ForceMinimum MinQuasiStaticForce(const LiftLaw& law, const RigidTrain& train, double omega) {
  RequireAcceleration(law);
  train.Validate();
  return Minimize(law, [&](double th) { return QuasiStaticForce(law, train, omega, th); });
}

double QuasiStaticLiftoffRpm(const LiftLaw& law, const RigidTrain& train) {
  RequireAcceleration(law);
  train.Validate();
  return RpmOfReserve(MinSpringReserve(law, train).force_N);
}

double RequiredPreloadN(const LiftLaw& law, const RigidTrain& train, double omega,
                        double safety_factor, double overspeed_factor) {
  RequireAcceleration(law);
  train.Validate();
  return RequiredOf(MinMinusRequired(law, train, overspeed_factor * omega, safety_factor), train);
}

std::optional<ExtremumBand> QuasiStaticLiftoffBand(const LiftLaw& law, const RigidTrain& train) {
  if (law.nodes().empty()) return std::nullopt;
  RequireAcceleration(law);
  train.Validate();
  const ForceMinimum m = MinSpringReserve(law, train);
  const double n_qs = RpmOfReserve(m.force_N);
  double low = kInf, high = kInf;  // min of the reserve at the band's two ends
  for (const LocalNode& n : BandNodes(law, m)) {
    low = std::min(low, train.SpringReserve(n.s[0], n.s[2] - n.band2));
    high = std::min(high, train.SpringReserve(n.s[0], n.s[2] + n.band2));
  }
  for (const LocalNode& n : law.ReachNodes(false))  // the unsafe end only
    low = std::min(low, train.SpringReserve(n.s[0], n.s[2] - n.band2));
  return ExtremumBand{std::min(RpmOfReserve(low), n_qs), std::max(RpmOfReserve(high), n_qs)};
}

std::optional<double> RequiredPreloadUnsafeN(const LiftLaw& law, const RigidTrain& train,
                                             double omega, double safety_factor,
                                             double overspeed_factor) {
  if (law.nodes().empty()) return std::nullopt;
  RequireAcceleration(law);
  train.Validate();
  const double w = overspeed_factor * omega;
  const ForceMinimum m = MinMinusRequired(law, train, w, safety_factor);
  double required = RequiredOf(m, train);
  std::vector<LocalNode> nodes = BandNodes(law, m);
  nodes.insert(nodes.end(), law.ReachNodes(false).begin(), law.ReachNodes(false).end());
  for (const LocalNode& n : nodes) {
    const double s2 = n.s[2] - n.band2;  // the deceleration's unsafe end
    if (s2 < 0.0) {
      required = std::max(required, safety_factor * train.mass_kg * w * w * -s2 -
                                        train.rate_N_m * n.s[0] + train.gas_force_N);
    }
  }
  return required;
}

}  // namespace needle
