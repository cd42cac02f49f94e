// A case bound once: the lift chosen and built, the scene and the run options, the sections the
// jobs read (bound_case.h).
#include "apps/case/bound_case.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/case/section_reader.h"
#include "dynamics/solver/integrator.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/helical_spring.h"
#include "spring/resonance.h"

namespace needle {

using case_internal::Number;

namespace {

// "FILE: [lift] lift_mm[3]" or "FILE: [lift] csv: TABLE.csv:12": where reading `index` is.
std::string ReadingAt(const BoundLift& l, size_t index) {
  if (index < l.lines.size()) {
    std::string at = l.csv_path + ":" + std::to_string(l.lines[index]);
    return l.csv_path != l.path ? l.path + ": [lift] csv: " + at : at;
  }
  return l.path + ": [lift] " + l.lift_key + "[" + std::to_string(index) + "]";
}

// A corner refuses the table: the lift's velocity jumps, the law cannot be differentiated there.
[[noreturn]] void ThrowCorner(const BoundLift& l, const LiftBreak& k) {
  throw CaseError(ReadingAt(l, k.index) + ": the lift has a corner at " +
                  Fixed(k.crank_rad / kDeg, 3) + " deg (its velocity jumps by " +
                  Fixed(k.jump * 1e3 * kDeg, 4) +
                  " mm/deg): a needle's lift has no corners; correct the readings there, or "
                  "round the corner off in the law the table was made from");
}

// Outliers of measured data: refused naming the first, or (outliers = "drop") left out with
// their places added to the choice's reason.
void TakeOutliers(const BoundLift& l, LiftLawChoice& choice) {
  // Where a reading is: the CSV file's line, or the entry of the case's array.
  auto where = [&](size_t index) {
    if (index < l.lines.size()) return "line " + std::to_string(l.lines[index]);
    return "entry " + std::to_string(index);
  };
  auto reading = [&](const LiftOutlier& x) {
    return Number(x.lift_m * 1e3) + " mm at " + Number(l.table.crank_rad[x.index] / kDeg) + " deg";
  };
  const LiftOutlier& first = choice.outliers.front();
  const size_t more = choice.outliers.size() - 1;
  if (!l.rule.drop_outliers) {
    std::string others;
    for (size_t k = 1; k < choice.outliers.size() && k <= 5; ++k) {
      others += (k > 1 ? ", " : "") + where(choice.outliers[k].index);
    }
    if (more > 5) others += ", …";
    throw CaseError(
        ReadingAt(l, first.index) + ": the reading " + reading(first) +
        " stands out of its neighbourhood (" + Number(first.expected_m * 1e3) +
        " mm by the cubic through the four readings around it, " +
        Number(std::round(first.sigmas)) + " robust sigma of " +
        Number(choice.robust_noise_m * 1e3) + " mm off): an outlier" +
        (more ? " (" + std::to_string(more) + " more: " + others + ")" : std::string()) +
        "; correct it, or set [lift] outliers = \"drop\" to leave it out" +
        (l.csv_path == l.path ? " (in a case file reading this table with csv = …)" : ""));
  }
  choice.reason += "; " + std::to_string(choice.outliers.size()) + " outlier" + (more ? "s" : "") +
                   " left out (";
  for (size_t k = 0; k < choice.outliers.size(); ++k) {
    const LiftOutlier& x = choice.outliers[k];
    choice.reason += (k ? "; " : "") + where(x.index) + ": " + reading(x) + ", neighbourhood " +
                     Number(x.expected_m * 1e3) + " mm";
  }
  choice.reason += ")";
}

}  // namespace

BoundLift UnchosenLift(const Case& c) {
  BoundLift l;
  l.table = c.lift.table;
  l.source = c.lift.source;
  LiftDataOptions& o = l.rule;
  if (c.lift.spline_given) o.kind = c.lift.spline.kind;
  o.spline = c.lift.spline;
  o.noise_m = c.lift.noise_m;
  if (c.lift.resolution_given) o.resolution_m = c.lift.resolution_m;
  o.open_rad = c.lift.open_rad;
  o.close_rad = c.lift.close_rad;
  o.breaks_rad = c.lift.breaks_rad;
  o.drop_outliers = c.lift.drop_outliers;
  o.find_breaks = !c.lift.breaks_given;
  l.path = c.path;
  l.csv_path = c.lift.csv_path;
  l.lines = c.lift.lines;
  l.lift_key = c.lift.lift_key;
  l.breaks_given = c.lift.breaks_given;
  return l;
}

LiftLawChoice ChooseLift(const BoundLift& l) {
  LiftLawChoice choice = ChooseLiftLaw(l.table, l.rule);
  if (choice.corner) ThrowCorner(l, *choice.corner);
  if (!choice.outliers.empty()) TakeOutliers(l, choice);
  return choice;
}

namespace {

// The choice for l.table by l.rule, and the law on it.
void ChooseAndBuild(BoundLift& l) {
  try {
    l.choice = ChooseLift(l);
    l.law = BuildChosenLaw(&l.choice);
  } catch (const CaseError&) {
    throw;
  } catch (const std::exception& e) {
    // A stated break the law refuses names its key (issue 51's trial: "[lift]: break 0 …").
    const std::string what = e.what();
    const bool breaks = l.breaks_given && what.rfind("break ", 0) == 0;
    throw CaseError(l.path + ": [lift]" + (breaks ? " breaks" : "") + ": " + what);
  }
}

}  // namespace

BoundLift RebindLift(const BoundLift& lift, LiftTable table) {
  BoundLift l = lift;
  l.table = std::move(table);
  ChooseAndBuild(l);
  return l;
}

BoundCase BindSections(const Case& c) {
  BoundCase b;
  static_cast<CaseSections&>(b) = c;  // the sections as read
  if (c.solver) {                     // [solver] was read straight into the run options
    b.run = c.solver->run;
    b.atol_given = c.solver->atol_given;
    b.start_rad = c.solver->start_rad;
    b.end_rad = c.solver->end_rad;
  } else {
    b.run.integrator.atol_m = DefaultAtol(b.run.integrator.rtol);
  }
  return b;
}

BoundLift BindLift(const Case& c) {
  BoundLift l = UnchosenLift(c);
  ChooseAndBuild(l);
  return l;
}

BoundCase Bind(const Case& c) {
  BoundCase b = BindSections(c);
  b.lift = BindLift(c);
  if (b.needle && b.spring && b.train && b.lift.law->HasAcceleration()) {
    try {
      b.scene = BindScene(b, b.lift.law);
    } catch (const CaseError&) {
      // A scene the model refuses (a ramp, a spring gone solid, a cycle count) refuses the jobs
      // that run it, when they do, with this message (BindScene again): a kinematics table or
      // a sizing of such a case is no less valid.
    }
  }
  return b;
}

Scene SceneFor(const BoundCase& b, const std::shared_ptr<const LiftLaw>& law) {
  return b.scene && b.scene->law == law ? *b.scene : BindScene(b, law);
}

Scene BindScene(const BoundCase& b, std::shared_ptr<const LiftLaw> law) {
  if (!b.needle)
    throw CaseError(
        b.path +
        ": [needle] mass_kg: section [needle] is missing; the dynamics needs the moving mass");
  if (!b.spring)
    throw CaseError(
        b.path +
        ": [spring] preload: section [spring] is missing; the dynamics needs preload and rate");
  if (!b.train)
    throw CaseError(b.path +
                    ": [train] contact_stiffness: section [train] is missing; the dynamics needs "
                    "the contact stiffness");
  const NeedleParameters& needle = *b.needle;
  const SpringParameters& spring = *b.spring;
  const TrainSection& train = *b.train;
  Scene s;
  s.law = std::move(law);
  if (!s.law->HasAcceleration()) {
    throw CaseError(b.path + ": [lift] spline: \"" + SplineKindName(s.law->kind()) +
                    "\" is C1 only; the dynamics needs a C2 spline (not-a-knot, natural, clamped, "
                    "quintic, smoothing, local)");
  }
  try {
    s.cam = std::make_shared<const CamInput>(
        *s.law, train.play_m, train.linear_ramp ? RampKind::kLinear : RampKind::kTangent,
        train.ramp_rad);
  } catch (const std::invalid_argument& e) {
    throw CaseError(b.path + ": [train] ramp: " + e.what());
  }
  TrainParameters& t = s.train;
  t.mass_kg = needle.mass_kg;
  t.gas_force_N = needle.gas_force_N;
  t.preload_N = spring.preload_N;
  t.rate_N_m = spring.rate_N_m ? *spring.rate_N_m : HelicalRate(*spring.helical);
  t.coil_masses = spring.masses;
  if (spring.masses > 1) {
    t.spring_mass_kg = ActiveSpringMassKg(*spring.helical);
    t.surge_damping_ratio = spring.surge_damping_ratio;
    // The travel from installed to solid (the helical check's lengths).
    try {
      const HelicalSpringCheck lengths = CheckHelicalSpring(*spring.helical, spring.preload_N, 0.0,
                                                            b.engine.speed_rpm, b.engine.cycle);
      t.coil_travel_m = lengths.length_preload_m - lengths.solid_length_m;
    } catch (const std::invalid_argument& e) {
      throw CaseError(b.path + ": [spring] preload: " + e.what());
    }
    t.coil_clash = spring.coil_clash;
    t.clash_stiffness_N_m = spring.clash_stiffness_N_m.value_or(train.contact_stiffness_N_m);
    t.clash_damping_ratio = spring.clash_damping_ratio.value_or(train.contact_damping_ratio);
  }
  static_cast<ContactParameters&>(t) = train;  // [train]'s contacts, as read
  s.revolution_rad = 2.0 * kPi * CrankTurnsPerCycle(b.engine.cycle);
  s.start_rad = b.start_rad;
  s.end_rad = b.end_rad;
  const auto refusal = b.run.cycles > 1 ? CyclesRefusal(s) : std::nullopt;
  if (refusal) throw CaseError(b.path + ": [solver] cycles: " + *refusal);
  return s;
}

SpringCheckResult CheckSpring(const BoundCase& b, const LiftLaw& law, double speed_rpm) {
  if (!b.needle) {
    throw CaseError(
        b.path +
        ": [needle] mass_kg: section [needle] is missing; the spring check needs the moving mass");
  }
  if (!b.spring) {
    throw CaseError(
        b.path +
        ": [spring] preload: section [spring] is missing; the spring check needs preload and rate");
  }
  return CheckSpring(*b.needle, *b.spring, law, speed_rpm, b.engine.cycle, b.path);
}

std::optional<double> PaperVelocityAt(const BoundCase& b, double crank_rad) {
  if (!b.paper) return std::nullopt;
  for (size_t i = 0; i < b.paper->crank_rad.size(); ++i) {
    if (std::abs(b.paper->crank_rad[i] - crank_rad) < 1e-9) return b.paper->velocity_m_s[i];
  }
  return std::nullopt;
}

}  // namespace needle
