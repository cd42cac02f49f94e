// The coil chain's side of ClosedFormPiece (closed_form.h, chain_modes.h): the particular
// solution of every node, the modal coefficients of the start's homogeneous part, the needle's
// modal sum and its bounds, and the whole chain's state along the piece.
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "dynamics/solver/closed_form.h"
#include "dynamics/solver/piece_polynomial.h"
#include "lib/units.h"

namespace needle {
namespace {

// |z| as √(x² + y²) where that neither overflows nor underflows (a few ulps against
// std::abs's hypot, 6× its cost; the bounds it feeds carry kSlack), else std::abs.
double Magnitude(std::complex<double> z) {
  const double norm = std::norm(z);
  return norm > 1e-290 && norm < 1e290 ? std::sqrt(norm) : std::abs(z);
}

// e^{λτ} − 1 = (e^{aτ} − 1 − 2 e^{aτ} sin²(bτ/2)) + i e^{aτ} sin(bτ): no cancellation where
// the mode is slow against τ.
std::complex<double> ExpMinusOne(std::complex<double> lambda, double tau) {
  const double a = lambda.real(), b = lambda.imag();
  const double em1 = std::expm1(a * tau), e = 1.0 + em1;
  const double sin_half = std::sin(0.5 * b * tau), cos_half = std::cos(0.5 * b * tau);
  return {em1 - 2.0 * e * sin_half * sin_half, 2.0 * e * sin_half * cos_half};
}

}  // namespace

void ClosedFormPiece::StartChain() {
  // The needle's row of the chain: its mass, and K₀₀ and C₀₀ (for the accessors only).
  m_ = chain_->NeedleMass();
  K_ = chain_->NeedleStiffness();
  c_ = chain_->NeedleDamping();
  sigma_ = beta_ = root_ = 0.0;
  chain_p_ = chain_->Particular(f_.data(), kMaxDegree);
  for (int j = 0; j <= kMaxDegree; ++j) p_[j] = chain_p_(0, j);
  longest_step_ = kPi / chain_->Fastest();
  SetStart();
  // The start's homogeneous part z_h(0) = [q − P(0), q̇ − P′(0)], node 0 the needle, node i the
  // coil mass i (state entries 3 + i and 3 + (N − 1) + i).
  const int n = chain_->Dofs(), coils = n - 1;
  Eigen::VectorXd h0(2 * n);
  h0[0] = Y0_;
  h0[n] = V0_;
  for (int i = 1; i < n; ++i) {
    h0[i] = x0_[3 + i] - chain_p_(i, 0);
    h0[n + i] = x0_[3 + coils + i] - chain_p_(i, 1);
  }
  chain_rest_ = (h0.array() == 0.0).all();
  chain_h0_ = h0;
  chain_c_ = (chain_->Inverse() * h0.cast<std::complex<double>>())
                 .cwiseProduct(chain_->Weight().cast<std::complex<double>>());
  // What the modal sum leaves of the start, h(0) − Re V w c (round-off; on the dense path up to
  // ChainModes::kInverseError): a state built from the start carries it at every τ, the modal
  // form of ChainUpperBounds does not.
  {
    const Eigen::Index m = chain_c_.size();
    Eigen::VectorXd c(2 * m);
    c << chain_c_.real(), chain_c_.imag();
    chain_leftover_ = h0 - chain_->VectorsReal() * c;
  }
  alpha_ = chain_->Vectors().row(0).transpose().cwiseProduct(chain_c_);
  const Eigen::Index m = chain_c_.size();
  alpha_rates_.resize(m, 2);
  alpha_sizes_ = alpha_.cwiseAbs();
  for (Eigen::Index k = 0; k < m; ++k) {
    alpha_rates_(k, 0) = alpha_[k] * chain_->Lambda()[k];
    alpha_rates_(k, 1) = alpha_rates_(k, 0) * chain_->Lambda()[k];
  }
  grow_.resize(2 * m);
  terms_.resize(2 * m);
  dz_.resize(2 * n);
}

void ClosedFormPiece::ChainSampleTimes(const double* ts, int count) const {
  if (!chain_) return;
  sample_tau_.clear();
  chain_at_ = ChainNeedle{};  // a τ ChainAt kept may be one of them, from the other formula
  if (count < 2) return;
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  const Eigen::Index m = lambda.size();
  sample_tau_.resize(count);
  for (int j = 0; j < count; ++j) sample_tau_[j] = ts[j] - t0_;
  sample_step_ = (sample_tau_[count - 1] - sample_tau_[0]) / (count - 1);
  sample_grow_.resize(2 * m, count);
  for (Eigen::Index k = 0; k < m; ++k) {
    const std::complex<double> rho = ExpMinusOne(lambda[k], sample_step_);
    std::complex<double> g = ExpMinusOne(lambda[k], sample_tau_[0]);
    for (int j = 0; j < count; ++j) {
      if (j > 0) g += rho + g * rho;
      sample_grow_(k, j) = g.real();
      sample_grow_(m + k, j) = g.imag();
    }
  }
}

std::array<double, 2> ClosedFormPiece::ChainStartRinging() const {
  if (ringing_) return *ringing_;
  // Σ_k |V_ik w_k c_k| of every node's lift (rows 0 … N − 1) and velocity (rows N … 2N − 1).
  const int n = chain_->Dofs();
  const Eigen::VectorXd sums = chain_->VectorSizes() * chain_c_.cwiseAbs();
  ringing_ = std::array<double, 2>{sums.head(n).maxCoeff(), sums.tail(n).maxCoeff()};
  return *ringing_;
}

std::array<double, 2> ClosedFormPiece::ChainNeedleRateBounds() const {
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  std::array<double, 2> sums{0.0, 0.0};
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    const double r = std::abs(lambda[k]), a2 = alpha_sizes_[k] * r * r;
    sums[0] += a2;
    sums[1] += a2 * r;
  }
  return sums;
}

const ClosedFormPiece::ChainNeedle& ClosedFormPiece::ChainAt(double tau) const {
  if (tau == chain_at_.tau) return chain_at_;
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  const Eigen::Index m = lambda.size();
  // One of ChainSampleTimes' times: its column.
  Eigen::Index column = -1;
  if (const size_t count = sample_tau_.size(); count > 1) {
    const double j = std::round((tau - sample_tau_.front()) / sample_step_);
    if (j >= 0.0 && j < count && sample_tau_[static_cast<size_t>(j)] == tau)
      column = static_cast<Eigen::Index>(j);
  }
  double dh = 0.0, dhv = 0.0, ha = 0.0;
  for (Eigen::Index k = 0; k < m; ++k) {
    const std::complex<double> g =
        column >= 0 ? std::complex<double>(sample_grow_(k, column), sample_grow_(m + k, column))
                    : ExpMinusOne(lambda[k], tau);
    grow_[k] = g.real();
    grow_[m + k] = g.imag();
    // Re(α g), Re(αλ g), Re(αλ² (1 + g)), their real parts written out (the same operations).
    const std::complex<double> a = alpha_[k], al = alpha_rates_(k, 0), all = alpha_rates_(k, 1);
    dh += a.real() * g.real() - a.imag() * g.imag();
    dhv += al.real() * g.real() - al.imag() * g.imag();
    ha += all.real() * (1.0 + g.real()) - all.imag() * g.imag();
  }
  chain_at_ = {tau, dh, dhv, ha};
  return chain_at_;
}

TrainState ClosedFormPiece::ChainState(double tau, bool coil_speeds) const {
  const std::array<double, 2> yv = PositionVelocity(tau);  // fills grow_ at τ
  const int n = chain_->Dofs(), coils = n - 1;
  // Re(V (w c ∘ g)) = [Re V, −Im V] [Re(w c ∘ g); Im(w c ∘ g)]: one real product.
  const Eigen::Index m = chain_c_.size();
  for (Eigen::Index k = 0; k < m; ++k) {
    const std::complex<double> term = chain_c_[k] * std::complex<double>(grow_[k], grow_[m + k]);
    terms_[k] = term.real();
    terms_[m + k] = term.imag();
  }
  // Without the coils' speeds: the lifts' rows and the needle's and coil 1's speeds (the
  // spring's force on the needle).
  const int rows = coil_speeds ? 2 * n : n + 2;
  Eigen::VectorXd& dz = dz_;
  dz.head(rows).noalias() = chain_->VectorsReal().topRows(rows) * terms_;
  TrainState x(x0_.size(), 0.0);
  x[0] = yv[0];
  x[1] = yv[1];
  for (int i = 1; i < n; ++i) {
    // P_i(τ) − P_i(0) and P_i′(τ) − P_i′(0), by Horner.
    double p = 0.0, dp = 0.0;
    for (int j = degree_p_; j >= 1; --j) {  // every node's P has the needle's degree at most
      p = p * tau + chain_p_(i, j);
      dp = dp * tau + j * chain_p_(i, j);
    }
    p *= tau;
    x[3 + i] = x0_[3 + i] + p + dz[i];
    x[3 + coils + i] = n + i < rows ? x0_[3 + coils + i] + (dp - chain_p_(i, 1)) + dz[n + i]
                                    : std::numeric_limits<double>::quiet_NaN();
  }
  return x;
}

ChainTaylor ClosedFormPiece::ChainTaylorAt(double t_c, double reach, bool coils) const {
  using piece_polynomial::Shift;
  ChainTaylor out;
  out.t_c = t_c;
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  const Eigen::Index m = lambda.size();
  // The least degree D whose remainder of e^{λs} over |s| ≤ reach, at most ρ^{D+1}/(D+1)! e^ρ,
  // is below 2⁻⁵³; no less than the particular solution's degree (exact in D then).
  const double rho = chain_->Fastest() * reach;
  double remainder = std::exp(rho);
  int D = 0;
  while (D < ChainTaylor::kMaxDegree && (D < degree_p_ || !(remainder * rho / (D + 1) <= 0x1p-53)))
    remainder *= rho / ++D;
  if (!(remainder * rho / (D + 1) <= 0x1p-53)) return out;
  const double tau = t_c - t0_;
  const int n = chain_->Dofs(), nodes = coils ? n : 1;
  // Rows 0 … nodes − 1 the nodes' lifts, row `nodes` the needle's speed. Column 0 the closed
  // form's values at τ (which leave e^{λ_k τ} − 1 in grow_).
  out.coef.setZero(nodes + 1, D + 1);
  if (coils) {
    const TrainState x = ChainState(tau, false);  // the lifts and the needle's speed
    out.coef(0, 0) = x[0];
    for (int i = 1; i < n; ++i) out.coef(i, 0) = x[3 + i];
    out.coef(nodes, 0) = x[1];
  } else {
    const std::array<double, 2> yv = PositionVelocity(tau);
    out.coef(0, 0) = yv[0];
    out.coef(1, 0) = yv[1];
  }
  // w_k c_k e^{λ_k τ} λ_k^j / j!, [Re; Im] in rows k and m + k, column j − 1.
  Eigen::MatrixXd e(2 * m, D);
  for (Eigen::Index k = 0; k < m; ++k) {
    std::complex<double> z = chain_c_[k] * std::complex<double>(1.0 + grow_[k], grow_[m + k]);
    for (int j = 1; j <= D; ++j) {
      z *= lambda[k] / static_cast<double>(j);
      e(k, j - 1) = z.real();
      e(m + k, j - 1) = z.imag();
    }
  }
  // The modal sum's derivatives Re Σ_k V_ik w_k c_k e^{λτ} λ^j / j! (one product), then the
  // particular solution's.
  const Eigen::MatrixXd& v = chain_->VectorsReal();
  out.coef.block(0, 1, nodes, D).noalias() = v.topRows(nodes) * e;
  out.coef.row(nodes).tail(D).noalias() = v.row(n) * e;
  for (int i = 0; i < nodes; ++i) {
    Poly p{};
    for (int j = 0; j <= kMaxDegree; ++j) p[j] = chain_p_(i, j);
    const Poly sp = Shift(p, tau);
    for (int j = 1; j <= std::min(D, kMaxDegree); ++j) out.coef(i, j) += sp[j];
  }
  const Poly sv = Shift(dp_, tau);
  for (int j = 1; j <= std::min(D, kMaxDegree); ++j) out.coef(nodes, j) += sv[j];
  out.valid = true;
  return out;
}

double ChainTaylor::Row(Eigen::Index r, double t) const {
  const double s = t - t_c;
  const int degree = static_cast<int>(coef.cols()) - 1;
  double v = coef(r, degree);
  for (int j = degree - 1; j >= 0; --j) v = v * s + coef(r, j);
  return v;
}

std::array<double, 2> ChainTaylor::LiftAndSpeed(double t) const {
  return {Row(0, t), Row(coef.rows() - 1, t)};
}

TrainState ChainTaylor::At(double t, size_t state_size) const {
  const Eigen::Index nodes = coef.rows() - 1;
  const auto value = [&](Eigen::Index r) { return Row(r, t); };
  TrainState x(state_size, 0.0);
  x[0] = value(0);
  x[1] = value(nodes);
  for (Eigen::Index i = 1; i < nodes; ++i) x[3 + i] = value(i);
  return x;
}

bool ClosedFormPiece::HomogeneousZero() const {
  return chain_ ? chain_rest_ : Y0_ == 0.0 && V0_ == 0.0;
}

TrainState ClosedFormPiece::MotionState(double t, bool coil_speeds) const {
  if (chain_) return ChainState(t - t0_, coil_speeds);
  const std::array<double, 2> yv = PositionVelocity(t - t0_);
  return {yv[0], yv[1], 0.0, 0.0};
}

void ClosedFormPiece::ChainStart(double t) const {
  // The modal sum: each term's size |α_k| e^{Re λ_k τ} never grows after τ.
  const double tau = t - t0_;
  const ChainNeedle& h = ChainAt(tau);
  HomogeneousStart& s = start_;
  s = HomogeneousStart{t, Y0_ + h.dh, V0_ + h.dhv, h.ha, 0.0, 0.0, 0.0, 0.0};
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    const double size = alpha_sizes_[k] * std::exp(lambda[k].real() * tau);
    const double l = chain_->LambdaSizes()[k];
    s.lift_amplitude += size;
    s.e1 += size * l;
    s.e2 += size * l * l;
    s.b3 += size * l * l * l;
  }
}

std::array<double, 2> ClosedFormPiece::ChainUpperBounds(double t_a, double t_b) const {
  const int n = chain_->Dofs();
  const double k = train_.SegmentRateNm(), c = train_.SegmentDampingNsm();
  const Eigen::VectorXcd& lambda = chain_->Lambda();
  const Eigen::Index m = lambda.size();
  const double tau = t_a - t0_, span = t_b - t_a;
  // Row r's modal part Re Σ_j B_rj e^{λ_j s} from t_a, B_rj = D_rj c_j e^{λ_j τ_a} (D: the
  // chain's Differences, c: this start's modal coefficients w c; 0 ≤ s ≤ span). Each term is
  // bounded two ways: whole, by |B| (its size never grows, but by round-off in a nearly undamped
  // mode: by e^{max(0, Re λ) span} at most); or from t_a, for a mode slow against the stretch
  // (|λ| span ≤ 1), by Re B + s Re(Bλ) + |B| |λs|²/2 e^{max(0, Re λ) span} (Taylor's remainder),
  // else (|λ| span > 1) by its whole size again.
  // Columns: [whole size, remainder] of |D|, and [start, slope] ([Re; Im]) of D.
  Eigen::Matrix<double, Eigen::Dynamic, 2> sizes(m, 2), terms(2 * m, 2);
  bool any_slow = false;
  for (Eigen::Index j = 0; j < m; ++j) {
    const double a = lambda[j].real(), l = chain_->LambdaSizes()[j], decay = std::exp(a * tau);
    const double size = Magnitude(chain_c_[j]) * decay * (a > 0.0 ? std::exp(a * span) : 1.0);
    const bool slow = l * span <= 1.0;
    any_slow = any_slow || slow;
    sizes(j, 0) = size;
    sizes(j, 1) = slow ? size * 0.5 * l * l * span * span : size;
    if (!slow) {
      terms.row(j) << 0.0, 0.0;
      terms.row(m + j) << 0.0, 0.0;
      continue;
    }
    const double phase = lambda[j].imag() * tau;
    const std::complex<double> start =
        chain_c_[j] * decay * std::complex<double>(std::cos(phase), std::sin(phase));
    const std::complex<double> slope = start * lambda[j];
    terms.row(j) << start.real(), slope.real();
    terms.row(m + j) << start.imag(), slope.imag();
  }
  // Four matrix-vector products (column-major, O(N·count) each).
  Eigen::Matrix<double, Eigen::Dynamic, 2> modal(n + 1, 2), from_start(n + 1, 2);
  for (int col = 0; col < 2; ++col) {
    modal.col(col).noalias() = chain_->DifferenceSizes() * sizes.col(col);
    // A stretch that no mode is slow against (a long one): by the whole terms alone.
    if (any_slow) from_start.col(col).noalias() = chain_->Differences() * terms.col(col);
  }
  // Round-off: the samples are sums of terms of these sizes.
  constexpr double kSlack = 1e-12;
  // The start's leftover in row r (constant along the piece; node N is the fixed seat).
  const Eigen::VectorXd& left = chain_leftover_;
  const auto leftover = [&](Eigen::Index r) {
    if (r < n) return left[r] - (r + 1 < n ? left[r + 1] : 0.0);
    return k * (left[0] - left[1]) + c * (left[n] - left[n + 1]);
  };
  // Row r's bound with its polynomial q (the particular solution's part): the lesser of
  // max q + Σ|B| and q(τ_a) + Σ_slow Re B + max(0, span (q′(τ_a) + Σ_slow Re Bλ)) + q's higher
  // terms + the remainders; and the start's leftover.
  const auto bound = [&](const Poly& q, Eigen::Index r) {
    const Poly s = piece_polynomial::Shift(q, tau);
    double higher = 0.0, power = span;
    for (int j = 2; j <= kMaxDegree; ++j) {
      power *= span;
      higher += std::abs(s[j]) * power;
    }
    const double linear = std::abs(s[1]) * span;
    double best = s[0] + linear + higher + modal(r, 0);
    if (any_slow) {
      best =
          std::min(best, s[0] + from_start(r, 0) + std::max(0.0, span * (s[1] + from_start(r, 1))) +
                             higher + modal(r, 1));
    }
    return best + leftover(r) +
           kSlack * (std::abs(s[0]) + linear + higher + modal(r, 0) + modal(r, 1));
  };
  double compression = -std::numeric_limits<double>::infinity(), spring = 0.0;
  for (int s = 1; s <= n; ++s) {
    Poly d{};
    for (int j = 0; j <= kMaxDegree; ++j)
      d[j] = chain_p_(s - 1, j) - (s < n ? chain_p_(s, j) : 0.0);
    compression = std::max(compression, bound(d, s - 1));
    if (s == 1) {
      Poly f{};  // k s₁ + c ṡ₁ of the particular solution
      for (int j = 0; j <= kMaxDegree; ++j)
        f[j] = k * d[j] + (j < kMaxDegree ? c * (j + 1) * d[j + 1] : 0.0);
      const double preload = train_.parameters().preload_N;
      spring = preload + bound(f, n) + kSlack * std::abs(preload);
    }
  }
  return {compression, spring};
}

ClosedFormPiece::AuditTerms ClosedFormPiece::ChainAudit(double T, const Eigen::VectorXd& z1) const {
  using piece_polynomial::Eval;
  using piece_polynomial::ProductIntegral;
  // Audit()'s terms with the chain's vectors: q = P + h, h free (M h″ + C h′ + K h = 0), its
  // needle entries h₀ (h₀(0) = Y₀, h₀′(0) = V₀). Ẇ = F_c u̇ in cam mode; Ḋ = Σ_j c ṡ_j² over the
  // segments, c ġ² for each pushing contact, and the jump of a contact's conservative part:
  //   the products of h′ sum to ∫ h′ᵀC h′ = H(0) − H(T);
  //   the cross terms to 2 ∫ gᵀh′ = 2([gᵀh] − ∫ g′ᵀh), g = C_seg P′ − c_c (u̇ − P₀′) e₀ [cam]
  //   + c_s P₀′ e₀ [seat];  ∫ qᵀh by ChainModes::FreeIntegral;  polynomial products exactly.
  const int n = chain_->Dofs();
  const int d = kMaxDegree;
  const double c = train_.SegmentDampingNsm();
  const ContactLaw& cam = train_.cam_law();
  const ContactLaw& seat = train_.seat_law();
  const double kc = cam.ForceStiffness(), cc = cam.ForceDamping();
  const double ks = seat.ForceStiffness(), cs = seat.ForceDamping();
  // P′ of every node (N × (d + 1)), and the segments' rates of it, ΔP′_j = P′_{j−1} − P′_j
  // (row j − 1; node N is the fixed end).
  Eigen::MatrixXd dP = Eigen::MatrixXd::Zero(n, d + 1), seg(n, d + 1);
  for (int j = 1; j <= d; ++j) dP.col(j - 1) = j * chain_p_.col(j);
  for (int j = 0; j < n; ++j) {
    seg.row(j) = dP.row(j);
    if (j + 1 < n) seg.row(j) -= dP.row(j + 1);
  }
  // g and the polynomial products.
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(n, d + 1);
  double products = 0.0;
  if (c != 0.0) {
    for (int j = 0; j < n; ++j) {
      Poly s{};
      for (int k = 0; k <= d; ++k) s[k] = seg(j, k);
      products += c * ProductIntegral(s, s, T);
      g.row(j) += c * seg.row(j);
      if (j > 0) g.row(j) -= c * seg.row(j - 1);
    }
  }
  Poly rel{};  // u̇ − P₀′
  for (int k = 0; k <= d; ++k) rel[k] = du_[k] - dp_[k];
  if (mode_.cam && cc != 0.0) {
    products += cc * ProductIntegral(rel, rel, T);
    for (int k = 0; k <= d; ++k) g(0, k) -= cc * rel[k];
  }
  if (mode_.seat && cs != 0.0) {
    products += cs * ProductIntegral(dp_, dp_, T);
    for (int k = 0; k <= d; ++k) g(0, k) += cs * dp_[k];
  }
  const auto at = [&](const Eigen::MatrixXd& q, double tau) {
    Eigen::VectorXd v = q.col(d);
    for (int k = d - 1; k >= 0; --k) v = v * tau + q.col(k);
    return v;
  };
  const auto derivative = [&](const Eigen::MatrixXd& q) {
    Eigen::MatrixXd r = Eigen::MatrixXd::Zero(n, d + 1);
    for (int k = 1; k <= d; ++k) r.col(k - 1) = k * q.col(k);
    return r;
  };
  const Eigen::VectorXd& z0 = chain_h0_;
  AuditTerms out;
  out.dissipated_J = products;
  if (chain_->Damped()) out.dissipated_J += chain_->FreeEnergy(z0) - chain_->FreeEnergy(z1);
  if (!g.isZero(0.0)) {
    const double boundary = at(g, T).dot(z1.head(n)) - g.col(0).dot(z0.head(n));
    out.dissipated_J += 2.0 * (boundary - chain_->FreeIntegral(derivative(g), T, z0, z1));
  }
  // The contacts' conservative parts across their kinks, from the gaps at the ends.
  const double y1 = Eval(p_, T) + z1[0];
  const double gc0 = u_[0] - x0_[0], gc1 = Eval(u_, T) - y1;
  const double gs0 = -x0_[0], gs1 = -y1;
  const auto sq = [](double x) { return x * x; };
  if (mode_.cam) {
    // W = ∫ F_c u̇ = ∫ (k_c (u − P₀) + c_c rel) u̇ − k_c ∫ u̇ h₀ − c_c ∫ u̇ h₀′, with
    // ∫ u̇ h₀′ = [u̇ h₀] − ∫ ü h₀.
    Poly force{};
    for (int k = 0; k <= d; ++k) force[k] = kc * (u_[k] - p_[k]) + cc * rel[k];
    const Poly ddu = piece_polynomial::Derivative(du_);
    Eigen::MatrixXd q = Eigen::MatrixXd::Zero(n, d + 1);
    for (int k = 0; k <= d; ++k) q(0, k) = kc * du_[k] - cc * ddu[k];
    out.work_J = ProductIntegral(force, du_, T) - cc * (Eval(du_, T) * z1[0] - du_[0] * Y0_) -
                 chain_->FreeIntegral(q, T, z0, z1);
    out.dissipated_J += 0.5 * kc * (sq(std::min(gc1, 0.0)) - sq(std::min(gc0, 0.0)));
  } else {
    out.dissipated_J -= 0.5 * kc * (sq(std::max(gc1, 0.0)) - sq(std::max(gc0, 0.0)));
  }
  if (mode_.seat) {
    out.dissipated_J += 0.5 * ks * (sq(std::min(gs1, 0.0)) - sq(std::min(gs0, 0.0)));
  } else {
    out.dissipated_J -= 0.5 * ks * (sq(std::max(gs1, 0.0)) - sq(std::max(gs0, 0.0)));
  }
  return out;
}

}  // namespace needle
