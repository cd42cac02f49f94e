// Breaks found in a lift table: where s'' jumps between two smooth pieces (FindBreaks,
// lift_data.h; docs/model.md §2), by cubics fitted on each side of every reading.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "lib/lift_data.h"
#include "lib/side_polynomial.h"

namespace needle {

namespace {

// A polynomial fitted by least squares to readings [from, to) of (x, y), in u = (θ − c)/h.
using SideCubic = SidePolynomial<3>;

template <int Degree = 3>
SidePolynomial<Degree> FitSide(const std::vector<double>& x, const std::vector<double>& y,
                               size_t from, size_t to, double c, double h,
                               double* sum_squares = nullptr) {
  SidePolynomial<Degree> s;
  s.c = c;
  s.h = h;
  const Eigen::MatrixXd v = SideBasis<Degree>(x, from, to, c, h);
  const Eigen::Map<const Eigen::VectorXd> r(y.data() + from, static_cast<Eigen::Index>(to - from));
  s.a = QrSolve(v, r);
  if (sum_squares) *sum_squares = (v * s.a - r).squaredNorm();
  return s;
}

// The norm of the weights, on readings [from, to), of the `order`th derivative at t of the
// polynomial FitSide fits there: its standard deviation per unit σ of the readings.
template <int Degree = 3>
double DerivativeNoise(const std::vector<double>& x, size_t from, size_t to, double c, double h,
                       double t, int order) {
  const Eigen::MatrixXd v = SideBasis<Degree>(x, from, to, c, h);
  const double u = (t - c) / h;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(Degree + 1);  // the derivative's row
  for (int m = order; m <= Degree; ++m) {
    double falling = 1.0;
    for (int j = 0; j < order; ++j) falling *= (m - j);
    d(m) = falling * std::pow(u, m - order) / std::pow(h, order);
  }
  const Eigen::VectorXd g = v * LdltSolve(Gram(v), d);  // weights on the readings
  return g.norm();
}

}  // namespace

namespace {

// FindBreaks' first stage: s2[i] = 2 f[x_{i-1}, x_i, x_{i+1}] ≈ s'' with its weights on the
// three readings; over each interval (x_k, x_k+1) Ĵ_k, the right line's value at its middle
// minus the left's, from s2 at k−m … k−1 (readings ≤ x_k) and k+2 … k+m+1 (readings ≥ x_k+1);
// and Ĉ_k, the two windows across the interval less the mean of the two lines there: a corner
// (s' jumps by K) makes them K/h apiece, where an s'' jump or a smooth law leaves them between.
class BreakStatistics {
 public:
  static constexpr long m = kBreakSideWindows, d = kBreakSideWindows + 2;

  BreakStatistics(const std::vector<double>& x, const std::vector<double>& y, double sigma_m)
      : x_(x),
        n_(static_cast<long>(x.size())),
        sigma_m_(sigma_m),
        s2_(n_, 0.0),
        at_(n_, 0.0),
        w2_(n_),
        mean_at_(n_, 0.0),
        spread_(n_, 0.0),
        jump_(n_, 0.0),
        spike_(n_, 0.0),
        weights_(n_, 0.0),
        tail_(TailSigmas(n_, kBreakSigmas)) {
    for (long i = 1; i + 1 < n_; ++i) {
      const double a = x[i - 1], b = x[i], c = x[i + 1];
      w2_[i] = {2.0 / ((a - b) * (a - c)), 2.0 / ((b - a) * (b - c)), 2.0 / ((c - a) * (c - b))};
      s2_[i] = w2_[i][0] * y[i - 1] + w2_[i][1] * y[i] + w2_[i][2] * y[i + 1];
      at_[i] = (a + b + c) / 3.0;
    }
    for (long from = 1; from + m < n_; ++from) {  // each window's mean abscissa and spread
      double mean = 0.0, sxx = 0.0;
      for (long i = from; i < from + m; ++i) mean += at_[i] / m;
      for (long i = from; i < from + m; ++i) sxx += (at_[i] - mean) * (at_[i] - mean);
      mean_at_[from] = mean;
      spread_[from] = sxx;
    }
    for (long k = m + 1; k + m + 2 < n_; ++k) {
      const double mid = 0.5 * (x[k] + x[k + 1]);
      jump_[k] = Side(k + 2, mid, 1.0, nullptr) - Side(k - m, mid, -1.0, nullptr);
      for (long i = k; i <= k + 1; ++i) {
        spike_[k] += s2_[i] - 0.5 * (Side(k + 2, at_[i], -0.5, nullptr) +
                                     Side(k - m, at_[i], -0.5, nullptr));
      }
    }
  }

  // The intervals whose Ĵ or Ĉ stands out.
  std::vector<long> Flagged() {
    std::vector<long> flagged;
    for (long k = m + 1 + d + 3; k + m + 2 + d + 3 < n_; ++k) {
      if (StandsOut(jump_, true, k) || StandsOut(spike_, false, k)) flagged.push_back(k);
    }
    return flagged;
  }

  const std::vector<double>& jump() const { return jump_; }
  const std::vector<double>& spike() const { return spike_; }
  double tail() const { return tail_; }

 private:
  // The line through s2[from … from+m) at `where`; with `to`, its weights on the readings are
  // added there (times `sign`).
  double Side(long from, double where, double sign, std::vector<double>* to) const {
    double v = 0.0;
    for (long i = from; i < from + m; ++i) {
      const double a = Weight(from, where, i);
      v += a * s2_[i];
      if (to)
        for (int j = 0; j < 3; ++j) (*to)[i - 1 + j] += sign * a * w2_[i][j];
    }
    return v;
  }

  // The weight of s2[i] in the line through s2[from … from+m) at `where`.
  double Weight(long from, double where, long i) const {
    const double mean = mean_at_[from];
    return 1.0 / m + (at_[i] - mean) * (where - mean) / spread_[from];
  }

  // The noise of Ĵ_k (or Ĉ_k): σ times the norm of its weights on the readings.
  double Noise(long k, bool of_jump) {
    std::vector<double>& to = weights_;
    std::fill(to.begin() + (k - m - 1), to.begin() + (k + m + 3), 0.0);
    const double mid = 0.5 * (x_[k] + x_[k + 1]);
    if (of_jump) {
      Side(k + 2, mid, 1.0, &to);
      Side(k - m, mid, -1.0, &to);
    } else {
      for (long i = k; i <= k + 1; ++i) {
        Side(k + 2, at_[i], -0.5, &to);
        Side(k - m, at_[i], -0.5, &to);
        for (int j = 0; j < 3; ++j) to[i - 1 + j] += w2_[i][j];
      }
    }
    double w = 0.0;
    for (long i = k - m - 1; i < k + m + 3; ++i) w += to[i] * to[i];
    return sigma_m_ * std::sqrt(w);
  }

  // Stands out: above the smooth level around it, and above its noise (asked only then).
  bool StandsOut(const std::vector<double>& v, bool of_jump, long k) {
    // Above kBreakOverSmooth times the median of the eight around it (the fifth smallest): a
    // break beside (two or three of them) or the law's smooth level passing zero on one side
    // (a few) does not move it. Counted, not sorted: above it is above at least five of them.
    const double at = std::abs(v[k]);
    int below = 0;
    for (long j = 0; j < 4; ++j) {
      below += at > kBreakOverSmooth * std::abs(v[k - d - j]);
      below += at > kBreakOverSmooth * std::abs(v[k + d + j]);
    }
    return below >= 5 && at > tail_ * LeastNoise(k, of_jump) && at > tail_ * Noise(k, of_jump);
  }

  // A lower bound of Noise(k, of_jump), exact in floating point: σ times the norm of its weights
  // on the window's two outermost readings alone, each computed as Noise computes it (one or
  // two terms added to zero in the same order; a sum of squares only grows with more terms, and
  // rounding is monotone). A value not above it is not above Noise either, which is not asked.
  double LeastNoise(long k, bool of_jump) const {
    const long right = k + m + 1, left = k - m;  // s2 entries reaching readings k+m+2, k−m−1
    double outer_right = 0.0, outer_left = 0.0;
    if (of_jump) {
      const double mid = 0.5 * (x_[k] + x_[k + 1]);
      outer_right += 1.0 * Weight(k + 2, mid, right) * w2_[right][2];
      outer_left += -1.0 * Weight(k - m, mid, left) * w2_[left][0];
    } else {
      for (long i = k; i <= k + 1; ++i) {
        outer_right += -0.5 * Weight(k + 2, at_[i], right) * w2_[right][2];
        outer_left += -0.5 * Weight(k - m, at_[i], left) * w2_[left][0];
      }
    }
    return sigma_m_ * std::sqrt(outer_left * outer_left + outer_right * outer_right);
  }

  const std::vector<double>& x_;
  long n_;
  double sigma_m_;
  std::vector<double> s2_, at_;
  std::vector<std::array<double, 3>> w2_;
  std::vector<double> mean_at_, spread_, jump_, spike_;
  std::vector<double> weights_;  // Noise's weights on the readings, zeroed where used
  double tail_;
};

// The interval near `around` whose two sides' cubics fit their readings best: the readings of a
// side all lie on it there.
long BestInterval(const std::vector<double>& x, const std::vector<double>& y, long around) {
  const long p = kBreakFitPoints, n = static_cast<long>(x.size());
  double best = std::numeric_limits<double>::infinity();
  long k = around;
  for (long kk = around - 2; kk <= around + 2; ++kk) {
    if (kk - p + 1 < 0 || kk + p >= n) continue;
    const double h = x[kk + 1] - x[kk], c = 0.5 * (x[kk] + x[kk + 1]);
    double left_ss = 0.0, right_ss = 0.0;
    FitSide(x, y, kk - p + 1, kk + 1, c, h, &left_ss);
    FitSide(x, y, kk + 1, kk + p + 1, c, h, &right_ss);
    if (left_ss + right_ss < best) {
      best = left_ss + right_ss;
      k = kk;
    }
  }
  return k;
}

// A corner stands out of the noise of quintics through the 7 readings on each side too, and keeps
// its size on them where their noise can tell: a law that leaves the seat smoothly but steeply (s ∝
// ξ⁴, a degree-8 rise at 1.5° steps) bends the cubics' slopes apart by their truncation, "a corner
// at 3.192 deg (its velocity jumps by 0.0005 mm/deg)", and quintics, which hold ξ⁴, do not.
bool QuinticsSeeTheCorner(const std::vector<double>& x, const std::vector<double>& y, long k,
                          double sigma_m, double tail, const LiftBreak& b) {
  constexpr long q = 7;
  const long n = static_cast<long>(x.size());
  if (k - q + 1 < 0 || k + q >= n) return true;
  const double h = x[k + 1] - x[k], c = 0.5 * (x[k] + x[k + 1]);
  const auto left = FitSide<5>(x, y, k - q + 1, k + 1, c, h);
  const auto right = FitSide<5>(x, y, k + 1, k + q + 1, c, h);
  const double noise =
      sigma_m * std::hypot(DerivativeNoise<5>(x, k - q + 1, k + 1, c, h, b.crank_rad, 1),
                           DerivativeNoise<5>(x, k + 1, k + q + 1, c, h, b.crank_rad, 1));
  const double jump = right.Value(b.crank_rad, 1) - left.Value(b.crank_rad, 1);
  if (!(std::abs(jump) > tail * noise)) return false;  // no corner beyond the quintics' noise
  // Where their noise can tell, the same corner.
  return !(tail * noise < 0.25 * std::abs(b.jump)) ||
         std::abs(jump - b.jump) <= 0.25 * std::abs(b.jump);
}

// The cubics fitted to the kBreakFitPoints readings on each side of interval k, and the RMS of
// their residuals.
struct Sides {
  SideCubic left, right;
  double rms_m = 0.0;
};

Sides FitSides(const std::vector<double>& x, const std::vector<double>& y, long k) {
  const long p = kBreakFitPoints;
  const double h = x[k + 1] - x[k], c = 0.5 * (x[k] + x[k + 1]);
  Sides sides;
  double left_ss = 0.0, right_ss = 0.0;
  sides.left = FitSide(x, y, k - p + 1, k + 1, c, h, &left_ss);
  sides.right = FitSide(x, y, k + 1, k + p + 1, c, h, &right_ss);
  sides.rms_m = std::sqrt((left_ss + right_ss) / (2 * p - 8));
  return sides;
}

// The break over interval k where the two sides' cubics meet: an s'' jump where their slopes
// meet within half a step of it, else a corner (which must keep its size on twice the
// readings); its jump above what the readings' noise or rounding can make. Else std::nullopt.
std::optional<LiftBreak> SidesMeet(const std::vector<double>& x, const std::vector<double>& y,
                                   long k, const Sides& sides, double sigma_m, double tail) {
  const long p = kBreakFitPoints, n = static_cast<long>(x.size());
  LiftBreak b;
  const double h = x[k + 1] - x[k], c = 0.5 * (x[k] + x[k + 1]);
  const SideCubic &left = sides.left, &right = sides.right;
  const double lo = x[k] - 0.5 * h, hi = x[k + 1] + 0.5 * h;
  const auto slopes =
      RootIn([&](double t) { return right.Value(t, 1) - left.Value(t, 1); }, lo, hi);
  if (slopes) {
    b.order = 2;
    b.crank_rad = *slopes;
    b.jump = right.Value(b.crank_rad, 2) - left.Value(b.crank_rad, 2);
  } else {
    b.order = 1;
    const auto lifts =
        RootIn([&](double t) { return right.Value(t, 0) - left.Value(t, 0); }, lo, hi);
    b.crank_rad = lifts.value_or(c);
    b.jump = right.Value(b.crank_rad, 1) - left.Value(b.crank_rad, 1);
    // A corner's slope jump exceeds what the law's own s'' turns the slope by over two steps (a
    // coarse table of a law whose s''' jumps: sides that miss by 0.5 % of the peak velocity; a
    // dwell shorter than two steps, its s'' jumping to 0 and back: a harmonic rise of 108° into a
    // 3° dwell at 3° steps, its sides' slopes 1.03 h|s''| apart, was refused as a corner).
    const double turn =
        2.0 * h *
        std::max(std::abs(left.Value(b.crank_rad, 2)), std::abs(right.Value(b.crank_rad, 2)));
    if (!(std::abs(b.jump) > turn)) return std::nullopt;
    // A corner keeps its size when the sides' cubics take twice the readings; the slopes'
    // disagreement across a kink of s'' (a smooth exact law's junction of s''') grows ~4×.
    if (k - 2 * p + 1 >= 0 && k + 2 * p < n) {
      const SideCubic wide_left = FitSide(x, y, k - 2 * p + 1, k + 1, c, h);
      const SideCubic wide_right = FitSide(x, y, k + 1, k + 2 * p + 1, c, h);
      const double wide = wide_right.Value(b.crank_rad, 1) - wide_left.Value(b.crank_rad, 1);
      if (!(std::abs(wide - b.jump) <= 0.25 * std::abs(b.jump))) return std::nullopt;
    }
    if (!QuinticsSeeTheCorner(x, y, k, sigma_m, tail, b)) return std::nullopt;
  }
  b.lift_m = 0.5 * (left.Value(b.crank_rad, 0) + right.Value(b.crank_rad, 0));
  const double jump_noise =
      sigma_m * std::hypot(DerivativeNoise(x, k - p + 1, k + 1, c, h, b.crank_rad, b.order),
                           DerivativeNoise(x, k + 1, k + p + 1, c, h, b.crank_rad, b.order));
  if (!(std::abs(b.jump) > tail * jump_noise)) return std::nullopt;
  return b;
}

// A jump, not a steep but smooth change over a few readings (a jerk-limited law's ramp of s''):
// the two sides' cubics fit their readings kBreakOverSmooth times better than one cubic fits
// them all.
bool SidesFitApart(const std::vector<double>& x, const std::vector<double>& y, long k,
                   const Sides& sides, double sigma_m, double tail) {
  const long p = kBreakFitPoints;
  const double h = x[k + 1] - x[k], c = 0.5 * (x[k] + x[k + 1]);
  double joint_ss = 0.0;
  FitSide(x, y, k - p + 1, k + p + 1, c, h, &joint_ss);
  const double joint = std::sqrt(joint_ss / (2 * p - 4));
  return kBreakOverSmooth * sides.rms_m < joint && joint > tail * sigma_m;
}

// How near a reading a break over interval k is put at it (kBreakSnapFraction,
// kBreakSnapResiduals).
double SnapDistance(const std::vector<double>& x, long k, const Sides& sides, double sigma_m,
                    const LiftBreak& b) {
  const double h = x[k + 1] - x[k];
  double snap = kBreakSnapFraction * h;
  if (b.order != 2 || !(std::abs(b.jump) > 0.0)) return snap;
  const double fit_m = std::max(sigma_m, sides.rms_m);
  const double lift_says = std::sqrt(2.0 * kBreakSnapResiduals * fit_m / std::abs(b.jump));
  return std::min(std::max(snap, lift_says), 0.25 * h);
}

}  // namespace

std::vector<LiftBreak> FindBreaks(const std::vector<double>& x, const std::vector<double>& y,
                                  double sigma_m) {
  std::vector<LiftBreak> found;
  const long n = static_cast<long>(x.size());
  const long m = BreakStatistics::m, d = BreakStatistics::d, p = kBreakFitPoints;
  if (n != static_cast<long>(y.size()) || n < 2 * (m + d + 6) + 2) return found;
  BreakStatistics stats(x, y, sigma_m);
  const std::vector<long> flagged = stats.Flagged();
  const std::vector<double>&jump = stats.jump(), &spike = stats.spike();
  // Runs of flagged intervals (a break at a reading flags the two beside it, its neighbours see
  // a part of it): the largest |Ĵ| of each run is the break's interval.
  for (size_t r = 0; r < flagged.size();) {
    size_t e = r;
    long k = flagged[r];
    while (e + 1 < flagged.size() && flagged[e + 1] - flagged[e] <= 2) {
      ++e;
      if (std::max(std::abs(jump[flagged[e]]), std::abs(spike[flagged[e]])) >
          std::max(std::abs(jump[k]), std::abs(spike[k]))) {
        k = flagged[e];
      }
    }
    r = e + 1;
    k = BestInterval(x, y, k);
    if (k - p + 1 < 0 || k + p >= n) continue;
    const Sides sides = FitSides(x, y, k);
    std::optional<LiftBreak> met = SidesMeet(x, y, k, sides, sigma_m, stats.tail());
    if (!met || !SidesFitApart(x, y, k, sides, sigma_m, stats.tail())) continue;
    LiftBreak b = *met;
    // An s'' jump is measured alike by the lines of s2 and by the cubics; a jump of s''' (a
    // kink of s'', which the lines see as J₃·h and the cubics as nothing) is no break here.
    if (b.order == 2 && !(std::abs(b.jump - jump[k]) <= kBreakJumpAgreement * std::abs(jump[k])))
      continue;
    const double snap = SnapDistance(x, k, sides, sigma_m, b);
    b.index = static_cast<size_t>(k);
    if (std::abs(b.crank_rad - x[k]) <= snap) {
      b.crank_rad = x[k];
      b.lift_m = y[k];
    } else if (std::abs(b.crank_rad - x[k + 1]) <= snap) {
      b.crank_rad = x[k + 1];
      b.lift_m = y[k + 1];
      b.index = static_cast<size_t>(k + 1);
    }
    if (found.empty() || b.crank_rad > found.back().crank_rad) found.push_back(b);
  }
  return found;
}

}  // namespace needle

namespace needle {

LiftBreak RefineBreak(const std::vector<double>& x, const std::vector<double>& y,
                      const LiftBreak& found, double width_rad) {
  // Cubics fitted on each side's readings from one width to kRefineWidths widths away (clear of
  // the readings the approximate place may have on the wrong side), met as FindBreaks meets them.
  constexpr double kRefineWidths = 12.0;
  const double at = found.crank_rad;
  auto index = [&](double t) {
    return static_cast<size_t>(std::lower_bound(x.begin(), x.end(), t) - x.begin());
  };
  const size_t l0 = index(at - kRefineWidths * width_rad), l1 = index(at - width_rad);
  const size_t r0 = index(at + width_rad), r1 = index(at + kRefineWidths * width_rad);
  if (l1 < l0 + 8 || r1 < r0 + 8) return found;
  const double h = width_rad;
  const SideCubic left = FitSide(x, y, l0, l1, at, h);
  const SideCubic right = FitSide(x, y, r0, r1, at, h);
  const double lo = at - width_rad, hi = at + width_rad;
  LiftBreak b = found;
  const auto root =
      found.order == 2
          ? RootIn([&](double t) { return right.Value(t, 1) - left.Value(t, 1); }, lo, hi)
          : RootIn([&](double t) { return right.Value(t, 0) - left.Value(t, 0); }, lo, hi);
  if (!root) return found;
  b.crank_rad = *root;
  b.jump = right.Value(b.crank_rad, found.order) - left.Value(b.crank_rad, found.order);
  b.lift_m = 0.5 * (left.Value(b.crank_rad, 0) + right.Value(b.crank_rad, 0));
  b.index = index(b.crank_rad);
  b.index = b.index > 0 ? b.index - 1 : 0;
  if (b.index + 1 < x.size() && x[b.index + 1] == b.crank_rad) ++b.index;
  return b;
}

}  // namespace needle
