// Local polynomial regression with Lepski's window (lib/local_fit.h).
#include "lib/local_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace needle {

BinMeans MeansOfBins(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                     size_t to, size_t per) {
  BinMeans p;
  for (size_t i = from; i < to; i += per) {
    const size_t end = std::min(to, i + per);
    double sx = 0.0, sy = 0.0;
    for (size_t k = i; k < end; ++k) {
      sx += x[k];
      sy += y[k];
    }
    const double m = static_cast<double>(end - i);
    p.x.push_back(sx / m);
    p.y.push_back(sy / m);
    p.count.push_back(m);
  }
  return p;
}

namespace {

constexpr int kTerms = kLocalDegree + 1;
constexpr Eigen::Index kQrBelow = 40;  // windows up to this many readings are solved by QR
constexpr double kNodeSpacing = 0.5;   // nodes half a window's width apart

// Readings as fitted: a reading, or the mean of a bin of `count` consecutive readings.
using Points = BinMeans;

Points Binned(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  return MeansOfBins(x, y, 0, n, (n + kLocalMaxNodes - 1) / kLocalMaxNodes);  // ≥ 1 per bin
}

// The estimates of s, s', s'' at t from the points [lo, hi), and the standard deviation of s''
// per unit σ.
struct Estimate {
  double s[3] = {};
  double sd2 = 0.0;
  double width = 0.0;  // the window's span, rad
};

Estimate FitAt(const Points& p, double t, size_t lo, size_t hi, bool quantized) {
  const Eigen::Index k = static_cast<Eigen::Index>(hi - lo);
  double reach = 0.0;
  for (size_t i = lo; i < hi; ++i) reach = std::max(reach, std::abs(p.x[i] - t));
  const double b = 1.2 * reach;  // every reading of the window has a positive weight
  Eigen::MatrixXd v(k, kTerms);  // the basis (θ − t)/b powers, each row times √weight
  Eigen::VectorXd root_w(k);
  for (Eigen::Index r = 0; r < k; ++r) {
    const double u = (p.x[lo + r] - t) / b;
    const double a = 1.0 - std::abs(u * u * u);
    root_w(r) = std::sqrt(p.count[lo + r] * a * a * a);  // tricube, times the count
    double power = 1.0;
    for (int c = 0; c < kTerms; ++c, power *= u) v(r, c) = root_w(r) * power;
  }
  // The weights of β_0, β_1, β_2 on the weighted readings, V (VᵀV)⁻¹ e_d: by QR where few
  // readings make VᵀV ill-conditioned (a one-sided window of 7), by its Cholesky factor above.
  Eigen::MatrixXd g;
  if (k <= kQrBelow) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(v);
    const Eigen::MatrixXd r = qr.matrixQR().topRows(kTerms).triangularView<Eigen::Upper>();
    const Eigen::MatrixXd z =
        r.transpose().triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(kTerms, 3));
    g = qr.householderQ() * (Eigen::MatrixXd::Identity(k, kTerms) * z);
  } else {
    const Eigen::MatrixXd vtv = v.transpose() * v;
    g = v * vtv.ldlt().solve(Eigen::MatrixXd::Identity(kTerms, 3));
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
    // Rounding is no white noise: each reading's (a bin's) error is at most q/2 = √3 σ, the
    // estimate's at most √3 σ Σ|g|, which stands for 1.96 standard deviations.
    if (d == 2) e.sd2 = scale * (quantized ? std::sqrt(3.0) * sum_abs / 1.96 : std::sqrt(var));
    scale *= (d + 1) / b;
  }
  return e;
}

// The window sizes Lepski's rule tries: 7, 9, 11, … (×1.25, distinct), up to n.
std::vector<size_t> WindowSizes(size_t n) {
  std::vector<size_t> sizes;
  for (double want = kLocalMinimumPoints;; want *= 1.25) {
    const size_t k = std::min(n, static_cast<size_t>(std::lround(want)));
    if (sizes.empty() || k > sizes.back()) sizes.push_back(k);
    if (k == n) return sizes;
  }
}

// The node at t: Lepski's window among the K nearest points, trying sizes from sizes[from] on
// (a neighbour's choice less two: the rule compares a window with the narrower ones tried).
// `chosen` gets the index of the size chosen.
LocalNode NodeAt(const Points& p, double t, double sigma, bool quantized,
                 const std::vector<size_t>& sizes, size_t from, size_t* chosen_size) {
  const size_t n = p.x.size();
  size_t lo = std::lower_bound(p.x.begin(), p.x.end(), t) - p.x.begin(), hi = lo;
  std::vector<Estimate> tried;
  size_t chosen = 0;
  for (size_t j = from; j < sizes.size(); ++j) {
    while (hi - lo < sizes[j]) {  // grow towards the nearer side
      if (lo == 0) {
        ++hi;
      } else if (hi == n || t - p.x[lo - 1] <= p.x[hi] - t) {
        --lo;
      } else {
        ++hi;
      }
    }
    const Estimate e = FitAt(p, t, lo, hi, quantized);
    bool agrees = true;
    for (const Estimate& narrower : tried) {
      agrees = agrees && std::abs(e.s[2] - narrower.s[2]) <= kLepskiSigmas * sigma * narrower.sd2;
    }
    tried.push_back(e);
    if (!agrees) break;
    chosen = tried.size() - 1;
  }
  *chosen_size = from + chosen;
  const Estimate& e = tried[chosen];
  LocalNode node;
  node.x = t;
  for (int d = 0; d < 3; ++d) node.s[d] = e.s[d];
  node.window = static_cast<int>(sizes[from + chosen]);
  node.width = e.width;
  // Truncation's scale: the largest step from the narrower windows of at least half its size
  // (over which the bias grows 2⁴-fold; narrower ones are noise), from the next wider window
  // when the narrowest is chosen.
  double step = chosen == 0 && tried.size() > 1 ? std::abs(e.s[2] - tried[1].s[2]) : 0.0;
  for (size_t i = 0; i < chosen; ++i) {
    if (2 * sizes[from + i] >= sizes[from + chosen]) {
      step = std::max(step, std::abs(e.s[2] - tried[i].s[2]));
    }
  }
  node.band2 = 1.96 * sigma * e.sd2 + step;
  return node;
}

}  // namespace

PiecewisePolynomial QuinticHermite(const std::vector<LocalNode>& nodes) {
  const Eigen::Index n = static_cast<Eigen::Index>(nodes.size()) - 1;
  Eigen::MatrixXd c(n, kTerms);
  std::vector<double> breaks;
  for (Eigen::Index i = 0; i < n; ++i) {
    const LocalNode& a = nodes[i];
    const LocalNode& b = nodes[i + 1];
    const double h = b.x - a.x, dp = b.s[0] - a.s[0];
    c(i, 0) = a.s[0];
    c(i, 1) = a.s[1];
    c(i, 2) = 0.5 * a.s[2];
    c(i, 3) = (20.0 * dp - (8.0 * b.s[1] + 12.0 * a.s[1]) * h - (3.0 * a.s[2] - b.s[2]) * h * h) /
              (2.0 * h * h * h);
    c(i, 4) =
        (-30.0 * dp + (14.0 * b.s[1] + 16.0 * a.s[1]) * h + (3.0 * a.s[2] - 2.0 * b.s[2]) * h * h) /
        (2.0 * h * h * h * h);
    c(i, 5) = (12.0 * dp - 6.0 * (b.s[1] + a.s[1]) * h - (a.s[2] - b.s[2]) * h * h) /
              (2.0 * h * h * h * h * h);
    breaks.push_back(a.x);
  }
  breaks.push_back(nodes.back().x);
  return PiecewisePolynomial(std::move(breaks), std::move(c), 2);
}

LocalFit FitLocal(const std::vector<double>& x, const std::vector<double>& y, double sigma_m,
                  bool quantized) {
  if (x.size() != y.size() || static_cast<int>(x.size()) < kLocalMinimumPoints) {
    throw std::invalid_argument("local fit needs at least " + std::to_string(kLocalMinimumPoints) +
                                " points, got " + std::to_string(x.size()));
  }
  const Points p = static_cast<int>(x.size()) > kLocalMaxNodes
                       ? Binned(x, y)
                       : Points{x, y, std::vector<double>(x.size(), 1.0)};
  LocalFit fit{PiecewisePolynomial({0.0, 1.0}, Eigen::MatrixXd::Zero(1, kTerms), 2), {}};
  const std::vector<size_t> sizes = WindowSizes(p.x.size());
  // Nodes from the first reading to the last, each kNodeSpacing of its window's width past the
  // one before (at least the next point): the interpolant's s'' between two nodes is their s''
  // plus their values' noise over the spacing squared, which a spacing of the window's order
  // keeps at the noise of s'' itself.
  size_t last = 0;
  double t = x.front();
  for (;;) {
    const size_t from = last >= 2 ? last - 2 : 0;
    fit.nodes.push_back(NodeAt(p, t, sigma_m, quantized, sizes, from, &last));
    if (t >= x.back()) break;
    const size_t next = std::upper_bound(p.x.begin(), p.x.end(), t) - p.x.begin();
    double step = kNodeSpacing * fit.nodes.back().width;
    t = std::max(t + step, next < p.x.size() ? p.x[next] : x.back());
    if (t > x.back() - 0.5 * step || next >= p.x.size()) t = x.back();
  }
  fit.law = QuinticHermite(fit.nodes);
  return fit;
}

}  // namespace needle
