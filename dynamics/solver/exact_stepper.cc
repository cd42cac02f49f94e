// The closed-form backend of the event driver (method "exact", docs/model.md §9): each step is
// one ClosedFormPiece, from the step's start in the driver's contact mode on the cam segment the
// step lies in, and ends at the driver's limit (a break, the horizon) or after half an
// oscillation, whichever comes first, unless the driver lets it run on (SetLongest: a stretch in
// which nothing recorded can change); its dense output is the closed form itself. The driver
// bounds the witnesses on it (ClosedFormPiece::Bounds) so no crossing is missed.
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "dynamics/solver/stepper.h"

namespace needle {
namespace {

class ExactStepper final : public Stepper {
 public:
  ExactStepper(TrainSystem& system, bool audit) : system_(system), audit_(audit) {
    // A chain's modes in each of its four contact modes (the cam and the seat pushing or not),
    // made before the run (or kept from the thread's last runs of such a chain): a chain the
    // closed form cannot carry is refused before it starts.
    if (system_.train().Coils() > 0) modes_ = ChainModes::SharedEveryMode(system_.train());
  }
  void Initialize(const TrainState& z, double t, double /*dt*/) override {
    x_ = system_.FromScaled(z);
    t_ = t;
    step_ = 0.0;
    stop_ = std::numeric_limits<double>::infinity();
  }
  void LimitTo(double t_stop) override { stop_ = t_stop; }
  std::pair<double, double> DoStep() override {
    const NeedleTrain& train = system_.train();
    // The segment the step lies in: the one holding the middle of [t, limit] (the limit is the
    // next break, so both ends belong to one segment even where t sits on a break up to
    // round-off).
    const double limit = std::isfinite(stop_) ? stop_ : t_ + 1.0;
    piece_.emplace(train, system_.phase.mode, train.Angle(0.5 * (t_ + limit)), t_, x_,
                   Modes(system_.phase.mode));
    const double start = t_;
    const double cap = t_ + piece_->LongestStep();
    t_ = cap < stop_ && longest_ ? std::max(cap, std::min(stop_, longest_(*piece_, t_, cap, stop_)))
                                 : std::min(stop_, cap);
    step_ = t_ - start;
    x_ = StateAt(t_);
    return {start, t_};
  }
  void CalcState(double t, TrainState& z) override { z = system_.ToScaled(StateAt(t)); }
  void CalcMotion(double t, TrainState& z) override {
    z = system_.ToScaled(piece_->MotionState(t));
  }
  TrainState CurrentState() const override { return system_.ToScaled(x_); }
  double CurrentTime() const override { return t_; }
  double CurrentStep() const override { return step_; }
  const ClosedFormPiece* ClosedForm() const override { return piece_ ? &*piece_ : nullptr; }
  void SetLongest(
      std::function<double(const ClosedFormPiece&, double, double, double)> longest) override {
    longest_ = std::move(longest);
  }

 private:
  // The state at t: with the audit's W and D, or (no audit) with the piece's start values.
  TrainState StateAt(double t) const {
    if (audit_) return piece_->State(t);
    TrainState x = piece_->MotionState(t);
    x[2] = x_[2];
    x[3] = x_[3];
    return x;
  }
  // The coil chain's modes in `mode`; nullptr for one mass.
  const ChainModes* Modes(const ContactMode& mode) const {
    return modes_[ChainModes::ModeIndex(mode)].get();
  }

  TrainSystem& system_;
  bool audit_;
  TrainState x_{};
  double t_ = 0.0, step_ = 0.0, stop_ = 0.0;
  std::optional<ClosedFormPiece> piece_;
  std::array<std::shared_ptr<const ChainModes>, 4> modes_;
  std::function<double(const ClosedFormPiece&, double, double, double)> longest_;
};

}  // namespace

std::optional<std::string> ExactRefusal(const NeedleTrain& train) {
  if (train.ClashSegments() > 0) {
    return std::string(
        "method \"exact\" carries no coil clash; the spring's coils may clash ([spring] "
        "clash = true)");
  }
  if (train.Coils() > 0 && !(train.parameters().rate_N_m > 0.0)) {
    return std::string("method \"exact\" needs a coil chain with a spring rate above 0");
  }
  for (const ContactLaw* law : {&train.cam_law(), &train.seat_law()}) {
    if (!law->Linear()) {
      return std::string(
                 "method \"exact\" needs contact laws linear in the gap and its rate; "
                 "the ") +
             (law == &train.cam_law() ? "cam" : "seat") + " law \"" + law->name() + "\" is not";
    }
  }
  return std::nullopt;
}

std::optional<std::string> ExactRefusalWithModes(const NeedleTrain& train) {
  if (std::optional<std::string> why = ExactRefusal(train)) return why;
  if (train.Coils() == 0) return std::nullopt;
  try {
    ChainModes::SharedEveryMode(train);
  } catch (const std::invalid_argument& e) {
    // Without the refusal's advice ("take dopri5"): auto says which time stepper it takes.
    std::string why = e.what();
    const std::string advice = "; take dopri5";
    if (why.size() > advice.size() &&
        why.compare(why.size() - advice.size(), advice.size(), advice) == 0)
      why.resize(why.size() - advice.size());
    return why;
  }
  return std::nullopt;
}

MakeBackend MakeExact;  // checked against the table's type

std::unique_ptr<Stepper> MakeExact(TrainSystem& system, const IntegratorOptions& o) {
  if (const std::optional<std::string> why = ExactRefusal(system.train()))
    throw std::invalid_argument(*why);
  return std::make_unique<ExactStepper>(system, o.audit_energy);
}

}  // namespace needle
