// Interpolating quintic spline, C⁴, on non-uniform knots. Unknowns are the slopes m_i and
// second derivatives M_i at the knots; each piece is the quintic Hermite interpolant of
// (y, m, M) at its two ends. With h the piece length and
//     A = y_1 − y_0 − m_0 h − M_0 h²/2,   B = m_1 − m_0 − M_0 h,   C = M_1 − M_0,
// its coefficients are c0 = y_0, c1 = m_0, c2 = M_0/2,
//     c3 = (10A − 4Bh + Ch²/2)/h³,  c4 = (−15A + 7Bh − Ch²)/h⁴,  c5 = (6A − 3Bh + Ch²/2)/h⁵.
// Continuity of s''' and s'''' at the N−1 interior knots gives 2N−2 equations; the ends are
// closed by the quintic's not-a-knot conditions, s⁽⁵⁾ continuous at x_1, x_2, x_{N−2},
// x_{N−1}, so that the first and last three pieces are each one quintic.
#include <Eigen/SparseCore>
#include <array>

#include "lib/linear_solve.h"
#include "lib/spline.h"

namespace needle {
namespace {

using Row = std::array<double, 6>;  // coefficients of [y0, m0, M0, y1, m1, M1]

struct QuinticRows {
  Row c3, c4, c5;
};

// c3, c4, c5 of a piece of length h as linear forms in its end data.
QuinticRows Rows(double h) {
  const Row a = {-1.0, -h, -0.5 * h * h, 1.0, 0.0, 0.0};  // A
  const Row b = {0.0, -1.0, -h, 0.0, 1.0, 0.0};           // B
  const Row c = {0.0, 0.0, -1.0, 0.0, 0.0, 1.0};          // C
  QuinticRows r;
  const double h2 = h * h, h3 = h2 * h, h4 = h3 * h, h5 = h4 * h;
  for (int j = 0; j < 6; ++j) {
    r.c3[j] = (10.0 * a[j] - 4.0 * h * b[j] + 0.5 * h2 * c[j]) / h3;
    r.c4[j] = (-15.0 * a[j] + 7.0 * h * b[j] - h2 * c[j]) / h4;
    r.c5[j] = (6.0 * a[j] - 3.0 * h * b[j] + 0.5 * h2 * c[j]) / h5;
  }
  return r;
}

Row Combine(double w3, const Row& c3, double w4, const Row& c4, double w5, const Row& c5) {
  Row out;
  for (int j = 0; j < 6; ++j) out[j] = w3 * c3[j] + w4 * c4[j] + w5 * c5[j];
  return out;
}

}  // namespace

PiecewisePolynomial BuildQuinticSpline(const std::vector<double>& x, const std::vector<double>& y) {
  const int n = static_cast<int>(x.size()) - 1;  // pieces
  const int unknowns = 2 * (n + 1);              // m_i at 2i, M_i at 2i+1
  std::vector<QuinticRows> rows(n);
  for (int i = 0; i < n; ++i) rows[i] = Rows(x[i + 1] - x[i]);

  std::vector<Eigen::Triplet<double>> a;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns);
  int eq = 0;
  // Adds Σ sign·row·data(piece) to equation `eq`; y terms move to the right-hand side.
  auto add = [&](int piece, double sign, const Row& r) {
    const int k0 = piece, k1 = piece + 1;
    rhs(eq) -= sign * (r[0] * y[k0] + r[3] * y[k1]);
    a.emplace_back(eq, 2 * k0, sign * r[1]);
    a.emplace_back(eq, 2 * k0 + 1, sign * r[2]);
    a.emplace_back(eq, 2 * k1, sign * r[4]);
    a.emplace_back(eq, 2 * k1 + 1, sign * r[5]);
  };
  for (int k = 1; k < n; ++k) {
    const double h = x[k] - x[k - 1];
    const QuinticRows& left = rows[k - 1];
    const QuinticRows& right = rows[k];
    // s'''(x_k⁻) = 6c3 + 24c4 h + 60c5 h² of the left piece; s'''(x_k⁺) = 6c3 of the right.
    add(k - 1, 1.0, Combine(6.0, left.c3, 24.0 * h, left.c4, 60.0 * h * h, left.c5));
    add(k, -1.0, Combine(6.0, right.c3, 0.0, right.c4, 0.0, right.c5));
    ++eq;
    // s''''(x_k⁻) = 24c4 + 120c5 h; s''''(x_k⁺) = 24c4.
    add(k - 1, 1.0, Combine(0.0, left.c3, 24.0, left.c4, 120.0 * h, left.c5));
    add(k, -1.0, Combine(0.0, right.c3, 24.0, right.c4, 0.0, right.c5));
    ++eq;
  }
  // Not-a-knot: 120 c5 equal on both sides of x_1, x_2, x_{N−2}, x_{N−1}.
  for (int k : {1, 2, n - 2, n - 1}) {
    add(k - 1, 1.0, Combine(0.0, rows[k - 1].c3, 0.0, rows[k - 1].c4, 1.0, rows[k - 1].c5));
    add(k, -1.0, Combine(0.0, rows[k].c3, 0.0, rows[k].c4, 1.0, rows[k].c5));
    ++eq;
  }
  const Eigen::VectorXd u = SolveSparse(unknowns, a, rhs, "quintic spline");

  Eigen::MatrixXd c(n, 6);
  for (int i = 0; i < n; ++i) {
    const double data[6] = {y[i], u(2 * i), u(2 * i + 1), y[i + 1], u(2 * i + 2), u(2 * i + 3)};
    c(i, 0) = y[i];
    c(i, 1) = u(2 * i);
    c(i, 2) = 0.5 * u(2 * i + 1);  // M/2
    double c3 = 0, c4 = 0, c5 = 0;
    for (int j = 0; j < 6; ++j) {
      c3 += rows[i].c3[j] * data[j];
      c4 += rows[i].c4[j] * data[j];
      c5 += rows[i].c5[j] * data[j];
    }
    c(i, 3) = c3;
    c(i, 4) = c4;
    c(i, 5) = c5;
  }
  return PiecewisePolynomial(x, std::move(c), 4);
}

}  // namespace needle
