// The law of an open lift's readings built apart on the pieces between its breaks
// (lib/lift_pieces.h): each piece's fit with its trims, a dwell's piece its lift, and where a
// law leaves a seat.
#include "lib/lift_pieces.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "lib/local_join.h"
#include "lib/reading_kinks.h"
#include "lib/reading_steps.h"
#include "lib/side_polynomial.h"
#include "lib/spline_band.h"
#include "lib/units.h"

namespace needle {
namespace lift_pieces {
namespace {

std::string Deg(double rad) {  // as a stream writes it, 6 digits
  std::ostringstream out;
  out << rad / kDeg;
  return out.str();
}

// The misfit of reading `at` by the quintic through the kLocalMinimumPoints readings beyond it
// (away from `from`'s side: toward larger x for `forward`), and that value's rounding bound,
// both on the values z(i).
std::array<double, 2> ExtrapolationMisfit(const std::vector<double>& x,
                                          const std::function<double(size_t)>& z, double sigma,
                                          size_t at, bool forward) {
  const size_t k = kLocalMinimumPoints;
  Eigen::MatrixXd v(k, kLocalDegree + 1);
  Eigen::VectorXd b(k);
  const double h = std::abs(x[forward ? at + 1 : at - 1] - x[at]);
  for (size_t r = 0; r < k; ++r) {
    const size_t i = forward ? at + 1 + r : at - 1 - r;
    const double t = (x[i] - x[at]) / h;
    double power = 1.0;
    for (int c = 0; c <= kLocalDegree; ++c, power *= t) v(r, c) = power;
    b(r) = z(i);
  }
  // Its value at `at`, Σ g_i z_i, and that value's rounding bound √3 σ Σ|g_i| (the
  // extrapolation amplifies it), plus the reading's own.
  const Eigen::RowVectorXd g = v.completeOrthogonalDecomposition().pseudoInverse().row(0);
  return {std::abs(g.dot(b) - z(at)), std::sqrt(3.0) * sigma * (g.cwiseAbs().sum() + 1.0)};
}

// How much of a piece's seat end (its first reading, `front`, or its last) a local fit leaves
// out: a zero the lift leaves from (or returns to) between it and the next reading, where the
// quintic through the next kLocalMinimumPoints readings misses that zero by more than twice the
// rounding's bound on the two: that reading is the base circle's, not the law's. 0 where it
// fits (the law starts on it) or the end is no seat. Half a step: the trim leaves the seat
// reading out and keeps its neighbour whatever the round-off of x.back() − trim.
double SeatTrim(const std::vector<double>& x, const std::vector<double>& y, double sigma,
                bool front) {
  const size_t n = x.size(), k = kLocalMinimumPoints;
  if (n < 2 * k + 1) return 0.0;
  const size_t seat = front ? 0 : n - 1;
  if (y[seat] > 0.0) return 0.0;
  const auto z = [&y](size_t i) { return y[i]; };
  const auto [misfit, bound] = ExtrapolationMisfit(x, z, sigma, seat, front);
  return misfit > 2.0 * bound ? 0.5 * std::abs(x[front ? 1 : n - 2] - x[seat]) : 0.0;
}

// The same at a dwell's end, a seat at its lift `level` above the piece for a top (`sign` −1:
// the readings as level − y) or below it, where the law's own extrapolation error counts too (an
// exact table's law, not a polynomial, misses its next reading by far more than its rounding):
// the dwell's reading is left out where it misses it by more than twice the rounding's bound
// plus four times the miss of the reading before it by the quintic through the readings before
// that, on the law.
double DwellTrim(const std::vector<double>& x, const std::vector<double>& y, double sigma,
                 bool front, double level, double sign) {
  const size_t n = x.size(), k = kLocalMinimumPoints;
  if (n < 2 * k + 2) return 0.0;
  const size_t end = front ? 0 : n - 1, before = front ? 1 : n - 2;
  const auto z = [&](size_t i) { return sign * (y[i] - level); };
  const auto [misfit, bound] = ExtrapolationMisfit(x, z, sigma, end, front);
  const double own = ExtrapolationMisfit(x, z, sigma, before, front)[0];
  return misfit > 2.0 * bound + 4.0 * own ? 0.5 * std::abs(x[before] - x[end]) : 0.0;
}

}  // namespace

// Where the lift `s` (the law, or a piece's law against a dwell's level) leaves the seat between
// the seat reading at `seat` and the next at `next` (either side of it): where it crosses zero,
// or else touches it (its least value there).
double Foot(const std::function<double(double)>& s, double seat, double next) {
  const auto zero_between = [&](double from, double to) {
    boost::uintmax_t iterations = 100;
    const auto [l, r] = boost::math::tools::toms748_solve(
        s, std::min(from, to), std::max(from, to), boost::math::tools::eps_tolerance<double>(52),
        iterations);
    return 0.5 * (l + r);
  };
  if (s(seat) <= 0.0 && s(next) > 0.0) return zero_between(seat, next);
  const auto [lo, hi] = std::minmax(seat, next);
  const double least = boost::math::tools::brent_find_minima(s, lo, hi, 52).first;
  // A dip below the seat: the law leaves it where it comes back up through zero.
  return s(least) < 0.0 && s(next) > 0.0 ? zero_between(least, next) : least;
}

// `node`, put at `to` with the law's s, s' and s'' there.
void MoveNode(const PiecewisePolynomial& law, double to, LocalNode* node) {
  node->x = to;
  for (int k = 0; k < 3; ++k) node->s[k] = law.Evaluate(to, k);
}

namespace {

// A local fit's trims of one piece (x, y): a found break's readings nearer than its uncertainty
// belong to either side's law; so does a seat reading at the open lift's first or last end
// (SeatTrim): the rise begins anywhere up to the next reading; and a reading added at a break,
// its lift an estimate (break_estimated). None for the other kinds.
LocalTrim PieceTrim(const std::vector<double>& x, const std::vector<double>& y,
                    const LiftLawOptions& options, size_t piece, size_t pieces) {
  if (options.spline.kind != SplineKind::kLocal) return {};
  const double u = options.break_uncertainty_rad, sigma = options.spline.sigma;
  // An estimated break reading: the least trim that leaves it out (the next reading is a
  // grid step on).
  const auto estimated = [&](size_t b) {
    const bool e = b < options.break_estimated.size() && options.break_estimated[b];
    return std::max(u, e ? 1e-9 * (x.back() - x.front()) : 0.0);
  };
  // A dwell's end: a seat at the dwell's lift.
  const auto dwell_trim = [&](bool front) -> std::optional<double> {
    for (const LiftDwell& d : options.dwells) {
      if ((front ? d.to_rad : d.from_rad) == (front ? x.front() : x.back()))
        return DwellTrim(x, y, sigma, front, d.lift_m, d.top ? -1.0 : 1.0);
    }
    return std::nullopt;
  };
  const std::optional<double> dwell_front = dwell_trim(true), dwell_back = dwell_trim(false);
  LocalTrim trim{
      piece == 0 ? SeatTrim(x, y, sigma, true) : dwell_front.value_or(estimated(piece - 1)),
      piece + 1 == pieces ? SeatTrim(x, y, sigma, false) : dwell_back.value_or(estimated(piece))};
  // An end at a break placed to within u: its readings may be the next piece's. Not where a
  // seat reading is trimmed too (a C∞ bump's foot trimmed to 8 readings read a_min 40 % off).
  const bool seat_trimmed =
      (piece == 0 && trim.front_rad > 0.0) || (piece + 1 == pieces && trim.back_rad > 0.0);
  if (u > 0.0 && !seat_trimmed &&
      ((piece > 0 && !dwell_front) || (piece + 1 < pieces && !dwell_back)))
    trim.least = kTrimmedLeastReadings;
  return trim;
}

// The spline of one piece; its nodes, which carry the band of s'' (a local fit's, a smoothing
// spline's or an interpolating spline's: lib/spline_band.h), are added to `nodes`.
PiecewisePolynomial BuildPiece(const std::vector<double>& x, const std::vector<double>& y,
                               const SplineOptions& options, LiftLawNodes* nodes,
                               LocalTrim trim = {}, bool* trimmed = nullptr) {
  auto keep = [&](LocalFit fit) {
    nodes->ready.insert(nodes->ready.end(), fit.nodes.begin(), fit.nodes.end());
    return std::move(fit.law);
  };
  if (options.kind == SplineKind::kLocal) {
    CheckSplineInputs(x, y, options);
    LocalFit fit = FitLocal(x, y, options.sigma, options.quantized, trim);
    if (trimmed) *trimmed = fit.trimmed;
    AddLocalFitBias(x, y, options, &fit, trim);
    if (options.quantized) AddReadingKinks(x, y, options.sigma, trim, &fit);
    const std::array<std::vector<LocalNode>, 2> steps =
        HiddenSteps(x, y, options.sigma, options.quantized, fit, trim);
    for (const bool largest : {false, true})
      nodes->reach[largest].insert(nodes->reach[largest].end(), steps[largest].begin(),
                                   steps[largest].end());
    return keep(std::move(fit));
  }
  if (options.kind == SplineKind::kSmoothing) {
    CheckSplineInputs(x, y, options);
    return keep(BuildSmoothingFit(x, y, options));
  }
  PiecewisePolynomial law = BuildSpline(x, y, options);
  nodes->deferred.push_back(
      [x, y, options, law] { return InterpolationNodes(x, y, options, law); });
  return law;
}

// Where the rise leaves the seat between the seat reading and the next: where the polynomial of
// `degree` through the `count` readings after the seat reading has s' = 0 (the base circle's
// slope; a junction's place, as the break finder's sides meet), or nullopt when it has none there.
std::optional<double> SeatSlopeRoot(const std::vector<double>& x, const std::vector<double>& y,
                                    bool front, size_t count, int degree) {
  const size_t n = x.size(), seat = front ? 0 : n - 1;
  const double h = x[front ? 1 : n - 2] - x[seat];  // signed: the next reading at t = 1
  const size_t from = front ? 1 : n - 1 - count, to = from + count;
  const Eigen::VectorXd c =
      QrSolve(PowerBasis(x, from, to, x[seat], h, degree),
              Eigen::Map<const Eigen::VectorXd>(y.data() + from, static_cast<Eigen::Index>(count)));
  const auto slope = [&c, degree](double t) {
    double d = 0.0;
    for (int k = degree; k >= 1; --k) d = d * t + k * c(k);
    return d;
  };
  const std::optional<double> t = RootIn(slope, 0.0, 1.0);
  if (!t || !(*t > 0.0 && *t < 1.0)) return std::nullopt;
  return x[seat] + *t * h;
}

// An end piece too short for SeatTrim (under 2 kLocalMinimumPoints + 1 readings) keeps a seat
// reading that is the base circle's, the rise leaving the seat between it and the next reading:
// the fit takes its 0 as the law's and reads a peak s'' there short (a harmonic return over
// 8.47° every 0.7° to 1e-4 mm meeting the seat 0.39 of a step before its last reading: a_max
// −6.1 %, 2.4 half-widths past its band). The law stays as fitted (the fit without that reading
// read this one better and others worse: docs/lift-data.md, "A seat between readings"); what the
// piece reads at the seat with that reading moved to where the rise leaves the seat, and its
// band, go to `reach` (LiftLawNodes::reach, which the extremes' bands reach on their unsafe
// side: a node's own band widened both ways took a law leaving the seat with s'' = 0, read
// a step off, to an a_min band of 91 % for 6.5 %).
void ShortSeatBand(const std::vector<double>& x, const std::vector<double>& y,
                   const SplineOptions& options, const LocalTrim& trim, bool front,
                   std::array<std::vector<LocalNode>, 2>* reach) {
  const size_t n = x.size(), seat = front ? 0 : n - 1, next = front ? 1 : n - 2;
  const size_t k = kLocalMinimumPoints;
  if (n >= 2 * k + 1 || n < k + 3 || y[seat] > 0.0) return;
  // The seat reading off the law: missed by the quintic through the next readings by more than
  // twice the rounding's bound and that quintic's own miss of the next reading (an exact table's
  // law is no polynomial: DwellTrim's test, whose factor 4 left the trial's table alone).
  const auto z = [&y](size_t i) { return y[i]; };
  const auto [misfit, bound] = ExtrapolationMisfit(x, z, options.sigma, seat, front);
  const double before = ExtrapolationMisfit(x, z, options.sigma, next, front)[0];
  if (!(misfit > 2.0 * bound + before)) return;
  // The seat's place from the quintics through 7 and 8 readings and the quartic through 6, when
  // the three agree to a quarter of a step (a law leaving the seat with s'' = 0 has no single
  // root of s' there to find); the piece is fitted with its seat reading moved to each, and the
  // band reaches each fit's s'' at its seat and its band (the places' spread standing for the
  // seat's own uncertainty).
  std::vector<double> feet;
  for (const auto& [count, degree] : {std::pair<size_t, int>{k, 5}, {k + 1, 5}, {k - 1, 4}}) {
    const std::optional<double> foot = SeatSlopeRoot(x, y, front, count, degree);
    if (!foot) return;
    feet.push_back(*foot);
  }
  const auto [lo, hi] = std::minmax_element(feet.begin(), feet.end());
  if (*hi - *lo > 0.25 * std::abs(x[next] - x[seat])) return;
  const auto x_less = [](const LocalNode& l, const LocalNode& r) { return l.x < r.x; };
  for (const double foot : feet) {
    std::vector<double> moved = x;
    moved[seat] = foot;
    LiftLawNodes at_foot;
    BuildPiece(moved, y, options, &at_foot, trim);
    if (at_foot.ready.empty()) continue;
    const LocalNode& end =
        front ? *std::min_element(at_foot.ready.begin(), at_foot.ready.end(), x_less)
              : *std::max_element(at_foot.ready.begin(), at_foot.ready.end(), x_less);
    for (std::vector<LocalNode>& r : *reach) r.push_back(end);
  }
}

// Piece `piece` of `pieces` (BuildPiece with its PieceTrim); a first or last piece records
// whether its fit left its seat reading out (LiftLawNodes::seat_left_out); `left_out`, whether
// it left out its first and its last reading.
PiecewisePolynomial BuildPart(const std::vector<double>& x, const std::vector<double>& y,
                              const LiftLawOptions& options, size_t piece, size_t pieces,
                              LiftLawNodes* nodes, std::array<bool, 2>* left_out = nullptr) {
  const LocalTrim trim = PieceTrim(x, y, options, piece, pieces);
  bool trimmed = false;
  PiecewisePolynomial part = BuildPiece(x, y, options.spline, nodes, trim, &trimmed);
  if (piece == 0) nodes->seat_left_out[0] = trimmed && trim.front_rad > 0.0;
  if (piece + 1 == pieces) nodes->seat_left_out[1] = trimmed && trim.back_rad > 0.0;
  if (options.spline.kind == SplineKind::kLocal) {
    if (piece == 0 && trim.front_rad == 0.0)
      ShortSeatBand(x, y, options.spline, trim, true, &nodes->reach);
    if (piece + 1 == pieces && trim.back_rad == 0.0)
      ShortSeatBand(x, y, options.spline, trim, false, &nodes->reach);
  }
  if (left_out) *left_out = {trimmed && trim.front_rad > 0.0, trimmed && trim.back_rad > 0.0};
  return part;
}

// The pieces' readings split at the breaks: each piece's first and last index into x.
std::vector<size_t> PieceCuts(const std::vector<double>& x, const LiftLawOptions& options) {
  std::vector<size_t> cuts{0};
  for (size_t b = 0; b < options.breaks_rad.size(); ++b) {
    const double at = options.breaks_rad[b];
    const auto it = std::find_if(x.begin(), x.end(), [&](double xi) {
      return std::abs(xi - at) <= 1e-9 * std::max(1.0, std::abs(at));
    });
    if (it == x.end() || it == x.begin() || it == x.end() - 1) {
      throw std::invalid_argument(
          "break " + std::to_string(b) + " (" + Deg(at) +
          "°) must be an angle of the table strictly inside the open lift (" + Deg(x.front()) +
          "° to " + Deg(x.back()) + "°)");
    }
    const size_t i = static_cast<size_t>(it - x.begin());
    if (i <= cuts.back()) {
      throw std::invalid_argument("break " + std::to_string(b) + " (" + Deg(at) +
                                  "°) must come after the one before it");
    }
    cuts.push_back(i);
  }
  cuts.push_back(x.size() - 1);
  return cuts;
}

// One piece of BuildPieces: its law, its nodes [node_from, node_to) in LiftLawNodes::ready,
// whether its fit left its end readings out, and its dwell (the piece is one).
struct BuiltPiece {
  PiecewisePolynomial law;
  size_t node_from = 0, node_to = 0;
  std::array<bool, 2> left_out{};
  const LiftDwell* dwell = nullptr;
};

// Piece b's last (first) node in LiftLawNodes::ready, by angle; b has nodes.
LocalNode* EndNode(const BuiltPiece& b, bool last, LiftLawNodes* nodes) {
  const auto first = nodes->ready.begin() + static_cast<std::ptrdiff_t>(b.node_from);
  const auto end = nodes->ready.begin() + static_cast<std::ptrdiff_t>(b.node_to);
  const auto x_less = [](const LocalNode& l, const LocalNode& r) { return l.x < r.x; };
  return &*(last ? std::max_element(first, end, x_less) : std::min_element(first, end, x_less));
}

// The dwell `p` is, at its lift between where the pieces beside it reach the lift: each ends
// at the dwell's reading, or, where its fit left that reading out (the dwell's, not its own:
// DwellTrim), where its law reaches the lift between that reading and the one before (Foot).
// Their laws are cut there and their end nodes moved there.
void JoinDwell(const std::vector<double>& x, const std::vector<size_t>& cuts, size_t p,
               std::vector<BuiltPiece>& parts, LiftLawNodes* nodes) {
  const LiftDwell& d = *parts[p].dwell;
  BuiltPiece& before = parts[p - 1];
  BuiltPiece& after = parts[p + 1];
  const double sign = d.top ? -1.0 : 1.0;
  const auto against = [&](const PiecewisePolynomial& law) {
    return [&law, &d, sign](double t) { return sign * (law.Evaluate(t) - d.lift_m); };
  };
  double from = x[cuts[p]], to = x[cuts[p + 1]];
  if (before.left_out[1]) from = Foot(against(before.law), from, x[cuts[p] - 1]);
  if (after.left_out[0]) to = Foot(against(after.law), to, x[cuts[p + 1] + 1]);
  if (from < before.law.breaks().back())
    before.law = before.law.Restrict(before.law.breaks().front(), from);
  if (to > after.law.breaks().front())
    after.law = after.law.Restrict(to, after.law.breaks().back());
  if (before.node_to > before.node_from) MoveNode(before.law, from, EndNode(before, true, nodes));
  if (after.node_to > after.node_from) MoveNode(after.law, to, EndNode(after, false, nodes));
  Eigen::MatrixXd level = Eigen::MatrixXd::Zero(1, before.law.coefficients().cols());
  level(0, 0) = d.lift_m;
  parts[p].law = PiecewisePolynomial({from, to}, level, 0);
}

// A local fit's two end nodes' bands at each break where neither side is a dwell and the break's
// place is a reading's (no uncertainty, not estimated): they reach one fit of both sides with s
// and s' shared (JoinAtBreak). The laws stay as fitted.
void JoinBreaks(const std::vector<double>& x, const std::vector<double>& y,
                const std::vector<size_t>& cuts, const LiftLawOptions& options,
                const std::vector<BuiltPiece>& parts, LiftLawNodes* nodes) {
  if (options.spline.kind != SplineKind::kLocal || options.break_uncertainty_rad > 0.0) return;
  const auto readings = [&](size_t k) {
    return std::pair(std::vector<double>(x.begin() + cuts[k], x.begin() + cuts[k + 1] + 1),
                     std::vector<double>(y.begin() + cuts[k], y.begin() + cuts[k + 1] + 1));
  };
  for (size_t p = 0; p + 1 < parts.size(); ++p) {
    const BuiltPiece &before = parts[p], &after = parts[p + 1];
    if (before.dwell || after.dwell || before.node_to == before.node_from ||
        after.node_to == after.node_from)
      continue;
    if (p < options.break_estimated.size() && options.break_estimated[p]) continue;
    const auto [xl, yl] = readings(p);
    const auto [xr, yr] = readings(p + 1);
    JoinAtBreak(xl, yl, xr, yr, options.spline.sigma, options.spline.quantized,
                EndNode(before, true, nodes), EndNode(after, false, nodes));
  }
}

}  // namespace

// The spline through (x, y), built apart on each piece between options.breaks_rad (each an x_i
// strictly inside) and joined at the breaks, where s'' (and s' by the pieces' error) jump: C⁰
// for the interpolating kinds; a local fit's two ends are each piece's own estimate there (its
// readings within the break's uncertainty left out). A dwell's piece is its lift (JoinDwell).
PiecewisePolynomial BuildPieces(const std::vector<double>& x, const std::vector<double>& y,
                                const LiftLawOptions& options, LiftLawNodes* nodes) {
  if (options.breaks_rad.empty()) return BuildPart(x, y, options, 0, 1, nodes);
  const std::vector<size_t> cuts = PieceCuts(x, options);
  std::vector<BuiltPiece> parts;
  const size_t pieces = cuts.size() - 1;
  for (size_t p = 0; p < pieces; ++p) {
    const std::vector<double> px(x.begin() + cuts[p], x.begin() + cuts[p + 1] + 1);
    const std::vector<double> py(y.begin() + cuts[p], y.begin() + cuts[p + 1] + 1);
    const LiftDwell* dwell = nullptr;
    for (const LiftDwell& d : options.dwells)
      if (d.from_rad == px.front() && d.to_rad == px.back() && p > 0 && p + 1 < pieces) dwell = &d;
    if (dwell) {  // its law once the pieces beside it are built
      parts.push_back({PiecewisePolynomial({px.front(), px.back()}, Eigen::MatrixXd::Zero(1, 1), 0),
                       nodes->ready.size(),
                       nodes->ready.size(),
                       {},
                       dwell});
      continue;
    }
    if (static_cast<int>(px.size()) < MinimumPoints(options.spline.kind)) {
      throw std::invalid_argument(
          "the piece " + Deg(px.front()) + "° to " + Deg(px.back()) + "° between breaks has " +
          std::to_string(px.size()) + " points; \"" + SplineKindName(options.spline.kind) +
          "\" needs at least " + std::to_string(MinimumPoints(options.spline.kind)));
    }
    BuiltPiece b{PiecewisePolynomial({0.0, 1.0}, Eigen::MatrixXd::Zero(1, 1), 0),
                 nodes->ready.size(),
                 0,
                 {},
                 nullptr};
    b.law = BuildPart(px, py, options, p, pieces, nodes, &b.left_out);
    b.node_to = nodes->ready.size();
    parts.push_back(std::move(b));
  }
  for (size_t p = 0; p < pieces; ++p)
    if (parts[p].dwell) JoinDwell(x, cuts, p, parts, nodes);
  JoinBreaks(x, y, cuts, options, parts, nodes);
  std::vector<double> breaks{x.front()};
  Eigen::Index rows = 0;
  for (const BuiltPiece& part : parts) {
    breaks.insert(breaks.end(), part.law.breaks().begin() + 1, part.law.breaks().end());
    rows += part.law.coefficients().rows();
  }
  Eigen::MatrixXd c(rows, parts.front().law.coefficients().cols());
  Eigen::Index row = 0;
  for (const BuiltPiece& part : parts) {
    c.block(row, 0, part.law.coefficients().rows(), c.cols()) = part.law.coefficients();
    row += part.law.coefficients().rows();
  }
  return PiecewisePolynomial(std::move(breaks), std::move(c), 0);
}

}  // namespace lift_pieces
}  // namespace needle
