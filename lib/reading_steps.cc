// Steps and kinks of s'' the readings allow near each extreme of a local fit
// (lib/reading_steps.h).
#include "lib/reading_steps.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "lib/side_polynomial.h"

namespace needle {
namespace {

// Where in a gap (x_g, x_g+1) ξ is tried, as shares of the step.
constexpr double kGapShares[] = {0.0, 0.5};

// The two cubics leave at most this many times the squares of a quintic (as many coefficients)
// through the same readings: a step the readings allow as well as a smooth law, to the ratio's
// sampling error (some √(2/5) with 10 degrees of freedom). Where a smooth law's truncation
// passes for a step in 16 readings (a 3-4-5 rise every 0.5° to 1e-3 mm) the ratio is 6 to 13;
// the 2-3 cubic's step leaves 0.05 of the quintic's in 32 readings, and 0.2 to 0.7 in 64 (0.2 mm
// every 0.5° to 1e-3 mm).
constexpr double kStepSquaresRatio = 1.5;
// ...and at most this share of a cubic kinked near ξ (s''' jumping, s'' not: a kink is read by
// lib/reading_kinks.h): a step the readings favour over a kink. The 2-3 cubics' steps leave 0.1
// to 0.4 of the kinked cubic's; a cubic spline law's knot every 1° to 1e-4 mm, in 16 readings,
// 0.8 to 5. (Two knots in one window can leave less: such a law's band is widened.)
constexpr double kStepOverKink = 0.5;
// A cubic kinked at ξ leaves at most this share of a quintic's squares: a kink the readings
// allow as well as a smooth law. (Half as much took 11 and 8 of the 44 and 50 B-spline extremes
// beyond their bands in bench/bspline_trial.py seeds 7 and 11 into them, as much 19 and 21; as
// much widened 55 of bench/export_trial.py's 1200 bands (seed 5), half as much 6.)
constexpr double kKinkOverQuintic = 1.0;
// The kinks tried are within this many steps of ξ.
constexpr double kKinkSteps = 4.0;

// Readings [from, to) of the table and the cubics' least-squares fit to them: an orthonormal
// basis q of the cubics there (v R⁻¹, R the Cholesky factor of vᵀv), and the readings less their
// projection on it. A model of the cubics and more columns e is then fitted by projecting e off q
// (each column's part the cubics do not hold) and the rest onto those: O(n) a column, no
// decomposition of the whole model. The quintic's extra columns span the same, wherever u is
// centred.
struct CubicWindow {
  size_t from = 0, to = 0;
  double middle = 0.0, half = 1.0;  // u = (θ − middle)/half on [−1, 1]
  Eigen::MatrixX4d q;
  Eigen::VectorXd rest;  // the cubic's residuals
  double quintic_squares = 0.0;
};

// The residuals of the cubics and the two columns `e` on the window's readings.
Eigen::VectorXd Beyond(const CubicWindow& w, const Eigen::MatrixX2d& e) {
  const Eigen::MatrixX2d off = e - w.q * (w.q.transpose() * e);
  const Eigen::Matrix2d gram = off.transpose() * off;
  return w.rest - off * gram.ldlt().solve(off.transpose() * w.rest);
}

// The residuals of the cubics and the column `e` on the window's readings.
Eigen::VectorXd Beyond(const CubicWindow& w, const Eigen::VectorXd& e) {
  const Eigen::VectorXd off = e - w.q * (w.q.transpose() * e);
  const double norm = off.squaredNorm();
  return norm > 0.0 ? Eigen::VectorXd(w.rest - off * (off.dot(w.rest) / norm)) : w.rest;
}

// The squares the cubics and the column `e` leave on the window's readings.
double SquaresBeyond(const CubicWindow& w, const Eigen::VectorXd& e) {
  const Eigen::VectorXd off = e - w.q * (w.q.transpose() * e);
  const double along = off.dot(w.rest), norm = off.squaredNorm();
  return w.rest.squaredNorm() - (norm > 0.0 ? along * along / norm : 0.0);
}

CubicWindow MakeWindow(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                       size_t to) {
  CubicWindow w;
  w.from = from;
  w.to = to;
  w.middle = 0.5 * (x[from] + x[to - 1]);
  w.half = 0.5 * (x[to - 1] - x[from]);
  const Eigen::MatrixX4d v = PowerBasis(x, from, to, w.middle, w.half, 3);
  const Eigen::Index n = v.rows();
  // q = v R⁻¹, RᵀR = vᵀv (u on [−1, 1]: the Gram matrix of the cubics is well conditioned).
  const Eigen::Matrix4d gram = v.transpose() * v;
  w.q = Eigen::LLT<Eigen::Matrix4d>(gram).matrixU().solve<Eigen::OnTheRight>(v);
  const Eigen::Map<const Eigen::VectorXd> r(y.data() + from, n);
  w.rest = r - w.q * (w.q.transpose() * r);
  Eigen::MatrixX2d higher(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u = v(i, 1);
    higher.row(i) << u * u * u * u, u * u * u * u * u;
  }
  w.quintic_squares = Beyond(w, higher).squaredNorm();
  return w;
}

// ((θ − at)₊ / half)^power, power 2 or 3, at the window's readings.
Eigen::VectorXd TruncatedPower(const std::vector<double>& x, const CubicWindow& w, double at,
                               int power) {
  Eigen::VectorXd c(static_cast<Eigen::Index>(w.to - w.from));
  for (size_t i = w.from; i < w.to; ++i) {
    const double d = std::max(x[i] - at, 0.0) / w.half;
    c(static_cast<Eigen::Index>(i - w.from)) = power == 2 ? d * d : d * d * d;
  }
  return c;
}

// The least squares a cubic kinked at a reading of the window (not either end's) or midway
// between two leaves there, the kink within kKinkSteps steps (`h`) of ξ: one farther off
// cannot stand for a step at ξ.
double KinkedCubicSquares(const std::vector<double>& x, const CubicWindow& w, double xi, double h) {
  double least = std::numeric_limits<double>::infinity();
  for (size_t i = w.from + 1; i + 1 < w.to; ++i) {
    for (const double at : {x[i], 0.5 * (x[i] + x[i + 1])}) {
      if (std::abs(at - xi) <= kKinkSteps * h)
        least = std::min(least, SquaresBeyond(w, TruncatedPower(x, w, at, 3)));
    }
  }
  return least;
}

// The two cubics' step columns at ξ, (θ − ξ)²₊ and (θ − ξ)³₊ (scaled).
Eigen::MatrixX2d StepColumns(const std::vector<double>& x, const CubicWindow& w, double xi) {
  Eigen::MatrixX2d e(static_cast<Eigen::Index>(w.to - w.from), 2);
  e.col(0) = TruncatedPower(x, w, xi, 2);
  e.col(1) = TruncatedPower(x, w, xi, 3);
  return e;
}

// The join's columns at ξ: a step's (θ − ξ)²₊ and (θ − ξ)³₊, a kink's (θ − ξ)³₊ (scaled).
Eigen::MatrixXd JoinColumns(const std::vector<double>& x, const CubicWindow& w, double xi,
                            bool step) {
  if (!step) return TruncatedPower(x, w, xi, 3);
  return StepColumns(x, w, xi);
}

// Each side's s''(ξ) of the cubics joined at ξ (a step's two sides; a kink's one s''), fitted to
// the window, its error, and s, s' there, as nodes into `steps`.
void AddSides(const std::vector<double>& x, const std::vector<double>& y, const CubicWindow& w,
              double xi, bool step, double sigma_m, bool quantized, std::vector<LocalNode>* steps) {
  const Eigen::Index n = static_cast<Eigen::Index>(w.to - w.from), extra = step ? 2 : 1;
  Eigen::MatrixXd v(n, 4 + extra);
  v.leftCols(4) = PowerBasis(x, w.from, w.to, xi, w.half, 3);
  v.rightCols(extra) = JoinColumns(x, w, xi, step);
  const Eigen::Map<const Eigen::VectorXd> r(y.data() + w.from, n);
  const Eigen::MatrixXd gram = Gram(v);
  const Eigen::VectorXd a = LdltSolve(gram, v.transpose() * r);
  // The side whose s''(ξ) is d·a (u = (θ − ξ)/half): its weights on the readings, its node.
  const auto add = [&](const Eigen::VectorXd& d) {
    const Eigen::VectorXd g = v * LdltSolve(gram, d);
    LocalNode node;
    node.x = xi;
    node.s[0] = a(0);
    node.s[1] = a(1) / w.half;
    node.s[2] = g.dot(r);
    node.band2 = quantized ? std::sqrt(3.0) * sigma_m * g.lpNorm<1>() : 1.96 * sigma_m * g.norm();
    node.window = static_cast<int>(n);
    steps->push_back(node);
  };
  Eigen::VectorXd d = Eigen::VectorXd::Zero(4 + extra);
  d(2) = 2.0 / (w.half * w.half);
  add(d);  // the left side's (a kink's one s'')
  if (step) {
    d(4) = d(2);
    add(d);  // the right side's: 2 b₂ more
  }
}

// The steps in gap g (between readings g and g + 1) of readings [first, last): at each ξ of
// kGapShares, the widest of kStepSideReadings, twice, four and eight times that each side of the
// gap that the two cubics fit to the rounding's bound; its sides' s'' and errors go to `steps`
// when one cubic misfits those readings and the two cubics leave no more than a quintic's
// squares (times kStepSquaresRatio) and a kinked cubic's (times kStepOverKink); and the same of a
// kink at ξ, against a quintic's squares (times kKinkOverQuintic).
void StepsInGap(const std::vector<double>& x, const std::vector<double>& y, size_t first,
                size_t last, size_t g, double sigma_m, bool quantized,
                std::vector<LocalNode>* steps) {
  const double bound = RoundingMisfitBound(sigma_m), h = x[g + 1] - x[g];
  // The windows, each wider than the one before, made as a share's step fits the one before.
  std::vector<CubicWindow> windows;
  windows.reserve(4);  // never moved: the shares keep pointers to them
  const auto window = [&](size_t k) -> const CubicWindow* {
    while (windows.size() <= k) {
      const size_t w = kStepSideReadings << windows.size();
      if (w > 8 * kStepSideReadings) return nullptr;
      const size_t from = g + 1 >= first + w ? g + 1 - w : first;
      const size_t to = std::min(last, g + 1 + w);
      if (g + 1 - from < kLocalMinimumPoints || to - g - 1 < kLocalMinimumPoints) return nullptr;
      if (!windows.empty() && windows.back().from == from && windows.back().to == to)
        return nullptr;
      windows.push_back(MakeWindow(x, y, from, to));
    }
    return &windows[k];
  };
  // The widest window the cubics and `columns(window)` fit to the bound, where one cubic does
  // not, and the squares they leave there; none where no window is so.
  const auto widest = [&](const auto& columns) -> std::pair<const CubicWindow*, double> {
    std::pair<const CubicWindow*, double> fit{nullptr, 0.0};
    for (size_t k = 0; const CubicWindow* w = window(k); ++k) {
      const Eigen::VectorXd misfit = Beyond(*w, columns(*w));
      if (misfit.cwiseAbs().maxCoeff() > bound) break;
      fit = {w, misfit.squaredNorm()};
    }
    if (fit.first && fit.first->rest.cwiseAbs().maxCoeff() <= bound) fit.first = nullptr;
    return fit;
  };
  for (const double share : kGapShares) {
    const double xi = x[g] + share * h;
    const auto [step, step_squares] =
        widest([&](const CubicWindow& w) { return StepColumns(x, w, xi); });
    if (step && step_squares <= kStepSquaresRatio * step->quintic_squares &&
        step_squares <= kStepOverKink * KinkedCubicSquares(x, *step, xi, h))
      AddSides(x, y, *step, xi, true, sigma_m, quantized, steps);
    // A kink at ξ, where a cubic kinked there fits as a smooth law does not.
    const auto [kink, kink_squares] =
        widest([&](const CubicWindow& w) { return TruncatedPower(x, w, xi, 3); });
    if (kink && kink_squares <= kKinkOverQuintic * kink->quintic_squares)
      AddSides(x, y, *kink, xi, false, sigma_m, quantized, steps);
  }
}

}  // namespace

std::array<std::vector<LocalNode>, 2> HiddenSteps(const std::vector<double>& x,
                                                  const std::vector<double>& y, double sigma_m,
                                                  bool quantized, const LocalFit& fit,
                                                  LocalTrim trim) {
  std::array<std::vector<LocalNode>, 2> steps;
  const auto& nodes = fit.nodes;
  if (x.size() != y.size() || x.size() > static_cast<size_t>(kLocalMaxNodes) || nodes.empty() ||
      !(sigma_m > 0.0)) {
    return steps;
  }
  // The fit's readings (FitLocal's trim, dropped where it applied none).
  size_t from = 0, to = x.size();
  if (fit.trimmed) {
    from = std::lower_bound(x.begin(), x.end(), x.front() + trim.front_rad) - x.begin();
    to = std::upper_bound(x.begin(), x.end(), x.back() - trim.back_rad) - x.begin();
  }
  for (const double sign : {1.0, -1.0}) {
    const auto e = std::max_element(
        nodes.begin(), nodes.end(),
        [sign](const LocalNode& a, const LocalNode& b) { return sign * a.s[2] < sign * b.s[2]; });
    // The gaps within kStepGaps readings of it (its neighbours may stand nearer than a step
    // that rounds it off: a 2-3 cubic's, 5 readings from the node of its a_min).
    const size_t at = static_cast<size_t>(std::lower_bound(x.begin(), x.end(), e->x) - x.begin());
    const size_t first = std::max(from, at > kStepGaps ? at - kStepGaps : 0);
    const size_t last = std::min(to, at + kStepGaps + 1);
    for (size_t g = first; g + 1 < last; ++g)
      StepsInGap(x, y, from, to, g, sigma_m, quantized, &steps[sign > 0.0]);
  }
  return steps;
}

}  // namespace needle
