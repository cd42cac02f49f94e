// The end nodes' bands at a break from one fit of both sides (lib/local_join.h).
#include "lib/local_join.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "lib/local_window.h"

namespace needle {
namespace {

using local_window::kTerms;

// JoinAtBreak on the last kl readings of (xl, yl) and the first kr of (xr, yr); false where the
// joint polynomials misfit them.
bool JoinWindows(const std::vector<double>& xl, const std::vector<double>& yl,
                 const std::vector<double>& xr, const std::vector<double>& yr, double sigma_m,
                 bool quantized, size_t kl, size_t kr, LocalNode* left, LocalNode* right) {
  const size_t nl = xl.size();
  const double t = xl.back();
  // The rows: the left window's readings up to the break, then the right one's after it.
  constexpr int kOwn = kTerms - 2, kColumns = 2 + 2 * kOwn;
  static_assert(kColumns <= local_window::kQrMaxTerms, "QrWeights' square holds the columns");
  const Eigen::Index k = static_cast<Eigen::Index>(kl + kr - 1);
  const double bl = 1.2 * (t - xl[nl - kl]), br = 1.2 * (xr[kr - 1] - t), b = std::max(bl, br);
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(k, kColumns);
  Eigen::VectorXd root_w(k), ys(k);
  for (Eigen::Index r = 0; r < k; ++r) {
    const bool on_left = r < static_cast<Eigen::Index>(kl);
    const size_t i = on_left ? nl - kl + static_cast<size_t>(r) : static_cast<size_t>(r) + 1 - kl;
    const double xi = on_left ? xl[i] : xr[i], d = xi - t, u = d / (on_left ? bl : br);
    const double a = 1.0 - std::abs(u * u * u);
    root_w(r) = std::sqrt(a * a * a);
    ys(r) = on_left ? yl[i] : yr[i];
    v(r, 0) = root_w(r);
    v(r, 1) = root_w(r) * d / b;
    double power = u;
    for (int c = 0; c < kOwn; ++c) {
      power *= u;
      v(r, 2 + (on_left ? 0 : kOwn) + c) = root_w(r) * power;
    }
  }
  Eigen::MatrixXd g(k, kColumns), factors = v;  // v is kept for the residuals
  local_window::QrWeights(factors, kColumns, g);
  // Each estimate, and for s'' its standard deviation per unit σ (FitAt's rule).
  const auto estimate = [&](int column, double scale, double* sd) {
    double value = 0.0, var = 0.0, sum_abs = 0.0;
    for (Eigen::Index r = 0; r < k; ++r) {
      const double w = g(r, column) * root_w(r);
      value += w * ys(r);
      var += w * w;
      sum_abs += std::abs(w);
    }
    if (sd) *sd = scale * local_window::NoisePerSigma(sum_abs, var, quantized);
    return scale * value;
  };
  // The joint polynomials must fit the readings as a window's must (Misfits: a residual within
  // the rounding's bound, or white noise's chi-square range, on its 2 + 2 x 4 terms): else the
  // law is no C1 pair of quintics there (the break placed a reading off the junction, an s'''
  // jump beside it: a modified trapezoid's): this pair is rejected and JoinAtBreak tries
  // narrower ones.
  local_window::Estimate fit;
  const Eigen::VectorXd beta = g.transpose() * root_w.cwiseProduct(ys);
  const Eigen::VectorXd fitted = v * beta;
  for (Eigen::Index r = 0; r < k; ++r) {
    const double residual = ys(r) - fitted(r) / root_w(r);
    fit.largest_residual = std::max(fit.largest_residual, std::abs(residual));
    fit.residual_square_sum += residual * residual;
  }
  if (local_window::Misfits(fit, static_cast<size_t>(k) - (kColumns - kTerms), sigma_m, quantized))
    return false;
  double sd_l = 0.0, sd_r = 0.0;
  const double s2_l = estimate(2, 2.0 / (bl * bl), &sd_l);
  const double s2_r = estimate(2 + kOwn, 2.0 / (br * br), &sd_r);
  // Each node keeps its value (the break may lie between readings, a fraction of a step off:
  // there one s' is wrong), and its band reaches the joint fit's s'' with that fit's noise and
  // what the node's own band held beyond its own window's noise (truncation, the half-density
  // fit's bias, ...).
  const auto widen = [&](LocalNode* node, const std::vector<double>& x,
                         const std::vector<double>& y, size_t lo, size_t hi, double s2, double sd) {
    const local_window::Points own = local_window::FittedPoints(x, y, lo, hi);
    const double own_noise =
        1.96 * sigma_m * local_window::FitAt(own, t, 0, hi - lo, quantized).sd2;
    const double beyond = std::max(0.0, node->band2 - own_noise);
    node->band2 = std::max(node->band2, std::abs(s2 - node->s[2]) + 1.96 * sigma_m * sd + beyond);
  };
  const size_t own_l = static_cast<size_t>(left->window),
               own_r = static_cast<size_t>(right->window);
  widen(left, xl, yl, nl - own_l, nl, s2_l, sd_l);
  widen(right, xr, yr, 0, own_r, s2_r, sd_r);
  return true;
}

}  // namespace

bool JoinAtBreak(const std::vector<double>& xl, const std::vector<double>& yl,
                 const std::vector<double>& xr, const std::vector<double>& yr, double sigma_m,
                 bool quantized, LocalNode* left, LocalNode* right) {
  const size_t most = kLocalMaxNodes, least = kLocalMinimumPoints;
  size_t kl = static_cast<size_t>(left->window), kr = static_cast<size_t>(right->window);
  if (xl.empty() || xr.empty() || xl.size() > most || xr.size() > most) return false;  // binned
  const double t = xl.back();
  if (!(xr.front() == t && left->x == t && right->x == t)) return false;
  if (kl < least || kr < least || kl > xl.size() || kr > xr.size()) return false;
  // The nodes' own windows, then narrower ones (by Lepski's factor, 1.25) until one fits.
  for (;;) {
    if (JoinWindows(xl, yl, xr, yr, sigma_m, quantized, kl, kr, left, right)) return true;
    if (kl == least && kr == least) return false;
    kl = std::max(least, static_cast<size_t>(std::lround(kl / 1.25)));
    kr = std::max(least, static_cast<size_t>(std::lround(kr / 1.25)));
  }
}

}  // namespace needle
