#pragma once
/// @file
/// The inside of `needle fit` (apps/study/fit_job.h), internal: the unknowns' coordinates, the
/// model that turns them into the traces' residuals, the local search (Ceres Solver) and its
/// starts, and the analysis of the optimum: the covariance and intervals, the scan of the cost,
/// the residual's structure, the second speed, n_dyn's draws. Not a public header.

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "apps/case/bound_case.h"
#include "apps/case/measured_trace.h"
#include "apps/study/fit_job.h"
#include "lib/case_error.h"
#include "lib/lift_data.h"
#include "lib/output.h"

namespace needle {
namespace fit_detail {

// Default bounds of the trace's offsets: ±kOffsetBoundDeg, ±kOffsetBoundFraction of the cam lift.
constexpr double kOffsetBoundDeg = 5.0;
constexpr double kOffsetBoundFraction = 0.1;
// Central-difference step in the internal coordinates (logs, or values over their scale).
constexpr double kDiffStep = 1e-4;
// Eigenvalues of JᵀWJ below this fraction of the largest, or below kRankFloor (a standard
// deviation of 100 in the internal coordinates: a factor e^100, or 100 times the scale), are
// taken as none (not identified).
constexpr double kRankFraction = 1e-10;
constexpr double kRankFloor = 1e-4;
// The model misses something when the residual RMS exceeds this many σ and its signs run in
// long stretches (runs test z below kStructuredZ).
constexpr double kMissSigmas = 2.0;
constexpr double kStructuredZ = -3.0;
// A second speed is named for an unseparated pair when its trace would narrow the pair's two
// intervals by at least this factor together (the product of the two narrowings).
constexpr double kSeparatingNarrowing = 4.0;
// The normal distribution's two-sided 95 % point, and the χ² (1 degree of freedom) 95 % level,
// its square: the linearised interval's half-width in standard deviations, and the likelihood-ratio
// level of the scan (ScanIntervals: a cost within ½·kChi2For95·s² of the optimum's).
constexpr double kZ95 = 1.959963984540054;
constexpr double kChi2For95 = kZ95 * kZ95;
// The screen's and the scan's reach about a value: a factor of 3 either way for an unknown in
// logs, ±50 % of its scale otherwise (in the internal coordinates).
constexpr double kSpreadLog = 1.0986122886681098;  // ln 3
constexpr double kSpreadLinear = 0.5;
inline double Spread(const FitKey& k) { return k.log_scale ? kSpreadLog : kSpreadLinear; }
inline bool SameQuantity(const FitKey& a, const FitKey& b) {
  return a.section == b.section && a.stem == b.stem && a.dimension == b.dimension;
}

// Each start's first search stops after this many iterations; the kFinalists best go on.
constexpr int kProbeIterations = 6;
constexpr int kFinalists = 3;
// Searches restarted at most where the scan finds a lower cost (FitCase).
constexpr int kScanRestarts = 2;

/// A value of key k in its unit, from SI, and back (a dimensionless key: as it is).
double Shown(const FitKey& k, double si);
double FromShown(const FitKey& k, double v);
inline bool IsAngleOffset(const FitKey& k) {
  return k.section == "trace" && k.dimension == Dimension::kAngle;
}
inline bool IsLiftOffset(const FitKey& k) {
  return k.section == "trace" && k.dimension == Dimension::kLength;
}

/// The value of key k in `c` (offsets: in `offsets`, rad and m), SI; throws CaseError where the
/// case has no such value to fit.
double& Slot(const FitKey& k, BoundCase& c, double offsets[2]);

// One unknown's internal coordinate: q = ln v (logs) or v / scale, and its bounds in q.
struct Coordinate {
  FitKey key;
  double scale = 1.0;  // SI per unit of q (linear)
  double lo_si = 0.0, hi_si = 0.0;
  double case_si = 0.0;   // the case's value
  double start_si = 0.0;  // where the search starts: the case's value, inside the bounds
  double ToQ(double v) const { return key.log_scale ? std::log(v) : v / scale; }
  double ToSi(double q) const { return key.log_scale ? std::exp(q) : q * scale; }
};

/// The unknowns of `o` in `b`: their bounds (stated, else DefaultBounds) and scales. Throws
/// CaseError on a key given twice or bounded twice, a bound of a key not freed or outside the
/// plausible range, a key the case's contacts do not have (a rigid contact's stiffness).
std::vector<Coordinate> Coordinates(const BoundCase& b, const FitOptions& o);

// A run at one speed asked for the lift at some crank angles (sorted).
struct Query {
  double speed_rpm = 0.0;
  std::vector<double> crank_rad;
};

// The model at internal coordinates q: the case with q's values, its scene and runs.
class FitModel {
 public:
  FitModel(const BoundCase& b, std::vector<Coordinate> cs, const std::vector<MeasuredTrace>& traces)
      : base_(b), work_(b), cs_(std::move(cs)), traces_(traces) {
    const LiftLaw& law = *b.lift.law;
    margin_rad_ = 0.0;
    for (const Coordinate& c : cs_) {
      if (IsAngleOffset(c.key)) margin_rad_ = std::max(std::abs(c.lo_si), std::abs(c.hi_si));
    }
    // A window that does not move with the unknowns (the play moves the cam input's rise): the
    // run window's margins (DefaultRunWindow) about the law's rise and fall, widened by the angle
    // offset's reach.
    start_rad_ = b.start_rad.value_or(law.start_rad() - kRunWindowLead_rad - margin_rad_);
    end_rad_ = b.end_rad.value_or(law.end_rad() + kRunWindowTail_rad + margin_rad_);
    for (const MeasuredTrace& t : traces_) {
      std::vector<int> used;
      for (size_t i = 0; i < t.table.crank_rad.size(); ++i) {
        const double th = t.table.crank_rad[i];
        if (th >= start_rad_ + margin_rad_ && th <= end_rad_ - margin_rad_) {
          used.push_back(static_cast<int>(i));
        }
      }
      Query query{t.speed_rpm, {}};
      for (int i : used) query.crank_rad.push_back(t.table.crank_rad[i]);
      queries_.push_back(std::move(query));
      used_.push_back(used);
      noise_m_.push_back(EstimateNoiseRobust(t.table.crank_rad, t.table.lift_m));
      rows_ += static_cast<int>(used.size());
    }
    // σ of a trace without noise (a model's own, exported exactly): the last digits of a lift.
    for (double& s : noise_m_) s = std::max(s, 1e-9 * law.Max(0).value);
  }
  int P() const { return static_cast<int>(cs_.size()); }
  int N() const { return rows_; }
  const std::vector<Coordinate>& coordinates() const { return cs_; }
  const std::vector<int>& used(size_t t) const { return used_[t]; }
  /// Each trace's used angles at its speed.
  const std::vector<Query>& queries() const { return queries_; }
  double noise_m(size_t t) const { return noise_m_[t]; }
  int runs() const { return runs_; }
  /// Why the model last refused an evaluation (BindScene's or the run's message).
  const std::string& last_refusal() const { return last_refusal_; }

  // The case at q, and its offsets (rad, m).
  BoundCase CaseAt(const double* q, double offsets[2]) const {
    BoundCase c = base_;
    SetUnknowns(q, c, offsets);
    c.scene.reset();
    return c;
  }

  // The lifts (m) the model gives at each query's angles at q, the lift offset added; false when
  // the model refuses q or a run does not reach every angle.
  bool Predict(const double* q, const std::vector<Query>& queries,
               std::vector<std::vector<double>>& lifts) {
    double offsets[2];
    SetUnknowns(q, work_, offsets);  // the case's copy the runs work on, set in place
    const BoundCase& c = work_;
    Scene scene;
    try {
      scene = BindScene(c, c.lift.law);
    } catch (const CaseError& e) {
      last_refusal_ = e.what();
      return false;
    }
    scene.start_rad = start_rad_;
    scene.end_rad = end_rad_;
    SimulationOptions o = c.run;
    o.record_series = false;
    o.series_sink = nullptr;
    o.force_dynamic = true;
    o.stop_at_liftoff = false;
    o.steady_state = false;
    o.cycles = 1;
    o.settle_limit_deg = 1.0;
    lifts.assign(queries.size(), {});
    for (size_t k = 0; k < queries.size(); ++k) {
      o.grid_rad = queries[k].crank_rad;
      for (double& th : o.grid_rad) th += offsets[0];
      SimulationResult r;
      try {
        ++runs_;
        r = Simulate(scene, queries[k].speed_rpm, o);
      } catch (const std::exception& e) {
        last_refusal_ = e.what();
        return false;
      }
      if (r.grid.size() != queries[k].crank_rad.size()) {
        last_refusal_ = "the run at " + Significant(queries[k].speed_rpm, 6) + " rpm ended at " +
                        Significant(r.run_end_rad / kDeg, 6) + " deg (" + RunStatusName(r.status) +
                        ": " + r.status_reason + "), before the trace's last reading";
        return false;
      }
      lifts[k].resize(r.grid.size());
      for (size_t i = 0; i < r.grid.size(); ++i) lifts[k][i] = r.grid[i].lift_m + offsets[1];
    }
    return true;
  }

  // The residuals r_i = (y + Δs − ŷ)/σ of every used reading, traces in order.
  bool Residuals(const double* q, Eigen::VectorXd& r) {
    std::vector<std::vector<double>> lifts;
    if (!Predict(q, queries_, lifts)) return false;
    r.resize(N());
    int row = 0;
    for (size_t t = 0; t < traces_.size(); ++t) {
      for (size_t i = 0; i < used_[t].size(); ++i) {
        r[row++] = (lifts[t][i] - traces_[t].table.lift_m[used_[t][i]]) / noise_m_[t];
      }
    }
    return true;
  }

  // d(values)/dq: `f` fills a vector of the function's values. With `at_q` (the values at q),
  // forward differences (backward at an upper bound): P runs, for the search's steps; without,
  // central differences (one-sided at a bound): 2P runs, for the covariance.
  template <class F>
  bool Differentiate(const double* q, int rows, F f, Eigen::MatrixXd& J,
                     const Eigen::VectorXd* at_q = nullptr) {
    J.resize(rows, P());
    std::vector<double> x(q, q + P());
    Eigen::VectorXd plus, minus;
    for (int j = 0; j < P(); ++j) {
      const double lo = cs_[j].ToQ(cs_[j].lo_si), hi = cs_[j].ToQ(cs_[j].hi_si);
      double up = std::min(q[j] + kDiffStep, hi), down = std::max(q[j] - kDiffStep, lo);
      if (at_q) {
        if (up > q[j])
          down = q[j];
        else
          up = q[j];
      }
      x[j] = up;
      if (up == q[j] && at_q) {
        plus = *at_q;
      } else if (!f(x.data(), plus)) {
        return false;
      }
      x[j] = down;
      if (down == q[j] && at_q) {
        minus = *at_q;
      } else if (!f(x.data(), minus)) {
        return false;
      }
      x[j] = q[j];
      J.col(j) = (plus - minus) / (up - down);
    }
    return true;
  }

 private:
  // Each unknown of q set in `c`, SI; the offsets (rad, m) in `offsets`.
  void SetUnknowns(const double* q, BoundCase& c, double offsets[2]) const {
    offsets[0] = offsets[1] = 0.0;
    for (int j = 0; j < P(); ++j) Slot(cs_[j].key, c, offsets) = cs_[j].ToSi(q[j]);
  }

  BoundCase base_;
  BoundCase work_;              // base_ with the last q's unknowns: what Predict runs
  std::vector<Query> queries_;  // each trace's used angles at its speed
  std::vector<Coordinate> cs_;
  const std::vector<MeasuredTrace>& traces_;
  std::vector<std::vector<int>> used_;
  std::vector<double> noise_m_;
  double margin_rad_ = 0.0, start_rad_ = 0.0, end_rad_ = 0.0;
  int rows_ = 0;
  int runs_ = 0;
  std::string last_refusal_;
};

// The residuals and their Jacobian at the last q asked: Ceres asks every reading's block at the
// same q, and one model evaluation answers them all. The search's Jacobian by forward
// differences; `central` (the covariance's) by central ones.
class CachedResiduals {
 public:
  explicit CachedResiduals(FitModel& m, bool central = false) : model_(m), central_(central) {}
  bool At(const double* q, bool jacobian) {
    const std::vector<double> x(q, q + model_.P());
    if (x != q_) {
      q_ = x;
      have_j_ = false;
      ok_ = model_.Residuals(q, r_);
    }
    if (ok_ && jacobian && !have_j_) {
      ok_ = model_.Differentiate(
          q, model_.N(),
          [&](const double* y, Eigen::VectorXd& v) { return model_.Residuals(y, v); }, j_,
          central_ ? nullptr : &r_);
      have_j_ = ok_;
    }
    return ok_;
  }
  const Eigen::VectorXd& r() const { return r_; }
  const Eigen::MatrixXd& J() const { return j_; }

 private:
  FitModel& model_;
  bool central_;
  std::vector<double> q_;
  bool ok_ = false, have_j_ = false;
  Eigen::VectorXd r_;
  Eigen::MatrixXd j_;
};

/// One local search's end.
struct StartResult {
  std::vector<double> q;
  double cost = std::numeric_limits<double>::quiet_NaN();
  int iterations = 0;
  std::string termination;
};

/// One local search (Ceres's trust region, one residual block a reading, Huber's loss) from q0;
/// `fixed` ≥ 0 holds that unknown at its start (a profile of the cost along it).
StartResult SolveFrom(FitModel& model, std::vector<double> q0, const FitOptions& o,
                      int max_iterations, int fixed = -1);
/// ½ Σ ρ(r²) with Huber's ρ (knee k): r² inside the knee, 2k|r| − k² beyond (Ceres's HuberLoss,
/// so that the cost is the search's own).
double HuberCost(const Eigen::VectorXd& r, double k);
/// The starts: the case's values, then the best of a screen (fit_model.cc).
std::vector<std::vector<double>> Starts(FitModel& m, const FitOptions& o);

/// Huber's weight of a residual, ρ'(r²): 1 inside the knee, knee/|r| beyond (Ceres's HuberLoss,
/// the loss the search minimises).
double HuberWeight(double r, double knee);
/// s² (JᵀWJ)⁻¹ with its small eigenvalues floored; `identified` false for the unknowns of a
/// direction the traces do not pin down.
Eigen::MatrixXd Covariance(const Eigen::MatrixXd& J, const Eigen::VectorXd& w, double s2,
                           std::vector<bool>* identified);
double CorrelationOf(const Eigen::MatrixXd& cov, int a, int b);
/// The fitted values with their 95 % intervals, in the keys' units.
std::vector<FittedValue> Values(const FitModel& m, const std::vector<double>& q,
                                const Eigen::MatrixXd& cov, const std::vector<bool>& identified);
/// The intervals widened to hold every value a scan of the cost (along the axes and the
/// covariance's principal axes) finds to fit as well; returns the lowest point it found below
/// the optimum's cost, if any (the optimum is then a local one).
std::optional<std::vector<double>> ScanIntervals(FitModel& m, const std::vector<double>& q,
                                                 double cost, double s2, const Eigen::MatrixXd& cov,
                                                 const FitOptions& o,
                                                 std::vector<FittedValue>& values);
/// Each trace's residual: RMS, runs test, where it is largest.
std::vector<TraceFit> TraceFits(FitModel& m, const std::vector<MeasuredTrace>& traces,
                                const Eigen::VectorXd& r);
/// Whether the model misses something, and the residual's note.
void JudgeModel(FitResult& r);
/// For each pair the traces do not separate, the second speed that would.
void SuggestSpeeds(FitModel& m, const std::vector<double>& q, const Eigen::MatrixXd& H,
                   const std::vector<MeasuredTrace>& traces, const BoundCase& b, FitResult& r);
/// n_dyn at q and over draws of q from N(q, cov), an unknown not identified or widened by the
/// scan drawn uniformly over its interval instead.
LiftoffPrediction PredictLiftoff(const FitModel& m, const std::vector<double>& q,
                                 const Eigen::MatrixXd& cov, const std::vector<FittedValue>& values,
                                 const FitOptions& o);

}  // namespace fit_detail
}  // namespace needle
