#pragma once
/// @file
/// The spring jobs: a case's spring checked at a speed (Basu's formula P₀ beside the case's, the
/// quasi-static contact force F = P₀ + k·s − m·a and its lift-off speed n_qs, the required
/// preload, the helical spring; spring/spring_check.h), and Basu's design chain from an engine
/// file (spring/design_chain.h). `needle spring`, `needle design` and the Python module call
/// them; the writers are in apps/report/spring_writer.h.

#include <optional>
#include <string>

#include "apps/case/bound_case.h"
#include "lib/spline.h"
#include "spring/design_chain.h"
#include "spring/spring_check.h"

namespace needle {

/// A case's spring check and what it was checked with.
struct CaseSpringCheck {
  BoundCase c;              ///< the case
  double speed_rpm = 0.0;   ///< the speed of the check, rpm
  SplineKind spline{};      ///< the lift law's spline
  SpringCheckResult check;  ///< the check
};

/// The spring check of a loaded case at `speed_rpm` (default: [engine] speed_rpm; messages name
/// it --rpm). Throws CaseError on bad input.
CaseSpringCheck CheckCaseSpring(const BoundCase& c, const std::optional<double>& speed_rpm);

/// Basu's design chain for a loaded engine file. Throws CaseError naming the file when the
/// chain cannot proceed.
DesignResult DesignFromEngine(const DesignInputs& in);

}  // namespace needle
