// Local polynomial regression with Lepski's window (lib/local_fit.h).
#include "lib/local_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "lib/local_window.h"

namespace needle {
namespace {

using local_window::kTerms;
constexpr double kNodeSpacing = 0.5;  // nodes half a window's width apart
// A shifted window is taken for a junction's side when its |s⁽⁵⁾| is below this share of every
// misfitting window's, or when every misfitting window misses by this many times the rounding's
// bound (ShiftedNodeAt).
constexpr double kSmoother = 0.1;
constexpr double kGrossMisfit = 1000.0;

}  // namespace

namespace {

using local_window::Estimate;
using local_window::FitAt;
using local_window::FittedPoints;
using local_window::Misfits;
using local_window::Points;

// The window sizes Lepski's rule tries: 7, 9, 11, … (×1.25, distinct), up to n.
std::vector<size_t> WindowSizes(size_t n) {
  std::vector<size_t> sizes;
  for (double want = kLocalMinimumPoints;; want *= 1.25) {
    const size_t k = std::min(n, static_cast<size_t>(std::lround(want)));
    if (sizes.empty() || k > sizes.back()) sizes.push_back(k);
    if (k == n) return sizes;
  }
}

// Which readings a window at t takes: the nearest, or only those at and before t (left), or at
// and after it (right). A one-sided window stays inside its piece next to a junction that the
// breaks did not find, where every centred one reaches across it (Katkovnik's LPA-ICI).
enum class Side { kNearest, kLeft, kRight };
constexpr Side kSides[] = {Side::kNearest, Side::kLeft, Side::kRight};

// Grows [lo, hi) to `size` points on `side` of t; false when that side has too few.
bool Grow(const Points& p, double t, Side side, size_t size, size_t* lo, size_t* hi) {
  const size_t n = p.x.size();
  while (*hi - *lo < size) {
    const bool left = side == Side::kLeft || (side == Side::kNearest && *lo > 0 &&
                                              (*hi == n || t - p.x[*lo - 1] <= p.x[*hi] - t));
    if (left ? *lo == 0 : *hi == n) return false;
    left ? --*lo : ++*hi;
  }
  return true;
}

// The node at t on `side`: Lepski's window, trying sizes from sizes[from] on (a neighbour's
// choice less two: the rule compares a window with the narrower ones tried), and none wider
// than the first whose polynomial misfits its readings. `chosen_size` gets the index of the size
// chosen; nullopt when the side has fewer than sizes[from] points.
std::optional<LocalNode> NodeAt(const Points& p, double t, double sigma, bool quantized,
                                const std::vector<size_t>& sizes, Side side, size_t from,
                                size_t* chosen_size, bool* misfit_ended = nullptr,
                                bool* narrowest_misfits = nullptr) {
  const auto at = std::lower_bound(p.x.begin(), p.x.end(), t);
  size_t lo = at - p.x.begin(), hi = lo;
  if (side == Side::kLeft) lo = hi = at != p.x.end() && *at == t ? lo + 1 : lo;
  std::vector<Estimate> tried;
  size_t chosen = 0, chosen_lo = lo, chosen_hi = hi;
  for (size_t j = from; j < sizes.size() && Grow(p, t, side, sizes[j], &lo, &hi); ++j) {
    const Estimate e = FitAt(p, t, lo, hi, quantized);
    bool agrees = true;
    for (const Estimate& narrower : tried) {
      agrees = agrees && std::abs(e.s[2] - narrower.s[2]) <= kLepskiSigmas * sigma * narrower.sd2;
    }
    const bool misfits = Misfits(e, hi - lo, sigma, quantized);
    // A neighbour's window too wide here: start again from the narrowest.
    if (misfits && tried.empty() && from > 0) {
      return NodeAt(p, t, sigma, quantized, sizes, side, 0, chosen_size, misfit_ended,
                    narrowest_misfits);
    }
    if (narrowest_misfits && tried.empty() && j == 0) *narrowest_misfits = misfits;
    tried.push_back(e);
    const bool ends = misfits && tried.size() > 1;
    if (misfit_ended) *misfit_ended = agrees && ends;
    if (!agrees || ends) break;
    chosen = tried.size() - 1;
    std::tie(chosen_lo, chosen_hi) = std::pair(lo, hi);
  }
  if (tried.empty()) return std::nullopt;
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
  // A piece of a few readings (a coarse rise's): no wider window measures the truncation,
  // narrower ones hardly do. A lower degree does, the quartic on the same readings, whose s''
  // differs from the quintic's by the quintic's error and more (a harmonic rise of 7 readings at
  // 1.5° and its break's: quintic −2.5 %, quartic +20 %; the windows of 7 and 8 differ by 0.9 %).
  if (p.x.size() < static_cast<size_t>(kLocalFewReadings) && chosen_hi - chosen_lo >= kTerms) {
    step = std::max(
        step, std::abs(e.s[2] - FitAt(p, t, chosen_lo, chosen_hi, quantized, kTerms - 1).s[2]));
  }
  node.band2 = 1.96 * sigma * e.sd2 + step;
  return node;
}

// Where the narrowest window of the nearest readings misfits them (a junction of s''' lies
// inside it that no break marks: a modified trapezoid's ends of constant acceleration, on a
// coarse exact table), the narrowest windows that hold t shifted either way, and of those whose
// polynomial fits its readings the smoothest, the least |s⁽⁵⁾| (Harten's ENO choice of stencil),
// when the junction shows: that window smoother than every misfitting one by kSmoother, or every
// misfitting one missing by kGrossMisfit roundings (a junction's s''' jump J makes each window
// across it miss by some J h³). Its readings then lie on one side of the junction, and the fit
// is that side's law. (A residual alone cannot choose: 7 readings leave a quintic one degree of
// freedom, which an odd-symmetric stretch, the cosine between a modified trapezoid's plateaus,
// fits to round-off whatever its s'' at the ends; a window across a junction symmetric about it
// has no fifth power either; and a smooth law that no quintic fits to the rounding, a
// C-infinity bump, has a window now and then that does, one-sided and worse than the nearest,
// its neighbours missing by tens of roundings.) Its band's step is the largest change of s'' to
// the nearest window and to the other windows that fit (how far the junction's place could move
// the value: the band holds what the nearest window read; BestNodeAt widens it to hold the node
// as read without the shift, band and all). nullopt when no shifted window is chosen.
std::optional<LocalNode> ShiftedNodeAt(const Points& p, double t, double sigma,
                                       const LocalNode& nearest, size_t size) {
  const size_t n = p.x.size();
  if (n < size) return std::nullopt;
  std::optional<Estimate> best;
  std::vector<double> fitting;  // s'' of every window that fits
  double least_misfit_fifth = std::numeric_limits<double>::infinity();
  double least_misfit = std::numeric_limits<double>::infinity();  // residual, m
  // (A node at a reading may lie a rounding off it: the window starting or ending there holds it.)
  const double slack = 1e-9 * (p.x[n - 1] - p.x[0]);
  for (size_t lo = 0; lo + size <= n; ++lo) {
    if (p.x[lo] > t + slack) break;
    if (p.x[lo + size - 1] < t - slack) continue;
    const Estimate e = FitAt(p, t, lo, lo + size, true);
    if (Misfits(e, size, sigma, true)) {
      least_misfit_fifth = std::min(least_misfit_fifth, e.fifth);
      least_misfit = std::min(least_misfit, e.largest_residual);
      continue;
    }
    fitting.push_back(e.s[2]);
    if (!best || e.fifth < best->fifth) best = e;
  }
  if (!best) return std::nullopt;
  const bool smoother = best->fifth < kSmoother * least_misfit_fifth;
  const bool gross = least_misfit > kGrossMisfit * RoundingMisfitBound(sigma);
  if (!smoother && !gross) return std::nullopt;
  LocalNode node = nearest;  // its place and spacing width
  for (int d = 0; d < 3; ++d) node.s[d] = best->s[d];
  node.window = static_cast<int>(size);
  double step = std::abs(best->s[2] - nearest.s[2]);
  for (double other : fitting) step = std::max(step, std::abs(other - best->s[2]));
  node.band2 = 1.96 * sigma * best->sd2 + step;
  return node;
}

// The node at t: the nearest readings' window, or where that window ended on a misfit (a
// junction the breaks did not find lies within its reach), a one-sided window that grows wider
// and has the narrower band. `last` holds each side's chosen size, the next node's start.
LocalNode BestNodeAt(const Points& p, double t, double sigma, bool quantized,
                     const std::vector<size_t>& sizes, std::array<size_t, 3>* last) {
  auto on = [&](int k, bool* misfit_ended, bool* narrowest_misfits) {
    const size_t from = (*last)[k] >= 2 ? (*last)[k] - 2 : 0;
    std::optional<LocalNode> node = NodeAt(p, t, sigma, quantized, sizes, kSides[k], from,
                                           &(*last)[k], misfit_ended, narrowest_misfits);
    if (!node && from > 0) {
      node = NodeAt(p, t, sigma, quantized, sizes, kSides[k], 0, &(*last)[k], misfit_ended,
                    narrowest_misfits);
    }
    return node;
  };
  bool misfit_ended = false, narrowest_misfits = false;
  LocalNode best = *on(0, &misfit_ended, &narrowest_misfits);  // the nearest side has the points
  // An exact or rounded table (the rounding's model) whose narrowest window misfits here: a
  // shifted window's value, with a band that also holds the node's as read without it.
  std::optional<LocalNode> shifted;
  if (quantized && narrowest_misfits && best.window == static_cast<int>(sizes[0])) {
    shifted = ShiftedNodeAt(p, t, sigma, best, sizes[0]);
  }
  const auto chosen = [&shifted](const LocalNode& node) {
    if (!shifted) return node;
    LocalNode out = *shifted;
    out.band2 = std::max(out.band2, std::abs(node.s[2] - out.s[2]) + node.band2);
    return out;
  };
  if (!misfit_ended) return chosen(best);
  const double spacing_width = best.width;
  std::optional<LocalNode> sides[2];
  for (int k = 1; k < 3; ++k) {
    sides[k - 1] = on(k, nullptr, nullptr);
    const std::optional<LocalNode>& node = sides[k - 1];
    if (node && node->window > best.window && node->band2 < best.band2) {
      best = *node;
      if (kSides[k] == Side::kLeft) best.width = spacing_width;  // its span lies behind the node
    }
  }
  // Where the two sides' s'' differ beyond their bands, s'' jumps here (a junction no break
  // marks): the band reaches each side's value and its band.
  if (sides[0] && sides[1] &&
      std::abs(sides[0]->s[2] - sides[1]->s[2]) > sides[0]->band2 + sides[1]->band2) {
    for (const std::optional<LocalNode>& node : sides) {
      best.band2 = std::max(best.band2, std::abs(node->s[2] - best.s[2]) + node->band2);
    }
  }
  return chosen(best);
}

// Where the law between two nodes misses a reading of an exact or rounded table by more than
// kRefineMisfits times their s'' bands over the interval (band2 L²/8) plus four rounding bounds,
// a node at the reading it misses most, a quarter of the interval or more from both, until none
// is (a 3-4-5 rise, one quintic, left 76° between two nodes: a_min 15 % short; docs/lift-data.md).
void AddNodesWhereTheLawMisses(const Points& p, double sigma, const std::vector<size_t>& sizes,
                               LocalFit* fit) {
  constexpr double kRefineMisfits = 16.0;
  if (!p.moments.empty()) return;
  for (size_t round = 0; round < p.x.size(); ++round) {
    double worst = 0.0;
    std::optional<size_t> at;
    auto& nodes = fit->nodes;
    for (size_t k = 0; k + 1 < nodes.size(); ++k) {
      const double a = nodes[k].x, b = nodes[k + 1].x, span = b - a;
      if (!(span > 0.0)) continue;
      const double allowed =
          4.0 * RoundingMisfitBound(sigma) +
          kRefineMisfits * std::max(nodes[k].band2, nodes[k + 1].band2) * span * span / 8.0;
      const auto first = std::lower_bound(p.x.begin(), p.x.end(), a + 0.25 * span);
      for (auto it = first; it != p.x.end() && *it <= b - 0.25 * span; ++it) {
        const size_t i = static_cast<size_t>(it - p.x.begin());
        const double miss = std::abs(p.y[i] - fit->law.Evaluate(p.x[i], 0)) / allowed;
        if (miss > 1.0 && miss > worst) {
          worst = miss;
          at = i;
        }
      }
    }
    if (!at) return;
    std::array<size_t, 3> last{};
    const LocalNode node = BestNodeAt(p, p.x[*at], sigma, true, sizes, &last);
    const auto later = [](const LocalNode& l, const LocalNode& r) { return l.x < r.x; };
    nodes.insert(std::upper_bound(nodes.begin(), nodes.end(), node, later), node);
    fit->law = QuinticHermite(nodes);
  }
}

// The least and largest s'' of `law` between the nodes either side of `at`, where either strays
// beyond what the three nodes read (each s'' and its band) by more than kStrayBands of their
// largest band; nullopt where both stay near them. A node closer to its neighbours than their
// windows are wide carries their values' differences, noise and bias, over the spacing squared
// into s'' (a modified sine's rise to 1e-4 mm at 0.1°: nodes of 159 and 42 readings 0.17° apart,
// the law's a_min −243.6 m/s² at 400 rpm against the closed form's −165.8).
std::optional<std::array<double, 2>> Stray(const PiecewisePolynomial& law,
                                           std::vector<LocalNode>::const_iterator at) {
  constexpr double kStrayBands = 1.0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, band = 0.0;
  for (auto it = at - 1; it != at + 2; ++it) {
    lo = std::min(lo, it->s[2] - it->band2);
    hi = std::max(hi, it->s[2] + it->band2);
    band = std::max(band, it->band2);
  }
  const PiecewisePolynomial part = law.Restrict((at - 1)->x, (at + 1)->x);
  const double least = ExtremeOf(part, 2, -1.0).second, most = ExtremeOf(part, 2, 1.0).second;
  if (least >= lo - kStrayBands * band && most <= hi + kStrayBands * band) return std::nullopt;
  return std::array<double, 2>{least, most};
}

// A node at the law's largest and smallest s'' where it lies a quarter of the interval or more
// from both nodes (a 3-4-5 rise, one quintic: nodes 10° apart, the Hermite's a_min 6.9 % short),
// kept where the law then stays near its nodes (Stray). Where it does not, the node is left out
// and its neighbours' bands reach the stray and the node's own s'' and band: what the table
// cannot tell apart there (a modified sine to 1e-4 mm at 0.5°: a_max +7.5 % with the node,
// +1.8 % without; a cubic-spline rise read every 2.5°, its a_min between two readings, which
// only the stray came near).
void AddNodesAtExtremes(const Points& p, double sigma, const std::vector<size_t>& sizes,
                        LocalFit* fit) {
  auto& nodes = fit->nodes;
  const auto later = [](const LocalNode& l, const LocalNode& r) { return l.x < r.x; };
  std::vector<std::pair<double, double>> widen;  // a neighbour's place and its band's reach
  for (int round = 0, added = 1; round < 4 && added; ++round) {
    added = 0;
    for (const double sign : {1.0, -1.0}) {
      LocalNode node{ExtremeOf(fit->law, 2, sign).first};
      const auto right = std::upper_bound(nodes.begin(), nodes.end(), node, later);
      if (right == nodes.begin() || right == nodes.end()) continue;
      const double a = (right - 1)->x, b = right->x, x = node.x, q = 0.25 * (b - a);
      if (!(x - a > q && b - x > q) || x < p.x.front() || x > p.x.back()) continue;
      std::array<size_t, 3> last{};
      node = BestNodeAt(p, x, sigma, true, sizes, &last);
      const auto at = nodes.insert(std::upper_bound(nodes.begin(), nodes.end(), node, later), node);
      PiecewisePolynomial law = QuinticHermite(nodes);
      // (`at` lies strictly between two nodes: x is inside (a, b), and BestNodeAt keeps it.)
      if (const std::optional<std::array<double, 2>> stray = Stray(law, at)) {
        for (auto it : {at - 1, at + 1}) {
          widen.push_back(
              {it->x, std::max({std::abs((*stray)[0] - it->s[2]), std::abs((*stray)[1] - it->s[2]),
                                std::abs(node.s[2] - it->s[2]) + node.band2})});
        }
        nodes.erase(at);
        continue;
      }
      fit->law = std::move(law);
      added = 1;
    }
  }
  // (After the rounds: a band widened before them would let a later node stray further.)
  for (const auto& [x, reach] : widen) {
    for (LocalNode& n : nodes) {
      if (n.x == x) n.band2 = std::max(n.band2, reach);
    }
  }
}

}  // namespace

LocalFit FitLocal(const std::vector<double>& x, const std::vector<double>& y, double sigma_m,
                  bool quantized, LocalTrim trim) {
  if (x.size() != y.size() || static_cast<int>(x.size()) < kLocalMinimumPoints) {
    throw std::invalid_argument("local fit needs at least " + std::to_string(kLocalMinimumPoints) +
                                " points, got " + std::to_string(x.size()));
  }
  // The readings the windows take: all but those within the trims of the ends.
  size_t from = std::lower_bound(x.begin(), x.end(), x.front() + trim.front_rad) - x.begin();
  size_t to = std::upper_bound(x.begin(), x.end(), x.back() - trim.back_rad) - x.begin();
  if (!(to > from && to - from >= trim.least)) {
    from = 0;  // too few left: no trim
    to = x.size();
  }
  const Points p = FittedPoints(x, y, from, to);
  LocalFit fit{PiecewisePolynomial({0.0, 1.0}, Eigen::MatrixXd::Zero(1, kTerms), 2),
               {},
               from > 0 || to < x.size()};
  const std::vector<size_t> sizes = WindowSizes(p.x.size());
  // Nodes from the first reading to the last, each kNodeSpacing of its window's width past the
  // one before (at least the next point): the interpolant's s'' between two nodes is their s''
  // plus their values' noise over the spacing squared, which a spacing of the window's order
  // keeps at the noise of s'' itself.
  std::array<size_t, 3> last{};
  double t = x.front();
  for (;;) {
    fit.nodes.push_back(BestNodeAt(p, t, sigma_m, quantized, sizes, &last));
    if (t >= x.back()) break;
    const size_t next = std::upper_bound(p.x.begin(), p.x.end(), t) - p.x.begin();
    const LocalNode& before = fit.nodes.back();
    double step = kNodeSpacing * before.width;
    t = std::max(t + step, next < p.x.size() ? p.x[next] : x.back());
    if (t < x.back() - 0.5 * step && next < p.x.size()) continue;
    // Less than half a step left: the last reading's node, where its window and this node's
    // meet (half of each); else the step as before. A node at 86° whose window spanned 56° and
    // the seat's 41° past it, its window 9°, left a law that missed the readings by up to
    // 0.28 mm (export_trial's seed 5, E0327: a cycloidal rise of 0.36 mm over 114°, then a
    // double-harmonic return over 14°, every 0.7° to 1e-3 mm; a_min −48 against −653 m/s²).
    std::array<size_t, 3> end_last = last;
    LocalNode end = BestNodeAt(p, x.back(), sigma_m, quantized, sizes, &end_last);
    if (t >= x.back() || next >= p.x.size() ||
        x.back() - before.x <= kNodeSpacing * (before.width + end.width)) {
      fit.nodes.push_back(std::move(end));
      break;
    }
  }
  fit.law = QuinticHermite(fit.nodes);
  if (quantized) AddNodesWhereTheLawMisses(p, sigma_m, sizes, &fit);
  if (quantized) AddNodesAtExtremes(p, sigma_m, sizes, &fit);
  return fit;
}

}  // namespace needle
