// The model, the local search and its starts of `needle fit` (apps/study/fit_model.h).
#include "apps/study/fit_model.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <random>
#include <sstream>

#include "apps/case/case_keys.h"

namespace needle {
namespace fit_detail {

double Shown(const FitKey& k, double si) {
  return k.dimension == Dimension::kNone ? si : FromSi(k.dimension, k.unit, si);
}

double FromShown(const FitKey& k, double v) {
  return k.dimension == Dimension::kNone ? v : ToSi(k.dimension, k.unit, v);
}

namespace {

// The default bounds of k, SI: the plausible range of its key (offsets: ±kOffsetBoundDeg, or
// ±kOffsetBoundFraction of the cam's lift); a log-scaled one's lower end at least 1e-8 of its
// upper.
std::pair<double, double> DefaultBounds(const FitKey& k, const BoundCase& c) {
  if (IsAngleOffset(k)) return {-kOffsetBoundDeg * kDeg, kOffsetBoundDeg * kDeg};
  if (IsLiftOffset(k)) {
    const double top = c.lift.law->Max(0).value;
    return {-kOffsetBoundFraction * top, kOffsetBoundFraction * top};
  }
  const CaseKey* declared = FindCaseKey(CaseFileKeys(), k.section, k.stem, k.dimension);
  double lo = declared->range->lo, hi = declared->range->hi;
  if (k.log_scale) lo = std::max(lo, 1e-8 * hi);
  return {lo, hi};
}

// One reading's residual as Ceres sees it: 1 residual, one parameter block of P.
class ReadingCost : public ceres::CostFunction {
 public:
  ReadingCost(CachedResiduals& cache, int row, int p) : cache_(cache), row_(row) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(p);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const bool jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    if (!cache_.At(parameters[0], jacobian)) return false;
    residuals[0] = cache_.r()[row_];
    if (jacobian) {
      for (int j = 0; j < parameter_block_sizes()[0]; ++j) jacobians[0][j] = cache_.J()(row_, j);
    }
    return true;
  }

 private:
  CachedResiduals& cache_;
  int row_;
};

// Ceres logs through glog to stderr (a failed evaluation, a step refused): a command's stderr
// is its one line of error, so glog keeps only what ends the program.
void QuietCeres() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("needle");
    FLAGS_minloglevel = google::GLOG_FATAL;
    FLAGS_stderrthreshold = google::GLOG_FATAL;
    FLAGS_logtostderr = false;
  });
}

// One screen point per unknown and stratum (Starts).
constexpr int kScreenPerUnknown = 16;

}  // namespace

// The value of key k in `c` (offsets: in `offsets`), SI.
double& Slot(const FitKey& k, BoundCase& c, double offsets[2]) {
  const std::string where = c.path + ": [" + k.section + "] " + k.stem + ": ";
  if (k.section == "trace") return offsets[IsAngleOffset(k) ? 0 : 1];
  if (k.section == "needle") {
    if (!c.needle) throw CaseError(where + "the case has no [needle] to fit");
    return c.needle->mass_kg;
  }
  if (k.section == "spring") {
    if (!c.spring) throw CaseError(where + "the case has no [spring] to fit");
    if (k.stem == "preload") return c.spring->preload_N;
    if (!c.spring->rate_N_m) {
      throw CaseError(where +
                      "the case's rate comes from its coil geometry; state rate_N_mm in [spring] "
                      "to fit it");
    }
    return *c.spring->rate_N_m;
  }
  if (!c.train) throw CaseError(where + "the case has no [train] to fit");
  TrainSection& t = *c.train;
  if (t.rigid() && k.stem != "play") {
    throw CaseError(where +
                    "the case's contacts are rigid ([train] contact = \"rigid\"): they have "
                    "no stiffness or damping ratio to fit (a compliant contact has)");
  }
  if (k.stem == "contact_stiffness") return t.contact_stiffness_N_m;
  if (k.stem == "seat_stiffness") return t.seat_stiffness_N_m;
  if (k.stem == "contact_damping_ratio") return t.contact_damping_ratio;
  if (k.stem == "seat_damping_ratio") return t.seat_damping_ratio;
  return t.play_m;
}

std::vector<Coordinate> Coordinates(const BoundCase& b, const FitOptions& o) {
  std::vector<Coordinate> cs;
  BoundCase probe = b;
  double offsets[2] = {0.0, 0.0};
  for (const FitKey& k : o.free) {
    for (const Coordinate& c : cs) {
      if (SameQuantity(c.key, k)) {
        throw CaseError("--free: '" + k.name + "' is given twice (also as '" + c.key.name + "')");
      }
    }
    Coordinate c;
    c.key = k;
    c.case_si = c.start_si = Slot(k, probe, offsets);
    std::tie(c.lo_si, c.hi_si) = DefaultBounds(k, b);
    const auto [lo_range, hi_range] = std::pair<double, double>{c.lo_si, c.hi_si};
    bool bounded = false;
    for (const FitBound& bound : o.bounds) {
      if (!SameQuantity(bound.key, k)) continue;
      if (bounded) throw CaseError("--bounds: " + k.name + " is bounded twice; give it once");
      bounded = true;
      c.lo_si = FromShown(bound.key, bound.low);
      c.hi_si = FromShown(bound.key, bound.high);
      if (k.section != "trace" && !(c.lo_si >= lo_range && c.hi_si <= hi_range)) {
        throw CaseError("--bounds: " + bound.key.name + "=" + Significant(bound.low, 6) + ":" +
                        Significant(bound.high, 6) + " reaches outside the plausible range " +
                        Significant(Shown(bound.key, lo_range), 6) + " to " +
                        Significant(Shown(bound.key, hi_range), 6) + " (docs/ranges.md)");
      }
    }
    if (k.log_scale && !(c.lo_si > 0.0)) {
      throw CaseError("--bounds: " + k.name + ": the low bound must be above 0 (fitted in logs)");
    }
    // A case value outside stated bounds: the search starts inside them (their middle, in logs
    // where the unknown is fitted in logs); outside the plausible range, it is refused.
    if (!(c.start_si >= c.lo_si && c.start_si <= c.hi_si)) {
      if (!bounded) {
        throw CaseError(c.key.name + ": the case's value " + Significant(Shown(k, c.start_si), 6) +
                        " is outside the plausible range " + Significant(Shown(k, c.lo_si), 6) +
                        " to " + Significant(Shown(k, c.hi_si), 6) + " (docs/ranges.md)");
      }
      c.start_si = k.log_scale ? std::sqrt(c.lo_si * c.hi_si) : 0.5 * (c.lo_si + c.hi_si);
    }
    const double unit_si = IsAngleOffset(k)  ? kDeg
                           : IsLiftOffset(k) ? 0.01 * b.lift.law->Max(0).value
                                             : 0.0;
    // A linear unknown's scale: its case value, or for a value of 0 (no play, no damping) a
    // twentieth of its range, so that the screen and the scan reach a useful part of it.
    c.scale = unit_si > 0.0       ? unit_si
              : c.start_si != 0.0 ? std::abs(c.start_si)
                                  : 0.05 * (c.hi_si - c.lo_si);
    cs.push_back(c);
  }
  for (const FitBound& bound : o.bounds) {
    const bool freed = std::any_of(
        cs.begin(), cs.end(), [&](const Coordinate& c) { return SameQuantity(c.key, bound.key); });
    if (!freed) throw CaseError("--bounds: " + bound.key.name + " is not among --free's keys");
  }
  return cs;
}

StartResult SolveFrom(FitModel& model, std::vector<double> q0, const FitOptions& o,
                      int max_iterations, int fixed) {
  QuietCeres();
  CachedResiduals cache(model);
  StartResult s;
  s.q = std::move(q0);
  if (!cache.At(s.q.data(), false)) return s;  // the model does not run from here
  ceres::HuberLoss loss(o.huber_sigmas);
  ceres::Problem::Options po;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (int i = 0; i < model.N(); ++i) {
    problem.AddResidualBlock(new ReadingCost(cache, i, model.P()), &loss, s.q.data());
  }
  for (int j = 0; j < model.P(); ++j) {
    const Coordinate& c = model.coordinates()[j];
    problem.SetParameterLowerBound(s.q.data(), j, c.ToQ(c.lo_si));
    problem.SetParameterUpperBound(s.q.data(), j, c.ToQ(c.hi_si));
  }
  if (fixed >= 0) problem.SetManifold(s.q.data(), new ceres::SubsetManifold(model.P(), {fixed}));
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = max_iterations;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.num_threads = 1;
  so.function_tolerance = 1e-9;
  so.parameter_tolerance = 1e-9;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  if (!summary.IsSolutionUsable()) return s;
  s.cost = summary.final_cost;
  s.iterations = static_cast<int>(summary.iterations.size());
  s.termination = summary.message;
  return s;
}

double HuberCost(const Eigen::VectorXd& r, double k) {
  const ceres::HuberLoss loss(k);
  double c = 0.0, rho[3];
  for (int i = 0; i < r.size(); ++i) {
    loss.Evaluate(r[i] * r[i], rho);
    c += rho[0];
  }
  return 0.5 * c;
}

double HuberWeight(double r, double knee) {
  double rho[3];
  ceres::HuberLoss(knee).Evaluate(r * r, rho);
  return rho[1];
}

// The starts: the case's values, then the best of a screen of kScreenPerUnknown points per
// unknown (a Latin hypercube over a factor of 3 either way in logs and ±50 % of the scale
// otherwise, inside the bounds), each costing one run per trace: events make the cost rough,
// with local minima a search from the case's values alone can stop in.

std::vector<std::vector<double>> Starts(FitModel& m, const FitOptions& o) {
  const int p = m.P(), n = std::max(32, kScreenPerUnknown * p);
  std::mt19937_64 gen(o.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<int>> strata(p);
  for (auto& s : strata) {
    for (int k = 0; k < n; ++k) s.push_back(k);
    std::shuffle(s.begin(), s.end(), gen);
  }
  std::vector<std::pair<double, std::vector<double>>> screened;
  std::vector<double> q0;
  for (const Coordinate& c : m.coordinates()) q0.push_back(c.ToQ(c.start_si));
  Eigen::VectorXd r;
  for (int k = 0; k < n; ++k) {
    std::vector<double> q(p);
    for (int j = 0; j < p; ++j) {
      const Coordinate& c = m.coordinates()[j];
      const double spread = Spread(c.key);
      const double x = q0[j] + spread * (2.0 * (strata[j][k] + u(gen)) / n - 1.0);
      q[j] = std::clamp(x, c.ToQ(c.lo_si), c.ToQ(c.hi_si));
    }
    if (m.Residuals(q.data(), r)) screened.push_back({HuberCost(r, o.huber_sigmas), q});
  }
  std::sort(screened.begin(), screened.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::vector<double>> starts = {q0};
  for (size_t k = 0; k < screened.size() && static_cast<int>(starts.size()) < o.starts; ++k) {
    starts.push_back(screened[k].second);
  }
  return starts;
}

}  // namespace fit_detail
}  // namespace needle
