// What a lift table holds (ReadTable, lib/lift_data.h): its residual against the law, whole and
// halved, piece by piece between its cuts.
#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/lift_data.h"

namespace needle {
namespace {

// Σe² and the count of the normalised fourth divided differences e = D/√Σw² over the windows
// of five consecutive entries of `idx` (readings of (x, y)) that span none of `cuts`; with
// `lag`, Σ e_i e_{i+1} over neighbouring windows both counted.
void AddResiduals(const std::vector<double>& x, const std::vector<double>& y,
                  const std::vector<size_t>& idx, const std::vector<double>& cuts, double* sum,
                  long* count, double* lag = nullptr) {
  double previous = 0.0;  // the window before's e, 0 when it was not counted
  for (size_t i = 0; i + 4 < idx.size(); ++i) {
    const double from = x[idx[i]], to = x[idx[i + 4]];
    if (std::any_of(cuts.begin(), cuts.end(), [&](double b) { return b > from && b < to; })) {
      previous = 0.0;
      continue;
    }
    double d = 0.0, w2 = 0.0;
    for (int j = 0; j <= 4; ++j) {
      double p = 1.0;
      for (int l = 0; l <= 4; ++l) {
        if (l != j) p *= x[idx[i + j]] - x[idx[i + l]];
      }
      d += y[idx[i + j]] / p;
      w2 += 1.0 / (p * p);
    }
    *sum += d * d / w2;
    ++*count;
    const double e = d / std::sqrt(w2);
    if (lag) *lag += previous * e;
    previous = e;
  }
}

// The sums of AddResiduals over the readings [from, to], whole and halved (its even and odd
// readings), and the whole's lag.
struct PieceResiduals {
  double sum = 0.0, half_sum = 0.0, lag = 0.0;
  long count = 0, half_count = 0;
  void Add(const PieceResiduals& p) {
    sum += p.sum;
    half_sum += p.half_sum;
    lag += p.lag;
    count += p.count;
    half_count += p.half_count;
  }
};

// The residuals of readings [from, to], piece by piece between the cuts: those of every piece,
// and those the halving compares, of only the pieces whose halved readings hold a window of their
// own (a piece of fewer than 9 readings has none halved: its windows would set the whole's
// residual, a coarse rise's own large one, against a halved residual of the other pieces alone,
// and the table would read as white; a harmonic rise of 7 readings at 1.5° did), or of every
// piece where none does. The windows are the whole table's: none spans a cut, so each lies in
// one piece.
struct Residuals {
  PieceResiduals every, compared;
};
Residuals PieceByPiece(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                       size_t to, const std::vector<double>& cuts) {
  std::vector<double> ends = cuts;
  std::sort(ends.begin(), ends.end());
  PieceResiduals kept, every;
  for (size_t k = 0; k <= ends.size(); ++k) {
    const double lo = k == 0 ? -std::numeric_limits<double>::infinity() : ends[k - 1];
    const double hi = k == ends.size() ? std::numeric_limits<double>::infinity() : ends[k];
    // The piece's readings, both ends' cut readings included (x increases).
    const size_t a = std::lower_bound(x.begin() + from, x.begin() + to + 1, lo) - x.begin();
    const size_t z = std::upper_bound(x.begin() + from, x.begin() + to + 1, hi) - x.begin();
    std::vector<size_t> all, even, odd;
    for (size_t i = a; i < z; ++i) {
      all.push_back(i);
      ((i - from) % 2 ? odd : even).push_back(i);
    }
    PieceResiduals p;
    AddResiduals(x, y, all, cuts, &p.sum, &p.count, &p.lag);
    AddResiduals(x, y, even, cuts, &p.half_sum, &p.half_count);
    AddResiduals(x, y, odd, cuts, &p.half_sum, &p.half_count);
    every.Add(p);
    if (p.half_count > 0) kept.Add(p);
  }
  return {every, kept.half_count > 0 ? kept : every};
}

}  // namespace

std::string TableKindName(TableKind kind) {
  switch (kind) {
    case TableKind::kExact:
      return "exact";
    case TableKind::kRounded:
      return "rounded";
    case TableKind::kMeasured:
      return "measured";
  }
  return "?";
}

TableReading ReadTable(const std::vector<double>& x, const std::vector<double>& y, size_t first,
                       size_t last, const std::vector<double>& cuts,
                       std::optional<double> resolution_m) {
  TableReading r;
  r.printed_m = resolution_m ? resolution_m : PrintedResolution(y);
  double largest = 0.0;
  for (double v : y) largest = std::max(largest, std::abs(v));
  r.rounding_sigma_m =
      r.printed_m ? *r.printed_m / std::sqrt(12.0) : kExactRelativeFloor * std::max(largest, 1e-9);
  // The seat's readings (the last zero before the rise, the first after the fall) are left
  // out: the rise may begin anywhere up to the next reading, and a window holding both sides of
  // that junction (an s'' jump between readings, off the cut) would read as noise above the
  // rounding (a harmonic exported to 9 decimals from an angle off its grid read as measured).
  const size_t from = y[first] <= 0.0 && first < last ? first + 1 : first;
  const size_t to = y[last] <= 0.0 && last > from ? last - 1 : last;
  r.rounding_sigma_m = std::hypot(r.rounding_sigma_m, AngleRoundingSigma(x, y, from, to));
  const Residuals res = PieceByPiece(x, y, from, to, cuts);
  const PieceResiduals& every = res.every;
  const PieceResiduals& compared = res.compared;
  const long half_count = compared.half_count;
  r.residual_m = every.count ? std::sqrt(every.sum / every.count) : 0.0;
  const double half = half_count ? std::sqrt(compared.half_sum / half_count) : 0.0;
  const double whole = compared.count ? std::sqrt(compared.sum / compared.count) : 0.0;
  r.halving_ratio = whole > 0.0 ? half / whole : 0.0;
  r.lag_correlation = every.sum > 0.0 ? every.lag / every.sum : 0.0;
  r.windows = every.count;
  if (r.printed_m && last > first) {
    long flat = 0;
    for (size_t i = first; i < last; ++i) {
      flat += std::abs(y[i + 1] - y[i]) <= *r.printed_m * (1.0 + 1e-6);
    }
    r.staircase = 2 * flat > static_cast<long>(last - first);
  }
  // A smooth residual (the law's own, growing ~16× when the table is halved) is an exact table's;
  // a white one at the rounding's level a rounded table's; a white one above it a measurement's.
  const bool white = half_count >= 3 && r.windows >= kWhiteLeastWindows && r.residual_m > 0.0 &&
                     r.halving_ratio < kWhiteHalvingRatio &&
                     r.lag_correlation < kWhiteLagCorrelation;
  r.sigma_m = r.rounding_sigma_m;
  if (!white) {
    r.kind = TableKind::kExact;
  } else if (r.residual_m <= kRoundingNoiseFactor * r.rounding_sigma_m) {
    r.kind = TableKind::kRounded;
  } else {
    r.kind = TableKind::kMeasured;
    r.sigma_m = r.residual_m;
  }
  return r;
}

}  // namespace needle
