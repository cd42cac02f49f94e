#include "lib/lift_data.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>
#include <sstream>

namespace needle {
namespace {

std::string Mm(double m) {
  std::ostringstream out;
  out.precision(3);
  out << m * 1e3;
  return out.str();
}

// The fourth divided difference of five readings (x[k[j]], y[k[j]]): its pseudo-residual
// e = D/√Σw² and the weight of each reading; flat when the five read the same.
struct Window {
  double d = 0.0, norm = 0.0;  // D and √Σw²
  double w[5] = {};
  bool flat = true;
};

Window FourthDifference(const std::vector<double>& x, const std::vector<double>& y,
                        const size_t* k) {
  constexpr int kOrder = 4;  // fourth divided differences: blind to cubics
  Window win;
  double w2 = 0.0;
  for (int j = 0; j <= kOrder; ++j) {
    double p = 1.0;
    for (int l = 0; l <= kOrder; ++l) {
      if (l != j) p *= x[k[j]] - x[k[l]];
    }
    win.w[j] = 1.0 / p;
    win.d += win.w[j] * y[k[j]];
    w2 += win.w[j] * win.w[j];
    if (y[k[j]] != y[k[0]]) win.flat = false;
  }
  win.norm = std::sqrt(w2);
  return win;
}

// |e| of every window that is not flat.
std::vector<double> PseudoResiduals(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> out;
  std::vector<size_t> k(5);
  for (size_t i = 0; i + 4 < x.size(); ++i) {
    for (size_t j = 0; j < 5; ++j) k[j] = i + j;
    const Window win = FourthDifference(x, y, k.data());
    if (!win.flat) out.push_back(std::abs(win.d) / win.norm);
  }
  return out;
}

}  // namespace

double TailSigmas(long readings, double floor_sigmas) {
  const double p = 1.0 / (100.0 * static_cast<double>(std::max(readings, 1L)));
  const boost::math::normal_distribution<double> normal;
  return std::max(floor_sigmas, boost::math::quantile(boost::math::complement(normal, p)));
}

double EstimateNoiseRobust(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> e = PseudoResiduals(x, y);
  if (e.empty()) return 0.0;
  const size_t mid = e.size() / 2;
  std::nth_element(e.begin(), e.begin() + mid, e.end());
  double median = e[mid];
  if (e.size() % 2 == 0) median = 0.5 * (median + *std::max_element(e.begin(), e.begin() + mid));
  return 1.4826 * median;  // 1/Φ⁻¹(3/4): the MAD of a Gaussian is 0.6745 σ
}

std::vector<LiftOutlier> FindOutliers(const std::vector<double>& x, const std::vector<double>& y,
                                      double robust_sigma_m) {
  std::vector<LiftOutlier> found;
  const long n = static_cast<long>(x.size());
  if (n < 6) return found;  // five readings always fit a quartic: nothing stands out
  double largest = 0.0;
  for (double v : y) largest = std::max(largest, std::abs(v));
  const double threshold =
      std::max(TailSigmas(2 * n, kOutlierSigmas) * robust_sigma_m, kOutlierFloorFraction * largest);
  if (!(threshold > 0.0)) return found;
  std::vector<size_t> kept(x.size());
  for (size_t i = 0; i < kept.size(); ++i) kept[i] = i;
  while (static_cast<int>(found.size()) < kMaxOutliers && kept.size() >= 6) {
    const long m = static_cast<long>(kept.size());
    std::vector<Window> windows(m - 4);
    for (long st = 0; st + 4 < m; ++st) windows[st] = FourthDifference(x, y, &kept[st]);
    long worst = -1;
    double worst_z = threshold;
    for (long p = 0; p < m; ++p) {
      // The windows that hold p in their middle three places; at the ends, the one there is.
      double z = std::numeric_limits<double>::infinity();
      for (long st = std::max(0L, p - 3); st <= std::min(m - 5, p - 1); ++st) {
        z = std::min(z, std::abs(windows[st].d) / windows[st].norm);
      }
      if (std::isinf(z)) {
        const long st = std::clamp(p - 2, 0L, m - 5);
        z = std::abs(windows[st].d) / windows[st].norm;
      }
      if (z > worst_z) {
        worst_z = z;
        worst = p;
      }
    }
    if (worst < 0) break;
    // Within two readings of an end, where a reading has fewer than two middle windows, the
    // windows alone cannot tell which of the first (last) three is bad: it is the one whose
    // leaving out leaves the windows around it flattest.
    long culprit = worst;
    double best = std::numeric_limits<double>::infinity();
    const bool near_end = worst < 2 || worst > m - 3;
    for (long q = std::max(0L, worst - 2); near_end && q <= std::min(m - 1, worst + 2); ++q) {
      std::vector<size_t> local;
      for (long r = std::max(0L, q - 6); r <= std::min(m - 1, q + 6); ++r) {
        if (r != q) local.push_back(kept[r]);
      }
      double largest_e = 0.0;
      for (size_t st = 0; st + 4 < local.size(); ++st) {
        const Window win = FourthDifference(x, y, &local[st]);
        largest_e = std::max(largest_e, std::abs(win.d) / win.norm);
      }
      if (largest_e < best ||
          (largest_e == best && std::abs(q - worst) < std::abs(culprit - worst))) {
        best = largest_e;
        culprit = q;
      }
    }
    const long st = std::clamp(culprit - 2, 0L, m - 5);    // the most central window: the cubic
    const Window win = FourthDifference(x, y, &kept[st]);  // through the other four gives s_i
    const size_t i = kept[culprit];
    const double e = std::abs(win.d) / win.norm;
    found.push_back(
        {i, y[i], y[i] - win.d / win.w[culprit - st],
         robust_sigma_m > 0.0 ? e / robust_sigma_m : std::numeric_limits<double>::infinity()});
    kept.erase(kept.begin() + culprit);
  }
  std::sort(found.begin(), found.end(),
            [](const LiftOutlier& a, const LiftOutlier& b) { return a.index < b.index; });
  return found;
}

namespace {

// The RMS pseudo-residual e = D/√Σw² (D the divided difference of `order`, Σw² the sum of its
// squared weights) over the windows of order + 1 consecutive readings that are not flat and
// span none of `breaks_rad`; 0 without any.
double PseudoResidualRms(const std::vector<double>& x, const std::vector<double>& y, int order,
                         const std::vector<double>& breaks_rad) {
  double sum = 0.0;
  long count = 0;
  for (size_t i = 0; i + order < x.size(); ++i) {
    bool across = false;
    for (double b : breaks_rad) across = across || (b > x[i] && b < x[i + order]);
    if (across) continue;
    double d = 0.0, w2 = 0.0;
    bool flat = true;
    for (int j = 0; j <= order; ++j) {
      double p = 1.0;
      for (int l = 0; l <= order; ++l) {
        if (l != j) p *= x[i + j] - x[i + l];
      }
      const double w = 1.0 / p;
      d += w * y[i + j];
      w2 += w * w;
      if (y[i + j] != y[i]) flat = false;
    }
    if (flat) continue;
    sum += d * d / w2;  // e²
    ++count;
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

}  // namespace

double EstimateNoise(const std::vector<double>& x, const std::vector<double>& y) {
  return PseudoResidualRms(x, y, 4, {});  // fourth divided differences: blind to cubics
}

std::optional<double> PrintedResolution(const std::vector<double>& lift_m) {
  for (int k = 0; k <= 12; ++k) {
    const double q = std::pow(10.0, -k);  // mm
    bool fits = true;
    for (double v : lift_m) {
      const double r = v * 1e3 / q;
      if (std::abs(r - std::round(r)) > 1e-6 * std::max(1.0, 1e-9 * std::abs(r))) {
        fits = false;
        break;
      }
    }
    if (fits) return q * 1e-3;
  }
  return std::nullopt;
}

double EstimateNoiseBetweenBreaks(const std::vector<double>& x, const std::vector<double>& y,
                                  const std::vector<double>& breaks_rad) {
  return PseudoResidualRms(x, y, 6, breaks_rad);  // sixth differences: blind to quintics
}

LiftLawChoice ChooseLiftLaw(const LiftTable& given, const LiftDataOptions& o) {
  LiftLawChoice c;
  c.law.spline = o.spline;
  c.law.open_rad = o.open_rad;
  c.law.close_rad = o.close_rad;
  c.law.breaks_rad = o.breaks_rad;
  const bool dense = static_cast<int>(given.crank_rad.size()) >= kDenseTablePoints;
  c.measured = (dense || o.noise_m.has_value()) && o.breaks_rad.empty();
  c.table = given;
  // Breaks found in the table (the file comment's FindBreaks): where they lie inside the open
  // lift and the table between them is exact to its printed digits, the law is built apart on
  // each piece, as with stated breaks.
  std::string found_reason;
  std::optional<double> noise_between;  // σ̂ with the windows across the breaks left out
  const size_t count = given.crank_rad.size();
  const bool seek = o.find_breaks && o.breaks_rad.empty() && !o.noise_m && count > 0 &&
                    count == given.lift_m.size();
  if (seek) {
    const auto& x = given.crank_rad;
    const auto& y = given.lift_m;
    // The open lift as LiftLaw takes an exact table's: last leading zero to first trailing one.
    // A corner at the seat (within a step of it) is the open lift's end, not the lift's.
    size_t first = 0, last = count - 1;
    while (first + 1 < count && y[first] <= 0.0 && y[first + 1] <= 0.0) ++first;
    while (last > first && y[last] <= 0.0 && y[last - 1] <= 0.0) --last;
    for (const LiftBreak& b : FindBreaks(x, y, EstimateNoiseRobust(x, y))) {
      if (b.order == 2) {
        c.breaks_found.push_back(b);
      } else if (!c.corner && b.crank_rad > x[std::min(first + 1, last)] &&
                 b.crank_rad < x[std::max(last - 1, first)]) {  // a step clear of the seat
        c.corner = b;
      }
    }
    if (c.corner) return c;  // refused by the caller
    const SplineKind kind = o.kind.value_or(SplineKind::kNotAKnot);
    const bool pieces_fit = kind == SplineKind::kNotAKnot || kind == SplineKind::kNatural ||
                            kind == SplineKind::kQuintic;
    // Each piece keeps the readings its spline needs: a break closer to the one before it (or
    // to the open lift's ends) is left out.
    std::vector<const LiftBreak*> inside;
    auto readings = [&](double from, double to) {  // readings strictly between, plus both ends
      return 2 + std::count_if(x.begin(), x.end(), [&](double t) { return t > from && t < to; });
    };
    for (const LiftBreak& b : c.breaks_found) {
      const double from = inside.empty() ? x[first] : inside.back()->crank_rad;
      if (b.crank_rad > x[first] && b.crank_rad < x[last] &&
          readings(from, b.crank_rad) >= MinimumPoints(kind)) {
        inside.push_back(&b);
      }
    }
    while (!inside.empty() && readings(inside.back()->crank_rad, x[last]) < MinimumPoints(kind)) {
      inside.pop_back();
    }
    if (!inside.empty()) {
      std::vector<double> at;
      for (const LiftBreak* b : inside) at.push_back(b->crank_rad);
      const std::optional<double> q = o.resolution_m ? o.resolution_m : PrintedResolution(y);
      // The open lift's ends are junctions too (the seat): windows across them are left out.
      std::vector<double> cuts = at;
      cuts.push_back(x[first]);
      cuts.push_back(x[last]);
      const double between = EstimateNoiseBetweenBreaks(x, y, cuts);
      double largest = 0.0;
      for (double v : y) largest = std::max(largest, std::abs(v));
      const bool exact = q && between <= std::max(kExactDigitsFactor * *q / std::sqrt(12.0),
                                                  kExactRelativeFloor * largest);
      std::string where;
      for (size_t k = 0; k < at.size() && k < 8; ++k) {
        std::ostringstream deg;
        deg.precision(6);
        deg << at[k] * 180.0 / 3.14159265358979323846;
        where += (k ? ", " : "") + deg.str();
      }
      if (at.size() > 8) where += ", …";
      found_reason = std::to_string(at.size()) + " breaks found (s'' jumps at " + where +
                     " deg); residual between them " + Mm(between) + " mm, " +
                     (q ? "printed digits " + Mm(*q) + " mm" : std::string("digits unknown"));
      if (exact && pieces_fit) {
        c.measured = false;
        c.law.breaks_rad = at;
        c.noise_m = *q / std::sqrt(12.0);
        c.noise_source = "rounding";
        // A reading at each break between readings, its lift from the sides' cubics.
        LiftTable t;
        size_t next = 0;
        for (size_t i = 0; i < count; ++i) {
          while (next < inside.size() && inside[next]->crank_rad < x[i]) {
            t.crank_rad.push_back(inside[next]->crank_rad);
            t.lift_m.push_back(inside[next]->lift_m);
            ++next;
          }
          if (next < inside.size() && inside[next]->crank_rad == x[i]) ++next;
          t.crank_rad.push_back(x[i]);
          t.lift_m.push_back(y[i]);
        }
        c.table = t;
        const std::string points = std::to_string(count) + " points";
        if (o.kind) {
          c.law.spline.kind = *o.kind;
          c.reason = "stated in the case; exact table (" + points + "), " + found_reason +
                     ": at them, built apart on each piece";
        } else {
          c.law.spline.kind = SplineKind::kNotAKnot;
          c.reason = "exact table (" + points + "), " + found_reason +
                     ": not-a-knot cubic on each piece between them";
        }
        return c;
      }
      found_reason +=
          exact ? ": \"" + SplineKindName(kind) + "\" cannot be built apart, breaks not used"
                : ": above them, measured data, breaks not used";
      if (!exact) noise_between = between;  // the jumps are no noise
    }
  }
  // Outliers are sought in dense measured data only: on a sparse table the shape itself stands
  // out of the cubic through each reading's neighbours.
  if (c.measured && dense && given.crank_rad.size() == given.lift_m.size()) {
    c.robust_noise_m = EstimateNoiseRobust(given.crank_rad, given.lift_m);
    c.outliers = FindOutliers(given.crank_rad, given.lift_m, c.robust_noise_m);
    if (o.drop_outliers && !c.outliers.empty()) {
      c.table = LiftTable{};
      size_t next = 0;
      for (size_t i = 0; i < given.crank_rad.size(); ++i) {
        if (next < c.outliers.size() && c.outliers[next].index == i) {
          ++next;
          continue;
        }
        c.table.crank_rad.push_back(given.crank_rad[i]);
        c.table.lift_m.push_back(given.lift_m[i]);
      }
    }
  }
  const LiftTable& table = c.table;
  const int n = static_cast<int>(table.crank_rad.size());
  const std::string points = std::to_string(n) + " points";
  if (o.noise_m) {
    c.noise_m = *o.noise_m;
    c.noise_source = "stated";
  } else if (dense) {
    c.estimated_noise_m =
        noise_between ? *noise_between : EstimateNoise(table.crank_rad, table.lift_m);
    c.noise_m = *c.estimated_noise_m;
    c.noise_source = "estimated";
    if (o.resolution_m && c.noise_m < *o.resolution_m / std::sqrt(12.0)) {
      c.noise_m = *o.resolution_m / std::sqrt(12.0);  // rounding is noise the data cannot hide
      c.noise_source = "rounding";
    }
    // Exact data: keep a floor far below any measurement so the smoothing stays well posed.
    c.noise_m = std::max(c.noise_m, 1e-10);
  } else {
    c.noise_m = o.resolution_m.value_or(1e-5) / std::sqrt(12.0);  // the paper's 0.01 mm
    c.noise_source = "rounding";
  }
  c.law.spline.sigma = c.noise_m;
  if (c.measured) {
    c.law.closed_level_m = kClosedLevelSigmas * c.noise_m;
    c.law.negative_sigmas = TailSigmas(n, kNegativeSigmas);
    c.law.negative_allowance_m = c.law.negative_sigmas * c.noise_m;
  }
  std::string noise = "noise " + Mm(c.noise_m) + " mm (" + c.noise_source + ")";
  if (!found_reason.empty()) noise += "; " + found_reason;
  if (o.kind) {
    c.law.spline.kind = *o.kind;
    c.reason = std::string("stated in the case; ") +
               (c.measured ? "measured data, " : "exact table, ") + points + ", " + noise;
    return c;
  }
  if (c.measured) {
    c.law.spline.kind = SplineKind::kSmoothing;
    c.reason = (o.noise_m ? "noise stated" : "dense table (" + points + ")") +
               std::string(": measured data, ") + noise + "; smoothing spline";
    return c;
  }
  if (!o.breaks_rad.empty()) {
    c.law.spline.kind = SplineKind::kNotAKnot;
    c.reason = "exact table with " + std::to_string(o.breaks_rad.size()) + " breaks (" + points +
               "): not-a-knot cubic on each piece between them";
    return c;
  }
  const bool at_rest =
      !table.lift_m.empty() && table.lift_m.front() == 0.0 && table.lift_m.back() == 0.0;
  if (at_rest) {
    c.law.spline.kind = SplineKind::kClamped;
    c.law.spline.start_slope = c.law.spline.end_slope = 0.0;
    c.reason = "sparse exact table (" + points +
               ") closed at both ends: clamped cubic at rest at the seat";
  } else {
    c.law.spline.kind = SplineKind::kNotAKnot;
    c.reason = "sparse exact table (" + points + ") open at an end: not-a-knot cubic";
  }
  return c;
}

std::vector<Field> LiftChoiceFields(const LiftLawChoice& choice) {
  std::vector<Field> fields = {
      TextField("spline_reason", choice.reason),
      {"noise", display::kMm, choice.noise_m},
      TextField("noise_source", choice.noise_source),
      FlagField("measured", choice.measured),
  };
  // Found in the table (stated ones are in the case): the law's breaks.
  if (!choice.breaks_found.empty()) {
    fields.push_back(ListField("breaks", display::kDegree, choice.law.breaks_rad));
    fields.back().decimals = 4;
  }
  return fields;
}

}  // namespace needle
