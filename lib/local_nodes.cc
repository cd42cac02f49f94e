// The local fit's law between its nodes and their bands (QuinticHermite, NearestHalfWidth,
// lib/local_fit.h).
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "lib/local_fit.h"

namespace needle {

PiecewisePolynomial QuinticHermite(const std::vector<LocalNode>& nodes) {
  const Eigen::Index n = static_cast<Eigen::Index>(nodes.size()) - 1;
  Eigen::MatrixXd c(n, kLocalDegree + 1);
  std::vector<double> breaks;
  for (Eigen::Index i = 0; i < n; ++i) {
    const LocalNode& a = nodes[i];
    const LocalNode& b = nodes[i + 1];
    const double h = b.x - a.x, dp = b.s[0] - a.s[0];
    c(i, 0) = a.s[0];
    c(i, 1) = a.s[1];
    c(i, 2) = 0.5 * a.s[2];
    c(i, 3) = (20.0 * dp - (8.0 * b.s[1] + 12.0 * a.s[1]) * h - (3.0 * a.s[2] - b.s[2]) * h * h) /
              (2.0 * h * h * h);
    c(i, 4) =
        (-30.0 * dp + (14.0 * b.s[1] + 16.0 * a.s[1]) * h + (3.0 * a.s[2] - 2.0 * b.s[2]) * h * h) /
        (2.0 * h * h * h * h);
    c(i, 5) = (12.0 * dp - 6.0 * (b.s[1] + a.s[1]) * h - (a.s[2] - b.s[2]) * h * h) /
              (2.0 * h * h * h * h * h);
    breaks.push_back(a.x);
  }
  breaks.push_back(nodes.back().x);
  return PiecewisePolynomial(std::move(breaks), std::move(c), 2);
}

double NearestHalfWidth(const std::vector<LocalNode>& nodes, double x) {
  double nearest = std::numeric_limits<double>::infinity(), band2 = 0.0;
  for (const LocalNode& n : nodes) {
    if (std::abs(n.x - x) < nearest) {
      nearest = std::abs(n.x - x);
      band2 = n.band2;
    }
  }
  return band2;
}

}  // namespace needle
