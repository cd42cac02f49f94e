// Exactness and structure of each spline kind on non-uniform knots.
#include "lib/spline.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

namespace needle {
namespace {

// Non-uniform knots on [−0.3, 0.7] (rad-sized), spacing varying by a factor ~3.
std::vector<double> Knots(int n) {
  std::vector<double> x;
  for (int i = 0; i <= n; ++i) {
    const double u = static_cast<double>(i) / n;
    x.push_back(-0.3 + u + (0.35 / n) * std::sin(7.0 * u) * (i > 0 && i < n));
  }
  return x;
}

double Cubic(double x, int d) {  // p = 1 − 2x + 3x² − 4x³
  switch (d) {
    case 0:
      return 1 - 2 * x + 3 * x * x - 4 * x * x * x;
    case 1:
      return -2 + 6 * x - 12 * x * x;
    case 2:
      return 6 - 24 * x;
    default:
      return -24;
  }
}

double Quintic(double x, int d) {  // p = 0.5 + x − x² + 2x³ + 3x⁴ − 5x⁵
  const double c[6] = {0.5, 1, -1, 2, 3, -5};
  double v = 0;
  for (int k = d; k <= 5; ++k) {
    double f = 1;
    for (int j = 0; j < d; ++j) f *= (k - j);
    v += f * c[k] * std::pow(x, k - d);
  }
  return v;
}

std::vector<double> Sample(const std::vector<double>& x, double (*f)(double, int)) {
  std::vector<double> y;
  for (double xi : x) y.push_back(f(xi, 0));
  return y;
}

// One lookup for s, s', s'', s''' (Kinematics::At's row) gives what four calls of Evaluate give,
// bit for bit, at and between the breaks and past both ends: up to degree 7 (the falling
// factorials read from a table) and degrees 8 and 9 (formed as before), and 0 past the degree.
TEST(SplineTest, EvaluateUpToIsEvaluateBitForBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (const int degree : {1, 3, 5, 7, 8, 9}) {
    const std::vector<double> breaks = {-0.3, 0.1, 0.45, 1.2};
    Eigen::MatrixXd c(3, degree + 1);
    for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] = u(rng);
    const PiecewisePolynomial p(breaks, c, 0);
    for (double x : {-0.5, -0.3, -0.11, 0.1, 0.2373, 0.45, 0.9, 1.2, 1.7}) {
      // Four orders and two (Kinematics::At's rows: each order's Horner sum with the piece's
      // coefficients read once), six (one Horner() per order).
      double four[4], two[2];
      p.EvaluateUpTo(x, 4, four);
      p.EvaluateUpTo(x, 2, two);
      for (int d = 0; d < 4; ++d) EXPECT_EQ(four[d], p.Evaluate(x, d)) << "x " << x << ", d " << d;
      for (int d = 0; d < 2; ++d) EXPECT_EQ(two[d], p.Evaluate(x, d)) << "x " << x << ", d " << d;
      double out[6];
      p.EvaluateUpTo(x, 6, out);
      const int i = p.Piece(x);
      const double t = x - breaks[i];
      for (int d = 0; d < 6; ++d) {
        EXPECT_EQ(out[d], p.Evaluate(x, d)) << "degree " << degree << ", x " << x << ", d " << d;
        EXPECT_EQ(out[d], p.OnPiece(i, x, d)) << "degree " << degree << ", x " << x << ", d " << d;
        double sum = 0.0, scale = 0.0;  // Σ k!/(k−d)! c_k t^(k−d), term by term
        for (int k = d; k <= degree; ++k) {
          double falling = 1.0;
          for (int j = 0; j < d; ++j) falling *= k - j;
          const double term = falling * c(i, k) * std::pow(t, k - d);
          sum += term;
          scale += std::abs(term);
        }
        EXPECT_NEAR(out[d], sum, 1e-13 * scale) << "degree " << degree << ", x " << x;
      }
      if (degree < 5) {
        EXPECT_EQ(out[5], 0.0);
      }
    }
  }
}

TEST(SplineTest, NotAKnotReproducesCubicExactly) {
  const auto x = Knots(9);
  SplineOptions o;
  o.kind = SplineKind::kNotAKnot;
  const auto s = BuildSpline(x, Sample(x, Cubic), o);
  for (double t = -0.3; t <= 0.7; t += 0.0137) {
    for (int d = 0; d <= 3; ++d)
      EXPECT_NEAR(s.Evaluate(t, d), Cubic(t, d), 1e-10) << t << " d" << d;
  }
}

TEST(SplineTest, ClampedWithTrueSlopesReproducesCubicExactly) {
  const auto x = Knots(7);
  SplineOptions o;
  o.kind = SplineKind::kClamped;
  o.start_slope = Cubic(x.front(), 1);
  o.end_slope = Cubic(x.back(), 1);
  const auto s = BuildSpline(x, Sample(x, Cubic), o);
  for (double t = -0.3; t <= 0.7; t += 0.0137) {
    for (int d = 0; d <= 3; ++d)
      EXPECT_NEAR(s.Evaluate(t, d), Cubic(t, d), 1e-10) << t << " d" << d;
  }
}

TEST(SplineTest, ClampedAtRestHasZeroEndSlopes) {
  const auto x = Knots(6);
  SplineOptions o;
  o.kind = SplineKind::kClamped;
  const auto s = BuildSpline(x, Sample(x, Cubic), o);
  EXPECT_NEAR(s.Evaluate(x.front(), 1), 0.0, 1e-12);
  EXPECT_NEAR(s.Evaluate(x.back(), 1), 0.0, 1e-12);
}

TEST(SplineTest, NaturalHasZeroEndCurvatureAndReproducesLines) {
  const auto x = Knots(6);
  SplineOptions o;
  o.kind = SplineKind::kNatural;
  const auto s = BuildSpline(x, Sample(x, Cubic), o);
  EXPECT_NEAR(s.Evaluate(x.front(), 2), 0.0, 1e-10);
  EXPECT_NEAR(s.Evaluate(x.back(), 2), 0.0, 1e-10);
  std::vector<double> line;
  for (double xi : x) line.push_back(2.0 - 3.0 * xi);
  const auto l = BuildSpline(x, line, o);
  EXPECT_NEAR(l.Evaluate(0.123), 2.0 - 3.0 * 0.123, 1e-13);
  EXPECT_NEAR(l.Evaluate(0.123, 1), -3.0, 1e-12);
}

TEST(SplineTest, QuinticReproducesQuinticExactlyAndIsC4) {
  const auto x = Knots(10);
  SplineOptions o;
  o.kind = SplineKind::kQuintic;
  const auto s = BuildSpline(x, Sample(x, Quintic), o);
  EXPECT_EQ(s.continuity(), 4);
  for (double t = -0.3; t <= 0.7; t += 0.0111) {
    for (int d = 0; d <= 3; ++d) {
      EXPECT_NEAR(s.Evaluate(t, d), Quintic(t, d), 1e-8 * (1 + std::abs(Quintic(t, d)))) << t;
    }
  }
}

TEST(SplineTest, QuinticIsC4AcrossKnotsOnArbitraryData) {
  const auto x = Knots(12);
  std::vector<double> y;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (size_t i = 0; i < x.size(); ++i) y.push_back(u(rng));
  SplineOptions o;
  o.kind = SplineKind::kQuintic;
  const auto s = BuildSpline(x, y, o);
  for (size_t i = 1; i + 1 < x.size(); ++i) {
    const double e = 1e-9;
    for (int d = 0; d <= 4; ++d) {
      const double left = s.Evaluate(x[i] - e, d), right = s.Evaluate(x[i] + e, d);
      EXPECT_NEAR(left, right, 1e-4 * (1 + std::abs(left))) << "knot " << i << " d" << d;
    }
  }
}

TEST(SplineTest, EveryInterpolatingKindPassesThroughTheData) {
  const auto x = Knots(11);
  std::vector<double> y;
  for (double xi : x) y.push_back(std::exp(xi) * std::sin(3 * xi) + 2);
  for (SplineKind kind : AllSplineKinds()) {
    if (kind == SplineKind::kSmoothing || kind == SplineKind::kLocal) continue;  // regressions
    SplineOptions o;
    o.kind = kind;
    const auto s = BuildSpline(x, y, o);
    for (size_t i = 0; i < x.size(); ++i) {
      EXPECT_NEAR(s.Evaluate(x[i]), y[i], 1e-12) << SplineKindName(kind) << " at knot " << i;
    }
  }
}

TEST(SplineTest, PchipAndMakimaAreC1WithoutAcceleration) {
  for (SplineKind kind : {SplineKind::kPchip, SplineKind::kMakima}) {
    EXPECT_FALSE(HasAcceleration(kind));
    const auto x = Knots(8);
    std::vector<double> y;
    for (double xi : x) y.push_back(xi * xi * xi);
    SplineOptions o;
    o.kind = kind;
    const auto s = BuildSpline(x, y, o);
    EXPECT_EQ(s.continuity(), 1);
    for (size_t i = 1; i + 1 < x.size(); ++i) {  // slope continuous across knots
      EXPECT_NEAR(s.Evaluate(x[i] - 1e-12, 1), s.Evaluate(x[i], 1), 1e-9);
    }
  }
  for (SplineKind kind : {SplineKind::kNatural, SplineKind::kNotAKnot, SplineKind::kClamped,
                          SplineKind::kQuintic, SplineKind::kSmoothing}) {
    EXPECT_TRUE(HasAcceleration(kind)) << SplineKindName(kind);
  }
}

TEST(SplineTest, PchipPreservesMonotonicityAndExtremaWhereCubicsOvershoot) {
  // A step-like table: the interpolating cubic overshoots, pchip must not.
  const std::vector<double> x = {0, 1, 2, 2.5, 3, 4, 6};
  const std::vector<double> y = {0, 0, 0.1, 1.0, 1.0, 1.0, 1.0};
  SplineOptions pchip;
  pchip.kind = SplineKind::kPchip;
  SplineOptions cubic;
  cubic.kind = SplineKind::kNotAKnot;
  const auto p = BuildSpline(x, y, pchip);
  const auto c = BuildSpline(x, y, cubic);
  double prev = -1, cubic_max = 0, cubic_min = 0;
  for (double t = 0; t <= 6; t += 0.001) {
    const double v = p.Evaluate(t);
    EXPECT_GE(v, prev - 1e-14) << t;
    EXPECT_LE(v, 1.0 + 1e-14);
    EXPECT_GE(v, -1e-14);
    prev = v;
    cubic_max = std::max(cubic_max, c.Evaluate(t));
    cubic_min = std::min(cubic_min, c.Evaluate(t));
  }
  EXPECT_GT(cubic_max, 1.01);  // the cubic does overshoot, so the test can tell them apart
}

TEST(SplineTest, MakimaReproducesLinesAndQuadraticsOnUniformKnots) {
  std::vector<double> x, y;
  for (int i = 0; i <= 8; ++i) {
    x.push_back(i * 0.5);
    y.push_back(3.0 - 2.0 * x.back());
  }
  SplineOptions o;
  o.kind = SplineKind::kMakima;
  const auto s = BuildSpline(x, y, o);
  EXPECT_NEAR(s.Evaluate(1.3), 3.0 - 2.6, 1e-13);
  EXPECT_NEAR(s.Evaluate(3.9, 1), -2.0, 1e-12);
}

// A smoothing fit of noisy samples (x, y) of `truth`: its weighted residual Σ((y − s)/σ)², and
// the squared errors against the truth of the fit and of the data.
template <typename Spline, typename Truth>
std::tuple<double, double, double> SmoothingSums(const std::vector<double>& x,
                                                 const std::vector<double>& y, double sigma,
                                                 const Spline& s, Truth truth) {
  double r = 0, err = 0, raw = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    r += std::pow((y[i] - s.Evaluate(x[i])) / sigma, 2);
    err += std::pow(s.Evaluate(x[i]) - truth(x[i]), 2);
    raw += std::pow(y[i] - truth(x[i]), 2);
  }
  return {r, err, raw};
}

TEST(SplineTest, SmoothingMeetsTheDiscrepancyPrinciple) {
  // Noisy samples of a smooth curve with known σ: the fit's weighted residual is N+1.
  std::vector<double> x, y;
  std::mt19937 rng(42);
  const double sigma = 0.01;
  std::normal_distribution<double> noise(0, sigma);
  for (int i = 0; i <= 40; ++i) {
    x.push_back(i * 0.05);
    y.push_back(std::sin(2 * x.back()) + noise(rng));
  }
  SplineOptions o;
  o.kind = SplineKind::kSmoothing;
  o.sigma = sigma;
  const auto s = BuildSpline(x, y, o);
  const auto [r, err, raw] =
      SmoothingSums(x, y, sigma, s, [](double t) { return std::sin(2 * t); });
  EXPECT_NEAR(r, 41.0, 1e-4 * 41.0);  // the root search stops within 1e-4 of N+1
  EXPECT_LT(err, raw);                // the smoothed values are nearer the truth than the data
  EXPECT_EQ(s.continuity(), 2);
  EXPECT_NEAR(s.Evaluate(x.front(), 2), 0.0, 1e-9);  // natural ends
}

// Past 64 knots the smoothing system is solved banded (LDLᵀ of the pentadiagonal matrix, R and
// QᵀQ formed once): on 2,001 noisy samples the fit still meets the discrepancy principle, its ends
// are natural, and it is nearer the truth than the data.
TEST(SplineTest, SmoothingOfALargeTableMeetsTheDiscrepancyPrinciple) {
  std::vector<double> x, y;
  std::mt19937 rng(7);
  const double sigma = 0.002;
  std::normal_distribution<double> noise(0, sigma);
  for (int i = 0; i <= 2000; ++i) {
    x.push_back(i * 0.001 + 0.0004 * std::sin(i));  // uneven steps
    y.push_back(std::sin(3 * x.back()) + noise(rng));
  }
  SplineOptions o;
  o.kind = SplineKind::kSmoothing;
  o.sigma = sigma;
  const auto s = BuildSpline(x, y, o);
  const auto [r, err, raw] =
      SmoothingSums(x, y, sigma, s, [](double t) { return std::sin(3 * t); });
  EXPECT_NEAR(r, 2001.0, 1e-4 * 2001.0);
  EXPECT_LT(err, 0.1 * raw);
  // The solve is the smoothing system's: the cubic through the fitted values with the solved
  // second derivatives has a continuous slope at every knot (Qᵀf = Rγ), which a wrong solve breaks.
  double jump = 0.0;
  for (size_t i = 1; i + 1 < x.size(); ++i) {
    jump = std::max(jump, std::abs(s.Evaluate(x[i] - 1e-9, 1) - s.Evaluate(x[i] + 1e-9, 1)));
  }
  EXPECT_LT(jump, 1e-6) << jump;  // 1.8e-8 here; a solve 1 % off in half its entries: 5.4
  EXPECT_NEAR(s.Evaluate(x.front(), 2), 0.0, 1e-6);
  EXPECT_NEAR(s.Evaluate(x.back(), 2), 0.0, 1e-6);
}

TEST(SplineTest, SmoothingOfDataWithinNoiseOfALineIsTheLine) {
  const std::vector<double> x = {0, 1, 2, 3, 4};
  const std::vector<double> y = {1.0, 1.001, 0.999, 1.0005, 1.0};
  SplineOptions o;
  o.kind = SplineKind::kSmoothing;
  o.sigma = 0.01;
  const auto s = BuildSpline(x, y, o);
  EXPECT_NEAR(s.Evaluate(2.5, 2), 0.0, 1e-12);
  EXPECT_NEAR(s.Evaluate(2.5, 1), s.Evaluate(0.5, 1), 1e-12);
}

// The smoothing spline through (x, y) with λ by GCV, σ = kGcvSigma (the noise of its tests).
constexpr double kGcvSigma = 0.02;
PiecewisePolynomial GcvSpline(const std::vector<double>& x, const std::vector<double>& y) {
  SplineOptions o;
  o.kind = SplineKind::kSmoothing;
  o.sigma = kGcvSigma;
  o.smoothing_rule = SmoothingRule::kGcv;
  return BuildSpline(x, y, o);
}

TEST(SplineTest, SmoothingGcvGivesAFiniteC2Fit) {
  std::vector<double> x, y;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, kGcvSigma);
  for (int i = 0; i <= 30; ++i) {
    x.push_back(i * 0.1);
    y.push_back(std::cos(x.back()) + noise(rng));
  }
  const auto s = GcvSpline(x, y);
  double err = 0, raw = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    err += std::pow(s.Evaluate(x[i]) - std::cos(x[i]), 2);
    raw += std::pow(y[i] - std::cos(x[i]), 2);
  }
  EXPECT_LT(err, raw);
}

// GCV on a table above the dense solver's 64 knots takes tr A from the band of the smoothing
// system's inverse (O(N)); it must pick the fit a brute-force GCV picks: the hat matrix
// A = I − cQ(R + cQᵀQ)⁻¹Qᵀ (Reinsch's Q and R) formed whole, GCV = N·RSS/(N − tr A)² minimised
// over log c by Brent. 151 unevenly spaced noisy readings of a sine.
TEST(SplineTest, GcvOnALargeTableIsTheDenseGcvs) {
  const int n = 150;
  std::vector<double> x, y;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0, kGcvSigma);
  for (int i = 0; i <= n; ++i) {
    x.push_back(0.1 * i + 0.03 * std::sin(1.7 * i));
    y.push_back(std::sin(x.back()) + noise(rng));
  }
  const auto s = GcvSpline(x, y);

  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(n + 1, n - 1), R = Eigen::MatrixXd::Zero(n - 1, n - 1);
  for (int j = 1; j < n; ++j) {
    const double h0 = x[j] - x[j - 1], h1 = x[j + 1] - x[j];
    Q(j - 1, j - 1) = 1.0 / h0;
    Q(j, j - 1) = -1.0 / h0 - 1.0 / h1;
    Q(j + 1, j - 1) = 1.0 / h1;
    R(j - 1, j - 1) = (h0 + h1) / 3.0;
    if (j < n - 1) R(j - 1, j) = R(j, j - 1) = h1 / 6.0;
  }
  const Eigen::VectorXd Y = Eigen::Map<const Eigen::VectorXd>(y.data(), n + 1);
  const auto hat = [&](double log_c) {
    const double c = std::pow(10.0, log_c);
    const Eigen::MatrixXd B = R + c * Q.transpose() * Q;
    return Eigen::MatrixXd(Eigen::MatrixXd::Identity(n + 1, n + 1) -
                           c * Q * B.ldlt().solve(Q.transpose()));
  };
  const auto gcv = [&](double log_c) {
    const Eigen::MatrixXd A = hat(log_c);
    const double rss = (Y - A * Y).squaredNorm(), dof = (n + 1) - A.trace();
    return (n + 1) * rss / (dof * dof);
  };
  const auto best = boost::math::tools::brent_find_minima(gcv, -12.0, 6.0, 40);
  const Eigen::VectorXd f = hat(best.first) * Y;
  for (int i = 0; i <= n; ++i) EXPECT_NEAR(s.Evaluate(x[i]), f[i], 1e-3 * kGcvSigma) << i;
}

TEST(SplineTest, RejectsBadInputWithAClearMessage) {
  SplineOptions o;
  o.kind = SplineKind::kQuintic;
  try {
    BuildSpline({0, 1, 2, 3, 4}, {0, 1, 2, 3, 4}, o);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "quintic spline needs at least 6 points, got 5");
  }
  o.kind = SplineKind::kNatural;
  try {
    BuildSpline({0, 1, 1, 3}, {0, 1, 2, 3}, o);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "natural spline: abscissae must increase strictly; point 2 is not above point 1");
  }
  try {
    BuildSpline({0, 1, 2}, {0, NAN, 2}, o);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "natural spline: point 1 is not finite");
  }
  o.sigma = -1;
  EXPECT_THROW(BuildSpline({0, 1, 2}, {0, 1, 2}, o), std::invalid_argument);
}

TEST(SplineTest, TwoPointTablesGiveTheLineWhereTheKindAllowsIt) {
  for (SplineKind kind : {SplineKind::kNatural, SplineKind::kPchip, SplineKind::kMakima}) {
    SplineOptions o;
    o.kind = kind;
    const auto s = BuildSpline({0.0, 2.0}, {1.0, 5.0}, o);
    EXPECT_NEAR(s.Evaluate(0.5), 2.0, 1e-14) << SplineKindName(kind);
    EXPECT_NEAR(s.Evaluate(1.5, 1), 2.0, 1e-14) << SplineKindName(kind);
  }
}

TEST(SplineTest, LargeTablesUseTheSparseSolverAndStayExact) {
  const auto x = Knots(400);  // 401 points: past the dense-solver threshold
  for (SplineKind kind : {SplineKind::kNotAKnot, SplineKind::kQuintic}) {
    SplineOptions o;
    o.kind = kind;
    const auto s = BuildSpline(x, Sample(x, Cubic), o);
    EXPECT_NEAR(s.Evaluate(0.2345, 2), Cubic(0.2345, 2), 1e-6) << SplineKindName(kind);
  }
}

}  // namespace
}  // namespace needle
