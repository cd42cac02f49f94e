// The Boost.Odeint backends of the event driver.
//
//   Dormand–Prince 5(4)   odeint's dense output (4th-order continuous extension)
//   Fehlberg 7(8)         no dense output in odeint: states inside a step are recomputed by
//                         one 7(8) step from its start (exact to the method's order)
//   Rosenbrock 4          odeint's rosenbrock4_dense_output, analytic Jacobian (stiff)
//
// GCC 12 reports -Wmaybe-uninitialized inside Boost.Odeint's own copy constructor of the
// Fehlberg stepper (its scratch buffers are sized on first use); a false positive there (also
// reported as -Wuninitialized once the copy is inlined).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"

#include <boost/numeric/odeint.hpp>
#include <functional>
#include <stdexcept>

#include "dynamics/solver/odeint_state.h"
#include "dynamics/solver/stepper.h"

namespace needle {
namespace {

namespace odeint = boost::numeric::odeint;
namespace ublas = boost::numeric::ublas;

// A step that would pass t_stop is shortened by a restart with the remaining length.
class OdeintStepper : public Stepper {
 public:
  void LimitTo(double t_stop) override {
    if (CurrentTime() + CurrentStep() > t_stop) {
      Initialize(CurrentState(), CurrentTime(), t_stop - CurrentTime());
    }
  }
};

class Dopri5Stepper final : public OdeintStepper {
 public:
  Dopri5Stepper(TrainSystem& system, const IntegratorOptions& o)
      : system_(system),
        dense_(odeint::make_dense_output(o.atol_m, o.rtol,
                                         odeint::runge_kutta_dopri5<TrainState>())) {}
  void Initialize(const TrainState& z, double t, double dt) override {
    dense_.initialize(z, t, dt);
  }
  std::pair<double, double> DoStep() override { return dense_.do_step(std::ref(system_)); }
  void CalcState(double t, TrainState& z) override {
    z.resize(dense_.current_state().size());
    dense_.calc_state(t, z);
  }
  TrainState CurrentState() const override { return dense_.current_state(); }
  double CurrentTime() const override { return dense_.current_time(); }
  double CurrentStep() const override { return dense_.current_time_step(); }

 private:
  TrainSystem& system_;
  odeint::result_of::make_dense_output<odeint::runge_kutta_dopri5<TrainState>>::type dense_;
};

class Rkf78Stepper final : public OdeintStepper {
 public:
  Rkf78Stepper(TrainSystem& system, const IntegratorOptions& o)
      : system_(system),
        controlled_(odeint::make_controlled(o.atol_m, o.rtol,
                                            odeint::runge_kutta_fehlberg78<TrainState>())) {}
  void Initialize(const TrainState& z, double t, double dt) override {
    x1_ = z;
    t1_ = t;
    dt_ = dt;
  }
  std::pair<double, double> DoStep() override {
    x0_ = x1_;
    t0_ = t1_;
    TrainState x = x1_;
    double t = t1_;
    int tries = 0;
    while (controlled_.try_step(std::ref(system_), x, t, dt_) == odeint::fail) {
      if (++tries > 500) throw std::runtime_error("rkf78: step size underflow");
    }
    x1_ = x;
    t1_ = t;
    return {t0_, t1_};
  }
  // One 7(8) step from the start of the last step: exact to the method's order.
  void CalcState(double t, TrainState& z) override {
    if (t == t1_) {
      z = x1_;
      return;
    }
    if (t == t0_) {
      z = x0_;
      return;
    }
    TrainState in = x0_;
    z.resize(in.size());
    controlled_.stepper().do_step(std::ref(system_), in, t0_, z, t - t0_);
  }
  TrainState CurrentState() const override { return x1_; }
  double CurrentTime() const override { return t1_; }
  double CurrentStep() const override { return dt_; }

 private:
  TrainSystem& system_;
  odeint::result_of::make_controlled<odeint::runge_kutta_fehlberg78<TrainState>>::type controlled_;
  TrainState x0_{}, x1_{};
  double t0_ = 0.0, t1_ = 0.0, dt_ = 0.0;
};

// Boost 1.74's rosenbrock4 loses order on non-autonomous systems: with the exact ∂f/∂t its
// embedded error estimate of a forced oscillator scales as h² instead of h⁴ (measured), and
// the controller then creeps at tiny steps. The standard cure is applied: time is carried as
// a last state τ (τ' = 1), the system is autonomous, and ∂f/∂t becomes the Jacobian's last
// column.
class Rosenbrock4Stepper final : public OdeintStepper {
 public:
  using Vector = ublas::vector<double>;
  using Matrix = ublas::matrix<double>;
  Rosenbrock4Stepper(TrainSystem& system, const IntegratorOptions& o)
      : system_(system),
        dense_(odeint::make_dense_output(o.atol_m, o.rtol, odeint::rosenbrock4<double>())),
        n_(system.train().StateSize()),
        v_(n_ + 1) {}
  void Initialize(const TrainState& z, double t, double dt) override {
    for (int i = 0; i < n_; ++i) v_(i) = z[i];
    v_(n_) = t;  // τ
    dense_.initialize(v_, t, dt);
  }
  std::pair<double, double> DoStep() override {
    auto rhs = [this](const Vector& x, Vector& dxdt, double /*t*/) {
      State(x, a_);
      system_(a_, d_, x(n_));
      for (int i = 0; i < n_; ++i) dxdt(i) = d_[i];
      dxdt(n_) = 1.0;  // τ' = 1
    };
    auto jacobian = [this](const Vector& x, Matrix& J, double /*t*/, Vector& dfdt) {
      State(x, a_);
      system_.Jacobian(a_, x(n_), j_, d_);
      for (int r = 0; r <= n_; ++r) {
        dfdt(r) = 0.0;  // autonomous
        for (int c = 0; c <= n_; ++c) J(r, c) = 0.0;
      }
      for (int r = 0; r < n_; ++r) {
        for (int c = 0; c < n_; ++c) J(r, c) = j_[r * n_ + c];
        J(r, n_) = d_[r];  // ∂f/∂τ
      }
    };
    return dense_.do_step(std::make_pair(rhs, jacobian));
  }
  void CalcState(double t, TrainState& z) override {
    dense_.calc_state(t, v_);
    State(v_, z);
  }
  TrainState CurrentState() const override {
    TrainState z;
    State(dense_.current_state(), z);
    return z;
  }
  double CurrentTime() const override { return dense_.current_time(); }
  double CurrentStep() const override { return dense_.current_time_step(); }

 private:
  TrainSystem& system_;
  void State(const Vector& v, TrainState& z) const {
    z.resize(n_);
    for (int i = 0; i < n_; ++i) z[i] = v(i);
  }

  odeint::result_of::make_dense_output<odeint::rosenbrock4<double>>::type dense_;
  int n_;  // the train's state size (τ is entry n_)
  Vector v_;
  TrainState a_, d_;  // scratch
  TrainJacobian j_;
};

}  // namespace

MakeBackend MakeDopri5, MakeRkf78, MakeRosenbrock4;  // checked against the table's type

std::unique_ptr<Stepper> MakeDopri5(TrainSystem& system, const IntegratorOptions& o) {
  return std::make_unique<Dopri5Stepper>(system, o);
}
std::unique_ptr<Stepper> MakeRkf78(TrainSystem& system, const IntegratorOptions& o) {
  return std::make_unique<Rkf78Stepper>(system, o);
}
std::unique_ptr<Stepper> MakeRosenbrock4(TrainSystem& system, const IntegratorOptions& o) {
  return std::make_unique<Rosenbrock4Stepper>(system, o);
}

}  // namespace needle
