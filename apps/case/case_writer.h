#pragma once
/// @file
/// The case files needle writes, each for `needle check` to read back: the case `design --case`
/// writes from Basu's design chain, the one `synth --case` writes for a synthesized law, and
/// the case `size --case` writes with the sized spring. What a file's maker does not know is
/// stated as an assumption, marked ASSUMED.

#include <string>

#include "apps/case/synthesis_file.h"
#include "lib/cam_synthesis.h"
#include "spring/design_chain.h"
#include "spring/spring_sizing.h"

namespace needle {

/// The shortest decimal that reads back as `v` (6 to 17 digits): how the writers write numbers.
std::string ExactDecimal(double v);

/// What Basu's design chain computed (the normal-curve lift, the needle, the formula's spring,
/// the cam disk and roller), and what it does not compute (moving mass, spring rate, contact
/// train) as assumptions marked ASSUMED.
std::string DesignCaseText(const DesignInputs& in, const DesignResult& r);

/// A needle case file for the synthesized law: every 10th step as crank angles, [profile]
/// from [checks], and [needle], [spring] with an assumed, marked [train] when [checks] has
/// a spring and a mass (so that `needle check` on it runs the spring and the dynamics).
std::string SynthesizedCaseText(const SynthesisFile& f, const SynthesizedLaw& law);

/// The case file's text `original` with the [spring] keys of `s` and [needle] mass_kg =
/// `needle_mass_kg` (the parts and a third of the sized coils) in place of the old ones; every
/// other line kept.
std::string SizedCaseText(const std::string& original, double needle_mass_kg, const SizedSpring& s,
                          const SizingSpace& space);

}  // namespace needle
