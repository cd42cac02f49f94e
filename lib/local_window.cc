// One window's weighted least-squares fit and its misfit test (lib/local_window.h).
#include "lib/local_window.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace needle {
namespace {

constexpr Eigen::Index kQrBelow = 40;  // windows up to this many readings are solved by QR

}  // namespace

namespace local_window {

// Readings [from, to) as fitted: themselves, or above kLocalMaxNodes the means of bins.
Points FittedPoints(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                    size_t to) {
  const size_t n = to - from;
  if (n > static_cast<size_t>(kLocalMaxNodes)) {
    return MeansOfBins(x, y, from, to, (n + kLocalMaxNodes - 1) / kLocalMaxNodes);  // ≥ 1 a bin
  }
  return Points{std::vector<double>(x.begin() + from, x.begin() + to),
                std::vector<double>(y.begin() + from, y.begin() + to),
                std::vector<double>(n, 1.0),
                {}};
}

namespace {

// The mean over point i's bin of u^c = ((θ − t)/b)^c, c = 0 … 5, u its mean's: u^c itself for a
// single reading, else Σ_j C(c, j) u^(c−j) μ_j with μ_j the bin's central moments over b^j.
std::array<double, kTerms> MeanPowers(const Points& p, size_t i, double u, double b) {
  std::array<double, kTerms> row, power;
  power[0] = 1.0;
  for (int c = 1; c < kTerms; ++c) power[c] = power[c - 1] * u;
  row = power;
  if (p.moments.empty()) return row;
  double mu[kTerms] = {1.0, 0.0};
  for (int j = 2; j < kTerms; ++j) mu[j] = p.moments[i][j - 2] / std::pow(b, j);
  static constexpr double kBinomial[kTerms][kTerms] = {
      {1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}, {1, 5, 10, 10, 5, 1}};
  for (int c = 2; c < kTerms; ++c) {
    for (int j = 2; j <= c; ++j) row[c] += kBinomial[c][j] * power[c - j] * mu[j];
  }
  return row;
}

}  // namespace

void QrWeights(Eigen::Ref<Eigen::MatrixXd> v, int terms, Eigen::Ref<Eigen::MatrixXd> g) {
  if (terms > kQrMaxTerms || v.cols() != terms || g.rows() != v.rows() || g.cols() != terms)
    throw std::logic_error("QrWeights: a window of " + std::to_string(terms) + " terms (at most " +
                           std::to_string(kQrMaxTerms) + ") and matching weights expected");
  using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kQrMaxTerms,
                               kQrMaxTerms>;
  const Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(v);  // in place
  const Square r = qr.matrixQR().topRows(terms).triangularView<Eigen::Upper>();
  g.setZero();  // [R⁻ᵀ; 0], then Q times it
  g.topRows(terms) =
      r.transpose().triangularView<Eigen::Lower>().solve(Square::Identity(terms, terms));
  g.applyOnTheLeft(qr.householderQ());
}

Estimate FitAt(const Points& p, double t, size_t lo, size_t hi, bool quantized, int terms) {
  if (terms > kTerms) throw std::logic_error("FitAt: at most kTerms terms (the stack's rows)");
  const Eigen::Index k = static_cast<Eigen::Index>(hi - lo);
  double reach = 0.0;
  for (size_t i = lo; i < hi; ++i) reach = std::max(reach, std::abs(p.x[i] - t));
  const double b = 1.2 * reach;  // every reading of the window has a positive weight
  // The basis (θ − t)/b powers, each row times √weight; a QR window's on the stack.
  alignas(16) double v_stack[kQrBelow * kTerms];
  Eigen::MatrixXd v_heap(k <= kQrBelow ? 0 : k, terms);
  Eigen::Map<Eigen::MatrixXd, Eigen::Aligned16> v(k <= kQrBelow ? v_stack : v_heap.data(), k,
                                                  terms);
  Eigen::VectorXd root_w(k);
  // Binned points: their rows of bin means of u^c, kept for the residuals.
  Eigen::MatrixXd binned(p.moments.empty() ? 0 : k, kTerms);
  for (Eigen::Index r = 0; r < k; ++r) {
    const double u = (p.x[lo + r] - t) / b;
    const double a = 1.0 - std::abs(u * u * u);
    root_w(r) = std::sqrt(p.count[lo + r] * a * a * a);  // tricube, times the count
    const std::array<double, kTerms> row = MeanPowers(p, lo + r, u, b);
    for (int c = 0; c < terms; ++c) v(r, c) = root_w(r) * row[c];
    if (binned.rows() > 0) {
      for (int c = 0; c < kTerms; ++c) binned(r, c) = row[c];
    }
  }
  // The weights of β_0 … β_5 on the weighted readings, V (VᵀV)⁻¹ e_d: by QR where few
  // readings make VᵀV ill-conditioned (a one-sided window of 7), by its Cholesky factor above.
  Eigen::MatrixXd g(k, terms);
  if (k <= kQrBelow) {
    QrWeights(v, terms, g);
  } else {
    const Eigen::MatrixXd vtv = v.transpose() * v;
    g = v * vtv.ldlt().solve(Eigen::MatrixXd::Identity(terms, terms));
  }
  Estimate e;
  e.width = p.x[hi - 1] - p.x[lo];
  double scale = 1.0;  // d!/b^d
  for (int d = 0; d < 3; ++d) {
    double value = 0.0, var = 0.0, sum_abs = 0.0;
    for (Eigen::Index i = 0; i < k; ++i) {
      const double wi = g(i, d) * root_w(i);  // weight on the reading (bin mean)
      value += wi * p.y[lo + i];
      var += wi * wi / p.count[lo + i];  // a bin mean's variance is σ²/count
      sum_abs += std::abs(wi);
    }
    e.s[d] = scale * value;
    if (d == 2) e.sd2 = scale * NoisePerSigma(sum_abs, var, quantized);
    scale *= (d + 1) / b;
  }
  // The residuals, from the whole polynomial β = gᵀ W s (the test of Misfits).
  Eigen::VectorXd ws(k);
  for (Eigen::Index i = 0; i < k; ++i) ws(i) = root_w(i) * p.y[lo + i];
  const Eigen::VectorXd beta = g.transpose() * ws;
  e.fifth = terms > 5 ? 120.0 * std::abs(beta(5)) / (b * b * b * b * b) : 0.0;
  for (Eigen::Index i = 0; i < k; ++i) {
    const double u = (p.x[lo + i] - t) / b;
    double fitted = 0.0;
    if (binned.rows() == 0) {
      for (int c = terms - 1; c >= 0; --c) fitted = fitted * u + beta(c);
    } else {
      for (int c = 0; c < terms; ++c) fitted += beta(c) * binned(i, c);
    }
    const double r = p.y[lo + i] - fitted;
    e.largest_residual = std::max(e.largest_residual, std::abs(r));
    e.residual_square_sum += p.count[lo + i] * r * r;
  }
  return e;
}

// Whether the window's polynomial misses its readings by more than their noise can: the
// rounding's bound q/2 = √3 σ twice over (a rounded reading is never further than q/2 from the
// law, the fit adds its own error), or for white noise Σ c_i r_i² above (k − 6) σ² by three of
// its χ² standard deviations and two readings' worth (the tricube weights make the unweighted
// sum somewhat larger: pure noise misfits about 1–3 % of single windows). A window that reaches
// past a junction the breaks did not find (s''' jumps where s'' does not) misfits there long before
// its s'' moves out of the narrower windows' noise (docs/lift-data.md, "Reading a table").
bool Misfits(const Estimate& e, size_t readings, double sigma, bool quantized) {
  if (quantized) return e.largest_residual > RoundingMisfitBound(sigma);
  const double dof = static_cast<double>(readings) - kTerms;
  return e.residual_square_sum > (dof + 3.0 * std::sqrt(2.0 * dof) + 2.0) * sigma * sigma;
}

}  // namespace local_window

}  // namespace needle
