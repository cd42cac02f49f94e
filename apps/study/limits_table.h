#pragma once
/// @file
/// Internal to the study floor: the limits table of `needle check` (docs/springs.md "The limits
/// table", docs/model.md §8), one row per limit, judged where the scene has what it needs.

#include "apps/case/bound_case.h"
#include "apps/study/check_scene.h"
#include "lib/lift_law.h"

namespace needle {

/// Judges every row of the limits table into `r.limits` (and `r.warnings`), from the check's
/// results already in `r`; `cam_zero_crank_rad` is the crank angle of the cam's zero.
/// `report_notes`: the notes only the report reads — the lift's harmonics (`r.harmonics`) and
/// the massless spring at f·n beside the surge jump row (false: not computed, not written).
void JudgeLimits(const BoundCase& c, const LiftLaw& law, double cam_zero_crank_rad, CheckResult& r,
                 bool report_notes = true);

}  // namespace needle
