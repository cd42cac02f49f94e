// Steps of s'' the readings favour near a local fit's extremes (lib/reading_steps.h), on
// rounded tables of closed-form laws: a 2-3 cubic rise and return, whose s'' steps at the top,
// and smooth laws, whose readings favour no step.
#include "lib/reading_steps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "lib/units.h"

namespace needle {
namespace {

struct Table {
  std::vector<double> x, y;  // rad, m
};

// A rise over `rise_deg` and a return over `fall_deg` of `shape` (ξ in 0…1, s(0) = 0, s(1) = 1),
// `height_mm` high, every `step_deg` from −pad to the end + pad, rounded to `q_mm`.
Table Export(const std::function<double(double)>& shape, double height_mm, double rise_deg,
             double fall_deg, double step_deg, double q_mm, double pad_deg) {
  Table t;
  const double end = rise_deg + fall_deg;
  for (double deg = -pad_deg; deg <= end + pad_deg; deg += step_deg) {
    double s = 0.0;
    if (deg > 0.0 && deg <= rise_deg) s = shape(deg / rise_deg);
    if (deg > rise_deg && deg < end) s = shape((end - deg) / fall_deg);
    t.x.push_back(deg * kDeg);
    t.y.push_back(std::round(height_mm * s / q_mm) * q_mm * 1e-3);
  }
  return t;
}

double Cubic23(double xi) { return xi * xi * (3.0 - 2.0 * xi); }
double Cycloidal(double xi) { return xi - std::sin(2.0 * kPi * xi) / (2.0 * kPi); }

// The 2-3 cubic of tests/data/two-three-cubic-0.05mm-1deg.csv, exported anew: s'' steps at the
// top from −6H/β₁² to −6H/β₂², and the readings favour two cubics meeting there over a quintic
// and a kinked cubic; each side (the rise's and the return's), read from the widest run of
// readings each side of the top the two cubics fit (32: its error under a tenth of itself; 16
// make it 0.2), holds the closed form within that error, near the top.
TEST(ReadingStepsTest, TheSidesOfAStepAtTheTopHoldTheClosedForm) {
  const double height = 0.05e-3, rise = 26.366054, fall = 32.271954;
  const Table t = Export(Cubic23, 0.05, rise, fall, 1.0, 1e-4, 4.570588);
  const double sigma = 1e-7 / std::sqrt(12.0);
  const LocalFit fit = FitLocal(t.x, t.y, sigma, true);
  const std::vector<LocalNode> steps = HiddenSteps(t.x, t.y, sigma, true, fit)[0];
  ASSERT_FALSE(steps.empty());
  // The rise's side and the return's, each within its own error at some ξ.
  const double rise_top = -6.0 * height / std::pow(rise * kDeg, 2);  // m/rad²
  const double fall_top = -6.0 * height / std::pow(fall * kDeg, 2);
  bool rise_held = false, fall_held = false;
  for (const LocalNode& n : steps) {
    EXPECT_NEAR(n.x / kDeg, rise, 3.0);
    const auto holds = [&n](double truth) {
      return std::abs(n.s[2] - truth) <= n.band2 && n.band2 < 0.1 * std::abs(truth);
    };
    rise_held = rise_held || holds(rise_top);
    fall_held = fall_held || holds(fall_top);
  }
  EXPECT_TRUE(rise_held);
  EXPECT_TRUE(fall_held);
}

// A cycloidal rise and return (s'' continuous, smooth but at its ends) of 3 mm over 40° each,
// every 0.5° to 1e-4 mm: no step is favoured near its extremes, and its bands stay the fit's.
TEST(ReadingStepsTest, ASmoothLawsReadingsFavourNoStep) {
  const Table t = Export(Cycloidal, 3.0, 40.0, 40.0, 0.5, 1e-4, 5.0);
  const double sigma = 1e-7 / std::sqrt(12.0);
  const LocalFit fit = FitLocal(t.x, t.y, sigma, true);
  const auto steps = HiddenSteps(t.x, t.y, sigma, true, fit);
  EXPECT_TRUE(steps[0].empty());
  EXPECT_TRUE(steps[1].empty());
}

}  // namespace
}  // namespace needle
