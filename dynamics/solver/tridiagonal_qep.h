#pragma once
/// @file
/// Internal to the solver: the eigenvalues of the coil chain's quadratic eigenproblem
///
///     det T(λ) = 0,   T(λ) = λ² M + λ C + K,   M = diag(m_i) > 0, K and C real symmetric
///     tridiagonal (N × N: the needle and N − 1 coil masses),
///
/// by the Ehrlich–Aberth iteration on det T (Bini, Gemignani & Tisseur, SIAM J. Matrix Anal.
/// Appl. 27 (2005); Plestenjak, Numer. Linear Algebra Appl. 13 (2006)): O(N²) a sweep, where the
/// first-order form's Hessenberg QR costs O(N³). In balanced units, μ = λ/s with
/// s = √‖M^-½ K M^-½‖∞ and T̃(μ) = M^-½ T(sμ) M^-½ / s² = μ² I + μ C̃ + K̃ (entries of one size),
/// det T̃ is a monic real polynomial of degree 2N whose leading minors obey
///
///     p_i = d_i p_{i−1} − e_{i−1}² p_{i−2},   d_i = μ² + μ C̃_ii + K̃_ii,
///     e_i = μ C̃_{i,i+1} + K̃_{i,i+1},
///
/// so Newton's ratio p_N/p_N′ costs O(N) at any μ (by the ratios r_i = p_i/p_{i−1} and the
/// logarithmic derivatives p_i′/p_i: no overflow). Aberth's correction of root z_k among the
/// approximations z_j is
///
///     w_k = ν_k / (1 − ν_k Σ_{j≠k} 1/(z_k − z_j)),   ν_k = p_N(z_k)/p_N′(z_k),
///
/// started from the undamped modes (K̃'s symmetric tridiagonal eigenproblem, Eigen) with each
/// mode's own damping φᵀC̃φ (a mode's two real roots a little off the axis: the damping of the
/// undamped modes may tell pair from real wrongly). Each root converged, the roots within
/// kAberthReal of the axis are taken as real and the others paired with the root nearest their
/// conjugate.
#include <Eigen/Dense>
#include <optional>

namespace needle {

/// The chain's M, K and C: their diagonals (N) and off-diagonals (N − 1, entry i joins i and
/// i + 1). SI: kg, N/m, N·s/m.
struct TridiagonalQep {
  Eigen::VectorXd mass, k_diag, k_off, c_diag, c_off;
};

/// All 2N eigenvalues λ (1/s) of `qep`, each complex pair side by side (Im λ > 0 first, then its
/// exact conjugate) and each real one with Im λ = 0 exactly, or nullopt where the iteration does
/// not certify them: a root not converged in kMaxAberthSweeps sweeps (to kAberthTolerance, in
/// balanced units), one whose last correction is not under kAberthIsolation of its distance to
/// every other root (a cluster: near critical damping), roots whose sum is not −tr(M⁻¹C) (one
/// missed, another found twice), or a complex root without its conjugate within kAberthPair.
/// The caller then takes a dense eigensolver.
std::optional<Eigen::VectorXcd> TridiagonalQepEigenvalues(const TridiagonalQep& qep);

constexpr int kMaxAberthSweeps = 60;
/// A root has converged when its correction is at most this, in balanced units (|μ| ≤ ~1): the
/// dense eigensolver's own absolute round-off on the balanced first-order matrix, some 100 ε.
constexpr double kAberthTolerance = 2e-14;
constexpr double kAberthIsolation = 1e-3;
/// A root with |Im μ| at most this (times max(1, |μ|)) is real: a real root's approximation
/// comes to the axis within round-off, and a pair nearer than this to it is a cluster.
constexpr double kAberthReal = 1e-11;
/// A pair's members each within this (times max(1, |μ|)) of the other's conjugate.
constexpr double kAberthPair = 1e-10;

}  // namespace needle
