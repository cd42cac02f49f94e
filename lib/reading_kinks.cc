// Kinks of s'' read from the readings next to each extreme of a local fit (lib/reading_kinks.h).
#include "lib/reading_kinks.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "lib/side_polynomial.h"

namespace needle {
namespace {

// The sides' degrees, tried in turn: a cubic B-spline's pieces, then any quintic law's.
constexpr int kSideDegrees[] = {3, 5};
// The longest side, readings.
constexpr size_t kLongestSide = 64;
// The sides' s''' differ by more than this many times the bound of their error...
constexpr double kJerkBounds = 3.0;
// ...and by at least this share of |s''(ξ)| over the shorter side's span (a kink that bends s''
// by a few percent of itself there; a smooth law's sides differ by their error alone).
constexpr double kJerkShare = 0.05;
// No limit on a fit's residual.
constexpr double kNoLimit = std::numeric_limits<double>::infinity();
// A side moved across a kink misfits by at least this many rounding bounds (KinkOf).
constexpr double kShiftMisfit = 8.0;
// ξ lies in the gap or within this share of a step of either reading (a kink at a reading).
constexpr double kRootReach = 0.25;
// The rounding's bound on one reading's error, in σ: q/2 = √3 σ.
const double kRoundingBound = std::sqrt(3.0);
// KinkInSquares: a septic through both sides misfits by this many times the residual of a cubic
// kinked at ξ, each per degree of freedom (a cubic B-spline's knot read every 0.25-1.5° to
// 1e-4 or 1e-3 mm: 4 to 100; a cycloidal, 3-4-5 or 4-5-6-7 peak: the kinked cubic misfits)...
constexpr double kSquaresRatio = 4.0;
// ...and by this many times the rounding's variance per degree of freedom.
constexpr double kSquaresOverRounding = 3.0;
// Where both sides together hold this many readings or more and the kinked cubic fits them to
// this many times the rounding's variance per degree of freedom, half those two: with n readings
// each variance is known to about √(2/n) of itself and their ratio to √(4/n), so a ratio of 2 at
// n = 64 lies four of that off 1. A cubic B-spline's knot every 0.05° and 0.1° to 1e-4 mm
// (bench/lift_tables.py's, 128 and 73 readings together): the septic 1.9 and 5.1 σ², the kinked
// cubic 0.9 and 1.5. Where the kinked cubic misfits, other knots lie within the sides and the
// kink's own s'' is theirs too: in a trial of 200 random B-spline laws (bench/bspline_trial.py
// seed 7), at 1e-3 mm, kinks taken at ratios of 2 to 4 with the kinked cubic at 2.4 to 8 σ² read
// their peaks 5 to 14 % high.
constexpr size_t kSquaresMany = 64;
constexpr double kSquaresKinkedFits = 2.0;
// The least readings of both sides for KinkInSquares (a septic's 8 and as many again).
constexpr size_t kSquaresLeast = 16;
// Gaps within this many readings of the fit's own top are tried without KinkMayLieBetween (a
// rounded table's knot, a cubic B-spline's at 1e-3 mm: within 6 of it in a trial of 200 laws);
// the others only where it passes, by the readings' shape and then by their squares.
constexpr size_t kTopReach = 6;

// A polynomial of degree `degree` fitted by least squares to readings [from, to), in
// u = (θ − c)/h, and what the weights of its derivatives on those readings are made from.
struct Side {
  size_t from = 0, to = 0;
  int degree = 0;
  double c = 0.0, h = 1.0;
  Eigen::VectorXd a;
  Eigen::MatrixXd v;                  // the basis on the readings, a row each
  Eigen::LDLT<Eigen::MatrixXd> gram;  // of VᵀV: a = (VᵀV)⁻¹Vᵀy

  // The row of the basis's `order`th derivative at t.
  Eigen::RowVectorXd Basis(double t, int order) const {
    const double u = (t - c) / h;
    Eigen::RowVectorXd b = Eigen::RowVectorXd::Zero(a.size());
    for (Eigen::Index m = order; m < a.size(); ++m) {
      double falling = 1.0;
      for (int j = 0; j < order; ++j) falling *= static_cast<double>(m - j);
      b(m) = falling * std::pow(u, static_cast<double>(m - order)) / std::pow(h, order);
    }
    return b;
  }
  double Value(double t, int order) const { return Basis(t, order) * a; }
  // Σ|g_i| of the derivative's weights g = V (VᵀV)⁻¹ bᵀ on the readings.
  double WeightSum(double t, int order) const {
    const Eigen::VectorXd b = Basis(t, order).transpose();
    return (v * gram.solve(b)).cwiseAbs().sum();
  }
  double Span(const std::vector<double>& x) const { return x[to - 1] - x[from]; }
};

// The side through readings [from, to), or nullopt where it leaves a residual above `bounds`
// times the rounding's (RoundingMisfitBound).
std::optional<Side> FitSide(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                            size_t to, int degree, double sigma, double bounds = 1.0) {
  Side s;
  s.from = from;
  s.to = to;
  s.degree = degree;
  s.c = 0.5 * (x[from] + x[to - 1]);  // u in [-1, 1]: VᵀV far better conditioned than on [0, 1]
  s.h = 0.5 * (x[to - 1] - x[from]);
  const Eigen::Index n = static_cast<Eigen::Index>(to - from);
  s.v = PowerBasis(x, from, to, s.c, s.h, degree);
  const Eigen::Map<const Eigen::VectorXd> r(y.data() + from, n);
  s.gram.compute(s.v.transpose() * s.v);
  s.a = s.gram.solve(s.v.transpose() * r);
  if ((s.v * s.a - r).cwiseAbs().maxCoeff() > bounds * RoundingMisfitBound(sigma))
    return std::nullopt;
  return s;
}

// The longest side of readings that ends at reading `end` (left: [end − p + 1, end]) or begins
// there (right: [end, end + p)), within [lo, hi) and kLongestSide readings, that fits; nullopt
// when the shortest does not. Doubling, then bisection (a longer side misfits once it reaches
// the next kink).
std::optional<Side> LongestSide(const std::vector<double>& x, const std::vector<double>& y,
                                size_t end, bool left, size_t lo, size_t hi, int degree,
                                double sigma) {
  const size_t room = std::min(kLongestSide, left ? end + 1 - lo : hi - end);
  const auto fit = [&](size_t p) {
    return left ? FitSide(x, y, end + 1 - p, end + 1, degree, sigma)
                : FitSide(x, y, end, end + p, degree, sigma);
  };
  size_t good = static_cast<size_t>(degree) + 2;
  if (good > room) return std::nullopt;
  std::optional<Side> best = fit(good);
  if (!best) return std::nullopt;
  size_t bad = room + 1;
  while (good < room) {  // doubling
    const size_t p = std::min(room, 2 * good);
    std::optional<Side> s = fit(p);
    if (!s) {
      bad = p;
      break;
    }
    good = p;
    best = std::move(s);
  }
  while (bad - good > 1) {  // bisection
    const size_t p = (good + bad) / 2;
    std::optional<Side> s = fit(p);
    if (s) {
      good = p;
      best = std::move(s);
    } else {
      bad = p;
    }
  }
  return best;
}

// Whether a kink may lie between readings j and j + 1, from the fewest readings: the degree + 2
// on each side each fit a polynomial of `degree`, and one of degree + 2 through both misfits (a
// smooth law's fits, where a cubic through both may not: a dense exact table's every gap). A
// kink the readings place shows there: its jump J makes J δ³/6 ≥ q within a step. The sides are
// then sought in full (LongestSide).
bool KinkMayLieBetween(const std::vector<double>& x, const std::vector<double>& y, size_t j,
                       int degree, double sigma, size_t lo, size_t hi) {
  const size_t m = static_cast<size_t>(degree) + 2;
  if (j + 1 < lo + m || j + 1 + m > hi) return false;
  return !FitSide(x, y, j + 1 - m, j + 1 + m, degree + 2, sigma) &&
         FitSide(x, y, j + 1 - m, j + 1, degree, sigma) &&
         FitSide(x, y, j + 1, j + 1 + m, degree, sigma);
}

// s''(ξ) from the half of each side's readings nearest ξ (at least degree + 2), nullopt where
// they leave no fewer.
std::optional<double> HalfSidesPeak(const std::vector<double>& x, const std::vector<double>& y,
                                    const Side& l, const Side& r, double xi, double sigma) {
  const size_t least = static_cast<size_t>(l.degree) + 2;
  const size_t pl = std::max(least, (l.to - l.from) / 2), pr = std::max(least, (r.to - r.from) / 2);
  if (pl >= l.to - l.from && pr >= r.to - r.from) return std::nullopt;
  const auto hl = FitSide(x, y, l.to - pl, l.to, l.degree, sigma, kNoLimit);
  const auto hr = FitSide(x, y, r.from, r.from + pr, r.degree, sigma, kNoLimit);
  return 0.5 * (hl->Value(xi, 2) + hr->Value(xi, 2));
}

// Whether the readings of both cubic sides tell a kink by their squares where no reading alone
// does (a rounded table's: each side, moved across it, still fits the rounding): a cubic
// kinked in the gap (at its best ξ within half a step of the gap) leaves a quarter or less of
// what a septic through them all leaves, per degree of freedom, and the septic misfits beyond
// the rounding (the kinked cubic itself need not fit to the rounding: B-spline knots in a trial
// left it 1 to 8 σ²). A smooth law's sides, each one cubic to the rounding, meet with s, s' apart
// by their error: kinked at one ξ they misfit, and the septic fits (a cycloidal peak every
// 0.25-1.5° to 1e-3 mm: 20 to 50 times the rounding per degree of freedom against 0.3 to 2).
bool KinkInSquares(const std::vector<double>& x, const std::vector<double>& y, size_t j,
                   const Side& l, const Side& r, double sigma) {
  if (l.degree != 3 || r.to - l.from < kSquaresLeast) return false;
  constexpr int kScan = 40;
  const double step = x[j + 1] - x[j];
  double kinked = std::numeric_limits<double>::infinity();
  for (int t = 0; t <= kScan; ++t) {
    const double at = x[j] - 0.5 * step + 2.0 * step * t / kScan;
    kinked = std::min(kinked, KinkedSquares(x, y, l.from, r.to, 3, {at}));
  }
  const double n = static_cast<double>(r.to - l.from);
  const double septic = KinkedSquares(x, y, l.from, r.to, 7, {}) / (n - 8);
  const double cubic = kinked / (n - 5), rounding = sigma * sigma;
  const bool many = r.to - l.from >= kSquaresMany && cubic <= kSquaresKinkedFits * rounding;
  const double share = many ? 0.5 : 1.0;
  return septic > share * kSquaresRatio * cubic && septic > share * kSquaresOverRounding * rounding;
}

// The kink between readings j and j + 1 from its two sides, or nullopt where they do not meet
// there as a kink that peaks in `sign`; readings [lo, hi) are the piece's. The readings show it
// (`by_shape`: KinkMayLieBetween saw it, it is placed and its sides misfit moved across it), or
// the sum of their squares does (KinkInSquares).
std::optional<LocalNode> KinkOf(const std::vector<double>& x, const std::vector<double>& y,
                                size_t j, const Side& l, const Side& r, double sigma, double sign,
                                size_t lo, size_t hi, bool by_shape) {
  const double step = x[j + 1] - x[j];
  const auto at = RootIn([&](double t) { return r.Value(t, 2) - l.Value(t, 2); },
                         x[j] - kRootReach * step, x[j + 1] + kRootReach * step);
  if (!at) return std::nullopt;
  const double xi = *at;
  const auto bound = [&](int order) {  // of the difference of the sides' derivative
    return kRoundingBound * sigma * (l.WeightSum(xi, order) + r.WeightSum(xi, order));
  };
  const auto diff = [&](int order) { return std::abs(r.Value(xi, order) - l.Value(xi, order)); };
  if (diff(0) > kJerkBounds * bound(0) || diff(1) > kJerkBounds * bound(1)) return std::nullopt;
  const double jerk_l = l.Value(xi, 3), jerk_r = r.Value(xi, 3);
  const double s2 = 0.5 * (l.Value(xi, 2) + r.Value(xi, 2));
  const double span = std::min(l.Span(x), r.Span(x));
  if (!(diff(3) > kJerkBounds * bound(3) && diff(3) * span >= kJerkShare * std::abs(s2)))
    return std::nullopt;
  // A top: sign·s'' rises into ξ and falls after it (to the sides' error).
  const double e3l = kRoundingBound * sigma * l.WeightSum(xi, 3);
  const double e3r = kRoundingBound * sigma * r.WeightSum(xi, 3);
  if (!(sign * jerk_l >= -e3l && sign * jerk_r <= e3r)) return std::nullopt;
  // The readings place it (lib/reading_kinks.h): δ = (6q/J)^⅓ under a step.
  const double q = std::sqrt(12.0) * sigma;
  by_shape = by_shape && std::cbrt(6.0 * q / diff(3)) < step;
  // And each side, moved `shift` readings on across ξ, misfits by kShiftMisfit bounds: a kink
  // of this jump J shows as J δ³/6 at δ = 3 (6q/J)^⅓ past it, 27 q, less what the fit takes up
  // (a cubic B-spline's knots, read to 9 decimals: 200 to 10⁵ bounds). A smooth law's side
  // misfits little more a few readings on (1 to 4 bounds: a 4-5-6-7 rise every 1.5° to 1e-4 mm,
  // whose sides each fit the rounding and differ in s''' by their bias, beyond its error).
  bool shown = false;
  if (by_shape) {
    const size_t shift =
        static_cast<size_t>(std::ceil(std::max(2.0, 3.0 * std::cbrt(6.0 * q / diff(3)) / step)));
    shown = l.to + shift <= hi && r.from >= lo + shift &&
            !FitSide(x, y, l.from + shift, l.to + shift, l.degree, sigma, kShiftMisfit) &&
            !FitSide(x, y, r.from - shift, r.to - shift, r.degree, sigma, kShiftMisfit);
  }
  // Or, where no reading shows it, the sum of their squares does.
  if (!shown && !KinkInSquares(x, y, j, l, r, sigma)) return std::nullopt;
  LocalNode k;
  k.x = xi;
  for (int d = 0; d < 2; ++d) k.s[d] = 0.5 * (l.Value(xi, d) + r.Value(xi, d));
  k.s[2] = s2;
  // Its error: the rounding's through the sides, and their truncation's (a smooth law's part,
  // or a smaller kink, that the rounding hides in each side), twice the change of s''(ξ) from
  // sides of half as many readings: the whole of a truncation error that halves with the sides
  // (one falling faster is overstated). A 9-decimal B-spline's sides agree to 1e-8 of s''.
  k.band2 = 0.5 * bound(2) + 2.0 * std::abs(s2 - HalfSidesPeak(x, y, l, r, xi, sigma).value_or(s2));
  k.window = static_cast<int>((l.to - l.from) + (r.to - r.from));
  k.width = l.Span(x) + r.Span(x) + step;
  return k;
}

// The kinks peaking in `sign` between readings [lo, hi) that a fit of `law` rounds off and that
// reach the extreme node's band (`extreme`: a kink that is only a local top, as the s'' = 0
// between a 3-4-5 rise and its return, is left to the fit).
std::vector<LocalNode> KinksIn(const std::vector<double>& x, const std::vector<double>& y,
                               size_t lo, size_t hi, double sigma, double sign,
                               const PiecewisePolynomial& law, const LocalNode& extreme,
                               size_t from, size_t to) {
  std::vector<LocalNode> kinks;
  size_t top = lo;  // the reading where the fit peaks
  for (size_t j = lo; j < hi; ++j)
    if (sign * law.Evaluate(x[j], 2) > sign * law.Evaluate(x[top], 2)) top = j;
  for (size_t j = lo; j + 1 < hi; ++j) {
    const bool near_top = j + kTopReach >= top && j <= top + kTopReach;
    for (const int degree : kSideDegrees) {
      const bool may = KinkMayLieBetween(x, y, j, degree, sigma, from, to);
      if (!may && !(near_top && degree == 3)) continue;
      const std::optional<Side> l = LongestSide(x, y, j, true, from, to, degree, sigma);
      if (!l) continue;
      const std::optional<Side> r = LongestSide(x, y, j + 1, false, from, to, degree, sigma);
      if (!r) continue;
      std::optional<LocalNode> k = KinkOf(x, y, j, *l, *r, sigma, sign, from, to, may);
      if (!k || !(sign * k->s[2] > sign * law.Evaluate(k->x, 2)) ||
          !(sign * k->s[2] >= sign * extreme.s[2] - extreme.band2)) {
        continue;
      }
      // One kink at a reading is seen from the gaps on both sides: keep the tighter.
      if (!kinks.empty() && k->x - kinks.back().x < x[j + 1] - x[j]) {
        if (k->band2 < kinks.back().band2) kinks.back() = *k;
      } else {
        kinks.push_back(*k);
      }
      break;
    }
  }
  return kinks;
}

}  // namespace

std::vector<LocalNode> ReadingKinks(const std::vector<double>& x, const std::vector<double>& y,
                                    double sigma_m, const LocalFit& fit, LocalTrim trim) {
  std::vector<LocalNode> kinks;
  const auto& nodes = fit.nodes;
  if (x.size() != y.size() || x.size() > static_cast<size_t>(kLocalMaxNodes) || nodes.size() < 3 ||
      !(sigma_m > 0.0)) {
    return kinks;
  }
  // The fit's readings (FitLocal's trim, dropped where it applied none).
  size_t from = 0, to = x.size();
  if (fit.trimmed) {
    from = std::lower_bound(x.begin(), x.end(), x.front() + trim.front_rad) - x.begin();
    to = std::upper_bound(x.begin(), x.end(), x.back() - trim.back_rad) - x.begin();
  }
  for (const double sign : {1.0, -1.0}) {
    size_t e = 0;  // the extreme node
    for (size_t i = 1; i < nodes.size(); ++i)
      if (sign * nodes[i].s[2] > sign * nodes[e].s[2]) e = i;
    const double a = nodes[e >= 1 ? e - 1 : 0].x;
    const double b = nodes[std::min(nodes.size() - 1, e + 1)].x;
    const size_t lo = std::max<size_t>(
        from, static_cast<size_t>(std::lower_bound(x.begin(), x.end(), a) - x.begin()));
    const size_t hi = std::min<size_t>(
        to, static_cast<size_t>(std::upper_bound(x.begin(), x.end(), b) - x.begin()));
    for (const LocalNode& k : KinksIn(x, y, lo, hi, sigma_m, sign, fit.law, nodes[e], from, to))
      kinks.push_back(k);
  }
  std::sort(kinks.begin(), kinks.end(),
            [](const LocalNode& p, const LocalNode& q) { return p.x < q.x; });
  return kinks;
}

void AddReadingKinks(const std::vector<double>& x, const std::vector<double>& y, double sigma,
                     LocalTrim trim, LocalFit* fit) {
  const std::vector<LocalNode> kinks = ReadingKinks(x, y, sigma, *fit, trim);
  if (kinks.empty()) return;
  // The piece's first and last nodes stay: its law starts and ends at its readings' ends.
  const double first = fit->nodes.front().x, last = fit->nodes.back().x;
  for (const LocalNode& k : kinks) {
    const auto near = [&](const LocalNode& n) {
      return n.x != first && n.x != last && std::abs(n.x - k.x) < 0.25 * n.width;
    };
    fit->nodes.erase(std::remove_if(fit->nodes.begin(), fit->nodes.end(), near), fit->nodes.end());
    fit->nodes.push_back(k);
  }
  std::stable_sort(fit->nodes.begin(), fit->nodes.end(),
                   [](const LocalNode& a, const LocalNode& b) { return a.x < b.x; });
  fit->law = QuinticHermite(fit->nodes);
}

std::vector<LocalNode> KinkPeaks(const std::vector<LocalNode>& nodes, double sign) {
  constexpr double kKinkContrast = 4.0;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<const LocalNode*> n;
  for (const LocalNode& node : nodes) n.push_back(&node);
  std::stable_sort(n.begin(), n.end(),
                   [](const LocalNode* a, const LocalNode* b) { return a->x < b->x; });
  const auto y = [&](size_t i) { return sign * n[i]->s[2]; };
  const auto x = [&](size_t i) { return n[i]->x; };
  // Half the second divided difference of s'' (about |s''''|/2) from the three nodes around i,
  // NaN where they are not on one piece.
  const auto second = [&](size_t i) {
    if (i == 0 || i + 1 >= n.size() || !(x(i - 1) < x(i) && x(i) < x(i + 1))) return kNaN;
    const double left = (y(i) - y(i - 1)) / (x(i) - x(i - 1));
    const double right = (y(i + 1) - y(i)) / (x(i + 1) - x(i));
    return std::abs(right - left) / (x(i + 1) - x(i - 1));
  };
  std::vector<LocalNode> peaks;
  for (size_t a = 1; a + 2 < n.size(); ++a) {
    const size_t b = a + 1;
    const double da = second(a), db = second(b);
    if (!(da >= 0.0 && db >= 0.0)) continue;  // the four nodes are not on one piece
    // The interval's nodes hold the narrowest windows (a local fit's on an exact table, where a
    // misfit stops them growing): wider ones are spaced too far apart to tell a kink from a
    // smooth peak.
    if (n[a]->window > kLocalMinimumPoints || n[b]->window > kLocalMinimumPoints) continue;
    const double before = a >= 2 ? second(a - 1) : kNaN, after = second(b + 1);
    const double beside = std::fmax(before, after);  // the one that is there
    if (!(std::min(da, db) > kKinkContrast * beside)) continue;
    // And above the nodes' own noise: each of the two bends off the line through its
    // neighbours by more than twice the largest half-width among the three.
    const auto bends = [&](size_t i) {
      const double t = (x(i) - x(i - 1)) / (x(i + 1) - x(i - 1));
      const double off = std::abs(y(i) - (1.0 - t) * y(i - 1) - t * y(i + 1));
      return off > 2.0 * std::max({n[i - 1]->band2, n[i]->band2, n[i + 1]->band2});
    };
    if (!bends(a) || !bends(b)) continue;
    const double left = (y(a) - y(a - 1)) / (x(a) - x(a - 1));   // slope into the interval
    const double right = (y(b + 1) - y(b)) / (x(b + 1) - x(b));  // and out of it
    if (!(left > right)) continue;
    const double at = (y(b) - y(a) + left * x(a) - right * x(b)) / (left - right);
    const double top = y(a) + left * (at - x(a));
    if (!(at > x(a) && at < x(b) && top > std::max(y(a), y(b)))) continue;  // no peak inside
    LocalNode peak;
    peak.x = at;
    peak.s[2] = sign * top;
    peak.band2 = std::max(n[a]->band2, n[b]->band2);
    peaks.push_back(peak);
  }
  return peaks;
}

}  // namespace needle
