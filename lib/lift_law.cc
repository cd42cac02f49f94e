#include "lib/lift_law.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "lib/lift_pieces.h"
#include "lib/reading_kinks.h"
#include "lib/units.h"

namespace needle {

LiftTable BasuNormalCurve(double max_lift_m) {
  if (!(max_lift_m > 0.0) || !std::isfinite(max_lift_m)) {
    throw std::invalid_argument("BasuNormalCurve: max_lift must be positive, got " +
                                std::to_string(max_lift_m));
  }
  // NACA TM 477, table "% of maximum lift" against crank angle.
  static const double kPercent[] = {0, 2, 8, 21, 42, 68, 92, 100, 88, 58, 26, 0};
  LiftTable table;
  for (int i = 0; i < 12; ++i) {
    table.crank_rad.push_back((-15.0 + 5.0 * i) * kDeg);
    table.lift_m.push_back(max_lift_m * kPercent[i] / 100.0);
  }
  return table;
}

namespace {

using lift_pieces::BuildPieces;
using lift_pieces::Foot;
using lift_pieces::MoveNode;

std::string Shown(double value) {  // as a stream writes it, 6 digits
  std::ostringstream out;
  out << value;
  return out.str();
}
std::string Mm(double m) { return Shown(m * 1e3); }
std::string Deg(double rad) { return Shown(rad / kDeg); }

void CheckReadings(const LiftTable& table, double allowance_m, double sigmas) {
  for (size_t i = 0; i < table.lift_m.size(); ++i) {
    if (table.lift_m[i] < -allowance_m) {
      // The angle too: a CSV's reader finds the reading by it, not by its index.
      std::string what = "entry " + std::to_string(i) + " of the lifts, at " +
                         Deg(table.crank_rad[i]) + " deg, is negative (" + Mm(table.lift_m[i]) +
                         " mm): lift is measured from the seat and cannot be below it";
      if (allowance_m > 0.0) {
        std::ostringstream n;
        n.precision(3);
        n << sigmas;
        what +=
            " by more than the noise allows (" + n.str() + " sigma = " + Mm(allowance_m) + " mm)";
      }
      throw std::invalid_argument(what);
    }
  }
}

// First θ in [from, to] (searching towards `to`) where f(θ) > level, located by sampling each
// piece and TOMS 748; nullopt when f never exceeds it.
std::optional<double> FirstAbove(const PiecewisePolynomial& p, double level, bool forward) {
  const auto& x = p.breaks();
  auto f = [&](double t) { return p.Evaluate(t) - level; };
  const int samples = 32;
  const int n = static_cast<int>(x.size()) - 1;
  double prev = forward ? x.front() : x.back();
  if (f(prev) > 0.0) return prev;
  for (int step = 0; step < n; ++step) {
    const int i = forward ? step : n - 1 - step;
    for (int k = 1; k <= samples; ++k) {
      const double t = forward ? x[i] + (x[i + 1] - x[i]) * k / samples
                               : x[i + 1] - (x[i + 1] - x[i]) * k / samples;
      if (f(t) > 0.0) {
        std::uintmax_t it = 100;
        const double lo = std::min(prev, t), hi = std::max(prev, t);
        const auto r = boost::math::tools::toms748_solve(
            f, lo, hi, boost::math::tools::eps_tolerance<double>(50), it);
        return 0.5 * (r.first + r.second);
      }
      prev = t;
    }
  }
  return std::nullopt;
}

// The spline of the table and the open lift it detects (file comment of lift_law.h): for
// measured data the whole table's fit and its crossings of the closed level; for an exact table
// the fit of its open part, from the last zero before the rise to the first zero after the fall.
PiecewisePolynomial FitOpenLift(const LiftTable& table, const LiftLawOptions& options,
                                double* open_rad, double* close_rad, LiftLawNodes* nodes) {
  const auto& th = table.crank_rad;
  const auto& s = table.lift_m;
  if (th.size() != s.size() || th.empty()) {
    throw std::invalid_argument("the lift table needs as many lifts as crank angles");
  }
  CheckReadings(table, options.negative_allowance_m, options.negative_sigmas);
  if (options.closed_level_m > 0.0) {
    PiecewisePolynomial full = BuildPieces(th, s, options, nodes);
    const auto open = FirstAbove(full, options.closed_level_m, true);
    const auto close = FirstAbove(full, options.closed_level_m, false);
    if (!open || !close || !(*close > *open)) {
      throw std::invalid_argument("the fitted lift never rises above the closed level (" +
                                  Mm(options.closed_level_m) +
                                  " mm, 3 sigma of the noise): no open lift in the table");
    }
    *open_rad = *open;
    *close_rad = *close;
    return full;
  }
  size_t first = 0, last = s.size() - 1;
  while (first + 1 < s.size() && s[first] <= 0.0 && s[first + 1] <= 0.0) ++first;
  while (last > first && s[last] <= 0.0 && s[last - 1] <= 0.0) --last;
  if (last <= first) throw std::invalid_argument("the lift table never opens: every lift is zero");
  const std::vector<double> x(th.begin() + first, th.begin() + last + 1);
  const std::vector<double> y(s.begin() + first, s.begin() + last + 1);
  if ((first > 0 || last + 1 < s.size()) &&
      static_cast<int>(x.size()) < MinimumPoints(options.spline.kind)) {
    throw std::invalid_argument("the open lift (" + Deg(x.front()) + "° to " + Deg(x.back()) +
                                "°) has " + std::to_string(x.size()) + " points; \"" +
                                SplineKindName(options.spline.kind) + "\" needs at least " +
                                std::to_string(MinimumPoints(options.spline.kind)));
  }
  *open_rad = x.front();
  *close_rad = x.back();
  PiecewisePolynomial law = BuildPieces(x, y, options, nodes);
  // A seat reading the local fit's law does not start on (SeatTrim): the rise leaves the seat
  // between it and the next reading, and the open lift begins there, not at the reading (the
  // law carried back to it overstates a 2-3 cubic's s'' by 4 % at 1.5° steps).
  // The end node there, its band kept, moves with it (it was the law carried to the reading).
  // (seat_left_out is set only by a local fit that applied its trims: 14 readings or more, and
  // its nodes.)
  if (nodes->seat_left_out[0] || nodes->seat_left_out[1]) {
    auto [front, back] =
        std::minmax_element(nodes->ready.begin(), nodes->ready.end(),
                            [](const LocalNode& a, const LocalNode& b) { return a.x < b.x; });
    const size_t n = x.size();
    const auto lift = [&law](double t) { return law.Evaluate(t); };
    if (nodes->seat_left_out[0]) {
      *open_rad = Foot(lift, x[0], x[1]);
      MoveNode(law, *open_rad, &*front);
    }
    if (nodes->seat_left_out[1]) {
      *close_rad = Foot(lift, x[n - 1], x[n - 2]);
      MoveNode(law, *close_rad, &*back);
    }
  }
  return law;
}

}  // namespace

LiftLaw::LiftLaw(LiftTable table, const SplineOptions& options)
    : LiftLaw(std::move(table), [&options] {
        LiftLawOptions o;  // every other field its default
        o.spline = options;
        return o;
      }()) {}

LiftLaw::LiftLaw(LiftTable table, const LiftLawOptions& options)
    : table_(std::move(table)),
      kind_(options.spline.kind),
      closed_level_m_(options.closed_level_m),
      spline_(FitOpenLift(table_, options, &open_rad_, &close_rad_, nodes_.get())) {
  if (options.open_rad) open_rad_ = *options.open_rad;
  if (options.close_rad) close_rad_ = *options.close_rad;
  const double lo = spline_.breaks().front(), hi = spline_.breaks().back();
  if (!(open_rad_ >= lo && close_rad_ <= hi && open_rad_ < close_rad_)) {
    throw std::invalid_argument("the open lift " + Deg(open_rad_) + "° to " + Deg(close_rad_) +
                                "° must lie inside the fitted table (" + Deg(lo) + "° to " +
                                Deg(hi) + "°) and open before it closes");
  }
  spline_ = spline_.Restrict(open_rad_, close_rad_);
  const Extremum low = Min(0);
  if (low.value < 0.0) {
    undershoot_m_ = -low.value;
    undershoot_rad_ = low.crank_rad;
  }
}

double LiftLaw::Lift(double crank_rad) const { return Derivative(crank_rad, 0); }

double LiftLaw::Derivative(double crank_rad, int order) const {
  if (crank_rad < open_rad_ || crank_rad > close_rad_) return 0.0;  // closed outside
  return spline_.Evaluate(crank_rad, order);
}

void LiftLaw::Derivatives(double crank_rad, int count, double* out) const {
  if (crank_rad < open_rad_ || crank_rad > close_rad_) {
    std::fill(out, out + count, 0.0);  // closed outside
    return;
  }
  spline_.EvaluateUpTo(crank_rad, count, out);
}

double LiftLaw::MeanLift() const { return spline_.Integral() / (end_rad() - start_rad()); }

const std::vector<LocalNode>& LiftLaw::nodes() const {
  std::call_once(nodes_->once, [this] {
    std::vector<LocalNode> all = nodes_->ready;
    for (const auto& band : nodes_->deferred) {
      const std::vector<LocalNode> more = band();
      all.insert(all.end(), more.begin(), more.end());
    }
    all.erase(
        std::remove_if(all.begin(), all.end(),
                       [&](const LocalNode& n) { return n.x < open_rad_ || n.x > close_rad_; }),
        all.end());
    nodes_->all = std::move(all);
    nodes_->deferred.clear();
  });
  return nodes_->all;
}

std::optional<ExtremumBand> LiftLaw::AccelerationBand(bool largest) const {
  if (nodes().empty()) return std::nullopt;
  const double sign = largest ? 1.0 : -1.0;  // the smallest s'' is the largest −s''
  const LocalNode e = ExtremeNode(largest);
  // The lower end: the largest of the nodes' (the extreme is at least each node's value). The
  // upper: the largest of theirs and of the estimate plus the nearest node's half-width (the
  // extreme may lie between nodes; else its unsafe end could be the estimate itself).
  double lo = -std::numeric_limits<double>::infinity();
  double hi = sign * e.s[2] + e.band2;
  const auto take = [&](const LocalNode& n) {
    lo = std::max(lo, sign * n.s[2] - n.band2);
    hi = std::max(hi, sign * n.s[2] + n.band2);
  };
  for (const LocalNode& n : nodes()) take(n);
  for (const LocalNode& n : KinkNodes(largest)) take(n);
  for (const LocalNode& n : nodes_->reach[largest]) hi = std::max(hi, sign * n.s[2] + n.band2);
  if (!largest) return ExtremumBand{-hi, -lo};
  return ExtremumBand{lo, hi};
}

LocalNode LiftLaw::ExtremeNode(bool largest) const {
  const Extremum e = largest ? Max(2) : Min(2);
  LocalNode at = NodeAt(e.crank_rad);
  at.s[2] = e.value;
  return at;
}

std::vector<LocalNode> LiftLaw::KinkNodes(bool largest) const {
  if (kind_ != SplineKind::kLocal) return {};
  std::vector<LocalNode> kinks = KinkPeaks(nodes(), largest ? 1.0 : -1.0);
  for (LocalNode& k : kinks) {
    const double peak = k.s[2];
    for (int d = 0; d < 3; ++d) k.s[d] = spline_.Evaluate(k.x, d);
    k.band2 += 0.5 * std::abs(peak - k.s[2]);  // the band spans the law's s'' there and the peak
    k.s[2] = 0.5 * (k.s[2] + peak);
  }
  return kinks;
}

LocalNode LiftLaw::NodeAt(double crank_rad) const {
  LocalNode at;
  at.x = crank_rad;
  for (int k = 0; k < 3; ++k) at.s[k] = spline_.Evaluate(crank_rad, k);
  at.band2 = NearestHalfWidth(nodes(), crank_rad);
  return at;
}

Extremum LiftLaw::Max(int order) const { return Extrema(order).second; }
Extremum LiftLaw::Min(int order) const { return Extrema(order).first; }

std::pair<Extremum, Extremum> LiftLaw::Extrema(int order) const {
  // Candidates: both sides of every break, and the interior roots of the next derivative
  // on each piece (found by sampling, then TOMS 748 to machine precision).
  const auto& x = spline_.breaks();
  const auto& c = spline_.coefficients();
  const int degree = spline_.degree();
  // The polynomial of piece i (its `k`th derivative), also at its right end.
  auto piece_value = [&](size_t i, double t, int k) {
    return spline_.OnPiece(static_cast<int>(i), t, k);
  };
  // The least and largest value at the pieces' ends: an interior candidate of a piece whose
  // values all lie strictly between them can be neither extreme, and its roots are not sought.
  double end_lo = spline_.Evaluate(x.front(), order), end_hi = end_lo;
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    for (const double t : {x[i], x[i + 1]}) {
      const double v = piece_value(i, t, order);
      end_lo = std::min(end_lo, v);
      end_hi = std::max(end_hi, v);
    }
  }
  // The piece's values lie within its value at the left end ± Σ |coefficient| · width^power.
  auto within_ends = [&](size_t i) {
    const double width = x[i + 1] - x[i];
    double reach = 0.0, scale = 0.0, power = 1.0;
    for (int m = order; m <= degree; ++m) {
      double falling = 1.0;
      for (int j = 0; j < order; ++j) falling *= (m - j);
      const double term = std::abs(falling * c(static_cast<Eigen::Index>(i), m)) * power;
      if (m > order) reach += term;
      scale += term;
      power *= width;
    }
    const double left = piece_value(i, x[i], order);
    reach += 1e-12 * scale;  // the roundoff of an evaluation
    return left + reach < end_hi && left - reach > end_lo;
  };
  Extremum lo{x.front(), spline_.Evaluate(x.front(), order)};
  Extremum hi = lo;
  auto consider = [&](double at, double value) {
    if (value < lo.value) lo = {at, value};
    if (value > hi.value) hi = {at, value};
  };
  const int samples = 16;
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    const double a = x[i], b = x[i + 1];
    consider(a, piece_value(i, a, order));
    consider(b, piece_value(i, b, order));
    if (within_ends(i)) continue;
    auto slope = [&](double t) { return piece_value(i, t, order + 1); };
    double t0 = a, s0 = slope(a);
    for (int k = 1; k <= samples; ++k) {
      const double t1 = a + (b - a) * k / samples;
      const double s1 = slope(t1);
      if (s0 == 0.0) consider(t0, piece_value(i, t0, order));
      if (s0 * s1 < 0.0) {
        std::uintmax_t it = 60;
        const auto r = boost::math::tools::toms748_solve(
            slope, t0, t1, s0, s1, boost::math::tools::eps_tolerance<double>(50), it);
        const double root = 0.5 * (r.first + r.second);
        consider(root, piece_value(i, root, order));
      }
      t0 = t1;
      s0 = s1;
    }
  }
  return {lo, hi};
}

}  // namespace needle
