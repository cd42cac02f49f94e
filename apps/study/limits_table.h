#pragma once
/// @file
/// Internal to the study floor: the limits table of `needle check` (docs/springs.md "The limits
/// table", docs/model.md §8), one row per limit, judged where the scene has what it needs.

#include "apps/scene/case_file.h"
#include "apps/study/check_scene.h"
#include "lib/lift_law.h"

namespace needle {

/// Judges every row of the limits table into `r.limits` (and `r.warnings`), from the check's
/// results already in `r`; `cam_zero_crank_rad` is the crank angle of the cam's zero.
/// `harmonics`: compute the lift's harmonics (`r.harmonics`, information; no row reads them).
void JudgeLimits(const Case& c, const LiftLaw& law, double cam_zero_crank_rad, CheckResult& r,
                 bool harmonics = true);

}  // namespace needle
