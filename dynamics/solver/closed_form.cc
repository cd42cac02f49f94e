#include "dynamics/solver/closed_form.h"

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "dynamics/solver/piece_polynomial.h"
#include "lib/units.h"

namespace needle {
using Poly = ClosedFormPiece::Poly;
using piece_polynomial::Degree;
using piece_polynomial::Eval;
using piece_polynomial::IsZero;
using piece_polynomial::ProductIntegral;
using piece_polynomial::Shift;

ClosedFormPiece::ClosedFormPiece(const NeedleTrain& train, const ContactMode& mode,
                                 double segment_angle_rad, double t0, const TrainState& x0,
                                 const ChainModes* chain)
    : train_(train), mode_(mode), t0_(t0), x0_(x0), chain_(chain) {
  const TrainParameters& p = train.parameters();
  m_ = p.mass_kg;
  c_ = 0.0;
  K_ = p.rate_N_m;
  // The cam input in τ: its segment's polynomial about the origin, shifted to θ(t₀), scaled by ω.
  const CamPiece piece = train.cam().Piece(segment_angle_rad);
  if (piece.coefficients.size() > 7) {
    throw std::invalid_argument("method \"exact\": a cam piece of degree " +
                                std::to_string(piece.coefficients.size() - 1) +
                                " is above the closed form's 6");
  }
  for (size_t k = 0; k < piece.coefficients.size(); ++k) u_[k] = piece.coefficients[k];
  u_ = Shift(u_, train.Angle(t0) - piece.origin_rad);
  double wk = 1.0;
  for (int k = 0; k <= kMaxDegree; ++k, wk *= train.omega()) u_[k] *= wk;

  du_ = piece_polynomial::Derivative(u_);
  f_[0] = -p.preload_N + p.gas_force_N;
  if (mode.cam) {
    const double kc = train.cam_law().ForceStiffness(), cc = train.cam_law().ForceDamping();
    for (int k = 0; k <= kMaxDegree; ++k) f_[k] += kc * u_[k] + cc * du_[k];
    K_ += kc;
    c_ += cc;
  }
  if (mode.seat) {
    K_ += train.seat_law().ForceStiffness();
    c_ += train.seat_law().ForceDamping();
  }
  if (chain_) {
    StartChain();
    return;
  }

  // The particular solution.
  if (K_ > 0.0) {
    for (int j = kMaxDegree; j >= 0; --j) {
      const double a1 = j + 1 <= kMaxDegree ? p_[j + 1] : 0.0;
      const double a2 = j + 2 <= kMaxDegree ? p_[j + 2] : 0.0;
      p_[j] = (f_[j] - c_ * (j + 1) * a1 - m_ * (j + 2) * (j + 1) * a2) / K_;
    }
  } else if (c_ == 0.0) {
    for (int j = 0; j + 2 <= kMaxDegree; ++j) p_[j + 2] = f_[j] / (m_ * (j + 2) * (j + 1));
  } else {
    throw std::logic_error("closed form: damping without stiffness");
  }

  sigma_ = c_ / (2.0 * m_);
  beta_ = K_ / m_ - sigma_ * sigma_;
  root_ = std::sqrt(std::abs(beta_));
  double fastest = std::sqrt(K_ / m_);
  if (beta_ < 0.0) {
    r1_ = -(K_ / m_) / (sigma_ + root_);
    r2_ = -sigma_ - root_;
    fastest = std::max(fastest, -r2_);
  }
  longest_step_ = fastest > 0.0 ? kPi / fastest : std::numeric_limits<double>::infinity();
  SetStart();
}

void ClosedFormPiece::SetStart() {
  dp_ = piece_polynomial::Derivative(p_);
  degree_p_ = Degree(p_);
  degree_dp_ = Degree(dp_);
  degree_u_ = Degree(u_);
  degree_du_ = Degree(du_);
  Y0_ = x0_[0] - p_[0];
  V0_ = x0_[1] - p_[1];
}

void ClosedFormPiece::Basis(double tau, double& ecm1, double& es) const {
  if (tau == basis_tau_) {
    ecm1 = basis_ecm1_;
    es = basis_es_;
    return;
  }
  BasisUncached(tau, ecm1, es);
  basis_tau_ = tau;
  basis_ecm1_ = ecm1;
  basis_es_ = es;
}

void ClosedFormPiece::BasisUncached(double tau, double& ecm1, double& es) const {
  // e^{−στ}C − 1 as (e^{−στ} − 1) + e^{−στ}(C − 1), with C − 1 = −2 sin²(√β τ/2) or
  // 2 sinh²(μτ/2): no cancellation where the motion is slow against the piece.
  // Undamped (σ = 0): e^{−στ} = 1 exactly, and the two calls are left out.
  const double e = sigma_ == 0.0 ? 1.0 : std::exp(-sigma_ * tau);
  const double em1 = sigma_ == 0.0 ? -0.0 : std::expm1(-sigma_ * tau);  // expm1(−0) = −0
  if (beta_ > 0.0) {
    const double half = std::sin(0.5 * root_ * tau);
    ecm1 = em1 - 2.0 * e * half * half;
    es = e * std::sin(root_ * tau) / root_;
  } else if (beta_ == 0.0) {
    ecm1 = em1;
    es = e * tau;
  } else if (root_ * tau < 0.5) {
    const double half = std::sinh(0.5 * root_ * tau);
    ecm1 = em1 + 2.0 * e * half * half;
    es = e * std::sinh(root_ * tau) / root_;
  } else {
    const double e1 = std::exp(r1_ * tau), e2 = std::exp(r2_ * tau);
    ecm1 = 0.5 * (e1 + e2) - 1.0;
    es = (e1 - e2) / (2.0 * root_);
  }
}

std::array<double, 2> ClosedFormPiece::PositionVelocity(double tau) const {
  if (chain_) {
    const ChainNeedle& h = ChainAt(tau);
    return {x0_[0] + (Eval(p_, degree_p_, tau) - p_[0]) + h.dh,
            x0_[1] + (Eval(dp_, degree_dp_, tau) - dp_[0]) + h.dhv};
  }
  double ecm1, es;
  Basis(tau, ecm1, es);
  // Written as the change from (y₀, ẏ₀), with φ₀ − 1 = (e^{−στ}C − 1) + σ e^{−στ}S and
  // φ₁' − 1 = (e^{−στ}C − 1) − σ e^{−στ}S: a large particular part (a soft spring against a
  // large load) does not cancel against a large homogeneous one.
  const double y =
      x0_[0] + (Eval(p_, degree_p_, tau) - p_[0]) + Y0_ * (ecm1 + sigma_ * es) + V0_ * es;
  const double v = x0_[1] + (Eval(dp_, degree_dp_, tau) - dp_[0]) - Y0_ * (K_ / m_) * es +
                   V0_ * (ecm1 - sigma_ * es);
  return {y, v};
}

std::array<double, 3> ClosedFormPiece::Motion(double t) const {
  const double tau = t - t0_;
  const auto [y, v] = PositionVelocity(tau);
  if (chain_) return {y, v, Eval(piece_polynomial::Derivative(dp_), tau) + ChainAt(tau).ha};
  return {y, v, (Eval(f_, tau) - c_ * v - K_ * y) / m_};
}

std::array<double, 2> ClosedFormPiece::Input(double t) const {
  return {Eval(u_, degree_u_, t - t0_), Eval(du_, degree_du_, t - t0_)};
}

double ClosedFormPiece::FormValue(const LinearForm& form, double t) const {
  return FormValue(form, t, PositionVelocity(t - t0_));
}

double ClosedFormPiece::FormValue(const LinearForm& form, double t,
                                  const std::array<double, 2>& yv) const {
  const double tau = t - t0_;
  const auto [y, v] = yv;
  double w = form.y * y + form.v * v + form.constant;
  if (form.u != 0.0) w += form.u * Eval(u_, degree_u_, tau);
  if (form.u_rate != 0.0) w += form.u_rate * Eval(du_, degree_du_, tau);
  return w;
}

TrainState ClosedFormPiece::State(double t) const {
  if (chain_) {
    if (t <= t0_) return x0_;
    TrainState x = ChainState(t - t0_);  // fills dz_, the homogeneous part's change
    const AuditTerms a = ChainAudit(t - t0_, chain_h0_ + dz_);
    x[2] = x0_[2] + a.work_J;
    x[3] = x0_[3] + a.dissipated_J;
    return x;
  }
  const std::array<double, 3> now = Motion(t);
  TrainState x = {now[0], now[1], x0_[2], x0_[3]};
  if (t <= t0_) return x;
  if (!(K_ > 0.0)) return StateByQuadrature(t, 1);
  const AuditTerms a = Audit(t - t0_, now[0], now[1]);
  x[2] += a.work_J;
  x[3] += a.dissipated_J;
  return x;
}

TrainState ClosedFormPiece::StateByQuadrature(double t, int parts) const {
  TrainState x = MotionState(t);
  x[2] = x0_[2];
  x[3] = x0_[3];
  if (t <= t0_) return x;
  using Rule = boost::math::quadrature::gauss<double, 10>;
  const Phase phase{mode_};
  TrainState dxdt;
  const double width = (t - t0_) / parts;
  for (int part = 0; part < parts; ++part) {
    const double half = 0.5 * width, mid = t0_ + (part + 0.5) * width;
    for (size_t i = 0; i < Rule::abscissa().size(); ++i) {
      for (const double sign : {-1.0, 1.0}) {
        const double s = mid + sign * half * Rule::abscissa()[i];
        train_.Derivative(MotionState(s), s, phase, dxdt);
        x[2] += half * Rule::weights()[i] * dxdt[2];
        x[3] += half * Rule::weights()[i] * dxdt[3];
      }
    }
  }
  return x;
}

double ClosedFormPiece::HomogeneousIntegral(const Poly& q, double T, double h1, double hv1) const {
  // J(q) = ∫₀ᵀ q h dτ for h of m h'' + c h' + K h = 0: with h = −(m h'' + c h')/K and
  // integration by parts, J(q) = −(m([q h'] − [q' h] + J(q'')) + c([q h] − J(q')))/K, which ends
  // at the polynomial's degree.
  if (IsZero(q)) return 0.0;
  const Poly q1 = piece_polynomial::Derivative(q), q2 = piece_polynomial::Derivative(q1);
  const double qT = Eval(q, T), q1T = Eval(q1, T);
  const double qh1 = qT * hv1 - q[0] * V0_;   // [q h']
  const double q1h = q1T * h1 - q1[0] * Y0_;  // [q' h]
  const double qh = qT * h1 - q[0] * Y0_;     // [q h]
  double j = m_ * (qh1 - q1h + HomogeneousIntegral(q2, T, h1, hv1)) + c_ * qh;
  if (c_ != 0.0) j -= c_ * HomogeneousIntegral(q1, T, h1, hv1);
  return -j / K_;
}

ClosedFormPiece::AuditTerms ClosedFormPiece::Audit(double T, double y1, double v1) const {
  if (chain_) throw std::logic_error("closed form: a chain's audit is ChainAudit's");
  // y = P + h, h homogeneous (h(0) = Y₀, h'(0) = V₀). Ẇ = F_c u̇ in cam mode; Ḋ = c ġ² for each
  // pushing contact plus the jump of its conservative part, (F − k g⁺) ġ:
  //   ∫ c_total h'² = H(0) − H(T), H = ½ m h'² + ½ K h²  (the homogeneous part's energy);
  //   ∫ q h' = [q h] − ∫ q' h;  ∫ q h by HomogeneousIntegral;  polynomial products exactly;
  //   ∫ (k g − k g⁺) ġ = [½ k min(g, 0)²] in mode, ∫ −k g⁺ ġ = −[½ k max(g, 0)²] out of it.
  double ecm1, es;
  Basis(T, ecm1, es);
  const double h1 = Y0_ * (1.0 + ecm1 + sigma_ * es) + V0_ * es;
  const double hv1 = -Y0_ * (K_ / m_) * es + V0_ * (1.0 + ecm1 - sigma_ * es);
  const auto at = [&](const Poly& q) { return Eval(q, T); };
  // ∫ q h' dτ.
  const auto with_rate = [&](const Poly& q) {
    return at(q) * h1 - q[0] * Y0_ -
           HomogeneousIntegral(piece_polynomial::Derivative(q), T, h1, hv1);
  };
  AuditTerms out;
  const double H0 = 0.5 * m_ * V0_ * V0_ + 0.5 * K_ * Y0_ * Y0_;
  const double H1 = 0.5 * m_ * hv1 * hv1 + 0.5 * K_ * h1 * h1;
  out.dissipated_J = c_ > 0.0 ? H0 - H1 : 0.0;  // ∫ c h'²: H is conserved without damping
  const ContactLaw& cam = train_.cam_law();
  const ContactLaw& seat = train_.seat_law();
  const double kc = cam.ForceStiffness(), cc = cam.ForceDamping();
  const double ks = seat.ForceStiffness(), cs = seat.ForceDamping();
  // Gaps at the ends: g_c = u − y, g_s = −y.
  const double gc0 = u_[0] - x0_[0], gc1 = at(u_) - y1;
  const double gs0 = -x0_[0], gs1 = -y1;
  (void)v1;
  const auto sq = [](double g) { return g * g; };
  if (mode_.cam) {
    Poly rel{};    // u̇ − P'
    Poly force{};  // k_c (u − P) + c_c (u̇ − P')
    for (int k = 0; k <= kMaxDegree; ++k) {
      rel[k] = du_[k] - dp_[k];
      force[k] = kc * (u_[k] - p_[k]) + cc * rel[k];
    }
    out.work_J = ProductIntegral(force, du_, T) - kc * HomogeneousIntegral(du_, T, h1, hv1) -
                 cc * with_rate(du_);
    if (cc != 0.0) out.dissipated_J += cc * (ProductIntegral(rel, rel, T) - 2.0 * with_rate(rel));
    out.dissipated_J += 0.5 * kc * (sq(std::min(gc1, 0.0)) - sq(std::min(gc0, 0.0)));
  } else {
    out.dissipated_J -= 0.5 * kc * (sq(std::max(gc1, 0.0)) - sq(std::max(gc0, 0.0)));
  }
  if (mode_.seat) {
    if (cs != 0.0) out.dissipated_J += cs * (ProductIntegral(dp_, dp_, T) + 2.0 * with_rate(dp_));
    out.dissipated_J += 0.5 * ks * (sq(std::min(gs1, 0.0)) - sq(std::min(gs0, 0.0)));
  } else {
    out.dissipated_J -= 0.5 * ks * (sq(std::max(gs1, 0.0)) - sq(std::max(gs0, 0.0)));
  }
  return out;
}

ClosedFormPiece::Poly ClosedFormPiece::FormPolynomial(const LinearForm& form) const {
  Poly q{};
  for (int k = 0; k <= kMaxDegree; ++k)
    q[k] = form.y * p_[k] + form.v * dp_[k] + form.u * u_[k] + form.u_rate * du_[k];
  return q;
}

ClosedFormPiece::Poly ClosedFormPiece::Shifted(const Poly& q, double t_a) const {
  return Shift(q, t_a - t0_);
}

FormBounds ClosedFormPiece::Bounds(const LinearForm& form, const Poly& q, double t_a,
                                   double t_b) const {
  const double len = t_b - t_a;
  // q′ and q″ (Derivative's products, k·q_k) and their bounds over [0, len] (Horner over
  // |coefficients| from the top one: max |p(s)| over s ∈ [0, len] ≤ Σ |p_k| len^k), on the degrees
  // known from q's.
  const int d = Degree(q);
  double q1[kMaxDegree + 1] = {0.0}, q2[kMaxDegree + 1] = {0.0};
  for (int k = 1; k <= d; ++k) q1[k - 1] = k * q[k];
  for (int k = 1; k <= d - 1; ++k) q2[k - 1] = k * q1[k];
  const auto bound_on = [len](const double* p, int degree) {
    double b = std::abs(p[degree]);
    for (int k = degree - 1; k >= 0; --k) b = b * len + std::abs(p[k]);
    return b;
  };
  const double q1_bound = bound_on(q1, d >= 1 ? d - 1 : 0);
  const double q2_bound = bound_on(q2, d >= 2 ? d - 2 : 0);
  // The homogeneous part h = y − P: its energy H = ½mh'² + ½Kh² at t_a bounds it from there on;
  // over a short interval a Taylor bound from h' and h'' at t_a is tighter.
  const HomogeneousStart& at = StartAt(t_a);
  const double hv = at.hv, ha = at.ha, e1 = at.e1, e2 = at.e2, b3 = at.b3;
  const double b2 = std::min(e2, std::abs(ha) + b3 * len);
  const double b1 = std::min(e1, std::abs(hv) + b2 * len);
  const double safety = 1.0 + 1e-9;  // round-off of the bounds themselves
  FormBounds out;
  out.slope_bound = safety * (q1_bound + std::abs(form.y) * b1 + std::abs(form.v) * b2);
  out.curvature_bound = safety * (q2_bound + std::abs(form.y) * b2 + std::abs(form.v) * b3);
  out.slope_at_start = q1[0] + form.y * hv + form.v * ha;
  return out;
}

std::array<double, 2> ClosedFormPiece::HomogeneousAt(double t) const {
  if (t != cached_t_) {
    double ecm1, es;
    Basis(t - t0_, ecm1, es);
    cached_h_ = {Y0_ * (1.0 + ecm1 + sigma_ * es) + V0_ * es,
                 -Y0_ * (K_ / m_) * es + V0_ * (1.0 + ecm1 - sigma_ * es)};
    cached_t_ = t;
  }
  return cached_h_;
}

const ClosedFormPiece::HomogeneousStart& ClosedFormPiece::StartAt(double t) const {
  if (chain_ && t != start_.t) {
    ChainStart(t);
    return start_;
  }
  if (t != start_.t) {
    const std::array<double, 2> hh = HomogeneousAt(t);
    HomogeneousStart& s = start_;
    s.t = t;
    s.h = hh[0];
    s.hv = hh[1];
    s.ha = (-c_ * s.hv - K_ * s.h) / m_;  // h″
    const double energy = 0.5 * m_ * s.hv * s.hv + 0.5 * K_ * s.h * s.h;
    s.e1 = std::sqrt(2.0 * energy / m_);                     // |h′|
    s.e2 = (c_ * s.e1 + std::sqrt(2.0 * energy * K_)) / m_;  // |h″| = |c h′ + K h| / m
    s.b3 = (c_ * s.e2 + K_ * s.e1) / m_;                     // |h‴| = |c h″ + K h′| / m
    s.lift_amplitude = K_ > 0.0 ? std::sqrt(2.0 * energy / K_) : 0.0;  // |h|
  }
  return start_;
}

double ClosedFormPiece::HomogeneousEnergy(double t) const {
  if (chain_) throw std::logic_error("closed form: a chain's needle has no energy of its own");
  const std::array<double, 2> h = HomogeneousAt(t);
  return 0.5 * m_ * h[1] * h[1] + 0.5 * K_ * h[0] * h[0];
}

int ClosedFormPiece::InputDegree() const {
  for (int k = kMaxDegree; k > 0; --k)
    if (u_[k] != 0.0) return k;
  return 0;
}

bool ClosedFormPiece::ForcingConstant() const {
  for (int k = 1; k <= kMaxDegree; ++k)
    if (f_[k] != 0.0) return false;
  return true;
}

FormRange ClosedFormPiece::Range(const LinearForm& form, const Poly& q, double t_a,
                                 double t_b) const {
  const double len = t_b - t_a;
  // Σ_{k ≥ 1} |q_k| len^k (len and len·len are pow's correctly rounded bits; from len³ on a
  // product would round twice, and the bound's decisions keep their bits only with pow's).
  double spread = 0.0;
  for (int k = Degree(q); k >= 1; --k) {
    if (q[k] != 0.0)
      spread += std::abs(q[k]) * (k == 1 ? len : k == 2 ? len * len : std::pow(len, k));
  }
  // |h| ≤ √(2H/K), |h'| ≤ √(2H/m) from t_a on.
  const HomogeneousStart& at = StartAt(t_a);
  double amplitude = std::abs(form.v) * at.e1;
  if (form.y != 0.0)
    amplitude +=
        K_ > 0.0 ? std::abs(form.y) * at.lift_amplitude : std::numeric_limits<double>::infinity();
  const double mid = q[0] + form.constant;
  const double reach = (1.0 + 1e-9) * (spread + amplitude) + 1e-15 * std::abs(mid);
  return {mid - reach, mid + reach};
}

}  // namespace needle
