// Junctions of a coarse exact table (FindJunctions, lib/lift_data.h): where the quintics fitted
// to the readings on either side of a reading disagree on s''.
#include <Eigen/Core>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
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
// The split at the largest |D| is kept unless another within p readings fits this many times
// better (CleanSplits): a clean split's misfit is the rounding's, one across a junction the jump's.
constexpr double kCleanSplitGain = 100.0;
// KinkBetween: the sides' slopes at a kink of s'' agree to this share of |D| over a step (an
// exact 3-4-5 top: 1e-5; a C∞ bump's foot, no kink: 0.025).
constexpr double kKinkSlopeShare = 0.05;
// JumpConfirmed judges only where the quintics' noise is below this share of the jump.
constexpr double kConfirmNoiseShare = 0.1;
// SmoothAcross: a kink sought within this many steps of the junction found...
constexpr double kKinkReachSteps = 3.0;
// ...fits its readings to this many times the rounding's variance per degree of freedom.
constexpr double kSmoothSquares = 3.0;

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
  q.a = QrSolve(v, r);
  // s''(c) = 2 a_2 / h²: its weights are row 2 of the pseudo-inverse, (VᵀV)⁻¹Vᵀ.
  Eigen::Matrix<double, 6, 1> e = Eigen::Matrix<double, 6, 1>::Zero();
  e(2) = 2.0 / (q.h * q.h);
  const Eigen::Matrix<double, 6, 1> weights = LdltSolve(Gram(v), e);
  q.w2 = v * weights;
  return q;
}

// The sum of squared residuals of the quintic fitted to readings [from, to), m².
double Misfit(const std::vector<double>& x, const std::vector<double>& y, size_t from, size_t to) {
  const SideQuintic q = FitQuintic(x, y, from, to, x[from]);
  double sum = 0.0;
  for (size_t i = from; i < to; ++i) {
    const double r = y[i] - q.Value(x[i], 0);
    sum += r * r;
  }
  return sum;
}

// The readings where the table leaves and meets the seat (the last reading of lift 0 before the
// first above it, and the first after the last): a quintic's readings straddle neither.
struct Seat {
  long first = 0, last = 0;
  bool Straddled(long from, long to) const {  // readings [from, to)
    return (from < first && to - 1 > first) || (from < last && to - 1 > last);
  }
};

// The misfit of the split between readings j and j + 1: the sum of squared residuals of the
// quintics through readings j − p + 1 … j and j + 1 … j + p, m² (+∞ where they do not fit in
// or straddle the seat's junction).
double SplitMisfit(const std::vector<double>& x, const std::vector<double>& y, long j, long p,
                   long n, const Seat& seat) {
  if (j - p + 1 < 0 || j + 1 + p > n || seat.Straddled(j - p + 1, j + 1) ||
      seat.Straddled(j + 1, j + 1 + p)) {
    return std::numeric_limits<double>::infinity();
  }
  return Misfit(x, y, static_cast<size_t>(j - p + 1), static_cast<size_t>(j + 1)) +
         Misfit(x, y, static_cast<size_t>(j + 1), static_cast<size_t>(j + 1 + p));
}

// The clean splits near reading k, cleanest first: j within p of k whose two sides' quintics fit
// kCleanSplitGain times better than the split the largest |D| chose (`at_k`) and than one quintic
// through both sides' readings (a junction lies between them). Where the largest |D| is not a
// junction's own (a second junction a few readings away, or a quintic across one whose s'' at
// its end strays further than the jump), the junctions lie between the sides of such splits:
// there the fits are the law's own. (Seven readings leave a quintic one residual: an s'' jump at
// a window's middle reading fits exactly. ConfirmedSplit's test of where the slopes meet sorts
// those out.)
std::vector<long> CleanSplits(const std::vector<double>& x, const std::vector<double>& y, long k,
                              long p, long n, double at_k, const Seat& seat) {
  std::vector<std::pair<double, long>> clean;
  for (long j = k - p; j <= k + p - 1; ++j) {
    const double r = SplitMisfit(x, y, j, p, n, seat);
    if (!(kCleanSplitGain * r < at_k)) continue;
    const double whole =
        Misfit(x, y, static_cast<size_t>(j - p + 1), static_cast<size_t>(j + 1 + p));
    if (!(kCleanSplitGain * r < whole)) continue;  // no junction between the two sides
    clean.emplace_back(r, j);
  }
  std::sort(clean.begin(), clean.end());
  std::vector<long> out;
  for (const auto& [r, j] : clean) out.push_back(j);
  return out;
}

// The junction at reading k (between = false) or between readings k and k + 1: where the slopes
// of the quintics through the p readings on each side meet (snapped to a reading within
// kBreakSnapFraction of a step), with the jump of their s'' there; `met`: whether they meet
// between the two readings.
LiftBreak Located(const std::vector<double>& x, const std::vector<double>& y, long k,
                  const SideQuintic& left, const SideQuintic& right, bool between,
                  bool* met = nullptr) {
  const double h = x[k + 1] - x[k];
  LiftBreak b;
  b.order = 2;
  b.index = static_cast<size_t>(k);
  if (between) {
    const auto at = RootIn([&](double t) { return right.Value(t, 1) - left.Value(t, 1); },
                           x[k] - 0.5 * h, x[k + 1] + 0.5 * h);
    b.crank_rad = at.value_or(0.5 * (x[k] + x[k + 1]));
    if (met)
      *met = at && *at >= x[k] - kBreakSnapFraction * h && *at <= x[k + 1] + kBreakSnapFraction * h;
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
  return b;
}

// The same from the quintics through the p readings on each side.
LiftBreak Located(const std::vector<double>& x, const std::vector<double>& y, long k, long p,
                  bool between) {
  const SideQuintic left = FitQuintic(x, y, k - p + 1, k + 1, x[k]);
  const SideQuintic right =
      between ? FitQuintic(x, y, k + 1, k + 1 + p, x[k + 1]) : FitQuintic(x, y, k, k + p, x[k]);
  return Located(x, y, k, left, right, between);
}

// Whether the quintics on each side of the split between readings k and k + 1 meet at a kink of s''
// (s''' jumps) that makes the |D| seen: where s''_right − s''_left has its root between them, their
// slopes agree (to kKinkSlopeShare of |D| over a step; they touch there, a double root Located does
// not find) and their s''' differ by at least half of |D| over a step. (A smooth law too fast for
// one quintic across both sides, a C∞ bump's foot, also meets there with one slope, but one s''':
// 0.1 of |D| over a step.)
bool KinkBetween(const std::vector<double>& x, long k, const SideQuintic& left,
                 const SideQuintic& right, double seen) {
  const double h = x[k + 1] - x[k];
  const auto at = RootIn([&](double t) { return right.Value(t, 2) - left.Value(t, 2); },
                         x[k] - kBreakSnapFraction * h, x[k + 1] + kBreakSnapFraction * h);
  if (!at) return false;
  const double slopes = std::abs(right.Value(*at, 1) - left.Value(*at, 1));
  const double jerk = std::abs(right.Value(*at, 3) - left.Value(*at, 3));
  return slopes <= kKinkSlopeShare * std::abs(seen) * h && jerk * h >= 0.5 * std::abs(seen);
}

// A junction between readings k and k + 1 located on a clean split (CleanSplits): kept where the
// two sides' slopes meet between the two readings (a smooth law's split, whose quintics agree
// to their extrapolation error, may have them meet anywhere or nowhere) with a jump at least a
// quarter of the |D| seen and above its noise. A kink of s'' (KinkBetween) locates to none and
// sets `kink`.
std::optional<LiftBreak> ConfirmedSplit(const std::vector<double>& x, const std::vector<double>& y,
                                        long k, long p, long n, double seen, double noise,
                                        bool* kink) {
  const SideQuintic left = FitQuintic(x, y, k - p + 1, k + 1, x[k]);
  const SideQuintic right = FitQuintic(x, y, k + 1, k + 1 + p, x[k + 1]);
  bool met = false;
  const LiftBreak b = Located(x, y, k, left, right, true, &met);
  if (!met || !(std::abs(b.jump) >= 0.25 * std::abs(seen))) {
    if (KinkBetween(x, k, left, right, seen)) *kink = true;
    return std::nullopt;
  }
  if (!(std::abs(b.jump) > TailSigmas(n, kBreakSigmas) * noise)) return std::nullopt;
  return b;
}

// Whether the readings within kSide of junction b are two quintics that meet at one ξ within
// kKinkReachSteps of it with equal s, s' and s'' (KinkedSquares), to the rounding: a kink of s''
// (a cubic B-spline's knot; the quintics of FindJunctions across it stray at their ends, and the
// split the largest |D| chose stood two readings past it), no s'' jump. A jump misfits them by
// D h²/2 a reading on, beyond any rounding FindJunctions' noise test lets through. ξ is sampled
// every quarter step, then found by Brent's minimum beside the best sample (on a 9-decimal
// table a sample a 16th of a step off the knot misfits by far more than the rounding). The
// window may reach the seat: a junction there is SeekBreaks' to drop or keep.
bool SmoothAcross(const std::vector<double>& x, const std::vector<double>& y, const LiftBreak& b,
                  double sigma_m) {
  const long n = static_cast<long>(x.size()), k = static_cast<long>(b.index);
  const long from = std::max(0L, k - kSide + 1), to = std::min(n, k + kSide + 1);
  constexpr long kParameters = 9;  // a quintic and three truncated powers
  if (to - from < kParameters + 3 || k + 1 >= n) return false;
  const double h = x[k + 1] - x[k], quarter = 0.25 * h;
  const auto squares = [&](double at) {
    return KinkedSquares(x, y, static_cast<size_t>(from), static_cast<size_t>(to), 5, {at}, 5);
  };
  const double lo = std::max(x[from], b.crank_rad - kKinkReachSteps * h);
  const double hi = std::min(x[to - 1], b.crank_rad + kKinkReachSteps * h);
  double least = std::numeric_limits<double>::infinity(), best = b.crank_rad;
  for (double at = lo; at <= hi; at += quarter) {
    if (const double v = squares(at); v < least) least = v, best = at;
  }
  const double refined = boost::math::tools::brent_find_minima(
                             squares, std::max(lo, best - quarter), std::min(hi, best + quarter),
                             std::numeric_limits<double>::digits / 2)
                             .second;
  return std::min(least, refined) <=
         kSmoothSquares * sigma_m * sigma_m * static_cast<double>(to - from - kParameters);
}

// The smooth level at reading i: the median |D| of the readings p+1 … p+6 away (clear of the
// windows that hold a junction at i), on the side where it is least (the other may hold a
// junction); +∞ where neither side has 3.
double SmoothLevel(const std::vector<double>& d, long i, long p) {
  const long n = static_cast<long>(d.size());
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
  return smooth;
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
  Seat seat{0, n - 1};
  while (seat.first + 1 < n && y[seat.first + 1] == 0.0) ++seat.first;
  while (seat.last > 0 && y[seat.last - 1] == 0.0) --seat.last;
  std::vector<long> flagged;
  for (long i = p - 1; i + p <= n; ++i) {
    const double smooth = SmoothLevel(d, i, p);
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
    // The split the largest |D| chose, or far cleaner ones near it that confirm a jump
    // (CleanSplits, ConfirmedSplit).
    const double at_k =
        Misfit(x, y, static_cast<size_t>(k - p + 1), static_cast<size_t>(k + 1)) +
        (between ? Misfit(x, y, static_cast<size_t>(k + 1), static_cast<size_t>(k + 1 + p))
                 : Misfit(x, y, static_cast<size_t>(k), static_cast<size_t>(k + p)));
    // Two clusters may meet at one junction: one break.
    const auto add = [&](const LiftBreak& b) {
      const double h = x[b.index + 1 < x.size() ? b.index + 1 : b.index] - x[b.index];
      if (std::none_of(found.begin(), found.end(), [&](const LiftBreak& f) {
            return std::abs(f.crank_rad - b.crank_rad) < 0.5 * h;
          })) {
        found.push_back(b);
      }
    };
    // Each clean split that confirms a jump, one within p readings (its windows hold no other's).
    std::vector<long> taken;
    bool kink = false;
    for (const long j : CleanSplits(x, y, k, p, n, at_k, seat)) {
      if (std::any_of(taken.begin(), taken.end(), [&](long t) { return std::abs(t - j) < p; }))
        continue;
      if (const auto b = ConfirmedSplit(x, y, j, p, n, d[k], noise[j], &kink)) {
        // A kink of s'' that the readings around it show (SmoothAcross) is none either; it
        // takes no room from the splits beside it.
        if (SmoothAcross(x, y, *b, sigma_m)) {
          kink = true;
          continue;
        }
        taken.push_back(j);
        add(*b);
      }
    }
    if (!taken.empty() || kink) continue;  // a kink of s'' (KinkBetween) is no junction
    // Else the split the largest |D| chose: the located jump is the jump seen (within a
    // quarter).
    const LiftBreak b = Located(x, y, k, p, between);
    if (std::abs(b.jump - d[k]) <= 0.25 * std::abs(d[k]) && !SmoothAcross(x, y, b, sigma_m)) add(b);
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
