// The train's Jacobian ∂f/∂x and ∂f/∂t (dynamics/model/needle_train.h) for the implicit methods:
// the needle's rows, the audit integrals' and the chain's coils'.
#include "dynamics/model/needle_train.h"

namespace needle {

void NeedleTrain::Jacobian(const TrainState& x, double t, const Phase& phase, TrainJacobian& J,
                           TrainState& dfdt) const {
  const Contacts c = Evaluate(x, t, phase);
  const int n = StateSize();
  const double m = needle_mass_kg_, w = omega_;
  const double up = c.u_slope, upp = cam_.Curvature(CamAngle(c.crank_rad, phase));
  const double ac = phase.mode.cam ? 1.0 : 0.0, as = phase.mode.seat ? 1.0 : 0.0;
  const double kc = cam_law_->ForceStiffness(), ks = seat_law_->ForceStiffness();
  const double cc = cam_law_->ForceDamping(), cs = seat_law_->ForceDamping();
  // Segment 1 (or the massless spring) acts on the needle.
  const double kr = coils_ > 0 ? SegmentStiffness(1, phase) : p_.rate_N_m;
  const double cr = coils_ > 0 ? SegmentDamping(1, phase) : 0.0;
  J.assign(static_cast<size_t>(n) * n, 0.0);
  dfdt.assign(n, 0.0);
  const auto at = [&](int r, int col) -> double& { return J[r * n + col]; };
  at(0, 1) = 1.0;                            // ∂ẏ/∂ẏ
  at(1, 0) = (-kc * ac - ks * as - kr) / m;  // ∂ÿ/∂y
  at(1, 1) = (-cc * ac - cs * as - cr) / m;  // ∂ÿ/∂ẏ
  const double fc = ac * c.f_c_raw;
  const double dfc_dt = ac * (kc * w * up + cc * w * w * upp);  // ∂F_c/∂t
  dfdt[1] = dfc_dt / m;
  at(2, 0) = -kc * ac * w * up;  // Ẇ = F_c ω u'
  at(2, 1) = -cc * ac * w * up;
  dfdt[2] = dfc_dt * w * up + fc * w * w * upp;
  // Ḋ = A_c ġ_c + A_s ġ_s with A = F − V'(g) (F from the mode). With ∂g_c/∂y = −1,
  // ∂ġ_c/∂ẏ = −1, ∂g_c/∂t = ω u', ∂ġ_c/∂t = ω² u'' (and g_s = −y, ġ_s = −ẏ):
  //   ∂A_c/∂y = −k_c a_c + V_c'',   ∂A_c/∂ẏ = −c_c a_c,
  //   ∂A_c/∂t = a_c (k_c ω u' + c_c ω² u'') − V_c'' ω u'.
  const double vc = cam_law_->ConservativeStiffness(c.g_c);
  const double vs = seat_law_->ConservativeStiffness(c.g_s);
  const double a_c = fc - cam_law_->ConservativeForce(c.g_c);
  const double a_s = as * c.f_s_raw - seat_law_->ConservativeForce(c.g_s);
  at(3, 0) = c.g_c_rate * (-kc * ac + vc) + c.g_s_rate * (-ks * as + vs);
  at(3, 1) = c.g_c_rate * (-cc * ac) - a_c + c.g_s_rate * (-cs * as) - a_s;
  dfdt[3] = (dfc_dt - vc * w * up) * c.g_c_rate + a_c * w * w * upp;
  // A sticking rigid contact: ÿ is the surface's (ω² u'' or 0), F = λ with ∂λ/∂y = k.
  const bool cam_stuck = cam_rigid_ && phase.mode.cam;
  const bool stuck = cam_stuck || (seat_rigid_ && phase.mode.seat);
  if (stuck) {
    // ẏ = ω u', ÿ = ω² u'' on the cam (0 on the seat): functions of t alone.
    const double uppp = cam_stuck ? cam_.Jerk(CamAngle(c.crank_rad, phase)) : 0.0;
    at(0, 1) = at(1, 0) = at(1, 1) = 0.0;  // ẏ, ÿ: the surface's, not the state's
    dfdt[0] = cam_stuck ? w * w * upp : 0.0;
    dfdt[1] = cam_stuck ? w * w * w * uppp : 0.0;
    if (cam_stuck) {  // Ẇ = λ ω u', λ = m ω² u'' + P₀ + k u − F_g: y is the surface's, u
      at(2, 0) = at(2, 1) = 0.0;
      dfdt[2] = (m * w * w * w * uppp + p_.rate_N_m * w * up) * w * up + fc * w * w * upp;
    }
    // Ḋ: the stuck contact's gap rate is zero, and the other's follows the surface, not y, ẏ.
    at(3, 0) = at(3, 1) = dfdt[3] = 0.0;
  }
  if (coils_ > 0) ChainJacobian(x, c, phase, upp, J, dfdt);
}

double NeedleTrain::SegmentStiffness(int j, const Phase& phase) const {
  const bool solid = clash_law_ && phase.mode.Solid(j);
  return segment_rate_N_m_ + (solid ? clash_law_->ForceStiffness() : 0.0);
}

double NeedleTrain::SegmentDamping(int j, const Phase& phase) const {
  const bool solid = clash_law_ && phase.mode.Solid(j);
  return segment_damping_N_s_m_ + (solid ? clash_law_->ForceDamping() : 0.0);
}

void NeedleTrain::ChainJacobian(const TrainState& x, const Contacts& c, const Phase& phase,
                                double upp, TrainJacobian& J, TrainState& dfdt) const {
  const int n = StateSize();
  const double m = needle_mass_kg_, w = omega_, up = c.u_slope;
  const bool cam_stuck = cam_rigid_ && phase.mode.cam;
  const bool stuck = cam_stuck || (seat_rigid_ && phase.mode.seat);
  const auto at = [&](int r, int col) -> double& { return J[r * n + col]; };
  const auto solid = [&](int j) { return clash_law_ && phase.mode.Solid(j); };
  const auto seg_k = [&](int j) { return SegmentStiffness(j, phase); };
  const auto seg_c = [&](int j) { return SegmentDamping(j, phase); };
  const double kr = seg_k(1), cr = seg_c(1);
  // The chain. Node 0 is the needle (columns 0 and 1, or the surface's motion while it sticks:
  // then its lift and velocity change with t at ω u' and ω² u''), nodes 1…N−1 the coils, node
  // N the fixed end. Segment j (nodes j − 1, j) pushes them apart with
  // S_j = P₀ + K (x_{j−1} − x_j) + C (v_{j−1} − v_j).
  const int nodes = coils_ + 1;
  const double mc = coil_mass_kg_;
  const double node0_rate = cam_stuck ? w * up : 0.0, node0_accel = cam_stuck ? w * w * upp : 0.0;
  const auto pos_col = [&](int i) { return i == 0 ? (stuck ? -1 : 0) : (i == nodes ? -1 : 3 + i); };
  const auto vel_col = [&](int i) {
    return i == 0 ? (stuck ? -1 : 1) : (i == nodes ? -1 : 3 + coils_ + i);
  };
  // Adds g·∂(node i's lift)/∂· and h·∂(its velocity)/∂· to row r.
  const auto add = [&](int r, int i, double g, double h) {
    if (pos_col(i) >= 0) at(r, pos_col(i)) += g;
    if (vel_col(i) >= 0) at(r, vel_col(i)) += h;
    if (i == 0 && stuck) dfdt[r] += g * node0_rate + h * node0_accel;
  };
  if (!stuck) {  // the needle's row: −S_1 depends on x_1, v_1 too
    add(1, 1, kr / m, cr / m);
  } else if (cam_stuck) {  // Ẇ = λ ω u', λ ∋ S_1
    add(2, 1, -kr * w * up, -cr * w * up);
  }
  for (int i = 1; i < nodes; ++i) {
    at(3 + i, 3 + coils_ + i) = 1.0;  // ẋ_i = v_i
    const int r = 3 + coils_ + i;     // v̇_i = (S_i − S_{i+1}) / m_c
    const double ka = seg_k(i), ca = seg_c(i), kb = seg_k(i + 1), cb = seg_c(i + 1);
    add(r, i - 1, ka / mc, ca / mc);
    add(r, i, -(ka + kb) / mc, -(ca + cb) / mc);
    add(r, i + 1, kb / mc, cb / mc);
  }
  // Ḋ ∋ Σ_j C ṡ_j² + (F_j − V'(g_j)) ṡ_j, F_j the clash force of the mode, g_j = s_j − δ.
  const double y0 = stuck ? c.y : x[0], v0 = stuck ? c.v : x[1];
  for (int j = 1; j <= nodes; ++j) {
    const auto [s, rate] = SegmentMotion(x, y0, v0, j);
    double ds = 0.0, dv = 2.0 * segment_damping_N_s_m_ * rate;
    if (clash_law_) {
      const double g = s - segment_travel_m_;
      const double f = solid(j) ? clash_law_->Force(g, rate) : 0.0;
      const double kc_j = solid(j) ? clash_law_->ForceStiffness() : 0.0;
      const double cc_j = solid(j) ? clash_law_->ForceDamping() : 0.0;
      ds = (kc_j - clash_law_->ConservativeStiffness(g)) * rate;
      dv += cc_j * rate + f - clash_law_->ConservativeForce(g);
    }
    add(3, j - 1, ds, dv);
    add(3, j, -ds, -dv);
  }
}

}  // namespace needle
