#include "apps/study/fit_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "apps/study/fit_model.h"
#include "lib/case_error.h"

namespace needle {

using namespace fit_detail;

namespace {

// The keys `needle fit` can free, in one table: section, stem, dimension, in logs, and the
// scale of a linear one's internal coordinate (SI; 0: the case's value).
struct FitStem {
  const char* section;
  const char* stem;
  Dimension dimension;
  bool log_scale;
  const char* shown_unit;  // for FitKeyList
};
constexpr FitStem kFitStems[] = {
    {"needle", "mass", Dimension::kMass, true, "kg"},
    {"spring", "preload", Dimension::kForce, false, "N"},
    {"spring", "rate", Dimension::kStiffness, true, "N_mm"},
    {"train", "contact_stiffness", Dimension::kStiffness, true, "N_m"},
    {"train", "seat_stiffness", Dimension::kStiffness, true, "N_m"},
    {"train", "contact_damping_ratio", Dimension::kNone, false, ""},
    {"train", "seat_damping_ratio", Dimension::kNone, false, ""},
    {"train", "play", Dimension::kLength, false, "mm"},
    {"trace", "offset", Dimension::kAngle, false, "deg"},
    {"trace", "offset", Dimension::kLength, false, "mm"},
};

}  // namespace

std::string FitKeyList() {
  std::string s;
  for (const FitStem& f : kFitStems) {
    s += (s.empty() ? "" : ", ") + std::string(f.section) + "." + f.stem +
         (f.shown_unit[0] ? "_" + std::string(f.shown_unit) : "");
  }
  return s;
}

FitKey ParseFitKey(const std::string& name, const std::string& option) {
  const size_t dot = name.find('.');
  if (dot != std::string::npos) {
    const std::string section = name.substr(0, dot), key = name.substr(dot + 1);
    for (const FitStem& f : kFitStems) {
      if (section != f.section) continue;
      const std::string stem = f.stem;
      std::string unit;
      if (f.dimension == Dimension::kNone) {
        if (key != stem) continue;
      } else {
        if (key.compare(0, stem.size() + 1, stem + "_") != 0) continue;
        unit = key.substr(stem.size() + 1);
        const std::vector<std::string> units = UnitSuffixes(f.dimension);
        if (std::find(units.begin(), units.end(), unit) == units.end()) continue;
      }
      return FitKey{name, section, stem, unit, f.dimension, f.log_scale};
    }
  }
  throw CaseError(option + ": '" + name + "' is not a key needle fit can free; expected one of " +
                  FitKeyList() + " (any unit suffix of the case file's)");
}

FitBound ParseFitBound(const std::string& text, const std::string& option) {
  const size_t eq = text.find('='), colon = text.find(':', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || colon == std::string::npos) {
    throw CaseError(option + ": '" + text + "': expected KEY=LOW:HIGH (train.play_mm=0:0.5)");
  }
  FitBound b;
  b.key = ParseFitKey(text.substr(0, eq), option);
  auto number = [&](const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v)) {
      throw CaseError(option + ": '" + text + "': '" + s + "' is not a finite number");
    }
    return v;
  };
  b.low = number(text.substr(eq + 1, colon - eq - 1));
  b.high = number(text.substr(colon + 1));
  if (!(b.low < b.high)) {
    throw CaseError(option + ": '" + text + "': the low bound must be below the high one");
  }
  return b;
}

namespace {

// Throws CaseError naming the field of `o` out of its range.
void ValidateFitOptions(const FitOptions& o) {
  auto require = [](bool ok, const std::string& field, double v, const std::string& rule) {
    if (!ok)
      throw CaseError("FitOptions." + field + " = " + Significant(v, 6) + ": must be " + rule);
  };
  if (o.free.empty())
    throw CaseError("--free: name at least one key to fit; expected " + FitKeyList());
  require(o.starts >= 1 && o.starts <= 64, "starts (--starts)", o.starts, "in [1, 64]");
  require(o.huber_sigmas > 0.0 && o.huber_sigmas <= 100.0, "huber_sigmas", o.huber_sigmas,
          "in (0, 100]");
  require(o.max_iterations >= 1 && o.max_iterations <= 10000, "max_iterations", o.max_iterations,
          "in [1, 10000]");
  require(o.liftoff_draws >= 10 && o.liftoff_draws <= 10000, "liftoff_draws", o.liftoff_draws,
          "in [10, 10000]");
}

// The best of the starts: each searched for kProbeIterations, the kFinalists best on to
// convergence; each start's cost in r.start_costs. Throws CaseError when none runs.
StartResult Search(FitModel& model, const FitOptions& o, const std::string& path, FitResult& r) {
  std::vector<StartResult> probes;
  for (const std::vector<double>& q0 : Starts(model, o)) {
    probes.push_back(SolveFrom(model, q0, o, std::min(kProbeIterations, o.max_iterations)));
    r.start_costs.push_back(probes.back().cost);
  }
  std::sort(probes.begin(), probes.end(), [](const StartResult& a, const StartResult& b) {
    return std::isfinite(a.cost) && !(a.cost >= b.cost);
  });
  StartResult best;
  for (size_t k = 0; k < probes.size() && static_cast<int>(k) < kFinalists; ++k) {
    if (!std::isfinite(probes[k].cost)) break;
    StartResult s = probes[k];
    if (o.max_iterations > kProbeIterations) {
      StartResult on = SolveFrom(model, probes[k].q, o, o.max_iterations);
      if (std::isfinite(on.cost)) {
        on.iterations += probes[k].iterations;
        s = on;
      }
    }
    if (!(s.cost >= best.cost)) best = s;
  }
  if (!std::isfinite(best.cost)) {
    throw CaseError(path +
                    ": the model does not run from the case's values nor from any other "
                    "start; the last refusal: " +
                    model.last_refusal());
  }
  return best;
}

// The optimum's analysis: the Jacobian (central differences, else forward ones where a run next
// to the optimum fails), the weights and χ², the covariance and intervals, the scan, the
// correlations and unseparated pairs, each trace's residual and the model's judgement.
struct Analysis {
  Eigen::MatrixXd cov;
  std::optional<std::vector<double>> lower;  // a point the scan found below the optimum's cost
};

Analysis Analyse(FitModel& model, const StartResult& best, const std::vector<MeasuredTrace>& traces,
                 const BoundCase& b, const FitOptions& o, FitResult& r) {
  r.parameters.clear();
  r.unseparated.clear();
  r.model_misses = false;
  r.model_note.clear();
  r.residual_note.clear();
  CachedResiduals central(model, true), forward(model, false);
  CachedResiduals& at = central.At(best.q.data(), true) ? central : forward;
  if (&at == &forward && !forward.At(best.q.data(), true)) {
    throw CaseError(b.path + ": the model does not run next to the fitted values (" +
                    "a bound the model refuses?); narrow --bounds");
  }
  const Eigen::VectorXd& res = at.r();
  Eigen::VectorXd w(res.size());
  double weighted = 0.0;
  for (int i = 0; i < res.size(); ++i) {
    w[i] = HuberWeight(res[i], o.huber_sigmas);
    weighted += w[i] * res[i] * res[i];
  }
  r.chi2_reduced = weighted / (model.N() - model.P());
  std::vector<double> abs_r(res.data(), res.data() + res.size());
  for (double& a : abs_r) a = std::abs(a);
  std::nth_element(abs_r.begin(), abs_r.begin() + abs_r.size() / 2, abs_r.end());
  const double robust = 1.482602218505602 * abs_r[abs_r.size() / 2];
  r.scale2 = std::max(1.0, robust * robust);
  const double s2 = r.scale2;
  std::vector<bool> identified;
  const Eigen::MatrixXd cov = Covariance(at.J(), w, s2, &identified);
  r.parameters = Values(model, best.q, cov, identified);
  Analysis a{cov, ScanIntervals(model, best.q, best.cost, s2, cov, o, r.parameters)};
  r.correlation.assign(model.P(), std::vector<double>(model.P(), 0.0));
  for (int i = 0; i < model.P(); ++i) {
    for (int c = 0; c < model.P(); ++c) r.correlation[i][c] = CorrelationOf(cov, i, c);
    for (int c = i + 1; c < model.P(); ++c) {
      if (std::abs(r.correlation[i][c]) > kUnseparatedCorrelation) {
        r.unseparated.push_back({i, c, r.correlation[i][c], std::nullopt, 0.0});
      }
    }
  }
  if (o.suggest_speed && !r.unseparated.empty()) {
    SuggestSpeeds(model, best.q, at.J().transpose() * w.asDiagonal() * at.J(), traces, b, r);
  }
  r.traces = TraceFits(model, traces, res);
  JudgeModel(r);
  return a;
}

}  // namespace

FitResult FitCase(const BoundCase& b, const std::vector<MeasuredTrace>& traces,
                  const FitOptions& o) {
  const auto clock = std::chrono::steady_clock::now();
  ValidateFitOptions(o);
  if (traces.empty()) throw CaseError("--trace: give at least one trace");
  for (size_t i = 0; i < traces.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (traces[i].path == traces[k].path && traces[i].path.rfind("traces[", 0) != 0) {
        throw CaseError("--trace: " + traces[i].path + " is given twice; each reading counts once");
      }
    }
  }
  for (const MeasuredTrace& t : traces) CheckMeasuredTrace(t, b);
  SceneFor(b, b.lift.law);  // throws what the dynamics lacks, naming it
  FitModel model(b, Coordinates(b, o), traces);
  if (model.N() <= model.P()) {
    throw CaseError("--trace: the traces hold " + std::to_string(model.N()) +
                    " readings inside the run window, not more than the " +
                    std::to_string(model.P()) + " unknowns");
  }
  FitResult r;
  StartResult best = Search(model, o, b.path, r);
  // Where the scan finds a lower cost than the optimum's, the search goes on from there.
  Analysis a = Analyse(model, best, traces, b, o, r);
  while (a.lower && r.restarts < kScanRestarts) {
    StartResult on = SolveFrom(model, *a.lower, o, o.max_iterations);
    if (!(on.cost < best.cost)) break;
    on.iterations += best.iterations;
    best = on;
    ++r.restarts;
    a = Analyse(model, best, traces, b, o, r);
  }
  if (a.lower) {
    r.residual_note += std::string(r.residual_note.empty() ? "" : "; ") +
                       "the scan of the cost found a lower one than the fit's optimum: the "
                       "optimum is a local one; more --starts may find a lower one";
  }
  r.cost = best.cost;
  r.iterations = best.iterations;
  r.termination = best.termination;
  const Eigen::MatrixXd& cov = a.cov;
  if (b.run.cycles > 1) {
    r.notes.push_back(
        "the fit runs one revolution from rest, as a trace's window: the case's "
        "[solver] cycles = " +
        std::to_string(b.run.cycles) + (b.run.steady_state ? " and its steady state are" : " is") +
        " not used (a bench trace of a steady engine may differ)");
  }
  double offsets[2];
  r.fitted = model.CaseAt(best.q.data(), offsets);
  r.fitted.scene = BindScene(r.fitted, r.fitted.lift.law);
  if (o.predict_liftoff) r.liftoff = PredictLiftoff(model, best.q, cov, r.parameters, o);
  r.model_runs = model.runs();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
  return r;
}

std::vector<std::pair<std::string, std::pair<std::string, double>>> FittedOverrides(
    const FitResult& r) {
  std::vector<std::pair<std::string, std::pair<std::string, double>>> out;
  for (const FittedValue& v : r.parameters) {
    if (v.key.section == "trace") continue;
    const std::string key = v.key.stem + (v.key.unit.empty() ? "" : "_" + v.key.unit);
    out.push_back({v.key.section, {key, v.value}});
  }
  return out;
}

}  // namespace needle
