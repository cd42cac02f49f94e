// Dwells of an exact or rounded table (FindDwells, lib/lift_data.h): a run of equal readings at
// a top or a bottom that one smooth law through it and the readings beside it misfits.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "lib/lift_data.h"
#include "lib/local_fit.h"
#include "lib/side_polynomial.h"

namespace needle {
namespace {

// Whether one quintic through readings [from, to] (least squares) misses one of them by more
// than `allowed`, m.
bool QuinticMisfits(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                    size_t to, double allowed) {
  const double c = 0.5 * (x[from] + x[to]), h = 0.5 * (x[to] - x[from]);
  const Eigen::MatrixXd v = PowerBasis(x, from, to + 1, c, h, 5);
  const Eigen::Map<const Eigen::VectorXd> r(y.data() + from,
                                            static_cast<Eigen::Index>(to + 1 - from));
  const Eigen::VectorXd a = QrSolve(v, r);
  return (v * a - r).cwiseAbs().maxCoeff() > allowed;
}

// Whether s'' jumps where a side of a dwell (its rise or its return) meets it. The side's
// kJumpReadings readings nearest the dwell (`nearest` the last of them, `end` the dwell's reading
// beside it) are fitted by a quartic or quintic that meets the dwell's lift tangentially at ξ
// between the two (C¹: a cam's flank meets its dwell so), ξ sampled every twentieth of the step:
// one with s''(ξ) free, y = L + a₂u² + a₃u³ + a₄u⁴, and one with s''(ξ) = 0, y = L + a₃u³ + a₄u⁴
// + a₅u⁵, u = x − ξ, three coefficients each. s'' jumps where the second misfits by
// kJumpSquares times the first and by as many times the rounding's variance, each per degree of
// freedom, and the first's s''(ξ) is above kJumpScale h/β², h and β the side's lift and span
// from `far` (a constant acceleration's peak is 4 h/β²): a harmonic's or double harmonic's rise
// ends with s'' at its peak (4.9 and 9.9 h/β²); a cycloidal, 3-4-5, trapezoidal or cubic B-spline
// rise reaches 0 (a B-spline's last knot interval read every 1.5° misfits the second fit 4 to 15
// 000 times the first, its s''(ξ) 0.02 to 1.1 h/β²).
bool JumpsIntoDwell(const std::vector<double>& x, const std::vector<double>& y, size_t nearest,
                    size_t end, size_t far, double level, double sigma) {
  const bool before = nearest < end;  // the side's readings [far, nearest], or [nearest, far]
  if (before ? nearest + 1 < far + kJumpReadings : nearest + kJumpReadings > far + 1) return false;
  const size_t from = before ? nearest + 1 - kJumpReadings : nearest;
  const double step = x[end] - x[nearest];
  double free = std::numeric_limits<double>::infinity(), flat = free, jump = 0.0;
  for (int k = 0; k <= 20; ++k) {
    const double xi = x[nearest] + step * k / 20.0;
    Eigen::MatrixXd u(kJumpReadings, 4);
    Eigen::VectorXd r(kJumpReadings);
    for (size_t i = 0; i < kJumpReadings; ++i) {
      const double t = (x[from + i] - xi) / step;
      for (int p = 0; p < 4; ++p) u(i, p) = std::pow(t, p + 2);
      r(i) = y[from + i] - level;
    }
    const Eigen::MatrixXd with = u.leftCols(3), without = u.rightCols(3);
    const Eigen::VectorXd a = QrSolve(with, r);  // a₂, a₃, a₄
    const double with_jump = (with * a - r).squaredNorm();
    if (with_jump < free) {
      free = with_jump;
      jump = 2.0 * a[0] / (step * step);
    }
    flat = std::min(flat, (without * QrSolve(without, r) - r).squaredNorm());
  }
  const double dof = static_cast<double>(kJumpReadings) - 4.0;  // three coefficients and ξ
  const double span = x[end] - x[far], height = std::abs(level - y[far]);
  return flat > kJumpSquares * free && flat > kJumpSquares * dof * sigma * sigma &&
         std::abs(jump) * span * span > kJumpScale * height;
}

}  // namespace

std::vector<LiftDwell> FindDwells(const std::vector<double>& x, const std::vector<double>& y,
                                  size_t first, size_t last, double sigma) {
  std::vector<LiftDwell> dwells;
  const double allowed = kDwellMisfits * RoundingMisfitBound(sigma);
  for (size_t i = first + 1; i < last;) {
    size_t j = i;
    while (j + 1 < last && y[j + 1] == y[i]) ++j;
    const bool top = y[i - 1] < y[i] && y[j + 1] < y[i];
    const bool bottom = y[i - 1] > y[i] && y[j + 1] > y[i];
    const size_t from = i - std::min(kDwellSide, i - first), to = std::min(j + kDwellSide, last);
    if (j + 1 - i >= kDwellLeastReadings && y[i] > 0.0 && (top || bottom) &&
        to + 1 - from >= kDwellLeastReadings + 2 * kDwellSide &&
        QuinticMisfits(x, y, from, to, allowed)) {
      const bool in = JumpsIntoDwell(x, y, i - 1, i, first, y[i], sigma);
      const bool out = JumpsIntoDwell(x, y, j + 1, j, last, y[i], sigma);
      if (in || out) dwells.push_back({x[i], x[j], y[i], top, in, out});
    }
    i = j + 1;
  }
  return dwells;
}

std::vector<LiftDwell> SeekDwells(const std::vector<double>& x, const std::vector<double>& y,
                                  size_t first, size_t last, double q, SplineKind kind,
                                  std::vector<const LiftBreak*>* inside) {
  std::vector<LiftDwell> kept;
  for (const LiftDwell& d : FindDwells(x, y, first, last, q / std::sqrt(12.0))) {
    const size_t i =
        static_cast<size_t>(std::lower_bound(x.begin(), x.end(), d.from_rad) - x.begin());
    const size_t j =
        static_cast<size_t>(std::lower_bound(x.begin(), x.end(), d.to_rad) - x.begin());
    const double lo = x[std::max(first, i - std::min<size_t>(2, i))], hi = x[std::min(last, j + 2)];
    // Junctions found at both its ends (each at its end reading or up to two outside; one
    // inside the run is none of them) hold it already: the dwell's piece between them is its
    // lift (a trapezoidal law's dwell, its s'' ramping to 0 just before: pieces cut at its
    // readings overshot there by 30 %). On a side whose s'' jumps into the dwell, only one in
    // the gap beside it: one a reading or two out leaves that side's readings off the dwell's
    // lift in its piece (a harmonic return's junction at 55.5° found at 57°, every 1° to 1e-4
    // mm: a_min −1209 against −614 m/s²).
    const auto found_near = [&](double from, double to) {
      return std::any_of(inside->begin(), inside->end(), [&](const LiftBreak* b) {
        return b->crank_rad >= from && b->crank_rad <= to;
      });
    };
    const double near_lo = d.jumps_before ? x[i - 1] : lo;  // i > first (FindDwells)
    const double near_hi = d.jumps_after ? x[j + 1] : hi;   // j < last (FindDwells)
    if (found_near(near_lo, d.from_rad) && found_near(d.to_rad, near_hi)) continue;
    const auto readings = [&](double from, double to) {  // x is increasing
      return std::upper_bound(x.begin(), x.end(), to) - std::lower_bound(x.begin(), x.end(), from);
    };
    // Each side long enough for its fit to leave the dwell's reading out (DwellTrim): a shorter
    // one was forced through it, overshot the dwell and met it with a corner.
    const auto least =
        static_cast<std::ptrdiff_t>(std::max<size_t>(kDwellSideReadings, MinimumPoints(kind)));
    // A break found closer than that to a side whose s'' jumps into the dwell, and jumping as
    // that junction does (s'' rises to the dwell's 0 into a top, falls from it out of one), is
    // that junction misplaced (a harmonic rise of 72.5° into a 5.3° dwell, read every 1°: found
    // at 69°).
    const double into = d.top ? 1.0 : -1.0;  // the sign of the jump of s'' into the dwell
    const auto misplaced = [&](const LiftBreak* b) {
      if (b->order != 2) return false;
      return (d.jumps_before && b->crank_rad < d.from_rad && into * b->jump > 0.0 &&
              readings(b->crank_rad, d.from_rad) < least) ||
             (d.jumps_after && b->crank_rad > d.to_rad && into * b->jump < 0.0 &&
              readings(d.to_rad, b->crank_rad) < least);
    };
    std::vector<const LiftBreak*> rest;
    for (const LiftBreak* b : *inside)
      if ((b->crank_rad < lo || b->crank_rad > hi) && !misplaced(b)) rest.push_back(b);
    // The pieces beside it, from the break or dwell before it and to the one after it.
    double before = x[first], after = x[last];
    for (const LiftBreak* b : rest) {
      if (b->crank_rad < d.from_rad) before = std::max(before, b->crank_rad);
      if (b->crank_rad > d.to_rad) after = std::min(after, b->crank_rad);
    }
    if (!kept.empty()) before = std::max(before, kept.back().to_rad);
    if (readings(before, d.from_rad) < least || readings(d.to_rad, after) < least) continue;
    *inside = rest;
    kept.push_back(d);
  }
  return kept;
}

void AddDwells(const std::vector<LiftDwell>& dwells, LiftLawOptions* law) {
  if (dwells.empty()) return;
  std::vector<std::pair<double, bool>> all;
  for (size_t k = 0; k < law->breaks_rad.size(); ++k)
    all.push_back({law->breaks_rad[k], k < law->break_estimated.size() && law->break_estimated[k]});
  for (const LiftDwell& d : dwells) all.insert(all.end(), {{d.from_rad, false}, {d.to_rad, false}});
  std::sort(all.begin(), all.end());
  law->breaks_rad.clear();
  law->break_estimated.clear();
  for (const auto& [angle, estimated] : all) {
    law->breaks_rad.push_back(angle);
    law->break_estimated.push_back(estimated);
  }
  law->dwells = dwells;
}

}  // namespace needle
