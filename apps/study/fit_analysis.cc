// The analysis of a fit's optimum (apps/study/fit_model.h): covariance and intervals, the scan
// of the cost, the residual's structure, the second speed, n_dyn's draws.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>

#include "apps/study/dynamics_jobs.h"
#include "apps/study/fit_model.h"

namespace needle {
namespace fit_detail {

// The covariance of q: s² (JᵀWJ)⁻¹, its eigenvalues below kRankFraction of the largest taken as
// that floor (a direction the traces do not pin down gets a variance that spans its bounds).
Eigen::MatrixXd Covariance(const Eigen::MatrixXd& J, const Eigen::VectorXd& w, double s2,
                           std::vector<bool>* identified) {
  const Eigen::MatrixXd H = J.transpose() * w.asDiagonal() * J;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
  const Eigen::VectorXd lambda = eig.eigenvalues();
  const double floor = std::max(lambda.maxCoeff() * kRankFraction, kRankFloor);
  Eigen::VectorXd inv(lambda.size());
  identified->assign(lambda.size(), true);
  for (int k = 0; k < lambda.size(); ++k) {
    inv[k] = 1.0 / std::max(lambda[k], floor);
    if (lambda[k] < floor) {
      // The unknowns that make up this direction are not identified.
      for (int j = 0; j < lambda.size(); ++j) {
        if (std::abs(eig.eigenvectors()(j, k)) > 0.1) (*identified)[j] = false;
      }
    }
  }
  return s2 * eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

double CorrelationOf(const Eigen::MatrixXd& cov, int a, int b) {
  return cov(a, b) / std::sqrt(cov(a, a) * cov(b, b));
}

// The fitted values with their 95 % intervals, in the keys' units.
std::vector<FittedValue> Values(const FitModel& m, const std::vector<double>& q,
                                const Eigen::MatrixXd& cov, const std::vector<bool>& identified) {
  std::vector<FittedValue> vs;
  for (int j = 0; j < m.P(); ++j) {
    const Coordinate& c = m.coordinates()[j];
    const double lo = c.ToQ(c.lo_si), hi = c.ToQ(c.hi_si);
    const double half = kZ95 * std::sqrt(cov(j, j));
    auto shown = [&](double q_j) { return Shown(c.key, c.ToSi(q_j)); };
    FittedValue v;
    v.key = c.key;
    v.start = Shown(c.key, c.case_si);
    v.value = shown(q[j]);
    v.identified = identified[j];
    // Without curvature at the optimum the slope gives no interval: it is where the scan of the
    // cost (ScanIntervals) finds the unknown fitting as well, from the fitted value out.
    if (!identified[j]) {
      v.note =
          "not identified: the cost is flat about the fitted value; the interval is where "
          "a scan of the cost finds it fitting as well";
    }
    v.low = shown(identified[j] ? std::max(lo, q[j] - half) : q[j]);
    v.high = shown(identified[j] ? std::min(hi, q[j] + half) : q[j]);
    v.lower_bound = shown(lo);
    v.upper_bound = shown(hi);
    const double tol = 1e-6 * std::max(1.0, hi - lo);
    v.at_bound = q[j] <= lo + tol || q[j] >= hi - tol;
    vs.push_back(v);
  }
  return vs;
}

// The residual of each trace: RMS, runs test, the 5 % window where it is largest.
std::vector<TraceFit> TraceFits(FitModel& m, const std::vector<MeasuredTrace>& traces,
                                const Eigen::VectorXd& r) {
  std::vector<TraceFit> fits;
  int row = 0;
  for (size_t t = 0; t < traces.size(); ++t) {
    TraceFit f;
    f.path = traces[t].path;
    f.speed_rpm = traces[t].speed_rpm;
    f.readings = static_cast<int>(traces[t].table.crank_rad.size());
    f.used = static_cast<int>(m.used(t).size());
    f.noise_m = m.noise_m(t);
    const double sigma = f.noise_m;
    int positive = 0, runs = 0;
    double sum2 = 0.0;
    for (int i = 0; i < f.used; ++i) {
      const int k = m.used(t)[i];
      const double ri = r[row + i];
      f.crank_rad.push_back(traces[t].table.crank_rad[k]);
      f.measured_m.push_back(traces[t].table.lift_m[k]);
      f.fitted_m.push_back(traces[t].table.lift_m[k] + ri * sigma);
      sum2 += ri * ri;
      positive += ri > 0.0;
      if (i == 0 || (ri > 0.0) != (r[row + i - 1] > 0.0)) ++runs;
    }
    f.rms_m = f.used ? sigma * std::sqrt(sum2 / f.used) : 0.0;
    const double n = f.used, n1 = positive, n2 = n - n1;
    const double mean = 2.0 * n1 * n2 / std::max(n, 1.0) + 1.0;
    const double var = (mean - 1.0) * (mean - 2.0) / std::max(n - 1.0, 1.0);
    f.runs_z = var > 0.0 ? (runs - mean) / std::sqrt(var) : 0.0;
    const int w = std::max(5, f.used / 20);
    for (int i = 0; i + w <= f.used; i += std::max(1, w / 4)) {
      double s = 0.0;
      for (int k = i; k < i + w; ++k) s += r[row + k] * r[row + k];
      const double rms = sigma * std::sqrt(s / w);  // (window RMS)
      if (rms > f.worst_rms_m) {
        f.worst_rms_m = rms;
        f.worst_from_rad = f.crank_rad[i];
        f.worst_to_rad = f.crank_rad[i + w - 1];
      }
    }
    row += f.used;
    fits.push_back(f);
  }
  return fits;
}

// Whether the model misses something: a trace whose residual RMS exceeds kMissSigmas σ with
// signs in long runs; the note says which and where.
void JudgeModel(FitResult& r) {
  for (const TraceFit& f : r.traces) {
    if (f.rms_m > kMissSigmas * f.noise_m && f.runs_z < kStructuredZ) {
      r.model_misses = true;
      std::ostringstream m;
      if (!r.model_note.empty()) m << "; ";
      m << f.path << " at " << Significant(f.speed_rpm, 5) << " rpm: the residual RMS is "
        << Significant(f.rms_m * 1e3, 3) << " mm, " << Significant(f.rms_m / f.noise_m, 3)
        << " times the trace's noise, and runs in long stretches (runs test z = "
        << Significant(f.runs_z, 3) << "); largest between "
        << Significant(f.worst_from_rad / kDeg, 4) << " and "
        << Significant(f.worst_to_rad / kDeg, 4) << " deg (RMS "
        << Significant(f.worst_rms_m * 1e3, 3) << " mm)";
      r.model_note += m.str();
    }
  }
  const double dof = 0.0 +
                     std::accumulate(r.traces.begin(), r.traces.end(), 0,
                                     [](int n, const TraceFit& f) { return n + f.used; }) -
                     static_cast<double>(r.parameters.size());
  // The robust scale's square scatters about 1 as 2.7/ν (the median's efficiency, 37 %): 5 of
  // its standard deviations, and the same test of χ² with 3 of its own.
  const double robust_hi = 1.0 + 5.0 * std::sqrt(2.0 / std::max(dof, 1.0));
  if (!r.model_misses && r.scale2 > robust_hi) {
    r.residual_note = "the residual is above the traces' noise (its robust scale squared " +
                      Significant(r.scale2, 4) + ", at most " + Significant(robust_hi, 4) +
                      " expected of noise alone): a local minimum, or a model that misses "
                      "something; more --starts may find a lower one";
  } else if (!r.model_misses && r.chi2_reduced > r.scale2 * (1.0 + 3.0 * std::sqrt(2.0 / dof))) {
    r.residual_note = "a few readings stand far out (reduced chi-square " +
                      Significant(r.chi2_reduced, 4) + " against " + Significant(r.scale2, 4) +
                      " from the residual's median): outliers, weighed as |r| by Huber's loss";
  }
  if (r.model_misses) {
    r.model_note = "the model misses something the traces show: " + r.model_note +
                   (r.scale2 > 1.0 ? ". The intervals are widened by the misfit, but"
                                   : ". The intervals are not widened (Huber's weights "
                                     "keep the reduced chi-square at 1 or below), and") +
                   " a parameter fitted to make up for a missing effect is not the part's value";
  }
}

// For each pair the traces do not separate: the speed (of 0.5, 0.75, 1.25, 1.5 and 2 times each
// trace's and the rated speed) whose trace, on the first trace's angles and noise, would narrow
// their two intervals most (the product of the narrowings, at least kSeparatingNarrowing).
void SuggestSpeeds(FitModel& m, const std::vector<double>& q, const Eigen::MatrixXd& H,
                   const std::vector<MeasuredTrace>& traces, const BoundCase& b, FitResult& r) {
  std::vector<double> speeds;
  std::vector<double> bases = {b.engine.speed_rpm};
  for (const MeasuredTrace& t : traces) bases.push_back(t.speed_rpm);
  for (double base : bases) {
    for (double f : {0.5, 0.75, 1.25, 1.5, 2.0}) {
      const double n = base * f;
      bool near = !(n > 0.0);
      for (const MeasuredTrace& t : traces) near = near || std::abs(n / t.speed_rpm - 1.0) < 0.05;
      for (double s : speeds) near = near || std::abs(n / s - 1.0) < 0.05;
      if (!near) speeds.push_back(n);
    }
  }
  std::sort(speeds.begin(), speeds.end());
  Query query = m.queries()[0];  // the first trace's angles, at each speed tried
  const double sigma = m.noise_m(0);
  const Eigen::MatrixXd before = H.completeOrthogonalDecomposition().pseudoInverse();
  for (double n : speeds) {
    query.speed_rpm = n;
    Eigen::MatrixXd Jn;
    auto lifts = [&](const double* x, Eigen::VectorXd& v) {
      std::vector<std::vector<double>> y;
      if (!m.Predict(x, {query}, y)) return false;
      v = Eigen::Map<Eigen::VectorXd>(y[0].data(), y[0].size()) / sigma;
      return true;
    };
    if (!m.Differentiate(q.data(), static_cast<int>(query.crank_rad.size()), lifts, Jn)) continue;
    const Eigen::MatrixXd cov =
        (H + Jn.transpose() * Jn).completeOrthogonalDecomposition().pseudoInverse();
    for (UnseparatedPair& p : r.unseparated) {
      const double na = std::sqrt(before(p.a, p.a) / cov(p.a, p.a));
      const double nb = std::sqrt(before(p.b, p.b) / cov(p.b, p.b));
      if (std::isfinite(na * nb) && na * nb >= kSeparatingNarrowing &&
          (!p.separating_rpm || na * nb > p.narrowing_a * p.narrowing_b)) {
        p.separating_rpm = n;
        p.correlation_with = CorrelationOf(cov, p.a, p.b);
        p.narrowing_a = na;
        p.narrowing_b = nb;
      }
    }
  }
}

// The cost's own check of the linearised intervals. Along each unknown's axis, out from the fit
// — kScanSteps either way over four standard deviations (the screen's reach where the optimum
// has no curvature), then
// doubling out to the bounds — the cost's profile: at each point the other unknowns held, and
// where that does not fit, searched again (kProfileIterations) with this one held; a direction
// ends at its first point that does not fit even so. Along each principal axis of the covariance
// (a correlated pair moved together), the cost itself at the same steps. A walk along an axis
// that stops ends the interval at its first point that does not fit: the safe side of the
// crossing, known to a step. A point whose
// cost is within ½·3.84·s² of the optimum's (the 95 % likelihood-ratio level) fits as well: every
// interval is widened to hold it, and an unknown it holds at a bound is not identified. (A play
// taken up on tangent ramps leaves the needle's lift the same for any play above a few
// hundredths of a millimetre: the slope at the optimum says nothing of that plateau.) The lowest
// point below the optimum's cost, if any, is returned: the optimum is then a local one.
constexpr int kScanSteps = 4;
constexpr int kProfileIterations = 6;

namespace {

// The steps t of a scan along d from the fit: 1/kScanSteps … 1, then 2, 4, … (each sign).
std::vector<double> ScanSteps(double sign) {
  std::vector<double> ts;
  for (int k = 1; k <= kScanSteps; ++k) ts.push_back(sign * k / kScanSteps);
  for (double t = 2.0; t <= 1e6; t *= 2.0) ts.push_back(sign * t);
  return ts;
}

}  // namespace

std::optional<std::vector<double>> ScanIntervals(FitModel& m, const std::vector<double>& q,
                                                 double cost, double s2, const Eigen::MatrixXd& cov,
                                                 const FitOptions& o,
                                                 std::vector<FittedValue>& values) {
  const int p = m.P();
  const double level = cost + 0.5 * kChi2For95 * s2;
  Eigen::VectorXd lo(p), hi(p), x0 = Eigen::Map<const Eigen::VectorXd>(q.data(), p);
  for (int j = 0; j < p; ++j) {
    lo[j] = m.coordinates()[j].ToQ(m.coordinates()[j].lo_si);
    hi[j] = m.coordinates()[j].ToQ(m.coordinates()[j].hi_si);
  }
  std::optional<std::vector<double>> lower;
  double lowest = cost * (1.0 - 1e-9);
  // A point that fits as well: the intervals widened to hold it.
  auto accept = [&](const Eigen::VectorXd& x, double at) {
    if (at < lowest) {
      lowest = at;
      lower = std::vector<double>(x.data(), x.data() + p);
    }
    for (int j = 0; j < p; ++j) {
      const Coordinate& c = m.coordinates()[j];
      FittedValue& v = values[j];
      const double shown = Shown(c.key, c.ToSi(x[j]));
      if (shown < v.low || shown > v.high) v.widened = true;
      v.low = std::min(v.low, shown);
      v.high = std::max(v.high, shown);
      if ((x[j] == lo[j] || x[j] == hi[j]) && x[j] != x0[j] && v.identified) {
        v.identified = false;
        v.note = "not identified: its bound " + Significant(shown, 6) + " fits as well";
      }
    }
  };
  Eigen::VectorXd r;
  auto cost_at = [&](const Eigen::VectorXd& x) {
    return m.Residuals(x.data(), r) ? HuberCost(r, o.huber_sigmas)
                                    : std::numeric_limits<double>::infinity();
  };
  std::vector<bool> curved(p);  // identified by the curvature at the optimum (Values)
  for (int j = 0; j < p; ++j) curved[j] = values[j].identified;
  for (int j = 0; j < p; ++j) {
    // Steps of one standard deviation out to four, then doubling; without curvature,
    // the screen's reach instead.
    Eigen::VectorXd d = Eigen::VectorXd::Zero(p);
    const double sd = std::sqrt(cov(j, j));
    d[j] = curved[j] && sd > 0.0 && std::isfinite(sd) ? 4.0 * sd : Spread(m.coordinates()[j].key);
    for (double sign : {1.0, -1.0}) {
      Eigen::VectorXd last = x0, held = x0;  // held: the others where the last point left them
      for (double t : ScanSteps(sign)) {
        Eigen::VectorXd x = held;
        x[j] = std::clamp(x0[j] + t * d[j], lo[j], hi[j]);
        if (x[j] == last[j]) break;  // at the bound already
        last = x;
        double at = cost_at(x);
        if (!(at <= level) && p > 1) {  // the others searched again, this one held
          const StartResult s =
              SolveFrom(m, std::vector<double>(x.data(), x.data() + p), o, kProfileIterations, j);
          if (std::isfinite(s.cost)) {
            x = Eigen::Map<const Eigen::VectorXd>(s.q.data(), p);
            at = s.cost;
          }
        }
        if (!(at <= level)) {
          // The level is crossed between the last point that fits and this one: the interval
          // ends here, on the safe side of the crossing (its end known to a step, not less).
          if (std::isfinite(at)) accept(x, level);
          break;
        }
        held = x;
        accept(x, at);
      }
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
  for (int k = 0; p > 1 && k < p; ++k) {
    const Eigen::VectorXd d =
        4.0 * std::sqrt(std::max(eig.eigenvalues()[k], 0.0)) * eig.eigenvectors().col(k);
    for (double sign : {1.0, -1.0}) {
      Eigen::VectorXd last = x0;
      for (double t : ScanSteps(sign)) {
        const Eigen::VectorXd x = (x0 + t * d).cwiseMax(lo).cwiseMin(hi);
        if ((x - last).norm() == 0.0) break;
        last = x;
        const double at = cost_at(x);
        if (at <= level) accept(x, at);
      }
    }
  }
  return lower;
}

// n_dyn at q and over draws of q from N(q, cov), clipped to the bounds.
LiftoffPrediction PredictLiftoff(const FitModel& m, const std::vector<double>& q,
                                 const Eigen::MatrixXd& cov, const std::vector<FittedValue>& values,
                                 const FitOptions& o) {
  LiftoffPrediction p;
  double offsets[2];
  OverspeedJobOptions jo;
  jo.threads = 1;
  const CaseOverspeed at = OverspeedOfCase(m.CaseAt(q.data(), offsets), jo);
  p.status = at.result.status;
  p.value = at.result.n_dyn_rpm;
  p.to_rpm = at.options.to_rpm;
  jo.from_rpm = at.options.from_rpm;
  jo.to_rpm = at.options.to_rpm;
  const Eigen::LLT<Eigen::MatrixXd> llt(cov);
  const Eigen::MatrixXd L = llt.info() == Eigen::Success
                                ? Eigen::MatrixXd(llt.matrixL())
                                : Eigen::MatrixXd(cov.diagonal().cwiseSqrt().asDiagonal());
  std::mt19937_64 gen(o.seed + 1);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> found;  // n_dyn of each draw; +∞: no lift-off up to the sweep's end
  for (int d = 0; d < o.liftoff_draws; ++d) {
    Eigen::VectorXd z(m.P());
    for (int j = 0; j < m.P(); ++j) z[j] = normal(gen);
    const Eigen::VectorXd dq = L * z;
    std::vector<double> x = q;
    for (int j = 0; j < m.P(); ++j) {
      const Coordinate& c = m.coordinates()[j];
      const FittedValue& v = values[j];
      const double u = uniform(gen);
      x[j] = !v.identified || v.widened
                 ? c.ToQ(FromShown(c.key, v.low + u * (v.high - v.low)))  // its interval, flat
                 : std::clamp(q[j] + dq[j], c.ToQ(c.lo_si), c.ToQ(c.hi_si));
    }
    ++p.draws;
    try {
      const CaseOverspeed r = OverspeedOfCase(m.CaseAt(x.data(), offsets), jo);
      found.push_back(r.result.n_dyn_rpm ? *r.result.n_dyn_rpm
                                         : std::numeric_limits<double>::infinity());
      if (!r.result.n_dyn_rpm) ++p.draws_without;
    } catch (const CaseError&) {
      ++p.draws_refused;
    }
  }
  std::sort(found.begin(), found.end());
  if (!found.empty()) {
    auto quantile = [&](double f) {
      const double x = f * (found.size() - 1);
      const size_t k = static_cast<size_t>(x);
      if (k + 1 >= found.size() || !std::isfinite(found[k + 1])) return found[k];
      return found[k] + (x - k) * (found[k + 1] - found[k]);
    };
    p.low = quantile(0.025);
    p.high = quantile(0.975);  // +∞: above the sweep's end
  }
  return p;
}

}  // namespace fit_detail
}  // namespace needle
