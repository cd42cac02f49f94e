// The SUNDIALS CVODE backends of the event driver: BDF or Adams–Moulton, one step at a time
// (CV_ONE_STEP) up to the driver's stop time, Newton iterations on a dense linear solver with
// the train's analytic Jacobian (CVodeSetJacFn), dense output from CVODE's interpolant
// (CVodeGetDky). A restart is CVodeReInit. CVODE's own rootfinding is not used: the event
// driver locates witnesses on the dense output as for every backend.
// Every C call's return code is checked and turned into an exception naming the function;
// RAII owners hold the context, vectors, matrix, linear solver and solver memory.
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

#include "dynamics/solver/stepper.h"

namespace needle {
namespace {

// CVODE's last error message: its handler keeps it here instead of printing it on stderr, and
// the exception carries it (one line).
thread_local std::string cvode_message;

void KeepMessage(int, const char*, const char* function, char* msg, void*) {
  cvode_message = std::string(function ? function : "") + ": " + (msg ? msg : "");
}

void Check(int flag, const char* function) {
  if (flag < 0) {
    char* name = CVodeGetReturnFlagName(flag);  // malloc'd by SUNDIALS: ours to free
    std::string text = std::string(function) + " failed with flag " + std::to_string(flag) + " (" +
                       (name ? name : "?") + ")";
    std::free(name);
    if (!cvode_message.empty()) text += ": " + cvode_message;
    cvode_message.clear();
    throw std::runtime_error(text);
  }
}

template <typename T>
T* CheckPointer(T* p, const char* function) {
  if (!p) throw std::runtime_error(std::string(function) + " returned NULL");
  return p;
}

struct Context {
  SUNContext ctx = nullptr;
  Context() { Check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create"); }
  ~Context() { SUNContext_Free(&ctx); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
};

struct Vector {
  N_Vector v;
  Vector(long n, SUNContext ctx) : v(CheckPointer(N_VNew_Serial(n, ctx), "N_VNew_Serial")) {}
  ~Vector() { N_VDestroy(v); }
  double* data() { return N_VGetArrayPointer(v); }
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;
};

struct Matrix {
  SUNMatrix m;
  Matrix(long n, SUNContext ctx) : m(CheckPointer(SUNDenseMatrix(n, n, ctx), "SUNDenseMatrix")) {}
  ~Matrix() { SUNMatDestroy(m); }
  Matrix(const Matrix&) = delete;
  Matrix& operator=(const Matrix&) = delete;
};

struct LinearSolver {
  SUNLinearSolver ls;
  LinearSolver(N_Vector y, SUNMatrix a, SUNContext ctx)
      : ls(CheckPointer(SUNLinSol_Dense(y, a, ctx), "SUNLinSol_Dense")) {}
  ~LinearSolver() { SUNLinSolFree(ls); }
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;
};

struct Memory {
  void* mem;
  Memory(int lmm, SUNContext ctx) : mem(CheckPointer(CVodeCreate(lmm, ctx), "CVodeCreate")) {}
  ~Memory() { CVodeFree(&mem); }
  Memory(const Memory&) = delete;
  Memory& operator=(const Memory&) = delete;
};

TrainState ToState(N_Vector y) {
  const double* p = N_VGetArrayPointer(y);
  return TrainState(p, p + N_VGetLength(y));
}

int Rhs(realtype t, N_Vector y, N_Vector ydot, void* user) {
  const auto* system = static_cast<const TrainSystem*>(user);
  const TrainState x = ToState(y);
  TrainState dx;
  (*system)(x, dx, t);
  double* out = N_VGetArrayPointer(ydot);
  double sum = 0.0;
  for (size_t i = 0; i < dx.size(); ++i) sum += out[i] = dx[i];
  return std::isfinite(sum) ? 0 : 1;  // recoverable: retry smaller
}

int Jacobian(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac, void* user, N_Vector, N_Vector,
             N_Vector) {
  const auto* system = static_cast<const TrainSystem*>(user);
  const TrainState x = ToState(y);
  TrainState dfdt;
  TrainJacobian j;
  system->Jacobian(x, t, j, dfdt);
  const size_t n = x.size();
  for (size_t r = 0; r < n; ++r) {
    for (size_t c = 0; c < n; ++c) SM_ELEMENT_D(jac, r, c) = j[r * n + c];
  }
  return 0;
}

// The first step after a restart, as a fraction of the driver's hint.
constexpr double kFirstStepFraction = 1e-3;

class CvodeStepper final : public Stepper {
 public:
  CvodeStepper(TrainSystem& system, const IntegratorOptions& o, bool bdf)
      : system_(system),
        y_(system.train().StateSize(), context_.ctx),
        dky_(system.train().StateSize(), context_.ctx),
        cvode_(bdf ? CV_BDF : CV_ADAMS, context_.ctx),
        a_(system.train().StateSize(), context_.ctx),
        ls_(y_.v, a_.m, context_.ctx),
        rtol_(o.rtol),
        atol_(o.atol_m) {}

  void Initialize(const TrainState& z, double t, double dt) override {
    std::copy(z.begin(), z.end(), y_.data());
    if (!initialized_) {
      Check(CVodeInit(cvode_.mem, Rhs, t, y_.v), "CVodeInit");
      Check(CVodeSetErrHandlerFn(cvode_.mem, KeepMessage, nullptr), "CVodeSetErrHandlerFn");
      cvode_message.clear();
      Check(CVodeSetUserData(cvode_.mem, &system_), "CVodeSetUserData");
      Check(CVodeSStolerances(cvode_.mem, rtol_, atol_), "CVodeSStolerances");
      Check(CVodeSetLinearSolver(cvode_.mem, ls_.ls, a_.m), "CVodeSetLinearSolver");
      Check(CVodeSetJacFn(cvode_.mem, Jacobian), "CVodeSetJacFn");
      Check(CVodeSetMaxNumSteps(cvode_.mem, 100000), "CVodeSetMaxNumSteps");
      Check(CVodeSetMaxHnilWarns(cvode_.mem, -1), "CVodeSetMaxHnilWarns");
      initialized_ = true;
    } else {
      Check(CVodeReInit(cvode_.mem, t, y_.v), "CVodeReInit");
      // A thousandth of the driver's first step (the last step's length): CVODE's own estimate
      // after a restart is far smaller and crawls through the roundoff of a witness at zero (a
      // grazing contact chatters into the event budget). DoStep falls back to CVODE's own
      // estimate if this one fails.
      first_step_ = kFirstStepFraction * dt;
      Check(CVodeSetInitStep(cvode_.mem, first_step_), "CVodeSetInitStep");
    }
    t0_ = t1_ = t;
    x0_ = x1_ = z;
  }
  void LimitTo(double t_stop) override { stop_ = t_stop; }
  std::pair<double, double> DoStep() override {
    // Set before every step: CVODE forgets a stop time once reached or after a restart.
    Check(CVodeSetStopTime(cvode_.mem, stop_), "CVodeSetStopTime");
    double t = t1_;
    int flag = CVode(cvode_.mem, stop_, y_.v, &t, CV_ONE_STEP);
    if ((flag == CV_ERR_FAILURE || flag == CV_CONV_FAILURE) && first_step_ > 0.0) {
      // The first step after a restart was too long for order 1: restart with CVODE's own.
      cvode_message.clear();
      std::copy(x1_.begin(), x1_.end(), y_.data());
      Check(CVodeReInit(cvode_.mem, t1_, y_.v), "CVodeReInit");
      Check(CVodeSetInitStep(cvode_.mem, 0.0), "CVodeSetInitStep");  // 0: CVODE estimates
      Check(CVodeSetStopTime(cvode_.mem, stop_), "CVodeSetStopTime");
      t = t1_;
      flag = CVode(cvode_.mem, stop_, y_.v, &t, CV_ONE_STEP);
    }
    first_step_ = 0.0;
    if (flag == CV_TOO_CLOSE) {
      // A restart a few ulps before the stop time (an event next to a break): CVODE cannot
      // start a step that short; the state is carried over it unchanged (an error of ẏ·Δt).
      cvode_message.clear();
      t0_ = t1_;
      x0_ = x1_;
      t1_ = stop_;
      return {t0_, t1_};
    }
    Check(flag, "CVode");
    t0_ = t1_;
    x0_ = x1_;
    t1_ = t;
    x1_ = ToState(y_.v);
    return {t0_, t1_};
  }
  void CalcState(double t, TrainState& z) override {
    if (t >= t1_) {
      z = x1_;
      return;
    }
    if (t <= t0_) {
      z = x0_;
      return;
    }
    Check(CVodeGetDky(cvode_.mem, t, 0, dky_.v), "CVodeGetDky");
    z = ToState(dky_.v);
  }
  TrainState CurrentState() const override { return x1_; }
  double CurrentTime() const override { return t1_; }
  double CurrentStep() const override { return t1_ - t0_; }

 private:
  TrainSystem& system_;
  Context context_;
  Vector y_, dky_;
  Memory cvode_;
  Matrix a_;
  LinearSolver ls_;
  double rtol_, atol_;
  bool initialized_ = false;
  double first_step_ = 0.0;  // the first step asked for after the last restart, 0: CVODE's
  double stop_ = 0.0;
  double t0_ = 0.0, t1_ = 0.0;
  TrainState x0_{}, x1_{};
};

}  // namespace

MakeBackend MakeCvodeBdf, MakeCvodeAdams;  // checked against the table's type

std::unique_ptr<Stepper> MakeCvodeBdf(TrainSystem& system, const IntegratorOptions& o) {
  return std::make_unique<CvodeStepper>(system, o, true);
}

std::unique_ptr<Stepper> MakeCvodeAdams(TrainSystem& system, const IntegratorOptions& o) {
  return std::make_unique<CvodeStepper>(system, o, false);
}

}  // namespace needle
