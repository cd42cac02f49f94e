#pragma once
/// @file
/// A piecewise polynomial on strictly increasing breaks x_0 < … < x_N:
///
///     p(x) = Σ_{k=0}^{K} c_{i,k} (x − x_i)^k   for x_i ≤ x < x_{i+1},  i = 0..N−1,
///
/// the common representation of every spline in needle. Derivatives are exact:
/// p^(d)(x) = Σ_{k≥d} k!/(k−d)! c_{i,k} (x − x_i)^{k−d}.

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace needle {

class PiecewisePolynomial {
 public:
  /// `breaks`: N+1 strictly increasing abscissae; `coefficients`: N rows, K+1 columns
  /// (column k multiplies (x − x_i)^k); `continuity`: the highest derivative order that is
  /// continuous across the breaks (1 for C¹ Hermite, 2 for cubic splines, 4 for quintic).
  /// Throws std::invalid_argument when the sizes disagree or breaks do not increase.
  PiecewisePolynomial(std::vector<double> breaks, Eigen::MatrixXd coefficients, int continuity);

  /// p^(derivative)(x), derivative 0..K. Outside [x_0, x_N] the end pieces are extended.
  double Evaluate(double x, int derivative = 0) const;

  /// p^(d)(x) into out[d] for d = 0 … count − 1 (count ≥ 0), each as Evaluate(x, d) gives it,
  /// bit for bit, from one lookup of the piece.
  void EvaluateUpTo(double x, int count, double* out) const;

  /// Index i of the piece with x_i ≤ x < x_{i+1} (0 below x_0, N−1 at and above x_N).
  int Piece(double x) const;

  /// Piece i's polynomial (extended past its ends), its `derivative`th derivative at x (0 past
  /// the degree): Evaluate(x, d) is OnPiece(Piece(x), x, d), bit for bit.
  double OnPiece(int i, double x, int derivative) const {
    return Horner(i, x - breaks_[i], derivative);
  }

  /// ∫_{x_0}^{x_N} p(x) dx, exact.
  double Integral() const;

  /// The same polynomial on [a, b] only (x_0 ≤ a < b ≤ x_N): breaks a, the x_i strictly inside,
  /// b; the first piece re-expanded about a (Taylor shift), values unchanged to round-off.
  /// Throws std::invalid_argument outside those bounds.
  PiecewisePolynomial Restrict(double a, double b) const;

  const std::vector<double>& breaks() const { return breaks_; }
  const Eigen::MatrixXd& coefficients() const { return coefficients_; }
  /// Polynomial degree K of the pieces.
  int degree() const { return static_cast<int>(coefficients_.cols()) - 1; }
  /// Highest continuous derivative order across the breaks.
  int continuity() const { return continuity_; }

 private:
  // Piece i's d-th derivative at t = x − x_i (0 ≤ d ≤ K).
  double Horner(int i, double t, int derivative) const;

  std::vector<double> breaks_;
  Eigen::MatrixXd coefficients_;
  int continuity_;
};

/// The largest (sign 1) or smallest (sign −1) value of p^(order) over [x_0, x_N] and where it is:
/// the best of nine samples of each piece, refined by Brent's method within an eighth of its
/// piece. (LiftLaw::Extrema is exact to machine precision; this is a quick locator.)
std::pair<double, double> ExtremeOf(const PiecewisePolynomial& p, int order, double sign);

}  // namespace needle
