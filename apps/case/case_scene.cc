#include "apps/case/case_scene.h"

#include <memory>
#include <utility>

namespace needle {

LiftLawChoice CaseLiftChoice(const Case& c) { return ChooseLift(UnchosenLift(c)); }

CaseLift ResolveLift(const Case& c) {
  BoundLift l = BindLift(c);
  return CaseLift{std::move(l.choice), std::move(l.law)};
}

LiftLaw MakeLiftLaw(const Case& c) { return *ResolveLift(c).law; }

Case WithSpline(Case c, const std::string& spline, const std::string& where) {
  const auto kind = ParseSplineKind(spline);
  if (!kind) {
    throw CaseError(where + ": unknown kind \"" + spline + "\"; expected one of " +
                    SplineKindList());
  }
  CheckSplineFits(c, *kind, where);
  if (*kind == SplineKind::kClamped && c.lift.spline.kind != SplineKind::kClamped) {
    c.lift.spline.start_slope = c.lift.spline.end_slope = 0.0;  // at rest unless the case says
  }
  c.lift.spline.kind = *kind;
  c.lift.spline_given = true;
  return c;
}

Scene MakeScene(const Case& c) { return MakeScene(c, ResolveLift(c).law); }

Scene MakeScene(const Case& c, std::shared_ptr<const LiftLaw> law) {
  return BindScene(BindSections(c), std::move(law));
}

SimulationOptions OptionsFromCase(const Case& c) { return BindSections(c).run; }

SpringCheckResult CheckSpring(const Case& c, const LiftLaw& law, double speed_rpm) {
  return CheckSpring(BindSections(c), law, speed_rpm);
}

}  // namespace needle
