#pragma once
// Lift laws the dynamics tests share.
#include "lib/lift_law.h"

namespace needle {

// A cam event far from the window: the cam input is constant (base_m) over [0, 0.8] rad.
inline LiftLaw FarLaw(double base_m = 0.0) {
  LiftTable t;
  t.crank_rad = {1.0, 1.1, 1.2, 1.3, 1.4};
  t.lift_m = {base_m, base_m + 0.5e-3, base_m + 1e-3, base_m + 0.5e-3, base_m};
  return LiftLaw(t, SplineOptions{});
}

}  // namespace needle
