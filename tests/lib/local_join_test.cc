// Tests of the end nodes' bands at a break from one fit of both sides (lib/local_join.h).
#include "lib/local_join.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace needle {
namespace {

// A quintic by its coefficients at 0: s(x) = Σ c_k x^k, m and rad.
double Quintic(const double (&c)[6], double x) {
  double sum = 0.0;
  for (int k = 5; k >= 0; --k) sum = sum * x + c[k];
  return sum;
}

struct Sides {
  std::vector<double> xl, yl, xr, yr;
};

// Readings every 0.01 rad, 11 on each side of the break at 0 (the break's reading on both).
Sides Read(const double (&left)[6], const double (&right)[6]) {
  Sides s;
  for (int i = -10; i <= 0; ++i) {
    s.xl.push_back(0.01 * i);
    s.yl.push_back(Quintic(left, 0.01 * i));
  }
  for (int i = 0; i <= 10; ++i) {
    s.xr.push_back(0.01 * i);
    s.yr.push_back(Quintic(right, 0.01 * i));
  }
  return s;
}

LocalNode EndNode(double s2, double band2) {
  LocalNode n;
  n.x = 0.0;
  n.s[2] = s2;
  n.band2 = band2;
  n.window = kLocalMinimumPoints;
  return n;
}

constexpr double kSigma = 1e-12 / 3.4641016151377544;  // 9 decimals of mm: q = 1e-12 m, σ = q/√12

// Two quintics with one s and s' at the break and s'' 2e-3 and −5e-3 m/rad² there: the joint
// fit reads both s'' to round-off, and each node's band reaches them from a value 10 % off,
// the value itself left as it was.
TEST(LocalJoinTest, TheBandsReachTwoQuinticsThatShareTheirSlope) {
  const double left[6] = {2e-3, 1e-4, 1e-3, -3e-3, 2e-2, 5e-2};
  const double right[6] = {2e-3, 1e-4, -2.5e-3, 4e-3, -1e-2, 3e-2};
  const Sides s = Read(left, right);
  LocalNode l = EndNode(1.1 * 2e-3, 1e-6), r = EndNode(0.9 * -5e-3, 1e-6);
  ASSERT_TRUE(JoinAtBreak(s.xl, s.yl, s.xr, s.yr, kSigma, true, &l, &r));
  EXPECT_EQ(l.s[2], 1.1 * 2e-3);
  EXPECT_EQ(r.s[2], 0.9 * -5e-3);
  EXPECT_GE(l.band2, 0.1 * 2e-3);
  EXPECT_GE(r.band2, 0.1 * 5e-3);
  EXPECT_LT(l.band2, 0.1 * 2e-3 + 1e-5);  // the joint s'' within its noise of the truth
  EXPECT_LT(r.band2, 0.1 * 5e-3 + 1e-5);
}

// A corner at the break (s' jumps by 0.01 m/rad): no pair of quintics with one slope fits the
// readings, and the bands stay as they were.
TEST(LocalJoinTest, SidesThatDoNotShareTheirSlopeLeaveTheBands) {
  const double left[6] = {2e-3, 1e-4, 1e-3, -3e-3, 2e-2, 5e-2};
  const double right[6] = {2e-3, 1e-4 + 1e-2, -2.5e-3, 4e-3, -1e-2, 3e-2};
  const Sides s = Read(left, right);
  LocalNode l = EndNode(2e-3, 1e-6), r = EndNode(-5e-3, 1e-6);
  EXPECT_FALSE(JoinAtBreak(s.xl, s.yl, s.xr, s.yr, kSigma, true, &l, &r));
  EXPECT_EQ(l.band2, 1e-6);
  EXPECT_EQ(r.band2, 1e-6);
}

}  // namespace
}  // namespace needle
