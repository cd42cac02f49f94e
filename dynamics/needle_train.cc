#include "dynamics/needle_train.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace needle {
namespace {

void Require(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok) {
    throw std::invalid_argument("TrainParameters." + field + " = " + std::to_string(value) + ": " +
                                rule);
  }
}

}  // namespace

void TrainParameters::Validate() const {
  Require(mass_kg > 0.0 && std::isfinite(mass_kg), "mass_kg", mass_kg, "must be positive");
  Require(preload_N >= 0.0 && std::isfinite(preload_N), "preload_N", preload_N,
          "must not be negative");
  Require(rate_N_m >= 0.0 && std::isfinite(rate_N_m), "rate_N_m", rate_N_m, "must not be negative");
  Require(std::isfinite(gas_force_N), "gas_force_N", gas_force_N, "must be finite");
  Require(contact_stiffness_N_m > 0.0 && std::isfinite(contact_stiffness_N_m),
          "contact_stiffness_N_m", contact_stiffness_N_m, "must be positive");
  Require(contact_damping_ratio >= 0.0 && std::isfinite(contact_damping_ratio),
          "contact_damping_ratio", contact_damping_ratio, "must not be negative");
  Require(seat_stiffness_N_m > 0.0 && std::isfinite(seat_stiffness_N_m), "seat_stiffness_N_m",
          seat_stiffness_N_m, "must be positive");
  Require(seat_damping_ratio >= 0.0 && std::isfinite(seat_damping_ratio), "seat_damping_ratio",
          seat_damping_ratio, "must not be negative");
}

double TrainParameters::contact_damping() const {
  return 2.0 * contact_damping_ratio * std::sqrt(contact_stiffness_N_m * mass_kg);  // 2ζ√(km)
}

double TrainParameters::seat_damping() const {
  return 2.0 * seat_damping_ratio * std::sqrt(seat_stiffness_N_m * mass_kg);
}

NeedleTrain::NeedleTrain(const CamInput& cam, const TrainParameters& p, double omega,
                         double theta_a_rad)
    : cam_(cam), p_(p), omega_(omega), theta_a_(theta_a_rad) {
  p_.Validate();
  if (!(omega > 0.0) || !std::isfinite(omega)) {
    throw std::invalid_argument("NeedleTrain: ω must be positive, got " + std::to_string(omega));
  }
  c_c_ = p_.contact_damping();
  c_s_ = p_.seat_damping();
}

Contacts NeedleTrain::Evaluate(const TrainState& x, double t) const {
  Contacts c;
  c.crank_rad = Angle(t);
  const double th = CamAngle(c.crank_rad);
  c.u = cam_.U(th);
  c.u_slope = cam_.Slope(th);

  c.g_c = c.u - x[0];                                                // g_c = u − y
  c.g_c_rate = omega_ * c.u_slope - x[1];                            // ġ_c = ω u' − ẏ
  c.f_c_raw = p_.contact_stiffness_N_m * c.g_c + c_c_ * c.g_c_rate;  // k_c g + c_c ġ
  c.g_s = -x[0];                                                     // g_s = −y
  c.g_s_rate = -x[1];
  c.f_s_raw = p_.seat_stiffness_N_m * c.g_s + c_s_ * c.g_s_rate;
  return c;
}

double NeedleTrain::CamAngle(double crank_rad) const {
  // At the end of a segment, the cam's value from the left (its pieces are [a, b)).
  if (crank_rad >= segment_end_) {
    return std::nextafter(segment_end_, -std::numeric_limits<double>::infinity());
  }
  return crank_rad;
}

double NeedleTrain::AppliedCamForce(const Contacts& c) const {
  if (gated_) return c.g_c > 0.0 ? std::max(0.0, c.f_c_raw) : 0.0;  // max(0, k g + c ġ)
  return CamForce(c, mode_);
}

double NeedleTrain::AppliedSeatForce(const Contacts& c) const {
  if (gated_) return c.g_s > 0.0 ? std::max(0.0, c.f_s_raw) : 0.0;
  return SeatForce(c, mode_);
}

void NeedleTrain::Jacobian(const TrainState& x, double t, std::array<double, 16>& J,
                           TrainState& dfdt) const {
  const Contacts c = Evaluate(x, t);
  const double m = p_.mass_kg, w = omega_;
  const double up = c.u_slope, upp = cam_.Curvature(CamAngle(c.crank_rad));
  const double ac = mode_.cam ? 1.0 : 0.0, as = mode_.seat ? 1.0 : 0.0;
  const double kc = p_.contact_stiffness_N_m, ks = p_.seat_stiffness_N_m;
  J.fill(0.0);
  dfdt.fill(0.0);
  J[0 * 4 + 1] = 1.0;                                     // ∂ẏ/∂ẏ
  J[1 * 4 + 0] = (-kc * ac - ks * as - p_.rate_N_m) / m;  // ∂ÿ/∂y
  J[1 * 4 + 1] = (-c_c_ * ac - c_s_ * as) / m;            // ∂ÿ/∂ẏ
  const double fc = ac * c.f_c_raw;
  const double dfc_dt = ac * (kc * w * up + c_c_ * w * w * upp);  // ∂F_c/∂t
  dfdt[1] = dfc_dt / m;
  J[2 * 4 + 0] = -kc * ac * w * up;  // Ẇ = F_c ω u'
  J[2 * 4 + 1] = -c_c_ * ac * w * up;
  dfdt[2] = dfc_dt * w * up + fc * w * w * upp;
  // Ḋ = A_c ġ_c + A_s ġ_s with A = F − k g⁺ (F from the mode). With ∂g_c/∂y = −1,
  // ∂ġ_c/∂ẏ = −1, ∂g_c/∂t = ω u', ∂ġ_c/∂t = ω² u'' (and g_s = −y, ġ_s = −ẏ):
  //   ∂A_c/∂y = −k_c a_c + k_c [g_c > 0],   ∂A_c/∂ẏ = −c_c a_c,
  //   ∂A_c/∂t = a_c (k_c ω u' + c_c ω² u'') − k_c [g_c > 0] ω u'.
  const double pc = c.g_c > 0.0 ? 1.0 : 0.0, ps = c.g_s > 0.0 ? 1.0 : 0.0;
  const double a_c = fc - kc * std::max(0.0, c.g_c);
  const double a_s = as * c.f_s_raw - ks * std::max(0.0, c.g_s);
  J[3 * 4 + 0] = c.g_c_rate * (-kc * ac + kc * pc) + c.g_s_rate * (-ks * as + ks * ps);
  J[3 * 4 + 1] = c.g_c_rate * (-c_c_ * ac) - a_c + c.g_s_rate * (-c_s_ * as) - a_s;
  dfdt[3] = (dfc_dt - kc * pc * w * up) * c.g_c_rate + a_c * w * w * upp;
}

double NeedleTrain::NetForce(const Contacts& c, const TrainState& x) const {
  return AppliedCamForce(c) + AppliedSeatForce(c) - (p_.preload_N + p_.rate_N_m * x[0]) +
         p_.gas_force_N;
}

void NeedleTrain::operator()(const TrainState& x, TrainState& dxdt, double t) const {
  ++evaluations_;
  const Contacts c = Evaluate(x, t);
  const double fc = AppliedCamForce(c), fs = AppliedSeatForce(c);

  dxdt[0] = x[1];
  dxdt[1] = NetForce(c, x) / p_.mass_kg;  // ÿ
  dxdt[2] = fc * omega_ * c.u_slope;      // Ẇ
  const double gc_plus = std::max(0.0, c.g_c), gs_plus = std::max(0.0, c.g_s);
  dxdt[3] = (fc - p_.contact_stiffness_N_m * gc_plus) * c.g_c_rate +
            (fs - p_.seat_stiffness_N_m * gs_plus) * c.g_s_rate;  // Ḋ
}

double NeedleTrain::Energy(const TrainState& x, double t) const {
  const Contacts c = Evaluate(x, t);
  const double y = x[0];
  const double gc = std::max(0.0, c.g_c), gs = std::max(0.0, c.g_s);
  return 0.5 * p_.mass_kg * x[1] * x[1] + p_.preload_N * y + 0.5 * p_.rate_N_m * y * y -
         p_.gas_force_N * y + 0.5 * p_.contact_stiffness_N_m * gc * gc +
         0.5 * p_.seat_stiffness_N_m * gs * gs;
}

double NeedleTrain::EnergyResidual(const TrainState& x0, const TrainState& xt, double t) const {
  const double e0 = Energy(x0, 0.0), e1 = Energy(xt, t);
  const double scale = std::max(std::abs(xt[2]), std::abs(e0));  // max(|W|, |E(0)|)
  return scale > 0.0 ? std::abs(e1 - e0 - xt[2] + xt[3]) / scale : 0.0;
}

TrainState NeedleTrain::EquilibriumStart() const {
  const double net = p_.preload_N - p_.gas_force_N;  // P₀ − F_g
  const double u_a = cam_.U(theta_a_);
  double y0;
  if (cam_.play_m() > 0.0) {
    y0 = -net / (p_.seat_stiffness_N_m + p_.rate_N_m);  // seat only
    if (u_a - y0 > 0.0) {  // the seat sinks below the base circle: cam and seat share the load
      y0 = (p_.contact_stiffness_N_m * u_a - net) /
           (p_.contact_stiffness_N_m + p_.seat_stiffness_N_m + p_.rate_N_m);
    }
  } else {
    y0 = (p_.contact_stiffness_N_m * u_a - net) /
         (p_.contact_stiffness_N_m + p_.seat_stiffness_N_m + p_.rate_N_m);
  }
  return {y0, 0.0, 0.0, 0.0};
}

}  // namespace needle
