#pragma once
/// @file
/// Internal to the study floor: `needle size`'s second stage (docs/sizing.md "The search, then
/// the check"). The closed form's kept springs, then the mass-fatigue front, each checked end to
/// end by CheckScene in order until one passes or [sizing] verify are checked; then, if none
/// passed, the case's own helical spring as stated, a candidate whenever its wire is one of the
/// space's and it fits the space.

#include <chrono>
#include <string>

#include "apps/case/bound_case.h"
#include "apps/study/spring_sizing_scene.h"
#include "lib/lift_law.h"
#include "spring/spring_sizing.h"

namespace needle {

namespace sizing_internal {
/// Seconds since `since`: a stage's wall time.
double Seconds(std::chrono::steady_clock::time_point since);
/// A length in m shown in mm with `digits` decimals ("16.00 mm").
std::string Mm(double m, int digits = 2);
}  // namespace sizing_internal

/// Checks the candidates of `r.closed_form` (and the case's own spring) on `law`, filling
/// `r.verified`, `r.winner`, the stage's row, `r.pass` and `r.no_fit` (which names the closest
/// spring checked and its binding limit row, after the closed form's own diagnosis when it
/// kept none).
void VerifyCandidates(const BoundCase& c, const LiftLaw& law, const SizingSection& z,
                      const SizingDuty& duty, const SizeOptions& options, SizeResult& r);

}  // namespace needle
