#include "dynamics/solver/tridiagonal_qep.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

namespace needle {
namespace {

using Complex = std::complex<double>;

// 1/d by its conjugate over |d|²: std::complex's division guards against overflow at some 40
// cycles (the iteration's cost); here |d| is of the entries' size, and an infinity or NaN from a
// d of 0 hands the eigenvalues to the dense QR.
Complex Inverse(Complex d) {
  const double size2 = d.real() * d.real() + d.imag() * d.imag();
  return {d.real() / size2, -d.imag() / size2};
}

// T̃(μ) = μ² I + μ C̃ + K̃ in balanced units: K̃'s and C̃'s diagonals and off-diagonals, and s.
struct Balanced {
  Eigen::VectorXd k, c, k_off, c_off;
  double scale = 1.0;
};

Balanced Balance(const TridiagonalQep& q) {
  const Eigen::Index n = q.mass.size();
  const Eigen::VectorXd inv_root = q.mass.cwiseSqrt().cwiseInverse();
  Balanced b;
  b.k = q.k_diag.cwiseProduct(inv_root.cwiseAbs2());
  b.c = q.c_diag.cwiseProduct(inv_root.cwiseAbs2());
  b.k_off = q.k_off.cwiseProduct(inv_root.head(n - 1)).cwiseProduct(inv_root.tail(n - 1));
  b.c_off = q.c_off.cwiseProduct(inv_root.head(n - 1)).cwiseProduct(inv_root.tail(n - 1));
  double norm = 0.0;  // ‖K̃‖∞, as ChainModes::Decompose balances its first-order matrix
  for (Eigen::Index i = 0; i < n; ++i) {
    norm = std::max(norm, std::abs(b.k[i]) + (i > 0 ? std::abs(b.k_off[i - 1]) : 0.0) +
                              (i + 1 < n ? std::abs(b.k_off[i]) : 0.0));
  }
  b.scale = std::sqrt(norm);
  const double s2 = norm;
  b.k /= s2;
  b.k_off /= s2;
  b.c /= b.scale;
  b.c_off /= b.scale;
  return b;
}

// p_N′/p_N at μ by the ratios r_i = p_i/p_{i−1} and g_i = p_i′/p_i:
//   r_i = d_i − e_{i−1}²/r_{i−1},
//   g_i = (d_i′ + d_i g_{i−1} − ((e_{i−1}²)′ + e_{i−1}² g_{i−2})/r_{i−1}) / r_i,
// from r_0 = d_0, g_0 = d_0′/d_0, g_{−1} = 0. A ratio of exactly 0 is taken as ε (the entries'
// size is 1).
Complex LogDerivative(const Balanced& b, Complex mu) {
  constexpr double kTiny = std::numeric_limits<double>::epsilon();
  const Eigen::Index n = b.k.size();
  const auto nonzero = [&](Complex r) { return r == 0.0 ? Complex(kTiny) : r; };
  Complex r = nonzero(mu * mu + mu * b.c[0] + b.k[0]);
  Complex g = (2.0 * mu + b.c[0]) * Inverse(r), g_before = 0.0;
  for (Eigen::Index i = 1; i < n; ++i) {
    const Complex d = mu * mu + mu * b.c[i] + b.k[i], d_rate = 2.0 * mu + b.c[i];
    const Complex e = mu * b.c_off[i - 1] + b.k_off[i - 1];
    const Complex e2 = e * e, e2_rate = 2.0 * e * b.c_off[i - 1];
    const Complex inv_r = Inverse(r);
    const Complex r_next = nonzero(d - e2 * inv_r);
    const Complex g_next = (d_rate + d * g - (e2_rate + e2 * g_before) * inv_r) * Inverse(r_next);
    g_before = g;
    g = g_next;
    r = r_next;
  }
  return g;
}

struct Root {
  Complex z;                // balanced units
  double moved = INFINITY;  // |last correction|
  bool done = false;        // converged: no longer corrected, still in the others' sums
};

// The undamped modes ω_j² of K̃ (symmetric tridiagonal) and their own damping b_j = φ_jᵀC̃φ_j:
// each mode's μ² + b_j μ + ω_j² = 0, a complex pair or two real roots (these a little off the
// axis, on either side: the iteration may take them to a pair). Empty if Eigen fails.
std::vector<Root> Start(const Balanced& b) {
  const Eigen::Index n = b.k.size();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> undamped;
  undamped.computeFromTridiagonal(b.k, b.k_off, Eigen::ComputeEigenvectors);
  if (undamped.info() != Eigen::Success) return {};
  std::vector<Root> roots;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::VectorXd phi = undamped.eigenvectors().col(j);
    double damping = b.c.dot(phi.cwiseAbs2());
    for (Eigen::Index i = 0; i + 1 < n; ++i) damping += 2.0 * b.c_off[i] * phi[i] * phi[i + 1];
    const double w2 = std::max(undamped.eigenvalues()[j], 0.0);
    const double disc = damping * damping - 4.0 * w2;
    if (disc < 0.0) {
      const Complex z(-0.5 * damping, 0.5 * std::sqrt(-disc));
      roots.push_back({z});
      roots.push_back({std::conj(z)});
      continue;
    }
    // Two real roots, the smaller one by the product (no cancellation).
    const double big = -0.5 * (damping + std::copysign(std::sqrt(disc), damping));
    const double small = big != 0.0 ? w2 / big : 0.0;
    roots.push_back({Complex(big, 1e-3 * std::abs(big))});
    roots.push_back({Complex(small, -1e-3 * std::abs(small) - 1e-6)});
  }
  return roots;
}

// Σ over every root but z_k of 1/(z_k − z_j).
Complex AberthSum(const std::vector<Root>& roots, size_t k) {
  const Complex z = roots[k].z;
  Complex sum = 0.0;
  for (size_t j = 0; j < roots.size(); ++j) {
    if (j != k) sum += Inverse(z - roots[j].z);
  }
  return sum;
}

// Aberth sweeps (Gauss–Seidel: each correction uses the others' latest); a root whose correction
// is at most kAberthTolerance is done (kept, no longer corrected). False if some root is not
// done within kMaxAberthSweeps.
bool Converge(const Balanced& b, std::vector<Root>& roots) {
  for (int sweep = 0; sweep < kMaxAberthSweeps; ++sweep) {
    bool all_done = true;
    for (size_t k = 0; k < roots.size(); ++k) {
      Root& root = roots[k];
      if (root.done) continue;
      // ν/(1 − νΣ) = 1/(1/ν − Σ), 1/ν = p′/p: finite also where p′ = 0.
      const Complex w = Inverse(LogDerivative(b, root.z) - AberthSum(roots, k));
      if (!std::isfinite(w.real()) || !std::isfinite(w.imag())) return false;
      root.moved = std::abs(w);
      root.z -= w;
      root.done = root.moved <= kAberthTolerance * std::max(1.0, std::abs(root.z));
      all_done = all_done && root.done;
    }
    if (all_done) return true;
  }
  return false;
}

// Each root's last correction under kAberthIsolation of its distance to every other root, and
// the roots' sum −tr(C̃): 2N distinct roots, all of them.
bool Certify(const Balanced& b, const std::vector<Root>& roots) {
  Complex sum = 0.0;
  double sizes = 0.0;
  for (size_t k = 0; k < roots.size(); ++k) {
    double nearest2 = INFINITY;  // squared
    for (size_t j = 0; j < roots.size(); ++j) {
      if (j != k) nearest2 = std::min(nearest2, std::norm(roots[k].z - roots[j].z));
    }
    const double moved = roots[k].moved;
    if (!(nearest2 > 0.0) || !(moved * moved <= kAberthIsolation * kAberthIsolation * nearest2))
      return false;
    sum += roots[k].z;
    sizes += std::abs(roots[k].z);
  }
  return std::abs(sum + b.c.sum()) <= 1e-10 * sizes + 1e-300;
}

// The roots as a real polynomial's: within kAberthReal of the axis real (Im 0), every other one
// beside the root nearest its conjugate, within kAberthPair, as an exact pair (their mean);
// false where one finds no partner.
bool Pair(std::vector<Root>& roots, std::vector<Complex>& out) {
  const auto scale = [](Complex z) { return std::max(1.0, std::abs(z)); };
  std::vector<bool> used(roots.size(), false);
  for (size_t k = 0; k < roots.size(); ++k) {
    if (used[k]) continue;
    used[k] = true;
    const Complex z = roots[k].z;
    if (std::abs(z.imag()) <= kAberthReal * scale(z)) {
      out.push_back(Complex(z.real(), 0.0));
      continue;
    }
    size_t best = roots.size();
    for (size_t j = 0; j < roots.size(); ++j) {
      if (!used[j] && (best == roots.size() || std::abs(roots[j].z - std::conj(z)) <
                                                   std::abs(roots[best].z - std::conj(z))))
        best = j;
    }
    if (best == roots.size() || !(std::abs(roots[best].z - std::conj(z)) <= kAberthPair * scale(z)))
      return false;
    used[best] = true;
    const Complex upper = z.imag() > 0.0 ? z : roots[best].z;
    const Complex mean = 0.5 * (upper + std::conj(z.imag() > 0.0 ? roots[best].z : z));
    out.push_back(mean);
    out.push_back(std::conj(mean));
  }
  return true;
}

}  // namespace

std::optional<Eigen::VectorXcd> TridiagonalQepEigenvalues(const TridiagonalQep& qep) {
  const Eigen::Index n = qep.mass.size();
  if (n < 1 || qep.k_diag.size() != n || qep.c_diag.size() != n || qep.k_off.size() != n - 1 ||
      qep.c_off.size() != n - 1 || !(qep.mass.minCoeff() > 0.0)) {
    return std::nullopt;
  }
  const Balanced b = Balance(qep);
  if (!(b.scale > 0.0) || !std::isfinite(b.scale)) return std::nullopt;
  std::vector<Root> roots = Start(b);
  std::vector<Complex> paired;
  if (roots.empty() || !Converge(b, roots) || !Certify(b, roots) || !Pair(roots, paired))
    return std::nullopt;
  Eigen::VectorXcd all(2 * n);
  for (Eigen::Index i = 0; i < all.size(); ++i) all[i] = b.scale * paired[i];
  return all;
}

}  // namespace needle
