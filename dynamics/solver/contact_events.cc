#include "dynamics/solver/contact_events.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/rigid_train.h"

namespace needle {
namespace {

// An extreme located inside a step is recorded after the step's samples: the series in time,
// as std::stable_sort leaves it. Each point out of place is moved back past the few later
// samples of its step (an insertion sort: O(n) for such a series, where a merge sort of a
// run's 10⁴-10⁵ points was some 5 % of a check), the merge sort kept for a series further out
// of order.
void SortSeries(std::vector<SeriesPoint>& series) {
  const auto earlier = [](const SeriesPoint& a, const SeriesPoint& b) {
    return a.time_s < b.time_s;
  };
  size_t moved = 0;
  for (auto it = std::is_sorted_until(series.begin(), series.end(), earlier); it != series.end();
       ++it) {
    if (!earlier(*it, *(it - 1))) continue;
    auto place = it - 1;  // back past the later points only: after its equals
    while (place != series.begin() && earlier(*it, *(place - 1))) --place;
    moved += static_cast<size_t>(it - place);
    if (moved > series.size()) {
      std::stable_sort(series.begin(), series.end(), earlier);
      return;
    }
    std::rotate(place, it, it + 1);
  }
}

// The same point twice (a crossing or an extreme sampled where a step ends, the run's last
// point): one row of the series.
bool SamePoint(const SeriesPoint& a, const SeriesPoint& b) {
  return a.time_s == b.time_s && a.crank_rad == b.crank_rad && a.lift_m == b.lift_m &&
         a.velocity_m_s == b.velocity_m_s && a.cam_m == b.cam_m &&
         a.contact_force_N == b.contact_force_N && a.seat_force_N == b.seat_force_N;
}

// Drops each point that repeats the one before it.
void DropRepeats(std::vector<SeriesPoint>& series) {
  series.erase(std::unique(series.begin(), series.end(), SamePoint), series.end());
}

// Angles equal to a break up to the roundoff of θ = θ_a + ω t.
double AngleTolerance(double crank_rad) { return 1e-12 * std::max(1.0, std::abs(crank_rad)); }

}  // namespace

EventValues Events(const NeedleTrain& train, const Phase& phase, const TrainState& x, double t) {
  return Events(train, phase, x, train.Evaluate(x, t, phase));
}

EventValues Events(const NeedleTrain& train, const Phase& phase, const TrainState& x,
                   const Contacts& c) {
  ContactWitnesses cam = train.cam_law().Witnesses(c.g_c, c.g_c_rate);
  ContactWitnesses seat = train.seat_law().Witnesses(c.g_s, c.g_s_rate);
  // A rigid contact: its gap counts past the touch tolerance, and is pinned while it sticks
  // (the needle is on the surface; integration drift must not read as an impact); its branch is
  // the constraint force λ.
  const auto rigid = [&](ContactWitnesses& w, bool stuck, double g, double lambda) {
    w = {stuck ? 1.0 : g - train.GapTolerance(), lambda};
  };
  if (train.cam_law().Constraint()) rigid(cam, phase.mode.cam, c.g_c, c.f_c_raw);
  if (train.seat_law().Constraint()) rigid(seat, phase.mode.seat, c.g_s, c.f_s_raw);
  // 5 and 6 only observe a lifted needle: at rest their arguments are zero up to roundoff
  // and would flip sign at every step.
  const bool lifted = x[0] > kSeparationLift_m;
  EventValues v = {cam[0],
                   cam[1],
                   seat[0],
                   seat[1],
                   x[0] - kSeparationLift_m,
                   (phase.mode.cam || !lifted) ? 1.0 : c.g_c_rate,
                   lifted ? x[1] : 1.0};
  for (int j = 1; j <= train.ClashSegments(); ++j) {
    const std::array<double, 2> g = train.SegmentPenetration(x, c, j);
    const ContactWitnesses w = train.clash_law().Witnesses(g[0], g[1]);
    v.push_back(w[0]);
    v.push_back(w[1]);
  }
  return v;
}

std::optional<LinearForm> WitnessForm(const NeedleTrain& train, const Phase& phase, int index,
                                      bool lifted) {
  const std::optional<LinearWitnesses> cam = train.cam_law().Linear();
  const std::optional<LinearWitnesses> seat = train.seat_law().Linear();
  if (!cam || !seat) return std::nullopt;
  // w = a g + b ġ with g_c = u − y, ġ_c = u̇ − ẏ (the cam) and g_s = −y, ġ_s = −ẏ (the seat).
  const auto on_cam = [](double a, double b) { return LinearForm{-a, -b, a, b, 0.0}; };
  const auto on_seat = [](double a, double b) { return LinearForm{-a, -b, 0.0, 0.0, 0.0}; };
  const LinearForm one{0.0, 0.0, 0.0, 0.0, 1.0};
  switch (index) {
    case kCamGap:
      return on_cam(cam->gap_g, cam->gap_rate);
    case kCamBranch:
      return on_cam(cam->branch_g, cam->branch_rate);
    case kSeatGap:
      return on_seat(seat->gap_g, seat->gap_rate);
    case kSeatBranch:
      return on_seat(seat->branch_g, seat->branch_rate);
    case 4:
      return LinearForm{1.0, 0.0, 0.0, 0.0, -kSeparationLift_m};
    case 5:
      return (phase.mode.cam || !lifted) ? one : LinearForm{0.0, -1.0, 0.0, 1.0, 0.0};
    case 6:
      return lifted ? LinearForm{0.0, 1.0, 0.0, 0.0, 0.0} : one;
  }
  return std::nullopt;
}

ContactMode ModeFromSigns(const NeedleTrain& train, const EventSigns& s) {
  ContactMode mode{train.cam_law().Pushes(s[kCamGap], s[kCamBranch]),
                   train.seat_law().Pushes(s[kSeatGap], s[kSeatBranch])};
  for (int j = 1; j <= train.ClashSegments(); ++j) {
    const int i = kEventCount + 2 * (j - 1);
    if (train.clash_law().Pushes(s[i], s[i + 1])) mode.SetSolid(j);
  }
  return mode;
}

Recorder::Recorder(const NeedleTrain& train, bool record_series,
                   std::function<void(const SeriesPoint&)> sink)
    : train_(train),
      record_series_(record_series),
      sink_(record_series ? std::move(sink) : nullptr) {
  // A table that ends while still rising (or falling faster than the ramp after it): the cam
  // input's slope drops at θ_N, a deceleration concentrated at one angle (u'' has a negative
  // Dirac there). A separation there is lift-off (docs/model.md §6, docs/model.md).
  // A drop below 1e-3 of the mean slope of the lift is roundoff of a closed end.
  const CamInput& cam = train.cam();
  const LiftLaw& law = cam.law();
  const double end = law.end_rad();
  const double mean_slope = cam.top().value / (end - law.start_rad());
  end_slope_drop_ = cam.Slope(end) < law.Derivative(end, 1) - 1e-3 * mean_slope;
}

bool Recorder::AtRest(double t, const TrainState& x, const Phase& phase) const {
  if (separated_) return false;
  // The needle's speed first: a run's end is sought at 65 samples of each step past the window
  // (EventDriver::FirstRest), where the needle mostly still moves; the contacts and the spring
  // force (a chain's coils) only where it may be at rest.
  if (!(std::abs(x[1]) <= kRestSpeed_m_s)) return false;
  const Contacts c = train_.Evaluate(x, t, phase);
  if (c.u_slope != 0.0) return false;  // the cam input still moves
  const double fc = train_.AppliedCamForce(c, phase), fs = train_.AppliedSeatForce(c, phase);
  if (!(fc > 0.0 || fs > 0.0)) return false;  // in flight
  const double net = train_.NetForce(c, phase);
  // The needle's own rest: the coils of a spring without damping may ring on (they carry
  // their state into the next revolution).
  return std::abs(net) <= RestForceTolerance();
}

double Recorder::RestForceTolerance() const {
  const TrainParameters& p = train_.parameters();
  const double scale = std::max(p.preload_N + std::abs(p.gas_force_N), p.mass_kg * 1.0 /* m/s² */);
  return kRestForceFraction * scale;
}

bool Recorder::MayChange(const StretchRanges& r, bool lift_covered, bool reported) const {
  if (record_series_ || separated_) return true;
  const bool all = !(reported && liftoff_only_);
  // The lift's extremes; the spring force P₀ + k y and (one mass) the segment compression y
  // grow with the lift, so they follow the largest lift.
  // A chain's segment compression and spring force do not follow the lift: by their bounds.
  if (train_.Coils() > 0 &&
      (!(r.compression_hi <= max_segment_compression_m_) || !(r.spring_hi <= max_spring_)))
    return true;
  if (seated_ && r.y_hi > std::max(secondary_lift_, kSeparationLift_m)) return true;
  if (!lift_covered && (r.y_hi > max_lift_ || (all && r.y_lo < min_lift_))) return true;
  if (lift_covered && !(train_.parameters().rate_N_m >= 0.0)) return true;
  if (all && (r.fc_hi > max_fc_ || r.fs_hi > max_fs_)) return true;
  // The least contact force over the lift, and its share of the holding load.
  if (r.u_hi > kSeparationLift_m && r.y_hi > kSeparationLift_m) {
    if (!lifted_) return true;
    const double f_lo = std::max(0.0, r.fc_lo);
    if (!seated_ && f_lo < min_fc_lift_) return true;
    const double hold_lo = std::min(HoldingLoadN(r.y_lo), HoldingLoadN(r.y_hi));
    const double hold_hi = std::max(HoldingLoadN(r.y_lo), HoldingLoadN(r.y_hi));
    const double ratio_lo = hold_lo > 0.0 ? f_lo / hold_hi : 0.0;
    if (all && !seated_ && ratio_lo < min_ratio_) return true;
  }
  return false;
}

double Recorder::HoldingLoadN(double y) const {
  const TrainParameters& p = train_.parameters();
  return RigidTrain{p.mass_kg, p.preload_N, p.rate_N_m, p.gas_force_N}.SpringForceN(y);
}

double Recorder::HoldShare(double fc, double y) const {
  const double hold = HoldingLoadN(y);
  return hold > 0.0 ? std::max(0.0, fc) / hold : 0.0;
}

double Recorder::ForceShare(double fc, double u, double y) const {
  if (seated_ || !(u > kSeparationLift_m && y > kSeparationLift_m)) return INFINITY;
  return HoldShare(fc, y);
}

bool Recorder::SampleMayChange(double y, std::optional<double> covering, double u_hi, double fc_lo,
                               double fc_hi, double fs, const StretchRanges& stretch) const {
  // The sample as a stretch of one point; the covering sample stands for its lift where the lift
  // passes a record the same way (and the spring force and segment compression, which follow
  // the lift, with it: MayChange refuses the cover where k < 0).
  const bool all = !liftoff_only_;  // else what a lift-off run reports
  const bool beyond = y > max_lift_ || (all && y < min_lift_);
  const bool covered = beyond && covering && !(y > max_lift_ && !(y < *covering)) &&
                       !(all && y < min_lift_ && !(y > *covering));
  return MayChange({y, y, u_hi, fc_lo, fc_hi, fs, stretch.compression_hi, stretch.spring_hi},
                   covered, true);
}

bool Recorder::InLift(double crank_rad) const {
  // θ_0 and θ_N are breaks the integrators step to exactly; θ = θ_a + ω t is that angle up to
  // roundoff.
  const LiftLaw& law = train_.cam().law();
  return crank_rad >= law.start_rad() - AngleTolerance(law.start_rad()) &&
         crank_rad <= law.end_rad() + AngleTolerance(law.end_rad());
}

bool Recorder::OnCamWindow(const Contacts& c, const TrainState& x) {
  return c.u > kSeparationLift_m && x[0] > kSeparationLift_m;
}

bool Recorder::Decelerating(double crank_rad) const {
  const LiftLaw& law = train_.cam().law();
  const double end = law.end_rad();
  if (std::abs(crank_rad - end) <= AngleTolerance(end)) return end_slope_drop_;
  return InLift(crank_rad) && law.Derivative(crank_rad, 2) < 0.0;
}

void Recorder::Update(double t, const TrainState& x, const Phase& phase) {
  Update(t, x, phase, train_.Evaluate(x, t, phase));
}

void Recorder::Sample(double t, const TrainState& x, const Phase& phase, const Contacts& c) {
  Update(t, x, phase, c);
}

void Recorder::Update(double t, const TrainState& x, const Phase& phase, const Contacts& c) {
  const double fc = train_.AppliedCamForce(c, phase), fs = train_.AppliedSeatForce(c, phase);

  const double th = c.crank_rad;
  const bool in_table = InLift(th);
  if (x[0] > max_lift_) {
    max_lift_ = x[0];
    max_lift_rad_ = th;
  }
  max_fc_ = std::max(max_fc_, fc);
  max_fs_ = std::max(max_fs_, fs);
  max_segment_compression_m_ =
      std::max(max_segment_compression_m_, train_.LargestSegmentCompression(x));
  min_lift_ = std::min(min_lift_, x[0]);
  max_spring_ = std::max(max_spring_, c.spring_N);
  if (seated_ && x[0] > kSeparationLift_m && x[0] > secondary_lift_) {
    secondary_lift_ = x[0];
    secondary_lift_rad_ = th;
  }
  // At a break the raw branch may be negative for an instant before its sign flips: a contact
  // never pulls.
  // The window's edge, where the lift crosses 1 µm (a located event) while the cam lifts the
  // needle (before it first seats), belongs to it: the least force may lie there, between the
  // samples inside. (After the seating a rebound's crossings are the secondary opening's.)
  if (OnCamWindow(c, x) || (at_lift_edge_ && !seated_ && c.u > kSeparationLift_m)) {
    lifted_ = true;
    const double f = std::max(0.0, fc);
    if (!seated_) min_fc_lift_ = std::min(min_fc_lift_, f);
    const double ratio = HoldShare(fc, x[0]);
    if (!seated_ && ratio < min_ratio_) {
      min_ratio_ = ratio;
      min_ratio_rad_ = th;
      min_ratio_force_ = f;
    }
  }
  // Separation episode: inside [θ0, θN], the cam not pushing and y > 1 µm.
  // An episode begins inside [θ0, θN]; one still open at θN goes on until the needle is back
  // on the cam or on its seat (docs/model.md §6).
  const bool separated = (in_table || separated_) && !(fc > 0.0) && x[0] > kSeparationLift_m;
  if (t < last_t_) {
    // A point located inside a step that was already sampled past it (an extreme, an event):
    // it counts for the extremes and the open episode's largest gap, never for the episodes'
    // order, so an episode cannot end before it began.
    if (separated && separated_ && th >= episodes_.back().start_rad) {
      episodes_.back().max_gap_m = std::max(episodes_.back().max_gap_m, x[0] - c.u);
    }
    if (record_series_) Keep({th, t, x[0], x[1], c.u, fc, fs});
    return;
  }
  last_t_ = t;

  if (separated && !separated_) {
    Episode e;
    e.start_rad = th;
    // docs/model.md §6 (rev. 4): a separation that begins after the needle first seats past
    // the cam's top is a rebound off the seat (a secondary opening), not a cam losing the needle.
    e.kind = seated_ ? "rebound" : Decelerating(th) ? "jump" : "bounce";
    e.max_gap_m = x[0] - c.u;
    episodes_.push_back(e);
  } else if (!separated && separated_) {
    // The end point counts for the largest gap: a needle landing on its seat while the cam
    // still falls away below stands farthest off it there.
    episodes_.back().end_rad = th;
    episodes_.back().max_gap_m = std::max(episodes_.back().max_gap_m, x[0] - c.u);
  }
  if (separated) {
    Episode& e = episodes_.back();
    e.max_gap_m = std::max(e.max_gap_m, x[0] - c.u);
    // docs/model.md §6: a jump is any separation that reaches the deceleration zone, wherever it
    // began — a rebound in the acceleration zone that carries on over the crest is lift-off.
    if (e.kind != "rebound" && Decelerating(th)) e.kind = "jump";
  }
  separated_ = separated;
  if (record_series_) Keep({th, t, x[0], x[1], c.u, fc, fs});
}

void Recorder::Start(double t, const TrainState& x, const Phase& phase) {
  cam_touched_ = train_.Evaluate(x, t, phase).g_c > 0.0;
  Update(t, x, phase);
}

void Recorder::GridSample(double t, const TrainState& x, const Phase& phase) {
  const Contacts c = train_.Evaluate(x, t, phase);
  grid_.push_back({t, x[0], train_.AppliedCamForce(c, phase)});
}

void Recorder::Sample(double t, const TrainState& x, const Phase& phase) { Update(t, x, phase); }

void Recorder::Crossing(int index, int direction, double t, const TrainState& x, const Phase& phase,
                        bool sample) {
  const Contacts c = train_.Evaluate(x, t, phase);
  if (index == kCamGap && direction > 0) {  // cam onset
    impacts_.push_back(
        {cam_touched_ ? "recontact" : "lash", c.crank_rad, std::max(0.0, c.g_c_rate)});
    cam_touched_ = true;
    if (separated_) episodes_.back().impact = static_cast<int>(impacts_.size()) - 1;
  } else if (index == kSeatGap && direction > 0) {  // seat onset
    impacts_.push_back(
        {seat_landed_ ? "seat-bounce" : "seat", c.crank_rad, std::max(0.0, c.g_s_rate)});
    seat_landed_ = true;
    // Seated: the first landing past the cam's top once lifted (a bounce on the seat while the
    // cam opens is an episode of the lift, not its end).
    seated_ = seated_ || (lifted_ && c.crank_rad > train_.cam().top().crank_rad);
  } else if (index == kLiftGate && seated_) {  // a secondary opening begins or ends
    if (direction > 0 && !reopened_) reopen_rad_ = c.crank_rad;
    if (direction < 0 && reopened_) secondary_open_rad_ += c.crank_rad - reopen_rad_;
    reopened_ = direction > 0;
  } else if (index >= kEventCount && (index - kEventCount) % 2 == 0 && direction > 0) {
    ++coil_clashes_;  // a segment's coils meet
  }
  if (!sample) return;
  at_lift_edge_ = index == kLiftGate;
  Update(t, x, phase);
  at_lift_edge_ = false;
}

void Recorder::ImpactLoss(double energy_J) {
  if (!impacts_.empty()) impacts_.back().energy_lost_J = energy_J;
}

void Recorder::Accumulation(bool cam, double t, const TrainState& x, const Phase& phase,
                            double speed_m_s, double energy_J) {
  impacts_.push_back(
      {cam ? "cam-sticking" : "seat-sticking", train_.Angle(t), speed_m_s, energy_J});
  if (separated_ && cam) episodes_.back().impact = static_cast<int>(impacts_.size()) - 1;
  Update(t, x, phase);
}

void Recorder::Keep(const SeriesPoint& p) {
  if (sink_ && p.time_s < committed_t_) {
    throw std::logic_error("Recorder: a series point at t = " + std::to_string(p.time_s) +
                           " s after the series was committed up to " +
                           std::to_string(committed_t_) + " s");
  }
  series_.push_back(p);
}

void Recorder::Send(size_t n) {
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < n; ++i) {
    if (sent_any_ && SamePoint(series_[i], last_sent_)) continue;
    sink_(series_[i]);
    last_sent_ = series_[i];
    sent_any_ = true;
  }
  series_.erase(series_.begin(), series_.begin() + static_cast<std::ptrdiff_t>(n));
  sink_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Recorder::Commit(double t) {
  if (!sink_ || !(t > committed_t_)) return;
  committed_t_ = t;
  SortSeries(series_);
  size_t n = 0;
  while (n < series_.size() && series_[n].time_s < t) ++n;
  if (n > 0) Send(n);
}

void Recorder::SendAll() {
  if (sink_) Send(series_.size());
}

void Recorder::Finish(double t, const TrainState& x, const Phase& phase) {
  Update(t, x, phase);
  SortSeries(series_);
  // The run ends where the needle came to rest, which may lie inside the last step already
  // sampled: its samples past the end are not the run's.
  const double end_rad = train_.Angle(t);
  while (!series_.empty() && series_.back().crank_rad > end_rad) series_.pop_back();
  DropRepeats(series_);
  SendAll();
  if (separated_) {
    episodes_.back().end_rad = train_.Angle(t);
    episodes_.back().open = true;  // still off cam and seat when the run ends: reported
  }
  if (reopened_) secondary_open_rad_ += train_.Angle(t) - reopen_rad_;
  reopened_ = false;
}

void Recorder::Stopped(double crank_rad) {
  SortSeries(series_);
  DropRepeats(series_);
  SendAll();
  if (separated_) {
    episodes_.back().end_rad = crank_rad;
    episodes_.back().open = true;
  }
  if (reopened_) secondary_open_rad_ += crank_rad - reopen_rad_;
  reopened_ = false;
}

std::optional<double> Recorder::min_coil_gap_m() const {
  const TrainParameters& p = train_.parameters();
  if (!(p.coil_travel_m > 0.0)) return std::nullopt;
  return p.coil_travel_m - p.coil_masses * max_segment_compression_m_;
}

double Recorder::jump_rad() const {
  double sum = 0.0;
  for (const Episode& e : episodes_) {
    if (e.kind == "jump") sum += e.end_rad - e.start_rad;
  }
  return sum;
}

double Recorder::longest_jump_rad() const {
  double best = 0.0;
  for (const Episode& e : episodes_) {
    if (e.kind == "jump") best = std::max(best, e.end_rad - e.start_rad);
  }
  return best;
}

}  // namespace needle
