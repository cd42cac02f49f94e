#pragma once
/// @file
/// Internal to the solver: the closed form's polynomials in τ = t − t₀ (closed_form.h), as
/// coefficient arrays p[k] of τ^k, k = 0 … ClosedFormPiece::kMaxDegree: degree, Horner value,
/// derivative, Taylor shift and the integral of a product, shared by the one-mass piece and the
/// coil chain's side of it.

#include <algorithm>

#include "dynamics/solver/closed_form.h"

namespace needle {
namespace piece_polynomial {

using Poly = ClosedFormPiece::Poly;

/// The index of the highest nonzero coefficient (0 for a constant or zero polynomial). The
/// loops below start there: Horner over leading zeros adds exact zeros, so the results are the
/// same bits as over all kMaxDegree + 1 coefficients.
inline int Degree(const Poly& p) {
  int d = ClosedFormPiece::kMaxDegree;
  while (d > 0 && p[d] == 0.0) --d;
  return d;
}

/// Horner from the coefficient of degree `degree` (Degree(p), known) down.
inline double Eval(const Poly& p, int degree, double x) {
  int k = degree;
  double v = p[k];
  while (--k >= 0) v = v * x + p[k];
  return v;
}

inline double Eval(const Poly& p, double x) { return Eval(p, Degree(p), x); }

inline Poly Derivative(const Poly& p) {
  Poly d{};
  for (int k = 1, n = Degree(p); k <= n; ++k) d[k - 1] = k * p[k];
  return d;
}

/// The coefficients of q(s) = p(a + s) (Taylor shift, by repeated synthetic division; a = 0
/// adds exact zeros, and is left out).
inline Poly Shift(Poly p, double a) {
  const int n = a == 0.0 ? 0 : Degree(p);
  for (int i = 0; i < n; ++i) {
    for (int k = n - 1; k >= i; --k) p[k] += a * p[k + 1];
  }
  return p;
}

/// ∫₀ᵀ a(τ) b(τ) dτ.
inline double ProductIntegral(const Poly& a, const Poly& b, double T) {
  const int n = ClosedFormPiece::kMaxDegree;
  double sum = 0.0;
  for (int d = Degree(a) + Degree(b); d >= 0;
       --d) {  // Σ_d (Σ_{i+j=d} a_i b_j) T^{d+1}/(d+1), by Horner
    double c = 0.0;
    for (int i = std::max(0, d - n); i <= std::min(d, n); ++i) c += a[i] * b[d - i];
    sum = sum * T + c / (d + 1);
  }
  return sum * T;
}

inline bool IsZero(const Poly& p) {
  for (double v : p)
    if (v != 0.0) return false;
  return true;
}

}  // namespace piece_polynomial
}  // namespace needle
