#include "lib/piecewise_polynomial.h"

#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace needle {

PiecewisePolynomial::PiecewisePolynomial(std::vector<double> breaks, Eigen::MatrixXd coefficients,
                                         int continuity)
    : breaks_(std::move(breaks)), coefficients_(std::move(coefficients)), continuity_(continuity) {
  if (breaks_.size() < 2 || coefficients_.rows() != static_cast<Eigen::Index>(breaks_.size()) - 1 ||
      coefficients_.cols() < 1) {
    throw std::invalid_argument("PiecewisePolynomial: " + std::to_string(breaks_.size()) +
                                " breaks need " + std::to_string(breaks_.size() - 1) +
                                " coefficient rows, got " + std::to_string(coefficients_.rows()));
  }
  for (size_t i = 1; i < breaks_.size(); ++i) {
    if (!(breaks_[i] > breaks_[i - 1])) {
      throw std::invalid_argument("PiecewisePolynomial: breaks must increase strictly; break " +
                                  std::to_string(i) + " is not above break " +
                                  std::to_string(i - 1));
    }
  }
}

int PiecewisePolynomial::Piece(double x) const {
  const int n = static_cast<int>(breaks_.size()) - 1;
  // First break strictly above x, minus one: x_i ≤ x < x_{i+1}.
  const auto it = std::upper_bound(breaks_.begin(), breaks_.end(), x);
  const int i = static_cast<int>(it - breaks_.begin()) - 1;
  return std::clamp(i, 0, n - 1);
}

namespace {
// k!/(k−d)! (0 where k < d), multiplied out as Horner forms it: exact.
constexpr double Falling(int k, int d) {
  double falling = 1.0;
  for (int j = 0; j < d; ++j) falling *= (k - j);
  return falling;
}
// Falling(k, d) for k < kFallingDegrees, d < kFallingOrders, formed once.
constexpr int kFallingDegrees = 8, kFallingOrders = 4;
constexpr std::array<std::array<double, kFallingOrders>, kFallingDegrees> Fallings() {
  std::array<std::array<double, kFallingOrders>, kFallingDegrees> f{};
  for (int k = 0; k < kFallingDegrees; ++k) {
    for (int d = 0; d < kFallingOrders; ++d) f[k][d] = Falling(k, d);
  }
  return f;
}
constexpr auto kFalling = Fallings();

// out[d] = Σ_{k≥d} k!/(k−d)! c_k t^{k−d}, d < count ≤ kFallingOrders, each by Horner as Horner()
// forms it (the same operations in the same order); kDegree ≥ 0 fixes the degree at compile
// time (the loops unrolled), −1 takes `degree`.
template <int kDegree>
void HornerSums(const double* c, double t, int count, double* out, int degree = kDegree) {
  if constexpr (kDegree >= 0) degree = kDegree;
  for (int d = 0; d < count; ++d) {
    double value = 0.0;
    for (int k = degree; k >= d; --k) value = value * t + kFalling[k][d] * c[k];
    out[d] = value;
  }
}
}  // namespace

double PiecewisePolynomial::Horner(int i, double t, int derivative) const {
  // Horner on the d-th derivative: Σ_{k≥d} k!/(k−d)! c_k t^{k−d} (0 past the degree).
  double value = 0.0;
  const bool tabled = degree() < kFallingDegrees && derivative < kFallingOrders;
  for (int k = degree(); k >= derivative; --k) {
    const double falling = tabled ? kFalling[k][derivative] : Falling(k, derivative);
    value = value * t + falling * coefficients_(i, k);
  }
  return value;
}

double PiecewisePolynomial::Evaluate(double x, int derivative) const {
  if (derivative < 0) throw std::invalid_argument("PiecewisePolynomial: negative derivative order");
  if (derivative > degree()) return 0.0;
  const int i = Piece(x);
  return Horner(i, x - breaks_[i], derivative);
}

void PiecewisePolynomial::EvaluateUpTo(double x, int count, double* out) const {
  const int i = Piece(x);
  const double t = x - breaks_[i];
  if (degree() >= kFallingDegrees || count > kFallingOrders) {
    for (int d = 0; d < count; ++d) out[d] = Horner(i, t, d);
    return;
  }
  // Horner's sums as Horner() forms them, the piece's coefficients read once for all orders;
  // the cubic's and the quintic's (every spline's but the smoothing one's) unrolled.
  std::array<double, kFallingDegrees> c;
  for (int k = 0; k <= degree(); ++k) c[k] = coefficients_(i, k);
  switch (degree()) {
    case 3:
      return HornerSums<3>(c.data(), t, count, out);
    case 5:
      return HornerSums<5>(c.data(), t, count, out);
    default:
      return HornerSums<-1>(c.data(), t, count, out, degree());
  }
}

double PiecewisePolynomial::Integral() const {
  double sum = 0.0;
  for (Eigen::Index i = 0; i < coefficients_.rows(); ++i) {
    const double h = breaks_[i + 1] - breaks_[i];
    double hk = h;  // h^{k+1}
    for (Eigen::Index k = 0; k < coefficients_.cols(); ++k) {
      sum += coefficients_(i, k) * hk / static_cast<double>(k + 1);  // ∫_0^h c_k t^k dt
      hk *= h;
    }
  }
  return sum;
}

PiecewisePolynomial PiecewisePolynomial::Restrict(double a, double b) const {
  if (!(a >= breaks_.front() && b <= breaks_.back() && a < b)) {
    throw std::invalid_argument("PiecewisePolynomial::Restrict: [" + std::to_string(a) + ", " +
                                std::to_string(b) + "] is not inside [" +
                                std::to_string(breaks_.front()) + ", " +
                                std::to_string(breaks_.back()) + "]");
  }
  const int first = Piece(a);
  std::vector<double> x = {a};
  for (size_t i = first + 1; i < breaks_.size() && breaks_[i] < b; ++i) x.push_back(breaks_[i]);
  x.push_back(b);
  const int pieces = static_cast<int>(x.size()) - 1;
  const Eigen::Index k_count = coefficients_.cols();
  Eigen::MatrixXd c(pieces, k_count);
  for (int p = 0; p < pieces; ++p) c.row(p) = coefficients_.row(first + p);
  // Taylor shift of the first piece: Σ c_k (t + d)^k = Σ_j (Σ_{k≥j} C(k, j) d^{k−j} c_k) t^j.
  const double d = a - breaks_[first];
  if (d != 0.0) {
    for (Eigen::Index j = 0; j < k_count; ++j) {
      double sum = 0.0, binom = 1.0, power = 1.0;  // C(k, j), d^{k−j} for k = j, j+1, …
      for (Eigen::Index k = j; k < k_count; ++k) {
        sum += binom * power * coefficients_(first, k);
        binom = binom * static_cast<double>(k + 1) / static_cast<double>(k + 1 - j);
        power *= d;
      }
      c(0, j) = sum;
    }
  }
  return PiecewisePolynomial(std::move(x), std::move(c), continuity_);
}

std::pair<double, double> ExtremeOf(const PiecewisePolynomial& p, int order, double sign) {
  const std::vector<double>& b = p.breaks();
  double best = -std::numeric_limits<double>::infinity(), at = b.front(), width = 0.0;
  for (size_t i = 0; i + 1 < b.size(); ++i) {
    for (int k = 0; k <= 8; ++k) {
      const double t = b[i] + (b[i + 1] - b[i]) * k / 8.0;
      const double v = sign * p.Evaluate(t, order);
      if (v > best) best = v, at = t, width = (b[i + 1] - b[i]) / 8.0;
    }
  }
  const double lo = std::max(b.front(), at - width), hi = std::min(b.back(), at + width);
  const auto r = boost::math::tools::brent_find_minima(
      [&](double t) { return -sign * p.Evaluate(t, order); }, lo, hi, 40);
  return -r.second > best ? std::pair{r.first, -sign * r.second} : std::pair{at, sign * best};
}

}  // namespace needle
