#pragma once
/// @file
/// `needle size` as a library function (issue 35): the valve spring of a case sized by the
/// closed-form search (spring/spring_sizing.h), then the best few verified end to end by
/// CheckScene, the code of `needle check` (the dynamics at the rated speed, the overspeed
/// sweep, the spring as coil masses, the limits table); the winner is the best that passes.
///
/// The space comes from [sizing] (apps/case/sizing_section.h); what it leaves out, from the
/// case's own spring: its installed length L₁ = L₀ − P₀/k as the largest, its outer and inner
/// diameters as bounds, its wire (a named grade: that grade's family, EN 10270-1 or -2; else the
/// case's R_m and G at every diameter), its ends, stress correction and peening. The duty is the
/// case's: the stroke is the largest lift, and the least preload of a spring of rate k and active
/// coil mass m_s is the largest of S·F_g, Basu's formula less its tolerance, and the inertia
/// sizing RequiredPreloadN with the moving mass m₀ + m_s/3 (m₀: [sizing]
/// mass_without_spring_kg, else [needle] mass_kg less a third of the case's active coils). The
/// limits are [limits]'s: fatigue_safety_factor, coil_gap_mm; the surge ratio 13 at the rated
/// speed.

#include <optional>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "apps/case/case_writer.h"
#include "apps/study/check_scene.h"
#include "spring/spring_sizing.h"

namespace needle {

/// Options of SizeCase; every field has a default.
struct SizeOptions {
  int threads = 0;  ///< the verification sweeps' threads (0: all cores)
};

/// A spring of the closed-form stage checked end to end.
struct VerifiedSpring {
  SizedSpring spring;
  BoundCase sized_case;  ///< the case with this spring (and its moving mass)
  CheckResult check;     ///< CheckScene's verdict on it
  double seconds = 0;    ///< wall time of the check
};

/// One stage of the sizing: how many springs it kept and what it took.
struct SizeStage {
  std::string name;  ///< "closed form", "dynamics"
  long in = 0;       ///< springs it was given
  long kept = 0;     ///< springs that passed it
  double seconds = 0;
  std::string note;
};

/// A stage as fields: its name, the springs it was given and kept, its time and note.
std::vector<Field> SizeStageFields(const SizeStage& stage);

struct SizeResult {
  SizingSpace space;
  std::string space_note;   ///< the space in words, with where each bound came from
  std::string objective;    ///< "mass", "height", "stress"
  double stroke_m = 0.0;    ///< h
  std::string stroke_note;  ///< where h came from when [sizing] states it (empty: the lift)
  double mass_without_spring_kg = 0.0;
  std::string mass_note;  ///< where m₀ came from
  SizingResult closed_form;
  std::vector<VerifiedSpring> verified;       ///< in order, up to the first that passes
  std::optional<size_t> winner;               ///< index into `verified`
  std::optional<double> case_spring_mass_kg;  ///< the case's own helical spring, all coils
  std::vector<SizeStage> stages;
  bool pass = false;
  std::string no_fit;  ///< when nothing passes: which rule binds, by how much, the best spring
};

/// Sizes the spring of case `c` (with [needle] and [spring]) with its lift law `law`. Throws
/// CaseError naming the section and key when the case cannot be sized (no [spring], no space to
/// size in, a [sizing] that leaves no candidate).
SizeResult SizeCase(const BoundCase& c, const LiftLaw& law, const SizeOptions& options = {});

/// Case `c` with spring `s` (preload, geometry; the rate from the geometry) and the moving mass
/// m₀ + m_s/3.
BoundCase CaseWithSpring(const BoundCase& c, const SizedSpring& s, const SizingSpace& space,
                         double mass_without_spring_kg);

}  // namespace needle
