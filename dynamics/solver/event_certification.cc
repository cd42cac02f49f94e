// The closed form's side of the event driver (event_driver.h): crossings certified on a piece's
// own polynomials (Certified, Isolate), the ranges of what the record sees over a stretch, how
// far a piece may run where nothing can change (LongestQuiet), and the extremes of the forces
// located inside a step (RecordExtremes).
#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>

#include "dynamics/solver/event_driver.h"
#include "lib/units.h"

namespace needle {
namespace internal {

std::optional<double> EventDriver::Certified(const ClosedFormPiece& piece, int i, int s, double a,
                                             double wa, double b, double wb) {
  if (!(b > a)) return std::nullopt;
  // Witnesses 5 and 6 are gated by y > 1 µm; on [a, b] (up to witness 4's crossing) the gate
  // is the one in the middle.
  // (Witness 5 is +1 in cam mode whatever the gate, and needs no lift.)
  const bool gated = i == 6 || (i == 5 && !system_.phase.mode.cam);
  const bool lifted = gated && piece.LiftAndSpeed(0.5 * (a + b))[0] > kSeparationLift_m;
  const std::optional<LinearForm> form = WitnessForm(train_, system_.phase, i, lifted);
  if (!form) throw std::logic_error("exact: a witness without a linear form");
  int budget = kIsolationBudget;
  // Inside the search the witness is evaluated on the piece's own polynomials, where they agree
  // in sign with the train's own evaluation at both ends (they differ by round-off: a witness at
  // zero on a break, or just after a restart, is left to the train's).
  value_form_ = &*form;
  value_piece_ = &piece;
  struct Reset {
    EventDriver* d;
    ~Reset() {
      d->value_form_ = nullptr;
      d->value_taylor_ = nullptr;
    }
  } reset{this};
  const ClosedFormPiece::Poly q0 = piece.FormPolynomial(*form);
  const std::optional<Bracket> bracket = Isolate(piece, *form, q0, i, s, {a, wa, b, wb}, budget);
  if (!bracket) return std::nullopt;
  // A chain's bracket is searched on its needle's Taylor polynomials about the middle, where
  // they hold (ChainTaylorAt): O(degree) a value against O(modes) sines and exponentials.
  ChainTaylor taylor;
  if (piece.Chain()) {
    const double half = 0.5 * (bracket->b - bracket->a);
    taylor = piece.ChainTaylorAt(bracket->a + half, half, false);
    if (taylor.valid) value_taylor_ = &taylor;
  }
  const double root = Refine(i, bracket->a, bracket->wa, bracket->b, bracket->wb);
  value_taylor_ = nullptr;
  // The root must be past the crossing for the train's own evaluation too (the two differ by
  // round-off): else it is refined again on the train's.
  value_form_ = nullptr;
  if (SignOf(Value(i, root)) != s) return root;
  const double fa = Value(i, bracket->a), fb = Value(i, bracket->b);
  if (SignOf(fa) == s && SignOf(fb) != s) return Refine(i, bracket->a, fa, bracket->b, fb);
  return Refine(i, a, wa, b, wb);
}

// On [a, b], w(a) = wa of sign s and w(b) = wb: the earliest sub-interval [lo, hi] where w
// leaves sign s, holding exactly one crossing, or nullopt when w keeps sign s on [a, b]. With
// |w'| ≤ L₁ and |w''| ≤ L₂ on [a, b] (ClosedFormPiece::Bounds):
//   no crossing   when |w(a)| + |w(b)| > L₁ (b − a) (a root would need more slope), or when w is
//                 monotone (|w'(a)| > L₂ (b − a)) and keeps its sign at both ends;
//   one crossing  when w is monotone and changes sign;
//   otherwise the interval is halved, the left half first. Below the time's round-off, or past
//   kIsolationBudget halvings, an interval without a sign change at its ends counts as none (a
//   tangency, or a witness pinned at zero by round-off).
std::optional<EventDriver::Bracket> EventDriver::Isolate(const ClosedFormPiece& piece,
                                                         const LinearForm& form,
                                                         const ClosedFormPiece::Poly& q0, int i,
                                                         int s, const Bracket& in, int& budget) {
  const bool change = SignOf(in.wb) != s;
  const ClosedFormPiece::Poly q = piece.Shifted(q0, in.a);
  if (!change) {
    // The values' range over the whole interval: no crossing where it keeps sign s.
    const FormRange range = piece.Range(form, q, in.a, in.b);
    if (s > 0 ? range.lo > 0.0 : range.hi <= 0.0) return std::nullopt;
  }
  const FormBounds bounds = piece.Bounds(form, q, in.a, in.b);
  const double h = in.b - in.a;
  const bool monotone = std::abs(bounds.slope_at_start) > bounds.curvature_bound * h;
  if (!change && (monotone || std::abs(in.wa) + std::abs(in.wb) > bounds.slope_bound * h))
    return std::nullopt;
  if (change && monotone) return in;
  const double mid = in.a + 0.5 * h;
  // The time's round-off, or a witness that stays within its own round-off of zero (a needle
  // resting on its seat without load): the ends decide, as on the time steppers.
  if (--budget < 0 || !(mid > in.a && mid < in.b)) {
    return change ? std::optional<Bracket>(in) : std::nullopt;
  }
  const double wm = Value(i, mid);
  if (auto left = Isolate(piece, form, q0, i, s, {in.a, in.wa, mid, wm}, budget)) return left;
  return Isolate(piece, form, q0, i, s, {mid, wm, in.b, in.wb}, budget);
}

bool EventDriver::Frozen(const ClosedFormPiece& piece, double t0, double t1) const {
  if (recorder_.RepeatsMatter() || !piece.Frozen()) return false;
  const Phase& phase = system_.phase;
  const TrainState x = piece.State(t0);  // its start state, which every t repeats
  const Contacts a = train_.Evaluate(x, t0, phase), b = train_.Evaluate(x, t1, phase);
  return a.u == b.u && a.u_slope == b.u_slope && a.f_c_raw == b.f_c_raw && a.f_s_raw == b.f_s_raw &&
         a.spring_N == b.spring_N;
}

StretchRanges EventDriver::Ranges(const ClosedFormPiece& piece, double t0, double t1) const {
  const Phase& phase = system_.phase;
  StretchRanges r;
  const FormRange y = piece.Range(LinearForm{1.0, 0.0, 0.0, 0.0, 0.0}, t0, t1);
  r.y_lo = y.lo;
  r.y_hi = y.hi;
  r.u_hi = piece.Range(LinearForm{0.0, 0.0, 1.0, 0.0, 0.0}, t0, t1).hi;
  // The applied forces of linear laws: k g + c ġ in mode, with g_c = u − y, g_s = −y.
  if (phase.mode.cam) {
    const double k = train_.cam_law().ForceStiffness(), c = train_.cam_law().ForceDamping();
    const FormRange f = piece.Range(LinearForm{-k, -c, k, c, 0.0}, t0, t1);
    r.fc_lo = f.lo;
    r.fc_hi = f.hi;
  }
  if (phase.mode.seat) {
    const double k = train_.seat_law().ForceStiffness(), c = train_.seat_law().ForceDamping();
    r.fs_hi = piece.Range(LinearForm{-k, -c, 0.0, 0.0, 0.0}, t0, t1).hi;
  }
  // A chain's bounds screen its record only where work may be left out (else: +∞, every
  // sample taken, every piece capped, as SimulationOptions::leave_out = false promises).
  if (piece.Chain() && o_.leave_out) {
    const std::array<double, 2> chain = piece.ChainUpperBounds(t0, t1);
    r.compression_hi = chain[0];
    r.spring_hi = chain[1];
  }
  return r;
}

void EventDriver::RestAllowance(const ClosedFormPiece& piece, StretchRanges& r) const {
  // A chain at rest up to round-off: a constant forcing (the cam does not push, or pushes from
  // a constant input) and a homogeneous part within 1e-12 of the cam's scale (and of its rate's)
  // at every node and every τ (ChainStartRinging). Its start and its pieces' particular
  // solutions agree only to round-off, so it rings there at some 1e-19 m: where one mass is
  // frozen, without this allowance its every piece would be sampled and capped.
  if (!piece.Chain() || !o_.leave_out || !piece.ForcingConstant()) return;
  const double lift_roundoff = kRoundoffFraction * lift_scale_;
  const double rate_roundoff = kRoundoffFraction * rate_scale_;
  const std::array<double, 2> ringing = piece.ChainStartRinging();
  if (!(ringing[0] <= lift_roundoff && ringing[1] <= rate_roundoff)) return;
  // What that ringing can move: a record within it is no change.
  const auto moved = [&](double k, double c) {
    return std::abs(k) * lift_roundoff + std::abs(c) * rate_roundoff;
  };
  const ContactLaw& cam = train_.cam_law();
  const ContactLaw& seat = train_.seat_law();
  r.y_lo += moved(1.0, 0.0);
  r.y_hi -= moved(1.0, 0.0);
  r.fc_lo += moved(cam.ForceStiffness(), cam.ForceDamping());
  r.fc_hi -= moved(cam.ForceStiffness(), cam.ForceDamping());
  r.fs_hi -= moved(seat.ForceStiffness(), seat.ForceDamping());
  r.compression_hi -= 2.0 * moved(1.0, 0.0);
  // The spring force is a sum of terms of the preload's size (P₀ + k s₁), its bound and its
  // record each by their own path: they differ by the round-off of P₀ as well (Example 1's
  // spring as 5 coil masses, at rest on the seat: 7.7e-9 of 7746 N, past k and c's share alone,
  // which capped each of its 474 seated pieces at half an oscillation).
  const double preload_roundoff = kRoundoffFraction * std::abs(train_.parameters().preload_N);
  r.spring_hi -=
      2.0 * (moved(train_.SegmentRateNm(), train_.SegmentDampingNsm()) + preload_roundoff);
}

double EventDriver::LongestQuiet(const ClosedFormPiece& piece, double t, double cap,
                                 double limit) const {
  const double end = std::min(limit, t_end_);
  // A piece on a curved stretch of the cam keeps its cap: over many caps the audit's integrals
  // of its polynomials lose digits (the stiff train's energy residual 3e-13 → 1.5e-12).
  if (piece.InputDegree() > 1 || !(cap > t)) return cap;
  // Stretches from t, twice the cap's length, then doubled, and at last to the end: the ranges
  // of a longer stretch hold a shorter one's, so the first that is not quiet ends the search.
  double quiet = cap;
  std::optional<EventValues> now;
  for (double span = 2.0 * (cap - t); quiet < end; span *= 2.0) {
    const double to = std::min(t + span, end);
    if (!Quiet(piece, t, to, now)) break;
    quiet = to;
  }
  return quiet;
}

bool EventDriver::Quiet(const ClosedFormPiece& piece, double t, double end,
                        std::optional<EventValues>& now) const {
  const StretchRanges ranges = Ranges(piece, t, end);
  // What the run reports (a lift-off run keeps only that: Recorder::set_liftoff_only).
  StretchRanges record = ranges;
  RestAllowance(piece, record);
  if (!(o_.leave_out && Frozen(piece, t, end)) && recorder_.MayChange(record, false, true))
    return false;
  // Every witness's range over the whole stretch keeps the sign it has at t: the certified
  // search then ends at its first test, without halving a long interval.
  const bool lifted = ranges.y_lo > kSeparationLift_m;
  if (lifted != (ranges.y_hi > kSeparationLift_m)) return false;  // the gate may change
  if (!now) now = Events(train_, system_.phase, piece.State(t), t);
  for (int i = 0; i < static_cast<int>(now->size()); ++i) {
    const std::optional<LinearForm> form = WitnessForm(train_, system_.phase, i, lifted);
    if (!form) return false;
    const FormRange range = piece.Range(*form, t, end);
    if (!(SignOf((*now)[i]) > 0 ? range.lo > 0.0 : range.hi <= 0.0)) return false;
  }
  return true;
}

StretchRanges EventDriver::SettledRanges(const ClosedFormPiece& piece, double t0, double t1,
                                         std::optional<double> covering, const EventSigns& signs,
                                         bool* lift_covered) {
  constexpr int n = kStretchSamples;
  StretchRanges ranges = Ranges(piece, t0, t1);
  RestAllowance(piece, ranges);
  // No witness leaves its sign inside the stretch (the certified search found none before its
  // end): off the seat (its gap g_s = −y at or below zero) the lift is at least 0, and below
  // (above) 1 µm where witness 4 says so; within round-off of the cam's scale.
  if (o_.leave_out) {
    const double roundoff = kRoundoffFraction * lift_scale_;
    const std::optional<LinearWitnesses> seat = train_.seat_law().Linear();
    if (seat && seat->gap_g > 0.0 && seat->gap_rate == 0.0 && signs[kSeatGap] < 0)
      ranges.y_lo = std::max(ranges.y_lo, -roundoff);
    if (signs[4] < 0) ranges.y_hi = std::min(ranges.y_hi, kSeparationLift_m + roundoff);
    if (signs[4] > 0) ranges.y_lo = std::max(ranges.y_lo, kSeparationLift_m - roundoff);
  }
  // A lift that rises (falls) over the whole stretch, by more than round-off between two
  // samples, from one the record holds to the covering one: its interior samples set no
  // extreme of the lift that the covering sample does not set after them.
  *lift_covered = false;
  if (covering) {
    const double y0 = system_.RoundTrip(0, piece.LiftAndSpeed(t0)[0]);  // Motion(t0)[0]
    const FormRange rate = piece.Range(LinearForm{0.0, 1.0, 0.0, 0.0, 0.0}, t0, t1);
    const double step = (t1 - t0) / n;
    const double roundoff = kRoundoffFraction * (std::abs(*covering) + lift_scale_);
    if (rate.lo * step > roundoff && !(y0 < recorder_.min_lift_m())) {
      *lift_covered = true;
      ranges.y_lo = std::max(ranges.y_lo, y0);
      ranges.y_hi = std::min(ranges.y_hi, *covering);
    } else if (-rate.hi * step > roundoff && !(y0 > recorder_.max_lift_m())) {
      *lift_covered = true;
      ranges.y_lo = std::max(ranges.y_lo, *covering);
      ranges.y_hi = std::min(ranges.y_hi, y0);
    }
  }
  return ranges;
}

void EventDriver::RecordExtremes(double t0, double t1, std::optional<double> covering,
                                 const EventSigns& signs) {
  constexpr int n = kStretchSamples;
  const Phase& phase = system_.phase;
  const ClosedFormPiece& piece = *stepper_->ClosedForm();
  // A frozen stretch: every sample repeats its start, which the record holds.
  if (o_.leave_out && Frozen(piece, t0, t1)) return;
  const bool screen = o_.leave_out && !phase.gated && !train_.HasConstraint();
  if (!screen) covering.reset();
  bool lift_covered = false;
  const StretchRanges ranges = SettledRanges(piece, t0, t1, covering, signs, &lift_covered);
  // Nothing recorded can change inside the stretch: its interior samples are left out.
  if (!recorder_.MayChange(ranges, lift_covered, true)) return;
  const double max_fc = recorder_.max_contact_force_N(), max_fs = recorder_.max_seat_force_N();
  const double min_fc = recorder_.min_contact_force_during_lift_N();
  const double share = recorder_.min_contact_force_ratio();
  const double max_compression = recorder_.max_segment_compression_m();
  const bool chain = train_.Coils() > 0;
  // A chain's least coil gap is located only where its bound reaches past the record.
  const bool chain_gap = chain && train_.parameters().coil_travel_m > 0.0 &&
                         !(ranges.compression_hi <= max_compression);
  // And its largest spring force (on the needle, the surge study's stress) where its bound does:
  // samples alone read it low, by what passes between them (a surge peak: the 2000 rpm engine's
  // stress 1.6e-3 MPa under dopri5's at rtol 1e-12).
  const double max_spring = recorder_.max_spring_force_N();
  const bool chain_spring = chain && !recorder_.liftoff_only() && !(ranges.spring_hi <= max_spring);
  // And the largest gap of a separation, which samples alone read low by what passes between
  // them (helper-59's engine at 4000 rpm: a jump's 0.06453 mm against dopri5 at rtol 1e-13's
  // 0.06455): where an episode is open (one begins only at an event or a break, where a stretch
  // begins), the cam does not push and the lift may pass 1 µm.
  const bool locate_gap = !phase.mode.cam && !recorder_.liftoff_only() &&
                          ranges.y_hi > kSeparationLift_m && recorder_.separated();
  const double max_gap_m = recorder_.open_gap_m();
  // The sample screen: the seat force from y and ẏ alone (the train's own bits); the cam force
  // from the piece's input, within kAllowance of the cam's scale (the two inputs differ by
  // round-off, some 1e-16 of it).
  constexpr double kAllowance = 1e-9;
  const ContactLaw& cam = train_.cam_law();
  const ContactLaw& seat = train_.seat_law();
  StretchSamples samples;
  std::array<double, n + 1>& ts = samples.ts;
  std::array<std::array<double, n + 1>, kExtremes>& f = samples.f;
  for (int k = 0; k <= n; ++k) ts[k] = t0 + (t1 - t0) * k / n;
  piece.ChainSampleTimes(ts.data(), n + 1);
  for (int k = 0; k <= n; ++k) {
    const bool inside = k > 0 && k < n;
    // A chain's screened sample needs the needle's lift and speed alone; its coils only where
    // the sample is recorded or its compression located.
    const bool needle_only = chain && screen && inside && !chain_gap && !chain_spring;
    // The record reads the lifts and the spring's force (coil 1's speed), not the other speeds.
    TrainState x = needle_only ? ForceState(ts[k]) : Motion(ts[k], false);
    f[3][k] = chain_gap ? ExtremeValue(3, ts[k], x) : 0.0;
    f[5][k] = chain_spring ? ExtremeValue(5, ts[k], x) : 0.0;
    f[6][k] = locate_gap ? ExtremeValue(6, ts[k], x) : 0.0;
    if (screen && inside) {
      const std::array<double, 2> in = piece.Input(ts[k]);
      const double fs = phase.mode.seat ? seat.Force(-x[0], -x[1]) : 0.0;
      double fc = 0.0, fc_allowance = 0.0;
      if (phase.mode.cam) {
        fc = cam.Force(in[0] - x[0], in[1] - x[1]);
        fc_allowance =
            kAllowance * (std::abs(cam.ForceStiffness()) * (std::abs(in[0]) + lift_scale_) +
                          std::abs(cam.ForceDamping()) * (std::abs(in[1]) + rate_scale_));
      }
      const double u_hi = in[0] + kAllowance * (std::abs(in[0]) + lift_scale_);
      const bool quiet = !recorder_.SampleMayChange(x[0], covering, u_hi, fc - fc_allowance,
                                                    fc + fc_allowance, fs, ranges) &&
                         (fc + fc_allowance <= 0.0 || fc - fc_allowance >= min_fc);
      if (quiet) {  // neither a record nor the least contact force's bracket
        f[0][k] = -fc;
        f[1][k] = -fs;
        f[2][k] = fc;
        f[4][k] = recorder_.ForceShare(fc, in[0], x[0]);
        continue;
      }
    }
    if (needle_only) x = Motion(ts[k], false);
    const Contacts c = train_.Evaluate(x, ts[k], phase);
    const double fc = train_.AppliedCamForce(c, phase);
    f[0][k] = -fc;
    f[1][k] = -train_.AppliedSeatForce(c, phase);
    f[2][k] = fc;
    f[4][k] = recorder_.ForceShare(fc, c.u, x[0]);
    if (k > 0 && k < n) recorder_.Sample(ts[k], x, phase, c);
  }
  piece.ChainSampleTimes(nullptr, 0);  // the stretch's own: later times take the closed form
  const std::array<double, kExtremes> record = {
      -max_fc,     -max_fs,   min_fc, -max_compression, std::isnan(share) ? INFINITY : share,
      -max_spring, -max_gap_m};
  // A lift-off run locates only the least contact force (Recorder::set_liftoff_only).
  LocateExtremes(samples, record, recorder_.liftoff_only() ? 2 : 0,
                 chain_gap && !recorder_.liftoff_only() ? 4 : 3);
  // The least share of the holding load, where it is not at the least force (stop 93: a new
  // user's engine read 1.9e-5 more margin than dopri5 at rtol 1e-12, from the samples alone).
  if (!recorder_.liftoff_only()) LocateExtremes(samples, record, 4, 5);
  if (chain_spring) LocateExtremes(samples, record, 5, 6);
  if (locate_gap) LocateExtremes(samples, record, 6, 7);
}

TrainState EventDriver::ForceState(double t) {
  const ClosedFormPiece* piece = stepper_->ClosedForm();
  if (!piece || !piece->Chain()) return Motion(t);
  // A chain's forces: linear contact laws (method exact) read the needle's lift and speed and
  // the cam alone, Motion()'s bits; the coils' O(N·m) state is left at 0 (so is the spring
  // force Evaluate computes from it, which no force here reads).
  const std::array<double, 2> yv = piece->LiftAndSpeed(t);
  TrainState x(train_.StateSize(), 0.0);
  x[0] = system_.RoundTrip(0, yv[0]);
  x[1] = system_.RoundTrip(1, yv[1]);
  return x;
}

double EventDriver::ExtremeValue(int which, double t, const TrainState& x) const {
  const Phase& phase = system_.phase;
  if (which == 3) return -train_.LargestSegmentCompression(x);
  const Contacts c = train_.Evaluate(x, t, phase);
  if (which == 5) return -c.spring_N;
  const double fc = train_.AppliedCamForce(c, phase);
  if (which == 6) return fc > 0.0 || !(x[0] > kSeparationLift_m) ? INFINITY : -(x[0] - c.u);
  if (which == 4) return recorder_.ForceShare(fc, c.u, x[0]);
  return which == 0 ? -fc : which == 1 ? -train_.AppliedSeatForce(c, phase) : fc;
}

void EventDriver::LocateExtremes(const StretchSamples& samples,
                                 const std::array<double, kExtremes>& record, int first, int last) {
  constexpr int n = kStretchSamples;
  for (int which = first; which < last; ++which) {
    const auto& v = samples.f[which];
    double least = record[which];  // the record, as this stretch's locations move it
    const int k = static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
    // Only a new record inside the step, and for the least contact force one while pushing.
    // An extreme may also lie between an end sample and its neighbour: stretches start and end
    // where a break or an event puts them, and a force may peak just past one (at the stretch's
    // start, already the record; at its end, a new one). One mass too since stop 93: a new
    // user's engine read its largest seat force 6.8e-4 low, where this was left to chains.
    if (k == 0 || k == n) {
      const bool edge = k == 0 ? v[0] <= least : v[n] < least;
      if (edge) least = std::min(least, LocateExtreme(samples, which, k, least));
    } else if (v[k] < least) {
      least = std::min(least, LocateExtreme(samples, which, k, least));
    }
    // Every other dip of the samples (and the least one where it did not pass the record) whose
    // parabola through it and its neighbours, its depth doubled, reaches past the record: a peak
    // between two samples may pass it where neither does (helper-59's engines: a chain's contact
    // force with two near-equal peaks read at the lower one, 6.8e-4 low; a seat force whose
    // samples fell either side of its peak, 7.8e-4 low).
    for (int j = 1; j < n; ++j) {
      if ((j == k && v[k] < record[which]) || !(v[j] <= v[j - 1] && v[j] <= v[j + 1])) continue;
      const double curvature = v[j - 1] - 2.0 * v[j] + v[j + 1];
      const double slope = 0.5 * (v[j + 1] - v[j - 1]);
      const double depth = curvature > 0.0 ? slope * slope / (2.0 * curvature) : 0.0;
      if (v[j] - 2.0 * depth < least)
        least = std::min(least, LocateExtreme(samples, which, j, least));
    }
  }
}

double EventDriver::LocateExtreme(const StretchSamples& samples, int which, int k, double record) {
  constexpr int n = kStretchSamples;
  const bool chain = train_.Coils() > 0;
  const std::array<double, n + 1>& ts = samples.ts;
  const auto& v = samples.f[which];
  const int lo = k == 0 ? 0 : k == n ? n - 1 : k - 1;
  const int hi = k == 0 ? 1 : k == n ? n : k + 1;
  if ((which == 2 || which == 4) && !(v[k] > 0.0 && std::isfinite(v[k]))) return record;
  std::uintmax_t iterations = 60;
  // In the fraction of the bracket: Brent's tolerance has an absolute part.
  const double base = ts[lo], width = ts[hi] - ts[lo];
  const auto at = [&](double d) { return base + d * width; };
  // A chain's bracket is searched on its Taylor polynomials about the middle (exact to the
  // modal sum's round-off there): O(N) a point against O(N·m) sines and exponentials. The
  // sample recorded is the closed form's.
  ChainTaylor taylor;
  // (Not the spring force: it reads coil 1's speed, which the polynomials do not hold.)
  if (chain && which != 5) {
    taylor = stepper_->ClosedForm()->ChainTaylorAt(base + 0.5 * width, 0.5 * width, which == 3);
  }
  const auto state = [&](double t) {
    if (taylor.valid) return taylor.At(t, train_.StateSize());
    return which == 3 || which == 5 ? Motion(t, false) : ForceState(t);
  };
  // An end sample that is the least of the bracket next to it as well, by a point 1e-3 of the
  // bracket inside: a value still falling toward the stretch's end (a force still rising) has
  // its extreme there, at the sample (one evaluation where Brent takes some twenty).
  if (k == 0 || k == n) {
    const double d = k == 0 ? 1e-3 : 1.0 - 1e-3;
    if (v[k] <= ExtremeValue(which, at(d), state(at(d)))) return record;
  }
  const auto best = boost::math::tools::brent_find_minima(
      [&](double d) { return ExtremeValue(which, at(d), state(at(d))); }, 0.0, 1.0,
      std::numeric_limits<double>::digits / 2, iterations);
  recorder_.Sample(at(best.first), Motion(at(best.first), false), system_.phase);
  return best.second;
}

}  // namespace internal
}  // namespace needle
