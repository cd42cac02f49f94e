#include "dynamics/model/cam_input.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "lib/output.h"
#include "lib/units.h"

namespace needle {
namespace {

// A tangent ramp longer than a crank revolution comes from an end slope that is flat up to
// noise (a dense measured table gave slopes of 1e-8 and ramps of 42.5 million degrees): no cam
// has one. (Basu's Example 1 has a 109° ramp at its flat start: long, but a cam's.)
constexpr double kLongestRamp_rad = 2 * kPi;

// Why tangent ramps cannot take up the play δ from the law's end lifts s0, sn with slopes
// slope0, slopen: which end is flat (its tangent would take more than kLongestRamp_rad to reach
// −δ: a law at rest there up to the table's noise, as most cam laws are) or slopes the wrong
// way, and the way out (ramp_deg; a clamped spline's ends are at rest by construction, the
// readings' own may not be).
std::string TangentRefusal(const LiftLaw& law, double play_m, double s0, double slope0, double sn,
                           double slopen) {
  // The fault of one end ("" where its slope takes the ramp to the base circle), `sign` the
  // slope's sign it needs.
  const auto fault = [&](const char* end, double lift, double slope, double sign) {
    if (std::abs(slope) * kLongestRamp_rad <= lift + play_m) return std::string(end) + " is flat";
    return sign * slope > 0.0 ? std::string() : std::string(end) + (sign > 0 ? " falls" : " rises");
  };
  const std::string start = fault("the start", s0, slope0, 1.0);
  const std::string end = fault("the end", sn, slopen, -1.0);
  const std::string why = start.empty() ? end : end.empty() ? start : start + " and " + end;
  // (+ 0.0: a slope of −0 printed as 0)
  const auto mm_per_deg = [](double slope) { return Significant(slope * 1e3 * kDeg + 0.0, 3); };
  return "tangent ramps need a rising start and a falling end, but the lift law's end slopes are " +
         mm_per_deg(slope0) + " and " + mm_per_deg(slopen) + " mm/deg (" + why +
         "): no tangent there reaches the base circle; give ramp_deg (a linear ramp over that "
         "many degrees takes up the play)" +
         (law.kind() == SplineKind::kClamped
              ? ", or a spline whose ends follow the readings (not-a-knot) in place of the "
                "clamped one, at rest by construction"
              : "");
}

}  // namespace

CamInput::CamInput(const LiftLaw& law, double play_m, RampKind ramp, double ramp_rad)
    : law_(law), top_(law.Max(0)), play_(play_m) {
  if (!(play_m >= 0.0) || !std::isfinite(play_m)) {
    throw std::invalid_argument("roller play must not be negative, got " +
                                std::to_string(play_m * 1e3) + " mm");
  }
  const double th0 = law.start_rad(), thn = law.end_rad();
  s0_ = law.spline().Evaluate(th0);
  sn_ = law.spline().Evaluate(thn);
  slope0_ = law.spline().Evaluate(th0, 1);
  slopen_ = law.spline().Evaluate(thn, 1);
  rise_start_ = th0;
  fall_end_ = thn;
  if (play_m > 0.0) {
    if (ramp == RampKind::kTangent) {
      // A slope below 1e-9 of the mean one is zero up to roundoff (clamped at-rest ends).
      const double tiny = 1e-9 * (top_.value + play_m) / (thn - th0);
      if (!(slope0_ > tiny) || !(slopen_ < -tiny)) {
        throw std::invalid_argument(TangentRefusal(law, play_m, s0_, slope0_, sn_, slopen_));
      }
      rise_start_ = th0 - (s0_ + play_m) / slope0_;  // s0 + s0'(θ − θ0) = −δ
      fall_end_ = thn + (sn_ + play_m) / -slopen_;   // sn + sn'(θ − θN) = −δ
      // A ramp longer than kLongestRamp_rad: refused, with the way out.
      for (const auto& [name, length, slope] :
           {std::tuple<const char*, double, double>{"start", th0 - rise_start_, slope0_},
            {"end", fall_end_ - thn, slopen_}}) {
        if (length > kLongestRamp_rad) {
          throw std::invalid_argument(
              std::string("the tangent ramp at the lift's ") + name + " would take " +
              std::to_string(length / kDeg) + " deg to take up the play (end slope " +
              Significant(slope * 1e3 * kDeg, 3) +
              " mm/deg), more than a crank revolution: the end slope is flat up to noise (a law "
              "at rest there, as most cam laws are) or the play too large for it; give ramp_deg "
              "(a linear ramp over that many degrees takes up the play)");
        }
      }
    } else {
      if (!(ramp_rad > 0.0)) {
        throw std::invalid_argument("ramp_deg must be positive, got " +
                                    std::to_string(ramp_rad / kDeg));
      }
      rise_start_ = th0 - ramp_rad;
      fall_end_ = thn + ramp_rad;
      slope0_ = (s0_ + play_m) / ramp_rad;   // from −δ to s(θ0) over X
      slopen_ = -(sn_ + play_m) / ramp_rad;  // from s(θN) to −δ over X
    }
  }
  breaks_ = law.spline().breaks();
  if (play_m > 0.0) {
    breaks_.insert(breaks_.begin(), rise_start_);
    breaks_.push_back(fall_end_);
  }
  std::sort(breaks_.begin(), breaks_.end());
}

// Every piece is half-open on the right, [a, b): at a break the value after it is used, so an
// integration step that starts at a break sees the right-hand side it will integrate.
double CamInput::U(double th) const {
  const double th0 = law_.start_rad(), thn = law_.end_rad();
  if (th >= th0 && th < thn) return law_.spline().Evaluate(th);
  if (play_ == 0.0) return th < th0 ? s0_ : sn_;
  if (th < th0) return std::max(-play_, s0_ + slope0_ * (th - th0));  // ramp, then base circle
  return std::max(-play_, sn_ + slopen_ * (th - thn));
}

double CamInput::Slope(double th) const {
  const double th0 = law_.start_rad(), thn = law_.end_rad();
  if (th >= th0 && th < thn) return law_.spline().Evaluate(th, 1);
  if (play_ == 0.0) return 0.0;
  if (th < th0) return th >= rise_start_ ? slope0_ : 0.0;
  return th < fall_end_ ? slopen_ : 0.0;
}

std::array<double, 2> CamInput::USlope(double th) const {
  const double th0 = law_.start_rad(), thn = law_.end_rad();
  if (!(th >= th0 && th < thn)) return {U(th), Slope(th)};
  // PiecewisePolynomial::Evaluate(th, 0) and (th, 1), their operations in their order, on one
  // search for the piece.
  const PiecewisePolynomial& spline = law_.spline();
  const int i = spline.Piece(th);
  const Eigen::MatrixXd& c = spline.coefficients();
  const double t = th - spline.breaks()[i];
  double value = 0.0, slope = 0.0;
  for (int k = spline.degree(); k >= 0; --k) value = value * t + 1.0 * c(i, k);
  for (int k = spline.degree(); k >= 1; --k) slope = slope * t + 1.0 * k * c(i, k);
  return {value, slope};
}

CamPiece CamInput::Piece(double th) const {
  const double th0 = law_.start_rad(), thn = law_.end_rad();
  if (th >= th0 && th < thn) {
    const PiecewisePolynomial& spline = law_.spline();
    const int i = spline.Piece(th);
    const Eigen::MatrixXd& c = spline.coefficients();
    CamPiece piece{spline.breaks()[i], std::vector<double>(c.cols())};
    for (int k = 0; k < c.cols(); ++k) piece.coefficients[k] = c(i, k);
    return piece;
  }
  // The same branches as U().
  if (play_ == 0.0) return {th < th0 ? th0 : thn, {th < th0 ? s0_ : sn_}};
  if (th < th0) return th >= rise_start_ ? CamPiece{th0, {s0_, slope0_}} : CamPiece{th0, {-play_}};
  return th < fall_end_ ? CamPiece{thn, {sn_, slopen_}} : CamPiece{thn, {-play_}};
}

double CamInput::Curvature(double th) const {
  if (th >= law_.start_rad() && th < law_.end_rad()) return law_.spline().Evaluate(th, 2);
  return 0.0;
}

double CamInput::Jerk(double th) const {
  if (th >= law_.start_rad() && th < law_.end_rad()) return law_.spline().Evaluate(th, 3);
  return 0.0;
}

}  // namespace needle
