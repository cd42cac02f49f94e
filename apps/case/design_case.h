#pragma once
/// @file
/// The case `needle design --case` writes (issue 11): what Basu's design chain computed (the
/// normal-curve lift, the needle, the formula's spring, the cam disk and roller), and what it
/// does not compute (moving mass, spring rate, contact train) as assumptions marked ASSUMED.

#include <string>

#include "spring/design_chain.h"

namespace needle {

/// The case file's text, for `needle check`.
std::string DesignCaseText(const DesignInputs& in, const DesignResult& r);

}  // namespace needle
