#pragma once
/// @file
/// The case-file layer's mapping of a case onto the modules' own parameters: the dynamic scene
/// and its solver options (dynamics/simulation.h), the spring check's inputs
/// (spring/spring_check.h). Each throws CaseError naming the file, the section and what is
/// missing or invalid.

#include <memory>

#include "apps/case/case_file.h"
#include "dynamics/simulation.h"
#include "spring/spring_check.h"

namespace needle {

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
