#include "dynamics/contact_events.h"

#include <algorithm>
#include <cmath>

namespace needle {

EventValues Events(const NeedleTrain& train, ContactMode mode, const TrainState& x, double t) {
  const Contacts c = train.Evaluate(x, t);
  // 5 and 6 only observe a lifted needle: at rest their arguments are zero up to roundoff
  // and would flip sign at every step.
  const bool lifted = x[0] > kSeparationLift_m;
  return {c.g_c,
          c.f_c_raw,
          c.g_s,
          c.f_s_raw,
          x[0] - kSeparationLift_m,
          (mode.cam || !lifted) ? 1.0 : c.g_c_rate,
          lifted ? x[1] : 1.0};
}

ContactMode ModeFromSigns(const std::array<int, kEventCount>& s) {
  return {s[0] > 0 && s[1] > 0, s[2] > 0 && s[3] > 0};
}

Recorder::Recorder(const NeedleTrain& train, bool record_series)
    : train_(train), record_series_(record_series) {}

void Recorder::Update(double t, const TrainState& x) {
  const Contacts c = train_.Evaluate(x, t);
  const double fc = train_.AppliedCamForce(c), fs = train_.AppliedSeatForce(c);

  const LiftLaw& law = train_.cam().law();
  const double th = c.crank_rad;
  const bool in_table = th >= law.start_rad() && th <= law.end_rad();
  if (x[0] > max_lift_) {
    max_lift_ = x[0];
    max_lift_rad_ = th;
  }
  max_fc_ = std::max(max_fc_, fc);
  max_fs_ = std::max(max_fs_, fs);
  if (in_table) min_fc_lift_ = std::min(min_fc_lift_, fc);
  // Separation episode: inside [θ0, θN], the cam not pushing and y > 1 µm.
  // An episode begins inside [θ0, θN]; one still open at θN goes on until the needle is back
  // on the cam or on its seat (model.md §6).
  const bool separated = (in_table || separated_) && !(fc > 0.0) && x[0] > kSeparationLift_m;

  if (separated && !separated_) {
    Episode e;
    e.start_rad = th;
    e.kind = law.Derivative(th, 2) < 0.0 ? "jump" : "bounce";
    e.max_gap_m = x[0] - c.u;
    episodes_.push_back(e);
  } else if (!separated && separated_) {
    episodes_.back().end_rad = th;
  }
  if (separated) {
    Episode& e = episodes_.back();
    e.max_gap_m = std::max(e.max_gap_m, x[0] - c.u);
    // model.md §6: a jump is any separation that reaches the deceleration zone, wherever it
    // began — a rebound in the acceleration zone that carries on over the crest is lift-off.
    if (law.Derivative(th, 2) < 0.0) e.kind = "jump";
  }
  separated_ = separated;
  if (record_series_) {
    series_.push_back({th, t, x[0], x[1], c.u, fc, fs});
  }
}

void Recorder::Start(double t, const TrainState& x) {
  cam_touched_ = train_.Evaluate(x, t).g_c > 0.0;
  Update(t, x);
}

void Recorder::GridSample(double t, const TrainState& x) {
  const Contacts c = train_.Evaluate(x, t);
  grid_.push_back({t, x[0], train_.AppliedCamForce(c)});
}

void Recorder::Sample(double t, const TrainState& x) { Update(t, x); }

void Recorder::Crossing(int index, int direction, double t, const TrainState& x) {
  const Contacts c = train_.Evaluate(x, t);
  if (index == 0 && direction > 0) {  // cam onset
    impacts_.push_back(
        {cam_touched_ ? "recontact" : "lash", c.crank_rad, std::max(0.0, c.g_c_rate)});
    cam_touched_ = true;
    if (separated_) episodes_.back().impact = static_cast<int>(impacts_.size()) - 1;
  } else if (index == 2 && direction > 0) {  // seat onset
    impacts_.push_back(
        {seat_landed_ ? "seat-bounce" : "seat", c.crank_rad, std::max(0.0, c.g_s_rate)});
    seat_landed_ = true;
  }
  Update(t, x);
}

void Recorder::Finish(double t, const TrainState& x) {
  Update(t, x);
  if (separated_) {
    episodes_.back().end_rad = train_.Angle(t);
    episodes_.back().open = true;  // still off cam and seat when the run ends: reported
  }
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
