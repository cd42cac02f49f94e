// Junctions of a coarse exact table (FindJunctions, lib/lift_data.h): where the quintics fitted
// to the readings on either side of a reading disagree on s''.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "lib/lift_data.h"
#include "lib/side_polynomial.h"

namespace needle {
namespace {

constexpr int kSide = kJunctionSide;  // readings of each side's quintic: one more than it needs
// A neighbour whose |D| is at least this share of the largest's: the junction lies between them
// (at a reading, its neighbours see about half of it).
constexpr double kBetweenShare = 0.75;
// JumpConfirmed judges only where the quintics' noise is below this share of the jump.
constexpr double kConfirmNoiseShare = 0.1;

// A quintic fitted to readings [from, to) by least squares, in u = (θ − c)/h, and the weights of
// its s'' at c on those readings.
struct SideQuintic : SidePolynomial<5> {
  Eigen::VectorXd w2;  // weights of s''(c) on the readings
};

SideQuintic FitQuintic(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                       size_t to, double c) {
  SideQuintic q;
  q.c = c;
  q.h = std::max(std::abs(x[from] - c), std::abs(x[to - 1] - c));
  const Eigen::MatrixXd v = SideBasis<5>(x, from, to, c, q.h);
  const Eigen::Map<const Eigen::VectorXd> r(y.data() + from, static_cast<Eigen::Index>(to - from));
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(v);
  q.a = qr.solve(r);
  // s''(c) = 2 a_2 / h²: its weights are row 2 of the pseudo-inverse, (VᵀV)⁻¹Vᵀ.
  const Eigen::MatrixXd vtv = v.transpose() * v;
  Eigen::Matrix<double, 6, 1> e = Eigen::Matrix<double, 6, 1>::Zero();
  e(2) = 2.0 / (q.h * q.h);
  q.w2 = v * vtv.ldlt().solve(e);
  return q;
}

}  // namespace

std::vector<LiftBreak> FindJunctions(const std::vector<double>& x, const std::vector<double>& y,
                                     double sigma_m) {
  std::vector<LiftBreak> found;
  const long n = static_cast<long>(x.size());
  const long p = kSide;
  if (n != static_cast<long>(y.size()) || n < 4 * p) return found;
  // D_i = s''_right(θ_i) − s''_left(θ_i), the quintics through the p readings ending at i and
  // beginning at i; and its noise σ‖w_right − w_left‖.
  std::vector<double> d(n, 0.0), noise(n, 0.0);
  for (long i = p - 1; i + p <= n; ++i) {
    const SideQuintic left = FitQuintic(x, y, i - p + 1, i + 1, x[i]);
    const SideQuintic right = FitQuintic(x, y, i, i + p, x[i]);
    d[i] = right.Value(x[i], 2) - left.Value(x[i], 2);
    double w = right.w2(0) - left.w2(p - 1);  // reading i is in both
    double sum = w * w;
    for (long k = 0; k + 1 < p; ++k)
      sum += left.w2(k) * left.w2(k) + right.w2(k + 1) * right.w2(k + 1);
    noise[i] = sigma_m * std::sqrt(sum);
  }
  const double tail = TailSigmas(n, kBreakSigmas);
  std::vector<long> flagged;
  for (long i = p - 1; i + p <= n; ++i) {
    // The smooth level: the median |D| of the readings p+1 … p+6 away (clear of the windows that
    // hold a junction at i), on the side where it is least (the other may hold a junction).
    double smooth = std::numeric_limits<double>::infinity();
    for (long sign : {-1L, 1L}) {
      std::vector<double> side;
      for (long j = p + 1; j <= p + 6; ++j) {
        const long at = i + sign * j;
        if (at >= p - 1 && at + p <= n) side.push_back(std::abs(d[at]));
      }
      if (side.size() < 3) continue;
      std::nth_element(side.begin(), side.begin() + side.size() / 2, side.end());
      smooth = std::min(smooth, side[side.size() / 2]);
    }
    if (!std::isfinite(smooth)) continue;
    if (std::abs(d[i]) > kBreakOverSmooth * smooth && std::abs(d[i]) > tail * noise[i]) {
      flagged.push_back(i);
    }
  }
  // Each flagged reading's windows may hold a junction up to p − 1 readings away: the junction
  // is at the flagged reading of largest |D| (its windows hold no other reading's side), or
  // between it and a neighbour that sees nearly as much (its windows each hold one reading of
  // the other side); the flagged within p − 1 of it are its, and the rest are searched again.
  std::vector<bool> open(n, false);
  for (long f : flagged) open[f] = true;
  for (;;) {
    long k = -1;
    for (long i = p - 1; i + 1 + p <= n; ++i) {
      if (open[i] && (k < 0 || std::abs(d[i]) > std::abs(d[k]))) k = i;
    }
    if (k < 0) break;
    bool between = false;
    if (k + 1 + p <= n && std::abs(d[k + 1]) >= kBetweenShare * std::abs(d[k])) {
      between = true;
    } else if (k - 1 >= p - 1 && std::abs(d[k - 1]) >= kBetweenShare * std::abs(d[k])) {
      between = true;
      --k;
    }
    for (long i = std::max(0L, k - p + 1); i <= std::min(n - 1, k + p); ++i) open[i] = false;
    const SideQuintic left = FitQuintic(x, y, k - p + 1, k + 1, x[k]);
    const SideQuintic right =
        between ? FitQuintic(x, y, k + 1, k + 1 + p, x[k + 1]) : FitQuintic(x, y, k, k + p, x[k]);
    const double h = x[k + 1] - x[k];
    LiftBreak b;
    b.order = 2;
    b.index = static_cast<size_t>(k);
    if (between) {
      const auto at = RootIn([&](double t) { return right.Value(t, 1) - left.Value(t, 1); },
                             x[k] - 0.5 * h, x[k + 1] + 0.5 * h);
      b.crank_rad = at.value_or(0.5 * (x[k] + x[k + 1]));
      if (std::abs(b.crank_rad - x[k]) <= kBreakSnapFraction * h) b.crank_rad = x[k];
      if (std::abs(b.crank_rad - x[k + 1]) <= kBreakSnapFraction * h) {
        b.crank_rad = x[k + 1];
        b.index = static_cast<size_t>(k + 1);
      }
    } else {
      b.crank_rad = x[k];
    }
    b.jump = right.Value(b.crank_rad, 2) - left.Value(b.crank_rad, 2);
    b.lift_m = b.crank_rad == x[b.index]
                   ? y[b.index]
                   : 0.5 * (left.Value(b.crank_rad, 0) + right.Value(b.crank_rad, 0));
    // The located jump is the jump seen (within a quarter).
    if (!(std::abs(b.jump - d[k]) <= 0.25 * std::abs(d[k]))) continue;
    found.push_back(b);
  }
  std::sort(found.begin(), found.end(),
            [](const LiftBreak& a, const LiftBreak& b) { return a.crank_rad < b.crank_rad; });
  return found;
}

}  // namespace needle

namespace needle {

bool JumpConfirmed(const std::vector<double>& x, const std::vector<double>& y, const LiftBreak& b,
                   double sigma_m, double reach_rad) {
  const long n = static_cast<long>(x.size());
  // The readings at or before the break, and those after it.
  const long last_left =
      static_cast<long>(std::upper_bound(x.begin(), x.end(), b.crank_rad) - x.begin()) - 1;
  const long first_right = x[std::max(0L, last_left)] == b.crank_rad ? last_left : last_left + 1;
  // Quintics through p readings on either side, p doubled until their noise is under a tenth of
  // the jump (s''s noise falls as p^2.5) while they reach no further than `reach_rad`.
  for (long p = kSide; last_left - p + 1 >= 0 && first_right + p <= n; p *= 2) {
    if (b.crank_rad - x[last_left - p + 1] > reach_rad ||
        x[first_right + p - 1] - b.crank_rad > reach_rad) {
      break;
    }
    const SideQuintic left = FitQuintic(x, y, last_left - p + 1, last_left + 1, b.crank_rad);
    const SideQuintic right = FitQuintic(x, y, first_right, first_right + p, b.crank_rad);
    const double noise = sigma_m * std::hypot(left.w2.norm(), right.w2.norm());
    if (!(noise < kConfirmNoiseShare * std::abs(b.jump))) continue;
    const double seen = right.Value(b.crank_rad, 2) - left.Value(b.crank_rad, 2);
    return std::abs(seen - b.jump) <= 0.5 * std::abs(b.jump);
  }
  return true;  // the readings cannot tell
}

}  // namespace needle
