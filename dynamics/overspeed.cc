#include "dynamics/overspeed.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include "lib/output.h"
#include "lib/threads.h"
#include "lib/units.h"

namespace needle {

void OverspeedOptions::Validate() const {
  if (!(from_rpm > 0.0))
    throw std::invalid_argument("overspeed: from_rpm must be positive, got " +
                                std::to_string(from_rpm));
  if (!(to_rpm > from_rpm)) {
    throw std::invalid_argument("overspeed: the sweep range is empty: to_rpm (" +
                                std::to_string(to_rpm) + ") must exceed from_rpm (" +
                                std::to_string(from_rpm) + ")");
  }
  if (!(resolution_rpm > 0.0))
    throw std::invalid_argument("overspeed: resolution_rpm must be positive");
  if (!(step_rpm >= 0.0) || !std::isfinite(step_rpm))
    throw std::invalid_argument("overspeed: step_rpm must be positive (or 0 for the default)");
  if (max_speeds < 1) throw std::invalid_argument("overspeed: max_speeds must be at least 1");
  if (!(max_step_fraction > 0.0 && max_step_fraction <= 1.0))
    throw std::invalid_argument("overspeed: max_step_fraction = " +
                                std::to_string(max_step_fraction) + ": must be in (0, 1]");
  if (!(floor_rpm >= 0.0 && floor_rpm < from_rpm))
    throw std::invalid_argument("overspeed: floor_rpm = " + std::to_string(floor_rpm) +
                                ": must be in [0, from_rpm) (0: from_rpm / 16)");
  if (!std::isfinite(to_rpm)) throw std::invalid_argument("overspeed: to_rpm must be finite");
  if (start_rpm && !(std::isfinite(*start_rpm) && *start_rpm > 0.0))
    throw std::invalid_argument("overspeed: start_rpm must be positive and finite");
}

std::string OverspeedOutcome(const OverspeedResult& r) {
  const auto rpm = [](double n) { return Fixed(n, 1) + " rpm"; };
  if (r.n_dyn_rpm) return rpm(*r.n_dyn_rpm);
  if (r.status == "floor")
    return "undecided: the needle lifts off at every speed tried down to " + rpm(r.floor_rpm);
  if (r.status == "budget")
    return "undecided: the scan budget ended the search at " + rpm(r.scanned_to_rpm);
  if (r.status == "run-budget")
    return "undecided: the run at " + rpm(r.scanned_to_rpm) + " stopped on its budget";
  if (r.status == "not-following")
    return "undecided: the needle does not follow its cam at " + rpm(r.scanned_to_rpm) +
           " (needle simulate --rpm " + Fixed(r.scanned_to_rpm, 1) + ")";
  return "none up to " + rpm(r.scanned_to_rpm);
}

OverspeedRow RowFromResult(const SimulationResult& r) {
  OverspeedRow row;
  row.speed_rpm = r.speed_rpm;
  row.min_contact_force_N = r.min_contact_force_during_lift_N;
  row.jump_rad = r.jump_rad;
  row.longest_jump_rad = r.longest_jump_rad;
  for (const Episode& e : r.episodes) row.max_gap_m = std::max(row.max_gap_m, e.max_gap_m);
  for (const Impact& i : r.impacts)
    row.max_impact_speed_m_s = std::max(row.max_impact_speed_m_s, i.speed_m_s);
  row.lifts_off = r.longest_jump_rad >= kMinJump_rad;
  row.status = r.status;
  row.status_reason = r.status_reason;
  return row;
}

namespace {

// Runs the speeds on up to `threads` threads; rethrows the first failure.
std::vector<OverspeedRow> RunAll(const Scene& scene, const std::vector<double>& speeds,
                                 const SimulationOptions& sim, int threads) {
  std::vector<OverspeedRow> rows(speeds.size());
  std::vector<std::exception_ptr> errors(speeds.size());
  // A shared queue, fastest speeds first: runs with lift-off and bouncing cost several times
  // more than runs in contact, so the longest jobs start first (LPT) and no core idles at the end.
  std::vector<size_t> order(speeds.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return speeds[a] > speeds[b]; });
  std::atomic<size_t> next{0};
  auto work = [&]() {
    for (size_t k = next++; k < order.size(); k = next++) {
      const size_t i = order[k];
      try {
        rows[i] = RowFromResult(Simulate(scene, speeds[i], sim));
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < threads && k < static_cast<int>(speeds.size()); ++k) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the ones running share the queue
    }
  }
  work();

  for (auto& t : pool) t.join();
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  return rows;
}

}  // namespace

namespace {

// Below this margin f = F_min/P₀ the scan's steps shrink in proportion (OverspeedSearch).
constexpr double kFullStepMargin = 0.5;
// The first step down from a start_rpm that lifts off, as a fraction of it (then doubling).
constexpr double kStartStepFraction = 0.05;

// The runs of one search: each speed run once, on demand; with several threads, Ahead() runs
// speeds the search may ask next alongside. Only the speeds asked for become rows, so the
// result does not depend on the thread count.
class Runs {
 public:
  Runs(const Scene& scene, const SimulationOptions& sim, int threads,
       const std::function<void(int, int)>& progress)
      : scene_(scene), sim_(sim), threads_(threads), progress_(progress) {}

  // The row at speed n, run now unless run ahead; `ahead`: speeds to run alongside it.
  const OverspeedRow& At(double n, const std::vector<double>& ahead = {}) {
    auto it = done_.find(n);
    if (it == done_.end()) {
      std::vector<double> batch{n};
      for (double a : ahead) {
        if (static_cast<int>(batch.size()) >= threads_) break;
        if (done_.count(a) == 0 && a != n) batch.push_back(a);
      }
      const std::vector<OverspeedRow> rows = RunAll(scene_, batch, sim_, threads_);
      for (size_t k = 0; k < batch.size(); ++k) done_[batch[k]] = rows[k];
      it = done_.find(n);
    }
    if (asked_.insert(n).second && progress_) progress_(static_cast<int>(asked_.size()), estimate_);
    return it->second;
  }
  void set_estimate(int total) { estimate_ = std::max(total, static_cast<int>(asked_.size())); }
  std::vector<OverspeedRow> AskedRows() const {
    std::vector<OverspeedRow> rows;
    for (double n : asked_) rows.push_back(done_.at(n));
    return rows;  // sorted: asked_ is
  }

 private:
  const Scene& scene_;
  const SimulationOptions& sim_;
  int threads_;
  const std::function<void(int, int)>& progress_;
  std::map<double, OverspeedRow> done_;
  std::set<double> asked_;
  int estimate_ = 0;
};

// The bisection's next speeds in the order it may ask for them, after the midpoint of
// [lo, hi]: the midpoints of its halves, then of their halves (breadth first), each computed as
// the bisection will.
std::vector<double> BisectionAhead(double lo, double hi, int count) {
  std::vector<std::pair<double, double>> queue{{lo, hi}};
  std::vector<double> out;
  for (size_t i = 0; i < queue.size() && static_cast<int>(out.size()) < count; ++i) {
    const auto [a, b] = queue[i];
    const double mid = a + 0.5 * (b - a);
    if (i > 0) out.push_back(mid);
    queue.push_back({a, mid});
    queue.push_back({mid, b});
  }
  return out;
}

// The step from speed n where the force gives no guidance (f ≤ 0), after `last` (n, f): Δn; but
// where the force has just reached zero the lift-off is near, and the step is no larger than the
// one that came here; while it stays at zero (contact lost, its jumps still shorter than
// kMinJump_rad), each step at most doubles the last.
double UnguidedStep(double step, double res, double n,
                    const std::optional<std::pair<double, double>>& last) {
  if (!last) return step;
  return std::min(step, std::max(res, (last->second > 0.0 ? 1.0 : 2.0) * (n - last->first)));
}

// The search's state between its phases (OverspeedSearch): the start (down from a guess, or
// halving below a start that lifts off), the scan up led by the contact margin, and the
// bisection of the first lift-off's bracket.
class Scan {
 public:
  Scan(const Scene& scene, const OverspeedOptions& o, const std::function<void(int, int)>& progress)
      : o_(o),
        sim_(SearchRuns(o)),
        threads_(ThreadsToUse(o.threads)),
        step_(o.step_rpm > 0.0 ? o.step_rpm : std::max(1.0, 0.025 * o.from_rpm)),
        floor_(o.floor_rpm > 0.0 ? o.floor_rpm : o.from_rpm / 16.0),
        res_(o.resolution_rpm),
        preload_(scene.train.preload_N > 0.0 ? scene.train.preload_N : 1.0),
        runs_(scene, sim_, threads_, progress) {
    result_.threads = threads_;
    result_.step_rpm = step_;
    result_.floor_rpm = floor_;
    runs_.set_estimate(static_cast<int>(std::ceil(std::log(o.to_rpm / o.from_rpm) /
                                                  std::log1p(o.max_step_fraction))) +
                       10);
  }

  Scan(const Scan&) = delete;  // runs_ holds a reference to sim_
  Scan& operator=(const Scan&) = delete;

  OverspeedResult Run() {
    if (!Start()) {
      ScanUp();
      if (found_) {
        Bisect();
      } else if (result_.status == "found") {
        result_.status = "none";
      }
    }
    result_.rows = runs_.AskedRows();
    return std::move(result_);
  }

 private:
  // The runs of the search: dynamic, no series, stopped at the first lift-off.
  static SimulationOptions SearchRuns(const OverspeedOptions& o) {
    SimulationOptions sim = o.simulation;
    sim.force_dynamic = true;  // lift-off is a dynamic question
    sim.record_series = false;
    sim.stop_at_liftoff = true;  // … and the only one asked
    return sim;
  }

  // Whether the run at n ends the search: a broken scene (no speed of it can be judged), or a
  // run stopped on its budget without a lift-off. Sets the status and the speed reached.
  bool BudgetStop(const OverspeedRow& row, double n) {
    result_.scanned_to_rpm = n;
    if (row.status == RunStatus::kNotFollowing) {
      result_.status = "not-following";
      return true;
    }
    if (row.lifts_off || row.status != RunStatus::kBudget) return false;
    result_.status = "run-budget";
    return true;
  }

  // Runs n (one more speed scanned) into row_; BudgetStop's answer.
  bool Ask(double n) {
    ++scanned_;
    row_ = &runs_.At(n);
    return BudgetStop(*row_, n);
  }

  // The start of the upward scan: start_rpm or below it, from_rpm, or below that where the
  // needle lifts off there. True when the search ends here.
  bool Start() {
    const bool guessed = o_.start_rpm && *o_.start_rpm > o_.from_rpm && *o_.start_rpm < o_.to_rpm;
    const bool hinted = guessed && !o_.start_after_rpm;  // start at the guess
    jump_ = guessed && o_.start_after_rpm.has_value();   // jump to it past start_after_rpm
    n_ = hinted ? *o_.start_rpm : o_.from_rpm;
    top_ = o_.to_rpm;  // the scan ends here (a lift-off known there, or the range's end)
    if (Ask(n_)) return true;
    for (double down = std::max(step_, kStartStepFraction * n_);
         hinted && row_->lifts_off && n_ > o_.from_rpm && scanned_ < o_.max_speeds; down *= 2.0) {
      top_ = n_;
      n_ = std::max(n_ - down, o_.from_rpm);
      if (Ask(n_)) return true;
    }
    if (row_->lifts_off && n_ > o_.from_rpm) {  // the scan budget ended the way down
      result_.status = "budget";
      result_.scanned_to_rpm = n_;
      return true;
    }
    if (!row_->lifts_off) return false;
    result_.lifts_off_at_start = true;
    while (row_->lifts_off) {
      if (n_ <= floor_) {
        result_.status = "floor";
        return true;
      }
      top_ = n_;
      n_ = std::max(0.5 * n_, floor_);
      if (Ask(n_)) return true;
    }
    return false;
  }

  // The scan's step from n_, where the contact margin is f.
  double ScanStep(double f) const {
    double d = UnguidedStep(step_, res_, n_, last_);
    if (!(f > 0.0)) return d;
    const double d_max = std::max(step_, o_.max_step_fraction * n_);
    if (last_ && last_->second > f) {
      // Falling: toward the zero of the secant through the last two (n², f), and just past.
      const double n2 = n_ * n_ + f * (n_ * n_ - last_->first * last_->first) / (last_->second - f);
      d = std::min(d_max, std::sqrt(n2) - n_ + res_);
    } else {
      d = d_max * std::min(1.0, f / kFullStepMargin);
      // Rising: out of a dip, perhaps into the next; no further than f would fall at the
      // rate it rose.
      if (last_ && last_->second < f)
        d = std::min(d, 0.5 * f * (n_ - last_->first) / (f - last_->second));
    }
    return std::max(d, res_);
  }

  // Upward, led by the margin, to the first lift-off (found_, its bracket [lo_, hi_]).
  void ScanUp() {
    while (true) {
      const double f = row_->min_contact_force_N / preload_;
      const double d = ScanStep(f);
      if (n_ >= top_) break;
      const auto before = last_;
      last_ = std::make_pair(n_, f);
      const double next = std::min(n_ + d, top_);
      if (scanned_ >= o_.max_speeds) {
        result_.status = "budget";
        break;
      }
      if (Ask(next)) break;
      if (row_->lifts_off) {
        found_ = true;
        last_ = before;  // the speed before lo
        lo_ = n_;
        lo_margin_ = f;
        hi_ = next;
        break;
      }
      // The margin went from positive to zero across the step without a lift-off at its end:
      // the contact was first lost inside it, where a lift-off window may lie that closes
      // again before `next` (a surge resonance).
      if (f > 0.0 && !(row_->min_contact_force_N > 0.0)) {
        BisectToLoss(n_, next);
        if (found_ || result_.status != "found") break;
        row_ = &runs_.At(next);
      }
      if (jump_ && next >= *o_.start_after_rpm && *o_.start_rpm > next && *o_.start_rpm < top_) {
        jump_ = false;
        const std::optional<double> known = JumpToGuess(next);
        if (!known) break;
        last_.reset();
        n_ = *known;
        row_ = &runs_.At(*known);
        continue;
      }
      n_ = next;
    }
  }

  // Bisects [a, b] on the margin's sign to where it reaches zero and asks there.
  void BisectToLoss(double a, double b) {
    while (b - a > res_ && !found_) {
      const double m = 0.5 * (a + b);
      ++scanned_;
      const OverspeedRow& probe = runs_.At(m);
      if (BudgetStop(probe, m)) break;
      if (probe.lifts_off) {
        found_ = true;
        last_.reset();
        lo_ = a;
        lo_margin_ = 0.0;
        hi_ = m;
      } else if (probe.min_contact_force_N > 0.0) {
        a = m;
      } else {
        b = m;
      }
    }
  }

  // Past start_after_rpm without a lift-off (every speed below it run as without a guess): on
  // to the guess, down from it while the needle lifts off there (not below `next`). The highest
  // speed known not to lift off, from which the scan goes on up; nullopt when the search ends.
  std::optional<double> JumpToGuess(double next) {
    double known = next, m = *o_.start_rpm;
    for (double down = std::max(step_, kStartStepFraction * m);; down *= 2.0) {
      if (scanned_ >= o_.max_speeds) {
        result_.status = "budget";
        return std::nullopt;
      }
      ++scanned_;
      const OverspeedRow& probe = runs_.At(m);
      if (BudgetStop(probe, m)) return std::nullopt;
      if (!probe.lifts_off) return m;
      top_ = m;
      m = std::max(m - down, known);
      if (m == known) return known;  // scan up from `next` to the lift-off at `top`
    }
  }

  // Bisection, guided: where the margin fell to a positive value at lo, the first probe is just
  // past the zero of the secant through lo and the speed before it (as in the scan); a guided
  // probe that did not halve the bracket hands over to plain halving.
  void Bisect() {
    runs_.set_estimate(scanned_ + static_cast<int>(std::ceil(std::log2((hi_ - lo_) / res_))));
    bool guide = true;
    while (hi_ - lo_ > res_) {
      const double width = hi_ - lo_;
      double probe = lo_ + 0.5 * width;
      std::vector<double> ahead = BisectionAhead(lo_, hi_, threads_ - 1);
      bool guided = false;
      if (guide && last_ && last_->first < lo_ && last_->second > lo_margin_ && lo_margin_ > 0.0) {
        const double n2 = lo_ * lo_ + lo_margin_ * (lo_ * lo_ - last_->first * last_->first) /
                                          (last_->second - lo_margin_);
        const double g = std::sqrt(n2) + 0.25 * res_;
        if (g > lo_ + 0.1 * res_ && g < hi_ - 0.1 * res_) {
          probe = g;
          guided = true;
          ahead.clear();
        }
      }
      const OverspeedRow& m = runs_.At(probe, ahead);
      // A run stopped on its budget shows no lift-off but proves none either: the bracket
      // keeps it on the high side, so n_dyn is never reported below an undecided speed.
      if (m.lifts_off || m.status == RunStatus::kBudget || m.status == RunStatus::kNotFollowing) {
        hi_ = probe;
      } else {
        last_ = std::make_pair(lo_, lo_margin_);
        lo_ = probe;
        lo_margin_ = m.min_contact_force_N / preload_;
      }
      if (guided) guide = hi_ - lo_ <= 0.5 * width;
    }
    result_.n_dyn_rpm = hi_;
    result_.bracket_low_rpm = lo_;
    result_.bracket_high_rpm = hi_;
  }

  const OverspeedOptions& o_;
  const SimulationOptions sim_;  // before runs_, which holds it
  const int threads_;
  const double step_, floor_, res_, preload_;
  Runs runs_;
  OverspeedResult result_;
  int scanned_ = 0;
  const OverspeedRow* row_ = nullptr;  // the last speed asked by the scan
  double n_ = 0.0, top_ = 0.0;         // the scan's speed and its end
  double lo_ = 0.0, hi_ = 0.0, lo_margin_ = 0.0;
  bool found_ = false, jump_ = false;
  std::optional<std::pair<double, double>> last_;  // (n, f) of the speed before
};

}  // namespace

OverspeedResult OverspeedSearch(const Scene& scene, const OverspeedOptions& o,
                                const std::function<void(int, int)>& progress) {
  o.Validate();
  return Scan(scene, o, progress).Run();
}

std::vector<Field> OverspeedFields(const OverspeedResult& r) {
  using namespace display;
  return {
      {"n_dyn", kRpm, r.n_dyn_rpm, 1, "liftoff_rpm_dynamic"},
      ListField("bracket", kRpm, {r.bracket_low_rpm, r.bracket_high_rpm}),
      FlagField("lifts_off_at_start", r.lifts_off_at_start),
      {"floor", kRpm, r.floor_rpm, 1},
      CountField("threads", r.threads),
      {"step", kRpm, r.step_rpm, 2},
      TextField("status", r.status),
      {"scanned_to", kRpm, r.scanned_to_rpm, 1},
  };
}

std::vector<Field> OverspeedRowFields(const OverspeedRow& row) {
  using namespace display;
  return {
      {"speed", kRpm, row.speed_rpm, 2},
      {"min_contact_force", kN, row.min_contact_force_N, 1},
      {"jump", kDegree, row.jump_rad, 3},
      {"max_gap", kMm, row.max_gap_m, 4},
      {"max_impact_speed", kMPerS, row.max_impact_speed_m_s, 4},
      FlagField("lifts_off", row.lifts_off),
      TextField("status", RunStatusName(row.status)),
      TextField("status_reason", row.status_reason),
  };
}

const std::vector<Column>& OverspeedColumns() {
  using namespace display;
  static const std::vector<Column> columns = {
      {"speed", kRpm},  {"min_contact_force", kN},    {"jump", kDegree},
      {"max_gap", kMm}, {"max_impact_speed", kMPerS}, {"lifts_off", kNone}};
  return columns;
}

std::vector<double> OverspeedRowSi(const OverspeedRow& row) {
  return {row.speed_rpm, row.min_contact_force_N,  row.jump_rad,
          row.max_gap_m, row.max_impact_speed_m_s, row.lifts_off ? 1.0 : 0.0};
}

}  // namespace needle
