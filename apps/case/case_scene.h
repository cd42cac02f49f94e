#pragma once
/// @file
/// The file model's side of binding (bound_case.h): a case's sections, lift and scene bound
/// one at a time, for the callers that hold a Case (the commands before they bind, tests,
/// bench). Each throws CaseError naming the file, the section and what is missing or invalid.

#include <memory>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "dynamics/simulation.h"
#include "spring/spring_check.h"

namespace needle {

/// Every section of `c` but the lift bound (Bind without choosing the lift or building the
/// scene): b.lift is empty.
BoundCase BindSections(const Case& c);

/// The lift of `c` with its rule and names, the choice not yet made.
BoundLift UnchosenLift(const Case& c);

/// The choice for the lift's table by its rule; throws CaseError on a corner or an outlier.
LiftLawChoice ChooseLift(const BoundLift& lift);

/// The lift of `c` chosen and its law built (Bind's lift).
BoundLift BindLift(const Case& c);

/// Case `c` with its [lift] spline set to `spline` (a SplineKind name; a clamped spline at rest
/// unless the case states its end slopes), as the option `where` asks. Throws CaseError naming
/// `where` on an unknown kind or one the table has too few points for.
Case WithSpline(Case c, const std::string& spline, const std::string& where);

/// Builds the scene of a case with [needle], [spring] and [train]; throws CaseError naming
/// the missing section or the invalid value.
Scene MakeScene(const Case& c);
/// The same on a lift law already built for the case (MakeLiftLaw(c)): the scene shares it.
Scene MakeScene(const Case& c, std::shared_ptr<const LiftLaw> law);

/// The options a case's [solver] section asks for.
SimulationOptions OptionsFromCase(const Case& c);

/// The spring check of a case with [needle] and [spring] at `speed_rpm`; throws CaseError
/// naming a missing section.
SpringCheckResult CheckSpring(const Case& c, const LiftLaw& law, double speed_rpm);

}  // namespace needle
