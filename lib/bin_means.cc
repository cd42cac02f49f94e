// Means of consecutive readings in bins, with their spread (MeansOfBins, lib/local_fit.h).
#include <algorithm>
#include <array>
#include <vector>

#include "lib/local_fit.h"

namespace needle {

BinMeans MeansOfBins(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                     size_t to, size_t per) {
  BinMeans p;
  for (size_t i = from; i < to; i += per) {
    const size_t end = std::min(to, i + per);
    double sx = 0.0, sy = 0.0;
    for (size_t k = i; k < end; ++k) {
      sx += x[k];
      sy += y[k];
    }
    const double m = static_cast<double>(end - i);
    p.x.push_back(sx / m);
    p.y.push_back(sy / m);
    p.count.push_back(m);
    std::array<double, 4> c{};
    for (size_t k = i; k < end; ++k) {
      const double d = x[k] - p.x.back();
      double power = d * d;
      for (double& moment : c) {
        moment += power / m;
        power *= d;
      }
    }
    p.moments.push_back(c);
  }
  return p;
}

}  // namespace needle
