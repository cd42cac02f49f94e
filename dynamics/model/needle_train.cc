#include "dynamics/model/needle_train.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "lib/field_error.h"
#include "lib/units.h"
#include "spring/resonance.h"

namespace needle {
namespace {

void Require(bool ok, const std::string& field, double value, const std::string& rule) {
  FieldRules{"TrainParameters"}(ok, field, value, rule);
}

}  // namespace

void ContactParameters::Validate() const { ValidateContacts("ContactParameters"); }

void ContactParameters::ValidateContacts(const char* owner) const {
  const FieldRules require{owner};
  if (contact == ContactKind::kCompliant) {  // the compliant law's own parameters
    require(contact_stiffness_N_m > 0.0 && std::isfinite(contact_stiffness_N_m),
            "contact_stiffness_N_m", contact_stiffness_N_m, "must be positive");
    require(contact_damping_ratio >= 0.0 && std::isfinite(contact_damping_ratio),
            "contact_damping_ratio", contact_damping_ratio, "must not be negative");
    require(seat_stiffness_N_m > 0.0 && std::isfinite(seat_stiffness_N_m), "seat_stiffness_N_m",
            seat_stiffness_N_m, "must be positive");
    require(seat_damping_ratio >= 0.0 && std::isfinite(seat_damping_ratio), "seat_damping_ratio",
            seat_damping_ratio, "must not be negative");
  }
  require(restitution >= 0.0 && restitution <= 1.0, "restitution", restitution,
          "must be in [0, 1]");
  require(seat_restitution >= 0.0 && seat_restitution <= 1.0, "seat_restitution", seat_restitution,
          "must be in [0, 1]");
}

void TrainParameters::Validate() const {
  Require(mass_kg > 0.0 && std::isfinite(mass_kg), "mass_kg", mass_kg, "must be positive");
  Require(preload_N >= 0.0 && std::isfinite(preload_N), "preload_N", preload_N,
          "must not be negative");
  Require(rate_N_m >= 0.0 && std::isfinite(rate_N_m), "rate_N_m", rate_N_m, "must not be negative");
  Require(std::isfinite(gas_force_N), "gas_force_N", gas_force_N, "must be finite");
  ValidateContacts("TrainParameters");
  Require(coil_masses >= 1 && coil_masses <= kMaxCoilMasses, "coil_masses", coil_masses,
          "must be in [1, " + std::to_string(kMaxCoilMasses) + "]");
  if (coil_masses > 1) {  // the chain's own parameters
    Require(rate_N_m > 0.0, "rate_N_m", rate_N_m, "must be positive for a chain of coil masses");
    Require(spring_mass_kg > 0.0 && spring_mass_kg < 3.0 * mass_kg, "spring_mass_kg",
            spring_mass_kg,
            "must be positive and below 3 mass_kg (mass_kg includes a third of the spring)");
    Require(surge_damping_ratio >= 0.0 && surge_damping_ratio <= 1.0, "surge_damping_ratio",
            surge_damping_ratio, "must be in [0, 1]");
  }
  Require(coil_travel_m >= 0.0 && std::isfinite(coil_travel_m), "coil_travel_m", coil_travel_m,
          "must not be negative");
  if (coil_clash) {  // the clash contact's own parameters
    Require(coil_masses > 1, "coil_masses", coil_masses,
            "must be at least 2 for coil_clash (the coils that meet)");
    Require(coil_travel_m > 0.0, "coil_travel_m", coil_travel_m,
            "must be positive for coil_clash (the travel to solid)");
    Require(clash_stiffness_N_m > 0.0 && std::isfinite(clash_stiffness_N_m), "clash_stiffness_N_m",
            clash_stiffness_N_m, "must be positive");
    Require(clash_damping_ratio >= 0.0 && std::isfinite(clash_damping_ratio), "clash_damping_ratio",
            clash_damping_ratio, "must not be negative");
  }
}

NeedleTrain::NeedleTrain(const CamInput& cam, const TrainParameters& p, double omega,
                         double theta_a_rad, std::shared_ptr<const ContactLaw> cam_law,
                         std::shared_ptr<const ContactLaw> seat_law)
    : cam_(cam), p_(p), omega_(omega), theta_a_(theta_a_rad) {
  p_.Validate();
  if (!(omega > 0.0) || !std::isfinite(omega)) {
    throw std::invalid_argument("NeedleTrain: ω must be positive, got " + std::to_string(omega));
  }
  const bool rigid = p_.contact == ContactKind::kRigid;
  coils_ = p_.coil_masses - 1;
  needle_mass_kg_ = p_.mass_kg;
  if (coils_ > 0) {
    const double n = p_.coil_masses, m_s = p_.spring_mass_kg;
    needle_mass_kg_ = p_.mass_kg - m_s / 3.0 + m_s / (2.0 * n);
    coil_mass_kg_ = m_s / n;
    segment_rate_N_m_ = n * p_.rate_N_m;
    const double omega_1 = 2.0 * kPi * SurgeFrequencyHz(p_.rate_N_m, m_s, 1);  // π√(k/m_s)
    segment_damping_N_s_m_ = 2.0 * p_.surge_damping_ratio * segment_rate_N_m_ / omega_1;
    segment_travel_m_ = p_.coil_travel_m / n;
    if (p_.coil_clash) {
      clash_law_ = std::make_shared<CompliantContact>(p_.clash_stiffness_N_m,
                                                      p_.clash_damping_ratio, coil_mass_kg_);
    }
  }
  if (cam_law) {
    cam_law_ = std::move(cam_law);
  } else if (rigid) {
    cam_law_ = std::make_shared<RigidContact>(p_.restitution);
  } else {
    cam_law_ = std::make_shared<CompliantContact>(p_.contact_stiffness_N_m,
                                                  p_.contact_damping_ratio, needle_mass_kg_);
  }
  if (seat_law) {
    seat_law_ = std::move(seat_law);
  } else if (rigid) {
    seat_law_ = std::make_shared<RigidContact>(p_.seat_restitution);
  } else {
    seat_law_ = std::make_shared<CompliantContact>(p_.seat_stiffness_N_m, p_.seat_damping_ratio,
                                                   needle_mass_kg_);
  }
  cam_rigid_ = cam_law_->Constraint();
  seat_rigid_ = seat_law_->Constraint();
  const std::vector<double>& lift = cam_.law().table().lift_m;
  const double top = lift.empty() ? 0.0 : *std::max_element(lift.begin(), lift.end());
  gap_tolerance_ = 1e-14 * std::max(top + cam_.play_m(), 1e-6);
  lift_energy_J_ = std::abs(p_.preload_N * top + 0.5 * p_.rate_N_m * top * top);
}

Contacts NeedleTrain::Evaluate(const TrainState& x, double t, const Phase& phase) const {
  return EvaluateWith(x, t, phase, nullptr, nullptr);
}

Contacts NeedleTrain::EvaluateWith(const TrainState& x, double t, const Phase& phase,
                                   double* coil_rates, double* dissipation_W) const {
  Contacts c;
  c.crank_rad = Angle(t);
  const double th = CamAngle(c.crank_rad, phase);
  const auto [u, u_slope] = cam_.USlope(th);
  c.u = u;
  c.u_slope = u_slope;

  c.y = x[0];
  c.v = x[1];
  if (cam_rigid_ && phase.mode.cam) {
    c.y = c.u;
    c.v = omega_ * c.u_slope;
  } else if (seat_rigid_ && phase.mode.seat) {
    c.y = c.v = 0.0;
  }
  c.g_c = c.u - c.y;                      // g_c = u − y
  c.g_c_rate = omega_ * c.u_slope - c.v;  // ġ_c = ω u' − ẏ
  c.f_c_raw = cam_law_->Force(c.g_c, c.g_c_rate);
  c.g_s = -c.y;  // g_s = −y
  c.g_s_rate = -c.v;
  c.f_s_raw = seat_law_->Force(c.g_s, c.g_s_rate);
  c.spring_N = SpringForce(x, c.y, c.v, phase, coil_rates, dissipation_W);
  if (cam_rigid_ || seat_rigid_) {
    // Constraint forces: what keeps the needle on a surface it sticks to, from
    // m ÿ = F_c + F_s − S + F_g with ÿ = ω² u'' on the cam and 0 on the seat.
    const double load = c.spring_N - p_.gas_force_N;
    if (cam_rigid_) {
      const double seat_push = !seat_rigid_ && phase.mode.seat ? c.f_s_raw : 0.0;
      c.f_c_raw = needle_mass_kg_ * omega_ * omega_ * cam_.Curvature(th) + load - seat_push;
    }
    if (seat_rigid_) {
      // A cam that sticks carries the whole load (its λ includes it): the seat lets go.
      const double cam_push = phase.mode.cam ? c.f_c_raw : 0.0;
      c.f_s_raw = load - cam_push;
    }
  }
  return c;
}

double NeedleTrain::SpringForce(const TrainState& x, double y, double v, const Phase& phase,
                                double* coil_rates, double* dissipation_W) const {
  if (coils_ == 0) return p_.preload_N + p_.rate_N_m * y;
  // Nodes 0 (the needle) … N (the spring's fixed end); segment j joins nodes j − 1 and j and
  // pushes them apart with S_j − P₀ (the preload cancels between segments).
  const int n = coils_ + 1;
  const double k = segment_rate_N_m_, c = segment_damping_N_s_m_;
  // Walking the nodes (SegmentMotion's values): node j − 1's lift and velocity carried over;
  // compiled twice, with the clash law and without it (this walk is most of a coil chain's
  // right-hand side).
  const auto walk = [&](auto clash) {
    const double* lifts = x.data() + 4;            // x_i = x[3 + i], i = 1 … N − 1
    const double* speeds = x.data() + 4 + coils_;  // v_i = x[3 + N − 1 + i]
    double lift_before = y, speed_before = v, power = 0.0;
    // Segment j between the last node and one at (lift, speed): S_j − P₀, its dashpot's and
    // clash contact's power added.
    const auto segment = [&](int j, double lift, double speed) {
      const double s = lift_before - lift, rate = speed_before - speed;
      lift_before = lift;
      speed_before = speed;
      double s_j = k * s + c * rate;
      power += c * rate * rate;
      if constexpr (decltype(clash)::value) {  // the coils in contact: F on the mode's (or the
        // gate's) branch
        const double g = s - segment_travel_m_;
        const double f = phase.gated           ? clash_law_->GatedForce(g, rate)
                         : phase.mode.Solid(j) ? clash_law_->Force(g, rate)
                                               : 0.0;
        s_j += f;
        power += (f - clash_law_->ConservativeForce(g)) * rate;
      }
      return s_j;
    };
    const double s_1 = segment(1, lifts[0], speeds[0]);
    if (!coil_rates && !dissipation_W) return p_.preload_N + s_1;  // the force at the needle
    double s_prev = s_1;
    for (int j = 2; j < n; ++j) {  // the inner segments (the last one, at the fixed end, below)
      const double s_j = segment(j, lifts[j - 1], speeds[j - 1]);
      if (coil_rates) coil_rates[j - 2] = (s_prev - s_j) / coil_mass_kg_;
      s_prev = s_j;
    }
    const double s_n = segment(n, 0.0, 0.0);
    if (coil_rates) coil_rates[n - 2] = (s_prev - s_n) / coil_mass_kg_;
    if (dissipation_W) *dissipation_W = power;
    return p_.preload_N + s_1;
  };
  return clash_law_ ? walk(std::true_type{}) : walk(std::false_type{});
}

std::array<double, 2> NeedleTrain::SegmentPenetration(const TrainState& x, const Contacts& c,
                                                      int j) const {
  const auto [s, rate] = SegmentMotion(x, c.y, c.v, j);
  return {s - segment_travel_m_, rate};
}

double NeedleTrain::LargestCoilSpeed(const TrainState& x) const {
  double v = 0.0;
  for (int i = 0; i < coils_; ++i) v = std::max(v, std::abs(x[4 + coils_ + i]));
  return v;
}

double NeedleTrain::LargestSegmentCompression(const TrainState& x) const {
  if (coils_ == 0) return x[0];
  double most = -std::numeric_limits<double>::infinity();
  double lift_before = x[0];  // node j − 1's lift (SegmentMotion's s_j, walking the nodes)
  for (int j = 1; j <= coils_ + 1; ++j) {
    const double lift = j == coils_ + 1 ? 0.0 : x[3 + j];
    most = std::max(most, lift_before - lift);
    lift_before = lift;
  }
  return most;
}

double NeedleTrain::CamAngle(double crank_rad, const Phase& phase) const {
  // At the end of a segment, the cam's value from the left (its pieces are [a, b)).
  if (crank_rad >= phase.segment_end_rad) {
    return std::nextafter(phase.segment_end_rad, -std::numeric_limits<double>::infinity());
  }
  return crank_rad;
}

double NeedleTrain::AppliedCamForce(const Contacts& c, const Phase& phase) const {
  if (phase.gated) return cam_law_->GatedForce(c.g_c, c.g_c_rate);
  return phase.mode.cam ? c.f_c_raw : 0.0;
}

double NeedleTrain::AppliedSeatForce(const Contacts& c, const Phase& phase) const {
  if (phase.gated) return seat_law_->GatedForce(c.g_s, c.g_s_rate);
  return phase.mode.seat ? c.f_s_raw : 0.0;
}

double NeedleTrain::NetForce(const Contacts& c, const Phase& phase) const {
  return AppliedCamForce(c, phase) + AppliedSeatForce(c, phase) - c.spring_N + p_.gas_force_N;
}

void NeedleTrain::Derivative(const TrainState& x, double t, const Phase& phase, TrainState& dxdt,
                             Contacts* at) const {
  dxdt.resize(x.size());
  double dashpots_W = 0.0;
  const Contacts c = coils_ > 0 ? EvaluateWith(x, t, phase, &dxdt[4 + coils_], &dashpots_W)  // v̇_i
                                : Evaluate(x, t, phase);
  const double fc = AppliedCamForce(c, phase), fs = AppliedSeatForce(c, phase);
  dxdt[0] = c.v;                                   // ẏ (the surface's while stuck to it)
  dxdt[1] = NetForce(c, phase) / needle_mass_kg_;  // ÿ
  dxdt[2] = fc * omega_ * c.u_slope;               // Ẇ
  dxdt[3] = (fc - cam_law_->ConservativeForce(c.g_c)) * c.g_c_rate +
            (fs - seat_law_->ConservativeForce(c.g_s)) * c.g_s_rate;  // Ḋ
  if (coils_ > 0) {
    for (int i = 0; i < coils_; ++i) dxdt[4 + i] = x[4 + coils_ + i];  // ẋ_i = v_i
    dxdt[3] += dashpots_W;
  }
  if (at) *at = c;
}

double NeedleTrain::Energy(const TrainState& x, double t) const {
  const Contacts c = Evaluate(x, t);
  const double y = x[0];
  double spring_J = 0.5 * p_.rate_N_m * y * y;
  if (coils_ > 0) {  // ½ K Σ s_j² (+ the clash potentials V(s_j − δ)) + ½ m_c Σ v_i²
    spring_J = 0.0;
    for (int j = 1; j <= coils_ + 1; ++j) {
      const double s = SegmentMotion(x, y, x[1], j)[0];
      spring_J += 0.5 * segment_rate_N_m_ * s * s;
      if (clash_law_) spring_J += clash_law_->Potential(s - segment_travel_m_);
    }
    for (int i = 0; i < coils_; ++i)
      spring_J += 0.5 * coil_mass_kg_ * x[4 + coils_ + i] * x[4 + coils_ + i];
  }
  return 0.5 * needle_mass_kg_ * x[1] * x[1] + p_.preload_N * y + spring_J - p_.gas_force_N * y +
         cam_law_->Potential(c.g_c) + seat_law_->Potential(c.g_s);
}

double NeedleTrain::EnergyResidual(const TrainState& x0, const TrainState& xt, double t) const {
  const double e0 = Energy(x0, 0.0), e1 = Energy(xt, t);
  // max(|W|, |E(0)|, P₀L + ½kL²): W of a needle that follows its cam all the way is ~0.
  const double scale = std::max({std::abs(xt[2]), std::abs(e0), lift_energy_J_});
  return scale > 0.0 ? std::abs(e1 - e0 - xt[2] + xt[3]) / scale : 0.0;
}

std::optional<TrainState> NeedleTrain::Reset(bool cam, const TrainState& x, double t,
                                             const Phase& phase) const {
  const Contacts c = Evaluate(x, t, phase);
  const ContactLaw& law = cam ? *cam_law_ : *seat_law_;
  const double before = cam ? c.g_c_rate : c.g_s_rate;
  std::optional<double> after = law.ImpactRate(before);
  if (!after) return std::nullopt;
  TrainState out = x;
  if (law.Constraint()) {
    out[0] = cam ? c.u : 0.0;             // on the surface: g = 0
    if (!(before > 0.0)) after = before;  // a touch without approach: no impulse
  }
  // ġ_c = ω u' − ẏ and ġ_s = −ẏ: the needle's velocity after, from the gap rate after.
  const double surface = cam ? omega_ * c.u_slope : 0.0;  // the contact surface's velocity
  out[1] = surface - *after;
  const double m = needle_mass_kg_;            // the coils take no impulse: springs join them
  const double impulse = m * (out[1] - x[1]);  // N·s on the needle
  const double work = impulse * surface;       // ΔW
  const double kinetic = 0.5 * m * (out[1] * out[1] - x[1] * x[1]);  // ΔE
  out[2] += work;
  out[3] += work - kinetic;  // ΔD = ΔW − ΔE: the audit closes across the impact
  return out;
}

ContactMode NeedleTrain::StickingMode(const TrainState& x, double t, const Phase& phase) const {
  ContactMode mode = phase.mode;
  const auto sticks = [&](double g, double g_rate) {
    return std::abs(g) <= gap_tolerance_ && std::abs(g_rate) <= RateTolerance();
  };
  // The cam first: a cam that sticks carries the load, and the seat's λ depends on it.
  if (cam_rigid_) {
    Phase free = phase;  // the needle's own motion: no rigid contact holding it
    free.mode.cam = false;
    free.mode.seat = phase.mode.seat && !seat_rigid_;
    const Contacts c = Evaluate(x, t, free);
    mode.cam = sticks(c.g_c, c.g_c_rate) && c.f_c_raw > 0.0;
  }
  if (seat_rigid_) {
    Phase with_cam = phase;
    with_cam.mode = {mode.cam, false};
    const Contacts c = Evaluate(x, t, with_cam);
    mode.seat = sticks(c.g_s, c.g_s_rate) && c.f_s_raw > 0.0;
  }
  return mode;
}

TrainState NeedleTrain::Project(const TrainState& x, double t, const Phase& phase) const {
  // Evaluate puts the needle on the surface of a sticking rigid contact (Contacts::y, v).
  const Contacts c = Evaluate(x, t, phase);
  TrainState out = x;
  out[0] = c.y;
  out[1] = c.v;
  out[3] -= Energy(out, t) - Energy(x, t);  // what the projection takes is dissipated
  return out;
}

double NeedleTrain::FastestAngularFrequency() const {
  // Rigid contacts add no stiffness; the cam's own speed bounds it from below.
  const double rate = coils_ > 0 ? segment_rate_N_m_ : p_.rate_N_m;
  const double needle = std::sqrt(
      (cam_law_->ForceStiffness() + seat_law_->ForceStiffness() + rate) / needle_mass_kg_);
  const double clash = clash_law_ ? clash_law_->ForceStiffness() : 0.0;
  const double chain =
      coils_ > 0 ? 2.0 * std::sqrt((segment_rate_N_m_ + clash) / coil_mass_kg_) : 0.0;
  return std::max({omega_, needle, chain});
}

TrainState NeedleTrain::EquilibriumStart() const {
  const double net = p_.preload_N - p_.gas_force_N;  // P₀ − F_g
  const double u_a = cam_.U(theta_a_);
  double y0;
  if (HasConstraint()) {
    y0 = std::max(0.0, u_a);  // on the seat, or on the cam where it stands above the seat
  } else if (cam_.play_m() > 0.0) {
    y0 = -net / (p_.seat_stiffness_N_m + p_.rate_N_m);  // seat only
    if (u_a - y0 > 0.0) {  // the seat sinks below the base circle: cam and seat share the load
      y0 = (p_.contact_stiffness_N_m * u_a - net) /
           (p_.contact_stiffness_N_m + p_.seat_stiffness_N_m + p_.rate_N_m);
    }
  } else {
    y0 = (p_.contact_stiffness_N_m * u_a - net) /
         (p_.contact_stiffness_N_m + p_.seat_stiffness_N_m + p_.rate_N_m);
  }
  TrainState x0 = {y0, 0.0, 0.0, 0.0};
  // The chain evenly compressed: node i of N at y₀ (N − i)/N, at rest.
  for (int i = 1; i <= coils_; ++i) x0.push_back(y0 * (coils_ + 1 - i) / (coils_ + 1));
  for (int i = 1; i <= coils_; ++i) x0.push_back(0.0);
  return x0;
}

}  // namespace needle
