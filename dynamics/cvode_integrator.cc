// SUNDIALS CVODE (BDF or Adams, dense linear solver) with its rootfinding on the same event
// functions as the Odeint integrator. After every mode switch and at every break of the cam
// input the integrator is re-initialised (CVodeReInit), so no step straddles a switch.
// Every C call's return code is checked and turned into an exception naming the function;
// RAII owners hold the context, vector, matrix, linear solver and solver memory.
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "dynamics/integrator.h"

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

struct UserData {
  NeedleTrain* train;
  ContactMode mode;
};

int Rhs(realtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* d = static_cast<UserData*>(user);
  TrainState x, dx;
  const double* in = N_VGetArrayPointer(y);
  for (int i = 0; i < 4; ++i) x[i] = in[i];
  (*d->train)(x, dx, t);
  double* out = N_VGetArrayPointer(ydot);
  for (int i = 0; i < 4; ++i) out[i] = dx[i];
  return std::isfinite(dx[0] + dx[1] + dx[2] + dx[3]) ? 0 : 1;  // recoverable: retry smaller
}

int Roots(realtype t, N_Vector y, realtype* g, void* user) {
  auto* d = static_cast<UserData*>(user);
  TrainState x;
  const double* in = N_VGetArrayPointer(y);
  for (int i = 0; i < 4; ++i) x[i] = in[i];
  const EventValues v = Events(*d->train, d->mode, x, t);
  for (int i = 0; i < kEventCount; ++i) g[i] = v[i];
  return 0;
}

TrainState ToState(N_Vector y) {
  const double* p = N_VGetArrayPointer(y);
  return {p[0], p[1], p[2], p[3]};
}

}  // namespace

IntegrationStats IntegrateCvode(bool bdf, NeedleTrain& train, const TrainState& x0, double t_end,
                                Recorder& recorder, const IntegratorOptions& o) {
  o.Validate();
  IntegrationStats stats;
  const long rhs_before = train.evaluations();
  const double t_limit = t_end + o.settle_limit_s;
  double horizon = t_end;  // t_limit once the run goes on to let the needle settle
  const Breaks all_breaks = BreakTimes(train, t_limit);
  const std::vector<double>& breaks = all_breaks.times;
  const std::vector<double>& grid = recorder.grid_times();
  size_t next_grid = 0, next_break = 0;

  std::array<int, kEventCount> signs = Signs(Events(train, train.mode(), x0, 0.0));
  UserData data{&train, ModeFromSigns(signs)};
  train.set_mode(data.mode);
  signs = Signs(Events(train, data.mode, x0, 0.0));
  recorder.Start(0.0, x0);
  while (next_grid < grid.size() && grid[next_grid] <= 0.0)
    recorder.GridSample(grid[next_grid++], x0);

  Context context;
  Vector y(4, context.ctx);
  Vector dky(4, context.ctx);
  for (int i = 0; i < 4; ++i) y.data()[i] = x0[i];
  Memory cvode(bdf ? CV_BDF : CV_ADAMS, context.ctx);
  Matrix a(4, context.ctx);
  LinearSolver ls(y.v, a.m, context.ctx);
  Check(CVodeInit(cvode.mem, Rhs, 0.0, y.v), "CVodeInit");
  Check(CVodeSetErrHandlerFn(cvode.mem, KeepMessage, nullptr), "CVodeSetErrHandlerFn");
  cvode_message.clear();
  Check(CVodeSetUserData(cvode.mem, &data), "CVodeSetUserData");
  Check(CVodeSStolerances(cvode.mem, o.rtol, o.atol_m), "CVodeSStolerances");
  Check(CVodeSetLinearSolver(cvode.mem, ls.ls, a.m), "CVodeSetLinearSolver");
  Check(CVodeRootInit(cvode.mem, kEventCount, Roots), "CVodeRootInit");
  Check(CVodeSetMaxNumSteps(cvode.mem, 100000), "CVodeSetMaxNumSteps");
  Check(CVodeSetMaxHnilWarns(cvode.mem, -1), "CVodeSetMaxHnilWarns");

  double t = 0.0;
  auto set_stop = [&]() {
    while (next_break < breaks.size() && breaks[next_break] <= t) ++next_break;
    const double stop =
        next_break < breaks.size() ? std::min(breaks[next_break], horizon) : horizon;
    train.set_segment_end(next_break < breaks.size() ? all_breaks.angles[next_break]
                                                     : std::numeric_limits<double>::infinity());
    Check(CVodeSetStopTime(cvode.mem, stop), "CVodeSetStopTime");
    return stop;
  };
  double stop = set_stop();
  double t_prev = 0.0;
  int found[kEventCount];
  // One event function takes its new sign at (t, x): the mode follows the signs, and the train
  // is switched before the crossing is recorded (the record takes the train's forces).
  auto flip = [&](int i, int sign, const TrainState& x) {
    if (++stats.events > o.max_events) ThrowOverBudget("events", o.max_events, train, t);
    signs[i] = sign;
    const ContactMode next = ModeFromSigns(signs);
    const bool switched = next.cam != data.mode.cam || next.seat != data.mode.seat;
    if (switched) {
      data.mode = next;
      train.set_mode(next);
      signs[5] = Events(train, next, x, t)[5] > 0.0 ? 1 : -1;  // event 5 depends on the mode
    }
    recorder.Crossing(i, sign, t, x);
    return switched;
  };
  bool restarted = false;  // one restart per stretch after CV_ILL_INPUT at a root
  while (t < horizon) {
    const double t_before = t;
    const TrainState x_before = ToState(y.v);
    const int flag = CVode(cvode.mem, stop, y.v, &t, CV_ONE_STEP);
    if (flag == CV_ILL_INPUT && !restarted) {
      // cvRcheck2, "Root found at and very near t": after a root that switched no contact, an
      // event function is still zero a hair past it (a stiff contact holds g at roundoff). A
      // known CVODE situation: restart there. CVodeReInit's first root check (cvRcheck1) sets
      // such a function aside until it leaves zero, instead of failing.
      restarted = true;
      cvode_message.clear();
      t = t_before;
      for (int i = 0; i < 4; ++i) y.data()[i] = x_before[i];
      Check(CVodeReInit(cvode.mem, t, y.v), "CVodeReInit");
      continue;
    }
    Check(flag, "CVode");
    restarted = false;
    if (++stats.steps > o.max_steps) ThrowOverBudget("steps", o.max_steps, train, t);
    TrainState x = ToState(y.v);
    // Grid times reached by this step, then dense samples inside it for the extremes
    // (CVodeGetDky on the step just taken).
    while (next_grid < grid.size() && grid[next_grid] <= t) {
      if (grid[next_grid] < t) {
        Check(CVodeGetDky(cvode.mem, grid[next_grid], 0, dky.v), "CVodeGetDky");
        recorder.GridSample(grid[next_grid++], ToState(dky.v));
      } else {
        recorder.GridSample(grid[next_grid++], x);
      }
    }
    for (int k = 1; k <= 3 && t > t_prev; ++k) {
      const double tk = t_prev + (t - t_prev) * k / 4.0;
      if (CVodeGetDky(cvode.mem, tk, 0, dky.v) == CV_SUCCESS) recorder.Sample(tk, ToState(dky.v));
    }
    if (flag == CV_ROOT_RETURN) {
      Check(CVodeGetRootInfo(cvode.mem, found), "CVodeGetRootInfo");
      bool switched = false;
      for (int i = 0; i < kEventCount; ++i) {
        if (found[i] != 0) switched = flip(i, found[i] > 0 ? 1 : -1, x) || switched;
      }
      if (switched) {
        Check(CVodeReInit(cvode.mem, t, y.v), "CVodeReInit");
        stop = set_stop();
      }
    } else {
      recorder.Sample(t, x);
      bool extended;
      if (RunIsOver(t, x, recorder, t_end, t_limit, horizon, extended)) break;
      if (extended) stop = set_stop();
      if (flag == CV_TSTOP_RETURN && t < horizon) {
        // The far side of a break: the cam's slope may jump there, and with it the force
        // branches k g + c ġ. CVODE's rootfinding restarts from the new values after
        // CVodeReInit and would never report a sign that flipped at the break itself, so
        // the signs are brought up to date here, each flip recorded as an event.
        stop = set_stop();  // moves the cam to the right-hand side of the break
        for (int pass = 0; pass < 3; ++pass) {
          const EventValues v = Events(train, data.mode, x, t);
          bool changed = false;
          for (int i = 0; i < kEventCount; ++i) {
            const int sign = v[i] > 0.0 ? 1 : -1;
            if (sign == signs[i]) continue;
            flip(i, sign, x);
            changed = true;
          }
          if (!changed) break;
        }
        Check(CVodeReInit(cvode.mem, t, y.v), "CVodeReInit");
      }
    }
    t_prev = t;
  }
  recorder.Finish(t, ToState(y.v));
  train.set_segment_end(std::numeric_limits<double>::infinity());

  stats.rhs_evaluations = train.evaluations() - rhs_before;
  stats.final_state = ToState(y.v);
  stats.final_time = t;
  return stats;
}

}  // namespace needle
