#include "lib/lift_data.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>

#include "lib/output.h"
#include "lib/units.h"

namespace needle {
namespace {

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

namespace {

// |r − round(r)|, the same bits as std::round's (r − trunc(r) and 1 − |that| are exact), without
// its library call: the dense tables' readings ask it up to 13 times each.
double DistanceToInteger(double r) {
  if (!(std::abs(r) < 0x1p52)) return r - r;  // an integer already: 0 (not finite: NaN)
  const double d = std::abs(r - static_cast<double>(static_cast<long long>(r)));
  return d < 0.5 ? d : 1.0 - d;
}

// Whether `value` is a multiple of the digit q (to 1e-6 of it): printed to q.
bool PrintedTo(double value, double q) {
  const double r = value / q;
  return DistanceToInteger(r) <= 1e-6 * std::max(1.0, 1e-9 * std::abs(r));
}

// Lifts printed to S significant digits (C's %g: "6.18933", "0.0123457"), in `unit_mm`: the
// digit of the highest decade that holds kDecadeLeast distinct readings or more, where it and the
// decade below print one decimal apart (S − 1 − e decimals in decade e: 5 and 6 for %g's six
// digits); nullopt where the decades print alike (fixed decimals) or too few readings tell (a
// fixed-decimal table whose top decade holds only its round peak, 10.0 mm to 0.1 mm, reads one
// decimal fewer there: helper-61's review).
std::optional<double> SignificantDigit(const std::vector<double>& lift_m, double unit_mm) {
  constexpr int kDecadeLeast = 8;
  // O(n): each reading's decade once, then each of the two decades' digit from its own readings
  // (the coarsest 10^-k all are multiples of, a first misfit ending each k's scan).
  static const std::array<double, 25> kPow = [] {  // 10^(e − 12), e = 0 … 24
    std::array<double, 25> p{};
    for (int e = 0; e < 25; ++e) p[e] = std::pow(10.0, e - 12);
    return p;
  }();
  std::vector<signed char> decade(lift_m.size(), std::numeric_limits<signed char>::min());
  std::array<int, 24> count{};  // of decades −12 … 11
  for (size_t i = 0; i < lift_m.size(); ++i) {
    const double x = std::abs(lift_m[i]) * 1e3 / unit_mm;
    if (!(x >= kPow[0] && x < kPow[24])) continue;
    // floor(log10 x) from the binary exponent (log10 2 = 0.30103), then one step either way.
    int e = std::clamp(static_cast<int>(std::floor(std::ilogb(x) * 0.30103)) + 12, 0, 23);
    if (x < kPow[e]) --e;
    if (x >= kPow[e + 1]) ++e;
    decade[i] = static_cast<signed char>(e - 12);
    ++count[e];
  }
  std::vector<int> told;  // decades of kDecadeLeast readings or more, highest first
  for (int e = 23; e >= 0 && told.size() < 2; --e)
    if (count[e] >= kDecadeLeast) told.push_back(e - 12);
  if (told.size() < 2 || told[1] != told[0] - 1) return std::nullopt;
  // Decimals of decade e's readings, every `stride`-th of them (13 where over 12), or −1 where
  // fewer than kDecadeLeast of them differ.
  const auto digits = [&](int e, int stride) {
    std::vector<double> xs;
    int seen = 0;
    for (size_t i = 0; i < lift_m.size(); ++i)
      if (decade[i] == e && seen++ % stride == 0) xs.push_back(std::abs(lift_m[i]) * 1e3 / unit_mm);
    std::sort(xs.begin(), xs.end());
    if (std::unique(xs.begin(), xs.end()) - xs.begin() < kDecadeLeast) return -1;
    int k = 0;
    for (; k <= 12; ++k) {
      const double q = std::pow(10.0, -k);
      if (std::all_of(xs.begin(), xs.end(), [q](double x) { return PrintedTo(x, q); })) break;
    }
    return k;
  };
  // Some 256 readings of each first (a fixed-decimal table ends here), then all of them.
  int top = 13;
  for (const bool all : {false, true}) {
    const auto stride = [&](int e) { return all ? 1 : std::max(1, count[e + 12] / 256); };
    top = digits(told[0], stride(told[0]));
    if (top < 0 || top > 12 || digits(told[1], stride(told[1])) != top + 1) return std::nullopt;
  }
  return std::pow(10.0, -top) * unit_mm * 1e-3;
}

}  // namespace

std::optional<double> PrintedResolution(const std::vector<double>& lift_m) {
  // A table printed to significant digits is rounded to its highest decade's digit.
  for (const double unit_mm : {kInchMm, 1.0})
    if (const std::optional<double> q = SignificantDigit(lift_m, unit_mm)) return q;
  // The digits 10^-k of each unit, the inch's first at each k: 1 in, 1 mm, 0.1 in, 0.1 mm, … (a
  // table in inches to 5 decimals is a multiple of 1e-6 mm too, and of 2.54e-4 mm first; a mm
  // table is read in inches only where every lift is a multiple of 127·10^-k mm).
  for (int k = 0; k <= 12; ++k) {
    const double q = std::pow(10.0, -k);  // in the unit
    for (const double unit_mm : {kInchMm, 1.0}) {
      bool fits = true;
      for (double v : lift_m) {
        if (!PrintedTo(v * 1e3 / unit_mm, q)) {
          fits = false;
          break;
        }
      }
      if (fits) return q * unit_mm * 1e-3;
    }
  }
  return std::nullopt;
}

bool InchDigit(double q_m) {
  const double k = -std::log10(q_m / (kInchMm * 1e-3));
  return std::abs(k - std::round(k)) < 1e-9;
}

double AngleRoundingSigma(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                          size_t to) {
  const size_t n = x.size();
  if (n < 3 || y.size() != n) return 0.0;
  static const std::array<double, 13> kDigit = {1,    1e-1, 1e-2, 1e-3,  1e-4,  1e-5, 1e-6,
                                                1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  std::vector<double> digit_rad(n, 0.0);  // 0: digits beyond 1e-12 deg, none that matter
  for (size_t i = 0; i < n; ++i) {
    for (double q : kDigit) {
      if (PrintedTo(x[i] / kDeg, q)) {
        digit_rad[i] = q * kDeg;
        break;
      }
    }
  }
  // The rounding's error as fourth differences see it: a uniform grid's rounding errors follow
  // the step's residue modulo the digit, correlated from reading to reading, below q/√12.
  // (Asked only of a grid printed finer than its step: most are not.)
  double uneven_rad = -1.0;
  const auto uneven = [&] {
    if (uneven_rad < 0.0) {
      std::vector<double> row(n);
      for (size_t i = 0; i < n; ++i) row[i] = static_cast<double>(i);
      uneven_rad = EstimateNoise(row, x);
    }
    return uneven_rad;
  };
  double sum = 0.0;
  long count = 0;
  for (size_t i = std::max<size_t>(from, 1); i <= std::min(to, n - 2); ++i) {
    const double step = 0.5 * (x[i + 1] - x[i - 1]);
    if (!(step > 0.0)) continue;
    // The finest of five neighbours' digits: an angle printed with a trailing zero ("%.10g" of
    // 123.45678 for 123.4567800) shows a coarser one than it was rounded to.
    double digit = digit_rad[i];
    for (size_t k = i >= 2 ? i - 2 : 0; k <= std::min(i + 2, n - 1); ++k) {
      digit = std::min(digit, digit_rad[k]);
    }
    // A digit at the step's own scale is a computed grid's (0.1° steps print 0.1°): exact.
    if (digit < kAngleDigitOfStep * step) {
      const double slope = (y[i + 1] - y[i - 1]) / (x[i + 1] - x[i - 1]);
      const double sd = std::min(digit / std::sqrt(12.0), uneven());
      sum += slope * slope * sd * sd;
    }
    ++count;
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

double EstimateNoiseBetweenBreaks(const std::vector<double>& x, const std::vector<double>& y,
                                  const std::vector<double>& breaks_rad) {
  return PseudoResidualRms(x, y, 6, breaks_rad);  // sixth differences: blind to quintics
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

namespace {

// Each break of `options` placed between readings (break_estimated) where `law` steps in lift
// by more than the printed digit or kBreakStepOfLift of the largest lift: its index and step, m.
std::vector<std::pair<size_t, double>> SteppingBreaks(const LiftLaw& law,
                                                      const LiftLawOptions& options) {
  const double span = law.table_end_rad() - law.table_start_rad(), eps = 1e-9 * span;
  const double top = *std::max_element(law.table().lift_m.begin(), law.table().lift_m.end());
  const double digit = options.spline.quantized ? std::sqrt(12.0) * options.spline.sigma : 0.0;
  const double allowed = std::max(digit, kBreakStepOfLift * top);
  std::vector<std::pair<size_t, double>> out;
  for (size_t k = 0; k < options.breaks_rad.size(); ++k) {
    if (k >= options.break_estimated.size() || !options.break_estimated[k]) continue;
    const double b = options.breaks_rad[k];
    const double step = law.Lift(b + eps) - law.Lift(b - eps);
    if (std::abs(step) > allowed) out.push_back({k, step});
  }
  return out;
}

// "0.00499 mm at 39.5656 deg, …" of SteppingBreaks.
std::string StepList(const LiftLawOptions& options,
                     const std::vector<std::pair<size_t, double>>& steps) {
  std::string s;
  for (size_t i = 0; i < steps.size(); ++i) {
    s += (i ? ", " : "") + Significant(std::abs(steps[i].second) * 1e3, 3) + " mm at " +
         Significant(options.breaks_rad[steps[i].first] / kDeg, 6) + " deg";
  }
  return s;
}

// Drops breaks[k] of `o`, and its reading from `table` (a break between readings has one added,
// its lift an estimate).
void DropBreak(size_t k, LiftLawOptions* o, LiftTable* table) {
  auto& x = table->crank_rad;
  const auto at = std::find(x.begin(), x.end(), o->breaks_rad[k]);
  if (at != x.end()) {
    table->lift_m.erase(table->lift_m.begin() + (at - x.begin()));
    x.erase(at);
  }
  o->breaks_rad.erase(o->breaks_rad.begin() + k);
  o->break_estimated.erase(o->break_estimated.begin() + k);
}

}  // namespace

double BreakUncertainty(const std::vector<LiftBreak>& found, const std::vector<double>& used_rad) {
  double widest = 0.0;
  for (const LiftBreak& b : found) {
    if (std::find(used_rad.begin(), used_rad.end(), b.crank_rad) != used_rad.end())
      widest = std::max(widest, b.uncertainty_rad);
  }
  return widest;
}

std::shared_ptr<const LiftLaw> BuildChosenLaw(LiftLawChoice* choice) {
  auto law = std::make_shared<const LiftLaw>(choice->table, choice->law);
  LiftLawOptions& o = choice->law;
  // Each build's stepping breaks dropped, until none steps (a piece merged with its neighbour
  // may step at its other end: at most one build per break).
  for (auto steps = SteppingBreaks(*law, o); !steps.empty(); steps = SteppingBreaks(*law, o)) {
    choice->reason += "; the fits either side of a break between readings stepped by " +
                      StepList(o, steps) +
                      " (a cam's lift does not jump): one fit across it instead";
    for (auto it = steps.rbegin(); it != steps.rend(); ++it)
      DropBreak(it->first, &o, &choice->table);
    o.break_uncertainty_rad = BreakUncertainty(choice->breaks_found, o.breaks_rad);
    choice->break_uncertainty_rad = o.break_uncertainty_rad;
    law = std::make_shared<const LiftLaw>(choice->table, o);
  }
  return law;
}

bool DipBeyondReadings(const LiftLawChoice& choice, const LiftLaw& law) {
  const double rounding = choice.noise_source == "rounding" ? std::sqrt(3.0) * choice.noise_m : 0.0;
  return law.undershoot_m() > std::max(rounding, law.closed_level_m());
}

std::string OffSeatEnds(const LiftLaw& law) {
  std::vector<std::string> ends;
  for (const bool last : {false, true}) {
    const double at = last ? law.end_rad() : law.start_rad();
    const std::vector<double>& y = law.table().lift_m;
    // An exact table's reading there (its law may miss 0 by round-off); measured data's fit.
    const double s = law.closed_level_m() > 0.0 ? law.Lift(at) : last ? y.back() : y.front();
    if (at != (last ? law.table_end_rad() : law.table_start_rad()) || !(s > law.closed_level_m()))
      continue;
    ends.push_back(std::string(last ? "ends" : "starts") + " at " + Significant(s * 1e3, 3) +
                   " mm (" + Fixed(at / kDeg, 2) + " deg)");
  }
  if (ends.empty()) return "";
  return "the lift table " + ends[0] + (ends.size() > 1 ? " and " + ends[1] : "") +
         ", above the seat: the runs take it as cut there and carry the cam on from it "
         "(docs/model.md section 3); if the readings carry an offset, take it off them";
}

}  // namespace needle
