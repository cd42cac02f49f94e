#pragma once
/// @file
/// A case bound once: `Bind` turns the file model (case_file.h) into what the jobs run: the
/// lift law chosen for the table, the dynamic scene and its run options, the spring's inputs,
/// the follower, the sweep, the limits, the tolerance model and the paper's values. Every
/// binding error is thrown by Bind, one CaseError line naming file, section and key. The study
/// and report floors read a BoundCase, never the file model (scripts/floors.py enforces it).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/case/case_sections.h"
#include "apps/case/sizing_section.h"
#include "dynamics/simulation.h"
#include "lib/lift_data.h"
#include "lib/lift_law.h"
#include "spring/spring_check.h"
#include "spring/spring_parameters.h"

namespace needle {

struct Case;  // the file model (case_file.h)

/// The lift as bound: the table, the choice made for it (lib/lift_data.h ChooseLiftLaw) and the
/// law built on that choice, with what a changed table needs to be chosen and named the same way.
struct BoundLift {
  LiftTable table;                     ///< the readings in SI, as read
  std::string source;                  ///< "table", "csv FILE" or "basu normal curve"
  LiftDataOptions rule;                ///< [lift]'s spline, noise, resolution, open lift and breaks
  LiftLawChoice choice;                ///< the spline, noise and open lift chosen for `table`
  std::shared_ptr<const LiftLaw> law;  ///< the law built on `choice`
  // Where a reading is, for messages: the case, the key of its lifts, or the CSV's line.
  std::string path;                  ///< the case file
  std::string csv_path;              ///< the CSV the table came from (empty: none)
  std::vector<int> lines;            ///< the CSV line of each reading (empty: not a CSV)
  std::string lift_key = "lift_mm";  ///< the key of the lifts, as written
  bool breaks_given = false;         ///< [lift] breaks_deg stated
};

/// The same rule on a changed table (a tolerance sample's): the choice made again and named as
/// Bind names it. Throws CaseError as Bind does.
BoundLift RebindLift(const BoundLift& lift, LiftTable table);

/// What the jobs of a case run: the sections as read (CaseSections: path, title, [engine],
/// [needle], [spring], [train], …) and what Bind makes of the rest.
struct BoundCase : CaseSections {
  BoundLift lift;
  /// The dynamic scene, when the case has [needle], [spring] and [train], the law gives an
  /// acceleration (a C¹ spline leaves it out: the check calls that undecided) and the model
  /// takes it (else left out: BindScene says why). Built by Bind
  /// from the fields around it: a caller that changes them builds it again (BindScene) or
  /// resets it (the jobs then build it on the changed inputs).
  std::optional<Scene> scene;
  SimulationOptions run;                     ///< [solver]'s method, tolerances and budgets
  bool atol_given = false;                   ///< [solver] atol_mm stated
  std::optional<double> start_rad, end_rad;  ///< [solver] start_deg, end_deg
};

/// Binds case `c`: its lift resolved (throws CaseError naming [lift] on a corner, an outlier or
/// a law the table cannot take) and its scene built where the model takes it. A scene it
/// refuses (a ramp, a spring gone solid, a cycle count) is left out: the jobs that run one
/// build it again (BindScene) and throw its CaseError, naming [train], [spring] or [solver],
/// where they always did; a kinematics table or a sizing of that case still runs.
BoundCase Bind(const Case& c);

/// The scene of `b` on lift law `law` (b.lift.law or another law of the same table). Throws
/// CaseError naming a missing [needle], [spring] or [train], a C¹ law, or what the model
/// refuses.
Scene BindScene(const BoundCase& b, std::shared_ptr<const LiftLaw> law);

/// The scene a job runs on `law`: the bound one when it is on that law, else BindScene's (which
/// throws what is missing or what the model refuses).
Scene SceneFor(const BoundCase& b, const std::shared_ptr<const LiftLaw>& law);

/// The spring check of `b` (which must have [needle] and [spring]: throws CaseError naming the
/// missing section) at `speed_rpm` on `law`.
SpringCheckResult CheckSpring(const BoundCase& b, const LiftLaw& law, double speed_rpm);

/// The published velocity magnitude at `crank_rad` (m/s), when [paper] gives one there.
std::optional<double> PaperVelocityAt(const BoundCase& b, double crank_rad);

}  // namespace needle
