#include "dynamics/overspeed.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

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
  if (!std::isfinite(to_rpm)) throw std::invalid_argument("overspeed: to_rpm must be finite");
}

OverspeedRow RowFromResult(const SimulationResult& r) {
  OverspeedRow row;
  row.speed_rpm = r.speed_rpm;
  row.min_contact_force_N = r.min_contact_force_during_lift_N;
  row.jump_deg = r.jump_rad / kDeg;
  row.longest_jump_deg = r.longest_jump_rad / kDeg;
  for (const Episode& e : r.episodes) row.max_gap_mm = std::max(row.max_gap_mm, e.max_gap_m * 1e3);
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

OverspeedResult OverspeedSearch(const Scene& scene, const OverspeedOptions& o,
                                const std::function<void(int, int)>& progress) {
  o.Validate();
  OverspeedResult result;
  SimulationOptions sim = o.simulation;
  sim.force_dynamic = true;  // lift-off is a dynamic question
  sim.record_series = false;
  const int hw = static_cast<int>(std::thread::hardware_concurrency());
  // More threads than cores do not help: the runs are compute-bound.
  const int cores = std::max(1, hw);
  const int threads = o.threads > 0 ? std::min(o.threads, cores) : cores;
  result.threads = threads;
  const double step = o.step_rpm > 0.0 ? o.step_rpm : std::max(1.0, 0.025 * o.from_rpm);
  result.step_rpm = step;
  const int estimate = static_cast<int>(
      std::min<double>(o.max_speeds, std::ceil((o.to_rpm - o.from_rpm) / step) + 1 + 3 * threads));
  int done = 0;
  // Scan upward, `threads` speeds at a time, to the first lift-off.
  double lo = 0.0, hi = 0.0;
  bool found = false;
  long index = 0;
  while (!found) {
    std::vector<double> speeds;
    for (int k = 0; k < threads; ++k, ++index) {
      const double n = std::min(o.from_rpm + step * static_cast<double>(index), o.to_rpm);
      if (!speeds.empty() && n <= speeds.back()) break;
      if (index >= o.max_speeds) break;
      speeds.push_back(n);
    }
    if (speeds.empty()) break;
    const std::vector<OverspeedRow> rows = RunAll(scene, speeds, sim, threads);
    done += static_cast<int>(rows.size());
    if (progress) progress(done, std::max(done, estimate));
    for (size_t k = 0; k < rows.size(); ++k) {
      result.rows.push_back(rows[k]);
      result.scanned_to_rpm = speeds[k];
      if (rows[k].lifts_off) {
        found = true;
        hi = speeds[k];
        lo = k > 0 ? speeds[k - 1] : speeds[k] - step;
        break;
      }
      if (rows[k].status == RunStatus::kBudget) {
        result.status = "run-budget";
        break;
      }
    }
    if (found || result.status == "run-budget" || speeds.back() >= o.to_rpm) break;
    if (index >= o.max_speeds) {
      result.status = "budget";
      break;
    }
  }
  if (found && hi <= o.from_rpm) {
    result.lifts_off_at_start = true;
    result.n_dyn_rpm = o.from_rpm;
    result.bracket_low_rpm = result.bracket_high_rpm = o.from_rpm;
  } else if (found) {
    while (hi - lo > o.resolution_rpm) {
      // k-section: `threads` interior speeds at once.
      std::vector<double> speeds;
      for (int k = 1; k <= threads; ++k) speeds.push_back(lo + (hi - lo) * k / (threads + 1));
      const std::vector<OverspeedRow> more = RunAll(scene, speeds, sim, threads);
      done += static_cast<int>(more.size());
      if (progress) progress(done, std::max(done, estimate));
      double new_lo = lo, new_hi = hi;
      for (size_t k = 0; k < more.size(); ++k) {
        if (more[k].lifts_off) {
          new_hi = speeds[k];
          break;
        }
        // A run stopped on its budget shows no lift-off but proves none either: the bracket
        // keeps it on the high side, so n_dyn is never reported below an undecided speed.
        if (more[k].status == RunStatus::kBudget) {
          new_hi = speeds[k];
          break;
        }
        new_lo = speeds[k];
      }
      lo = new_lo;
      hi = new_hi;
      result.rows.insert(result.rows.end(), more.begin(), more.end());
    }
    result.n_dyn_rpm = hi;
    result.bracket_low_rpm = lo;
    result.bracket_high_rpm = hi;
  } else if (result.status == "found") {
    result.status = "none";
  }
  std::sort(result.rows.begin(), result.rows.end(),
            [](const OverspeedRow& a, const OverspeedRow& b) { return a.speed_rpm < b.speed_rpm; });
  return result;
}

}  // namespace needle
