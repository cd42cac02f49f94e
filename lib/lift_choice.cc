// The choice of a lift table's reading (ChooseLiftLaw, lib/lift_data.h): its breaks, what the table
// holds (ReadTable, lib/table_kind.cc), and the law built on it.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "lib/lift_data.h"
#include "lib/local_fit.h"
#include "lib/output.h"
#include "lib/piecewise_polynomial.h"
#include "lib/spline.h"

namespace needle {
namespace {

std::string Mm(double m) {
  std::ostringstream out;
  out.precision(3);
  out << m * 1e3;
  return out.str();
}

// "1e-05 in (0.000254 mm)" or "1e-04 mm": a table's printed digit in its own unit.
std::string PrintedDigit(double q_m) {
  if (!InchDigit(q_m)) return Mm(q_m) + " mm";
  return Significant(q_m / (kInchMm * 1e-3), 3) + " in (" + Mm(q_m) + " mm)";
}

std::string DegreeList(const std::vector<double>& rad) {
  std::string where;
  for (size_t k = 0; k < rad.size() && k < 8; ++k) {
    std::ostringstream deg;
    deg.precision(6);
    deg << rad[k] * 180.0 / 3.14159265358979323846;
    where += (k ? ", " : "") + deg.str();
  }
  if (rad.size() > 8) where += ", …";
  return where;
}

// The dwell at the top of a sparse table: its first and last reading, a run of at least
// kDwellLeastReadings readings printed equal at the table's largest lift, the only readings
// there, with at least kSparseDwellSide readings on each side of it (each side's clamped cubic
// needs a curve to bend). A smooth top rounds to equal readings only where the steps are far
// finer than a sparse table's (a harmonic top of 3 mm over 24° to 1e-3 mm: 2 readings at 0.25°).
std::optional<std::array<size_t, 2>> TopDwell(const std::vector<double>& y) {
  constexpr size_t kSparseDwellSide = 4;
  if (y.empty()) return std::nullopt;
  const double top = *std::max_element(y.begin(), y.end());
  const auto first = std::find(y.begin(), y.end(), top);
  const auto after = std::find_if(first, y.end(), [&](double v) { return v != top; });
  if (!(top > 0.0) || std::find(after, y.end(), top) != y.end()) return std::nullopt;
  const size_t a = static_cast<size_t>(first - y.begin()),
               b = static_cast<size_t>(after - y.begin());
  if (b - a < kDwellLeastReadings || a + 1 < kSparseDwellSide ||
      y.size() - b + 1 < kSparseDwellSide)
    return std::nullopt;
  return std::array<size_t, 2>{a, b - 1};
}

// Whether s'' jumps where the rise or the return meets the top dwell: the side's own clamped
// cubic (tangent to the seat and to the dwell) ends on an s'' of at least a quarter of the whole
// table's clamped cubic's largest |s''| (a harmonic or double-harmonic rise: all of it; a
// cycloidal, 3-4-5 or modified-sine one meets its dwell with s'' = 0, and the one cubic through
// the table, tighter banded, is kept).
bool JumpsIntoTopDwell(const std::vector<double>& x, const std::vector<double>& y,
                       const std::array<size_t, 2>& top, const SplineOptions& clamped) {
  constexpr double kSparseDwellJump = 0.25;
  const PiecewisePolynomial whole = BuildSpline(x, y, clamped);
  const double peak = std::max(ExtremeOf(whole, 2, 1.0).second, -ExtremeOf(whole, 2, -1.0).second);
  const auto side = [&](size_t from, size_t to, bool end) {
    const std::vector<double> sx(x.begin() + from, x.begin() + to + 1);
    const std::vector<double> sy(y.begin() + from, y.begin() + to + 1);
    return std::abs(BuildSpline(sx, sy, clamped).Evaluate(end ? sx.back() : sx.front(), 2));
  };
  return std::max(side(0, top[0], true), side(top[1], x.size() - 1, false)) >
         kSparseDwellJump * peak;
}

// "; the piece from A to B deg holds N readings: …" for each piece between the cuts (inside
// readings first … last; a dwell's own is flat, not fitted) of fewer than kLocalFewReadings:
// its windows cannot grow, and its band holds the quartic's difference from the
// quintic (lib/local_fit.h), wide where the table reads the law coarsely.
std::string ShortPieces(const std::vector<double>& x, size_t first, size_t last,
                        std::vector<double> cuts, const std::vector<LiftDwell>& dwells) {
  std::sort(cuts.begin(), cuts.end());
  std::string out;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const auto lo = std::lower_bound(x.begin() + first, x.begin() + last + 1, cuts[k]);
    const auto hi = std::upper_bound(x.begin() + first, x.begin() + last + 1, cuts[k + 1]);
    const long n = static_cast<long>(hi - lo);
    const bool dwell = std::any_of(dwells.begin(), dwells.end(), [&](const LiftDwell& d) {
      return d.from_rad == cuts[k] && d.to_rad == cuts[k + 1];
    });
    if (n < kLocalFewReadings && cuts[k + 1] > cuts[k] && !dwell) {
      out += "; the piece from " + DegreeList({cuts[k]}) + " to " + DegreeList({cuts[k + 1]}) +
             " deg holds " + std::to_string(n) +
             " readings: its band holds the truncation a quartic sees (a finer table narrows it)";
    }
  }
  return out;
}

// An exact table's open lift, LiftLaw's: the last zero before the rise to the first after it.
std::pair<size_t, size_t> OpenReadings(const std::vector<double>& y) {
  size_t first = 0, last = y.size() - 1;
  while (first + 1 < y.size() && y[first] <= 0.0 && y[first + 1] <= 0.0) ++first;
  while (last > first && y[last] <= 0.0 && y[last - 1] <= 0.0) --last;
  return {first, last};
}

// The breaks of `given` found inside its open lift, each piece keeping the readings a `kind`
// spline needs; the first corner clear of the seat goes to c->corner.
std::vector<const LiftBreak*> SeekBreaks(const LiftTable& given, double sigma_m, SplineKind kind,
                                         LiftLawChoice* c) {
  const auto& x = given.crank_rad;
  const auto [first, last] = OpenReadings(given.lift_m);
  std::vector<const LiftBreak*> inside;
  // A jump of s'' too small for the noise of neighbouring readings' s'' (which grows as 1/h²)
  // stands out on means of bins of 2, 4, 8, … consecutive readings (σ/√count each; the noise of
  // their s'' shrinks as the bins' width^2.5): each coarser level adds the breaks the finer ones
  // did not find, located again on the readings and known to within its bin's width.
  std::vector<LiftBreak> found = FindBreaks(x, given.lift_m, sigma_m);
  // A coarse table's junctions by quintics. Beside breaks found (a degree-2 B-spline's knot
  // where s'' is largest, missed among seven found: a_max 28 % high), only where the quintics'
  // readings reach neither a break found nor the seat, whose jumps would make one (a 2-3 cubic's
  // return 5 steps from its foot).
  if (x.size() <= kJunctionsAtMost) {
    const size_t n_found = found.size();
    for (const LiftBreak& b : FindJunctions(x, given.lift_m, sigma_m)) {
      const double h = x[std::min(b.index + 1, x.size() - 1)] - x[b.index];
      const double clear = n_found > 0 ? kJunctionSide * h : 2.0 * h;
      const bool known = std::any_of(
          found.begin(), found.begin() + n_found,
          [&](const LiftBreak& f) { return std::abs(f.crank_rad - b.crank_rad) <= clear; });
      const bool at_seat =
          n_found > 0 && (b.crank_rad - x[first] <= clear || x[last] - b.crank_rad <= clear);
      if (!known && !at_seat) found.push_back(b);
    }
  }
  for (size_t per = 2; x.size() / per >= kBreakLeastBins; per *= 2) {
    std::vector<double> bx, by;
    for (size_t i = 0; i + per <= x.size(); i += per) {
      double sx = 0.0, sy = 0.0;
      for (size_t k = i; k < i + per; ++k) {
        sx += x[k];
        sy += given.lift_m[k];
      }
      bx.push_back(sx / per);
      by.push_back(sy / per);
    }
    const double width = bx[1] - bx[0];
    for (LiftBreak b : FindBreaks(bx, by, sigma_m / std::sqrt(static_cast<double>(per)))) {
      if (b.order != 2) continue;  // a corner shows among the readings themselves
      const LiftBreak coarse = b;
      b = RefineBreak(x, given.lift_m, b, width);
      // Located again on the readings, a jump keeps its size; a kink of s'' (a jump of its
      // derivative) that the bins' lines took for one does not.
      if (!(std::abs(b.jump) >= 0.5 * std::abs(coarse.jump) &&
            std::abs(b.jump) <= 2.0 * std::abs(coarse.jump)) ||
          !JumpConfirmed(x, given.lift_m, b, sigma_m, 12.0 * width)) {
        continue;
      }
      // Known already, or within two bins of the seat (a junction already: among bins of that
      // width the two cannot be told apart).
      const bool known = std::any_of(found.begin(), found.end(), [&](const LiftBreak& f) {
        return std::abs(f.crank_rad - b.crank_rad) <= 2.0 * width;
      });
      const bool at_seat =
          b.crank_rad - x[first] <= 2.0 * width || x[last] - b.crank_rad <= 2.0 * width;
      if (known || at_seat) continue;
      b.uncertainty_rad = width;
      found.push_back(b);
    }
  }
  std::sort(found.begin(), found.end(),
            [](const LiftBreak& a, const LiftBreak& b) { return a.crank_rad < b.crank_rad; });
  for (const LiftBreak& b : found) {
    if (b.order == 2) {
      c->breaks_found.push_back(b);
    } else if (!c->corner && b.crank_rad > x[std::min(first + 1, last)] &&
               b.crank_rad < x[std::max(last - 1, first)]) {  // a step clear of the seat
      c->corner = b;
    }
  }
  if (c->corner) return inside;
  auto readings = [&](double from, double to) {  // readings strictly between, plus both ends
    return 2 + std::count_if(x.begin(), x.end(), [&](double t) { return t > from && t < to; });
  };
  for (const LiftBreak& b : c->breaks_found) {
    const double from = inside.empty() ? x[first] : inside.back()->crank_rad;
    if (b.crank_rad > x[first] && b.crank_rad < x[last] &&
        readings(from, b.crank_rad) >= MinimumPoints(kind)) {
      inside.push_back(&b);
    }
  }
  while (!inside.empty() && readings(inside.back()->crank_rad, x[last]) < MinimumPoints(kind)) {
    inside.pop_back();
  }
  return inside;
}

// The table with a reading at each break between readings, its lift from the sides' cubics.
LiftTable WithBreakReadings(const LiftTable& given, const std::vector<const LiftBreak*>& inside) {
  LiftTable t;
  size_t next = 0;
  for (size_t i = 0; i < given.crank_rad.size(); ++i) {
    while (next < inside.size() && inside[next]->crank_rad < given.crank_rad[i]) {
      t.crank_rad.push_back(inside[next]->crank_rad);
      t.lift_m.push_back(inside[next]->lift_m);
      ++next;
    }
    if (next < inside.size() && inside[next]->crank_rad == given.crank_rad[i]) ++next;
    t.crank_rad.push_back(given.crank_rad[i]);
    t.lift_m.push_back(given.lift_m[i]);
  }
  return t;
}

// Outliers of measured data (dense tables only: on a sparse one the shape itself stands out of
// the cubic through each reading's neighbours), left out when the options say so.
void SeekOutliers(const LiftTable& given, const LiftDataOptions& o, LiftLawChoice* c) {
  c->robust_noise_m = EstimateNoiseRobust(given.crank_rad, given.lift_m);
  c->outliers = FindOutliers(given.crank_rad, given.lift_m, c->robust_noise_m);
  if (!o.drop_outliers || c->outliers.empty()) return;
  c->table = LiftTable{};
  size_t next = 0;
  for (size_t i = 0; i < given.crank_rad.size(); ++i) {
    if (next < c->outliers.size() && c->outliers[next].index == i) {
      ++next;
      continue;
    }
    c->table.crank_rad.push_back(given.crank_rad[i]);
    c->table.lift_m.push_back(given.lift_m[i]);
  }
}

void SetMeasured(LiftLawChoice* c) {
  const int n = static_cast<int>(c->table.crank_rad.size());
  c->measured = true;
  c->law.closed_level_m = kClosedLevelSigmas * c->noise_m;
  c->law.negative_sigmas = TailSigmas(n, kNegativeSigmas);
  c->law.negative_allowance_m = c->law.negative_sigmas * c->noise_m;
}

// σ̂ of the table as read (EstimateNoise), at least its stated rounding's q/√12 (noise the
// data cannot hide) and 1e-10 m (a floor far below any measurement that keeps the smoothing
// well posed on exact data).
void SetEstimatedNoise(const LiftDataOptions& o, LiftLawChoice* c) {
  c->estimated_noise_m = EstimateNoise(c->table.crank_rad, c->table.lift_m);
  c->noise_m = *c->estimated_noise_m;
  c->noise_source = "estimated";
  if (o.resolution_m && c->noise_m < *o.resolution_m / std::sqrt(12.0)) {
    c->noise_m = *o.resolution_m / std::sqrt(12.0);
    c->noise_source = "rounding";
  }
  c->noise_m = std::max(c->noise_m, 1e-10);
}

// Measured data, read as before issue 50 (docs/lift-data.md, "Measured lift data"): outliers
// sought, σ̂ the RMS pseudo-residual of all windows, the smoothing spline over the whole table
// (natural ends on the seated needle's readings), breaks found not used.
LiftLawChoice ReadMeasured(const LiftTable& given, const LiftDataOptions& o, LiftLawChoice c,
                           const std::vector<double>& breaks_found) {
  SeekOutliers(given, o, &c);
  SetEstimatedNoise(o, &c);
  c.law.spline.sigma = c.noise_m;
  SetMeasured(&c);
  const std::string points = std::to_string(c.table.crank_rad.size()) + " points";
  std::string noise = "noise " + Mm(c.noise_m) + " mm (" + c.noise_source + ")";
  if (!breaks_found.empty()) {
    noise += "; " + std::to_string(breaks_found.size()) + " breaks found (s'' jumps at " +
             DegreeList(breaks_found) + " deg): measured data, breaks not used";
  }
  if (o.kind) {
    c.law.spline.kind = *o.kind;
    c.reason = "stated in the case; measured data, " + points + ", " + noise;
  } else {
    c.law.spline.kind = SplineKind::kSmoothing;
    c.reason = "dense table (" + points + "): measured data, " + noise + "; smoothing spline";
  }
  return c;
}

// A dense table with nothing stated but, perhaps, its spline: read for what it holds
// (ReadTable), its breaks found, each piece fitted from its own readings.
LiftLawChoice ReadDenseTable(const LiftTable& given, const LiftDataOptions& o) {
  LiftLawChoice c;
  c.law.spline = o.spline;
  c.law.open_rad = o.open_rad;
  c.law.close_rad = o.close_rad;
  c.table = given;
  const auto& x = given.crank_rad;
  const auto& y = given.lift_m;
  const std::string points = std::to_string(x.size()) + " points";
  const auto [first, last] = OpenReadings(y);
  const SplineKind kind = o.kind.value_or(SplineKind::kLocal);
  const std::optional<double> q = o.resolution_m ? o.resolution_m : PrintedResolution(y);
  const double rounding = q ? *q / std::sqrt(12.0) : 0.0;
  std::vector<const LiftBreak*> inside;
  if (o.find_breaks) {
    inside = SeekBreaks(given, std::max(EstimateNoiseRobust(x, y), rounding), kind, &c);
    if (c.corner) return c;  // refused by the caller
  }
  // Dwells: a local fit's pieces meet them where they reach the dwell's lift.
  std::vector<LiftDwell> dwells;
  if (o.find_breaks && kind == SplineKind::kLocal && q)
    dwells = SeekDwells(x, y, first, last, *q, kind, &inside);
  std::vector<double> at;  // the breaks used; the widest bins' width among them (0: none binned)
  for (const LiftBreak* b : inside) at.push_back(b->crank_rad);
  c.break_uncertainty_rad = BreakUncertainty(c.breaks_found, at);
  std::vector<double> cuts = at;  // the open lift's ends are junctions too (the seat)
  for (const LiftDwell& d : dwells) cuts.insert(cuts.end(), {d.from_rad, d.to_rad});
  cuts.push_back(x[first]);
  cuts.push_back(x[last]);
  c.reading = ReadTable(x, y, first, last, cuts, q);  // q read once, above
  const TableReading& r = *c.reading;
  c.noise_m = std::max(r.sigma_m, 1e-18);  // positive: a spline's σ must be
  c.law.spline.sigma = c.noise_m;
  c.law.spline.kind = kind;
  std::ostringstream what;
  what.precision(3);
  what << TableKindName(r.kind) << (r.staircase ? " (a staircase)" : "") << " table (" << points
       << "): residual " << Mm(r.residual_m) << " mm, x" << r.halving_ratio << " when halved";
  if (r.kind == TableKind::kExact && r.halving_ratio > 0.0 &&
      r.halving_ratio < kWhiteHalvingRatio && r.lag_correlation >= kWhiteLagCorrelation) {
    what << " but not white (neighbours correlated " << r.lag_correlation << ", noise's -0.8)";
  } else if (r.kind == TableKind::kExact && r.halving_ratio > 0.0 &&
             r.halving_ratio < kWhiteHalvingRatio && r.windows < kWhiteLeastWindows) {
    what << " but over " << r.windows << " windows, too few to tell noise";
  }
  what << ", "
       << (r.printed_m ? "printed to " + PrintedDigit(*r.printed_m)
                       : std::string("digits unknown"));
  const std::string stated = o.kind ? "stated in the case; " : "";
  if (r.kind == TableKind::kMeasured) return ReadMeasured(given, o, std::move(c), at);
  // A reading below the seat by more than a printed digit is no export of a law (whose lift is
  // never below 0) but a gauge's: noise the law's own interpolation error hid from the residual.
  const double lowest = *std::min_element(y.begin(), y.end());
  const double digit = std::max(r.printed_m.value_or(0.0), r.rounding_sigma_m);
  if (lowest < -digit) {
    LiftLawChoice m = ReadMeasured(given, o, std::move(c), at);
    m.reason = "a reading at " + Mm(lowest) + " mm, below the seat: " + m.reason;
    return m;
  }
  c.noise_source = "rounding";
  c.law.negative_allowance_m = digit;  // a reading a printed digit below the seat: its round-off
  c.law.spline.quantized = true;       // exact or rounded: its error is the rounding's
  const bool pieces_fit = kind == SplineKind::kNotAKnot || kind == SplineKind::kNatural ||
                          kind == SplineKind::kQuintic || kind == SplineKind::kLocal;
  std::string breaks = "ends at " + DegreeList({x[first], x[last]}) + " deg (" +
                       (y[first] > 0.0 || y[last] > 0.0 ? "the table's" : "the seat") + ")";
  if (!dwells.empty()) {
    std::vector<double> spans;
    for (const LiftDwell& d : dwells) spans.insert(spans.end(), {d.from_rad, d.to_rad});
    breaks = std::to_string(dwells.size()) + (dwells.size() == 1 ? " dwell" : " dwells") +
             " (readings at one lift from " + DegreeList(spans) +
             " deg; the pieces beside meet each where they reach its lift), " + breaks;
  }
  if (!at.empty()) {
    std::string found =
        std::to_string(at.size()) + " breaks found (s'' jumps at " + DegreeList(at) + " deg";
    if (c.break_uncertainty_rad > 0.0) {
      found += ", each to within " + DegreeList({c.break_uncertainty_rad}) + " deg";
    }
    found += ")";
    if (pieces_fit) {
      c.law.breaks_rad = at;
      c.law.break_uncertainty_rad = c.break_uncertainty_rad;
      for (const LiftBreak* b : inside) {
        c.law.break_estimated.push_back(!std::binary_search(x.begin(), x.end(), b->crank_rad));
      }
      c.table = WithBreakReadings(c.table, inside);
      breaks = found + ", " + breaks;
    } else {
      breaks =
          found + ", not used: \"" + SplineKindName(kind) + "\" cannot be built apart; " + breaks;
    }
  }
  AddDwells(dwells, &c.law);
  c.reason = stated + what.str() + "; noise " + Mm(c.noise_m) + " mm (" + c.noise_source + "); " +
             breaks + ": " + SplineKindName(kind) + " fit of each piece from its own readings";
  if (kind == SplineKind::kLocal) c.reason += ShortPieces(x, first, last, cuts, dwells);
  return c;
}

}  // namespace

std::string UnresolvedSides(const LiftTable& table) {
  const std::vector<double>& y = table.lift_m;
  const std::vector<double>& x = table.crank_rad;
  if (y.size() < 3 || y.size() != x.size()) return "";
  const auto top = std::max_element(y.begin(), y.end());
  if (!(*top > 0.0)) return "";
  const size_t peak = static_cast<size_t>(top - y.begin());
  size_t last_peak = peak;
  while (last_peak + 1 < y.size() && y[last_peak + 1] == *top) ++last_peak;
  size_t rise = 0, fall = 0, from = peak, to = last_peak;  // readings above the seat each side
  while (from > 0 && y[from - 1] > 0.0) --from, ++rise;
  while (to + 1 < y.size() && y[to + 1] > 0.0) ++to, ++fall;
  std::string out;
  // From the seat reading before it to the top, or from the top to the seat reading after it.
  const auto side = [&](const char* name, size_t count, size_t lo, size_t hi) {
    if (count >= kResolvedSideReadings) return;
    out += std::string(out.empty() ? "" : "; ") + "the " + name + " from " + DegreeList({x[lo]}) +
           " to " + DegreeList({x[hi]}) + " deg holds " + std::to_string(count) +
           (count == 1 ? " reading" : " readings") + " above the seat";
  };
  if (from > 0) side("rise", rise, from - 1, peak);
  if (to + 1 < y.size()) side("return", fall, last_peak, to + 1);
  if (out.empty()) return "";
  return out +
         ": too few to resolve its acceleration, which may lie beyond its band; export the "
         "table finer there";
}

LiftLawChoice ChooseLiftLaw(const LiftTable& given, const LiftDataOptions& o) {
  const bool dense = static_cast<int>(given.crank_rad.size()) >= kDenseTablePoints;
  if (dense && !o.noise_m && o.breaks_rad.empty() &&
      given.crank_rad.size() == given.lift_m.size()) {
    return ReadDenseTable(given, o);
  }
  LiftLawChoice c;
  c.law.spline = o.spline;
  c.law.spline.sparse_table = !dense;
  c.law.open_rad = o.open_rad;
  c.law.close_rad = o.close_rad;
  c.law.breaks_rad = o.breaks_rad;
  c.measured = o.noise_m.has_value() && o.breaks_rad.empty();
  c.table = given;
  if (c.measured && dense && given.crank_rad.size() == given.lift_m.size()) {
    SeekOutliers(given, o, &c);
  }
  const int n = static_cast<int>(c.table.crank_rad.size());
  const std::string points = std::to_string(n) + " points";
  if (o.noise_m) {
    c.noise_m = *o.noise_m;
    c.noise_source = "stated";
  } else if (dense) {
    SetEstimatedNoise(o, &c);
  } else {
    // A sparse table's rounding: as stated, else the digits its lifts are printed to (the
    // paper's 0.01 mm when they are not decimal millimetres). Its band's noise is this σ.
    const std::optional<double> q =
        o.resolution_m ? o.resolution_m : PrintedResolution(c.table.lift_m);
    c.noise_m = q.value_or(1e-5) / std::sqrt(12.0);
    c.noise_source = "rounding";
  }
  c.law.spline.sigma = c.noise_m;
  if (c.measured) SetMeasured(&c);
  const std::string noise = "noise " + Mm(c.noise_m) + " mm (" + c.noise_source + ")";
  if (o.kind) {
    c.law.spline.kind = *o.kind;
    c.reason = std::string("stated in the case; ") +
               (c.measured ? "measured data, " : "exact table, ") + points + ", " + noise;
    return c;
  }
  if (c.measured) {
    c.law.spline.kind = SplineKind::kSmoothing;
    c.reason = "noise stated: measured data, " + noise + "; smoothing spline";
    return c;
  }
  if (!o.breaks_rad.empty()) {
    c.law.spline.kind = SplineKind::kNotAKnot;
    c.reason = "exact table with " + std::to_string(o.breaks_rad.size()) + " breaks (" + points +
               "): not-a-knot cubic on each piece between them";
    return c;
  }
  const bool at_rest =
      !c.table.lift_m.empty() && c.table.lift_m.front() == 0.0 && c.table.lift_m.back() == 0.0;
  if (at_rest) {
    c.law.spline.kind = SplineKind::kClamped;
    c.law.spline.start_slope = c.law.spline.end_slope = 0.0;
    c.reason = "sparse exact table (" + points +
               ") closed at both ends: clamped cubic at rest at the seat";
    const std::optional<std::array<size_t, 2>> top = TopDwell(c.table.lift_m);
    if (top && JumpsIntoTopDwell(c.table.crank_rad, c.table.lift_m, *top, c.law.spline)) {
      // Each piece clamped too: the rise and the return tangent to the dwell, the dwell flat.
      const auto& x = c.table.crank_rad;
      c.law.breaks_rad = {x[(*top)[0]], x[(*top)[1]]};
      c.reason = "sparse exact table (" + points +
                 ") closed at both ends, with a dwell at its top (" +
                 std::to_string((*top)[1] + 1 - (*top)[0]) + " readings at " +
                 Mm(c.table.lift_m[(*top)[0]]) + " mm from " + DegreeList(c.law.breaks_rad) +
                 " deg): clamped cubics at rest at the seat and at the dwell, each piece apart";
    }
  } else if (c.table.crank_rad.size() < 4) {  // too few for not-a-knot's four
    c.law.spline.kind = SplineKind::kNatural;
    c.reason = "sparse exact table (" + points +
               ") open at an end: natural cubic (not-a-knot needs 4 points)";
  } else {
    c.law.spline.kind = SplineKind::kNotAKnot;
    c.reason = "sparse exact table (" + points + ") open at an end: not-a-knot cubic";
  }
  return c;
}

}  // namespace needle
